#!/usr/bin/env bash
# Builds vdec with AddressSanitizer and UndefinedBehaviorSanitizer (build-asan) and runs, under
# them, the unit tests, the base-level verification problems, the mutated scenes and the
# replay of the fuzzer's regression inputs (with their known failures, hostile_input.py). The
# first finding stops the program that made it with SIGABRT, which fails its test, and the
# script. Not part of CI; docs/verification.md gives the time it takes.
#   scripts/sanitize.sh
# Reports go to build-asan/reports, never to reports/ (the audit's inputs).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=build-asan
start=$SECONDS

# float-cast-overflow: a double out of an integer's range cast to it is undefined behaviour,
# and GCC leaves it out of -fsanitize=undefined.
sanitizers="-fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVDEC_BUILD_BENCH=OFF -DVDEC_WERROR=OFF \
  -DCMAKE_CXX_FLAGS="$sanitizers" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
mkdir -p "$build"
cmake --build "$build" -j2 >"$build/build.log" 2>&1 || { tail -40 "$build/build.log" >&2; exit 1; }
echo "sanitize: built in $((SECONDS - start)) s" >&2

export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:abort_on_error=1:detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:abort_on_error=1:print_stacktrace=1}
reports=$root/$build/reports
mkdir -p "$reports"
failed=()

step=$SECONDS
"$build/tests/vdec_unit_tests" --gtest_brief=1 --gtest_output="xml:$reports/gtest-unit.xml" || failed+=("unit tests")
echo "sanitize: unit tests in $((SECONDS - step)) s" >&2

step=$SECONDS
PYTHONPATH=$root/verification/harness:$root/verification /usr/bin/python3 -m vdec_verify run \
  --vdec "$root/$build/vdec" --level base --problems "$root/verification/problems" \
  --out "$reports/verification" || failed+=("verification problems (base level)")
echo "sanitize: verification problems in $((SECONDS - step)) s" >&2

step=$SECONDS
VDEC_EXECUTABLE=$root/$build/vdec VDEC_FUZZ_REPLAY=$root/$build/tests/vdec_fuzz_replay \
  /usr/bin/python3 -m pytest -q -p no:cacheprovider --junitxml="$reports/pytest-hostile.xml" \
  tests/python/test_mutated_scenes.py tests/python/test_fuzz_regressions.py || failed+=("mutated scenes and fuzz regressions")
echo "sanitize: mutated scenes and fuzz regressions in $((SECONDS - step)) s" >&2

if [ ${#failed[@]} -gt 0 ]; then
  printf 'sanitize: FAIL (%d s): %s\n' "$((SECONDS - start))" "$(IFS=', '; echo "${failed[*]}")" >&2
  exit 1
fi
echo "sanitize: PASS in $((SECONDS - start)) s" >&2
