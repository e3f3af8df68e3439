#!/usr/bin/env bash
# The qualification run, the README's first Quick start command after the build: the unit
# tests, the Python tests and every verification problem at the full level, all from one build
# of one commit, then the traceability audit in qualification mode, which fails on any gap
# (docs/verification.md#configuration-control). It writes the qualification record in the
# source tree, and nothing else does:
#   reports/tests/         gtest-unit.xml, pytest.xml
#   reports/verification/  the full suite's report: summary.json, index.html, report.pdf, junit.xml
#   reports/traceability/  rtm.html, rtm.csv
# (The test suite, ctest, writes its base-level evidence under the build folder instead.)
#   scripts/qualify.sh [BUILD_DIR]      BUILD_DIR defaults to build
# Every step runs even after one fails, so that the audit states every gap. Exit status 0 when
# all steps passed, 1 otherwise; the audit is judged on a clean checkout only (uncommitted or
# untracked files are a gap), as qualification evidence must name the commit it came from.
set -uo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=$(cd "${1:-build}" 2>/dev/null && pwd) || { echo "qualify: no build folder ${1:-build}" >&2; exit 2; }
for program in vdec vdec_cy_reference tests/vdec_unit_tests tests/vdec_fuzz_replay; do
  [ -x "$build/$program" ] || { echo "qualify: $build/$program is not built" >&2; exit 2; }
done
reports=$root/reports
# Results of an earlier run must not stand in for this one's.
rm -f "$reports"/tests/*.xml
mkdir -p "$reports/tests"
failed=()
start=$SECONDS

"$build/tests/vdec_unit_tests" --gtest_brief=1 --gtest_output="xml:$reports/tests/gtest-unit.xml" \
  || failed+=("unit tests")
echo "qualify: unit tests in $((SECONDS - start)) s" >&2

step=$SECONDS
VDEC_EXECUTABLE=$build/vdec VDEC_CY_REFERENCE=$build/vdec_cy_reference VDEC_FUZZ_REPLAY=$build/tests/vdec_fuzz_replay \
  /usr/bin/python3 -m pytest -q -p no:cacheprovider --junitxml="$reports/tests/pytest.xml" tests/python \
  || failed+=("Python tests")
echo "qualify: Python tests in $((SECONDS - step)) s" >&2

step=$SECONDS
PYTHONPATH=$root/verification/harness:$root/verification /usr/bin/python3 -m vdec_verify run \
  --vdec "$build/vdec" --level full --problems verification/problems --out "$reports/verification" \
  || failed+=("verification problems (full level)")
echo "qualify: verification problems in $((SECONDS - step)) s" >&2

/usr/bin/python3 qa/traceability/audit.py --root "$root" --mode qualification || failed+=("qualification audit")

if [ ${#failed[@]} -gt 0 ]; then
  printf 'qualify: FAIL (%d s): %s\n' "$((SECONDS - start))" "$(IFS=', '; echo "${failed[*]}")" >&2
  exit 1
fi
echo "qualify: PASS in $((SECONDS - start)) s; reports in reports/ (verification, tests, traceability)" >&2
