#!/usr/bin/env bash
# The nightly verification run (docs/user-manual/nightly.md): builds vdec (Release) into the
# build folder, then runs `python -m vdec_verify nightly`, which runs the suite, appends its
# line to reports/history/nightly.jsonl, compares it with the baseline in reports/baseline and
# writes reports/nightly/index.html.
#   scripts/nightly.sh [NIGHTLY OPTIONS]     e.g. --level base, --filter RB-INCLINE-SLIP, --no-repeat
# Environment: VDEC_BUILD_DIR (default build), VDEC_BUILD_JOBS (default 2).
# Exit status: that of vdec_verify nightly (0 no regression, 1 a regression, 2 a usage or input
# error such as no baseline), or 3 when vdec does not build.
set -uo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=${VDEC_BUILD_DIR:-build}
if ! { cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DVDEC_BUILD_BENCH=OFF \
       && cmake --build "$build" -j "${VDEC_BUILD_JOBS:-2}"; }; then
  echo "nightly: vdec did not build in $build" >&2
  exit 3
fi
PYTHONPATH=$root/verification/harness:$root/verification exec /usr/bin/python3 -m vdec_verify nightly \
  --vdec "$build/vdec" "$@"
