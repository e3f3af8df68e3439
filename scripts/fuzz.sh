#!/usr/bin/env bash
# Fuzzes the scene reader (tests/fuzz) with libFuzzer, ASan and UBSan for a given time.
#   scripts/fuzz.sh [SECONDS] [--keep-going] [-- LIBFUZZER_OPTIONS...]
# SECONDS defaults to 300; CI runs 60. Seeds: every scene file in the repository and every
# input kept in tests/fuzz/regressions. Inputs that crash, hang or exhaust memory are copied
# into tests/fuzz/regressions (commit them: tests/python/test_fuzz_regressions.py replays them
# at every ctest) and the script exits 1. --keep-going fuzzes on past findings (libFuzzer's
# fork mode) instead of stopping at the first. docs/verification.md describes it.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

seconds=300
keep_going=0
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --keep-going) keep_going=1 ;;
    --) shift; extra=("$@"); break ;;
    ''|*[!0-9]*) echo "fuzz.sh: unknown argument '$1'; usage: scripts/fuzz.sh [SECONDS] [--keep-going] [-- LIBFUZZER_OPTIONS...]" >&2; exit 2 ;;
    *) seconds=$1 ;;
  esac
  shift
done
[ "$seconds" -ge 1 ] || { echo "fuzz.sh: SECONDS must be >= 1" >&2; exit 2; }

command -v clang++ >/dev/null ||
  { echo "fuzz.sh: clang++ not found; bash scripts/setup.sh installs clang, libclang-rt-dev and libomp-dev" >&2; exit 2; }
build=build-fuzz
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DVDEC_FUZZ=ON \
  -DBUILD_TESTING=OFF -DVDEC_BUILD_BENCH=OFF -DVDEC_WERROR=OFF >/dev/null
cmake --build "$build" -j2 --target vdec_fuzz_scene_reader >/dev/null
fuzzer=$root/$build/tests/fuzz/vdec_fuzz_scene_reader

work=$root/$build/fuzz-work
regressions=$root/tests/fuzz/regressions
rm -rf "$work/seeds" "$work/sandbox" "$work/findings"
mkdir -p "$work/corpus" "$work/seeds" "$work/sandbox/scene" "$work/findings" "$regressions"

# Seeds: the scene files (not problem.toml or requirements.toml), named by their path.
git ls-files '*.toml' | grep -v -e '/problem\.toml$' -e 'requirements\.toml$' | while read -r scene; do
  cp "$scene" "$work/seeds/$(echo "$scene" | tr '/' '_')"
done

# The data files the scenes name, relative to their folder ("unloading.csv") or to a sibling
# problem ("../DB-KIRSCH/far_field.csv"): the fuzz inputs are written to sandbox/scene.
git ls-files 'verification/problems/*' | grep -v -e '\.toml$' -e '\.py$' | while read -r data; do
  problem=$(basename "$(dirname "$data")")
  mkdir -p "$work/sandbox/$problem"
  cp "$data" "$work/sandbox/$problem/"
  [ -e "$work/sandbox/scene/$(basename "$data")" ] || cp "$data" "$work/sandbox/scene/"
done

# Dictionary: TOML's special numbers and edge values, table headers, and every key the readers
# ask for (string literals of src/io), so that mutations speak the scene language.
{
  for token in nan +nan -nan inf +inf -inf 1e308 -1e308 1e-308 4294967296 2147483648 -2147483649 \
               9223372036854775807 -9223372036854775808 0 -1 0.0 -0.0 true false '[]' '[[' ']]' '= ' '{' '}' \
               '"' "'''" '"""' '\u0000' '#' ',' '.'; do
    printf '"%s"\n' "$(printf '%s' "$token" | sed 's/\\/\\\\/g; s/"/\\"/g')"
  done
  grep -ohE '"[a-z][a-z_]*[a-z]"' src/io/*.cpp src/io/*.hpp | sort -u
} > "$work/scene.dict"

options=(-max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 -dict="$work/scene.dict"
         -artifact_prefix="$work/findings/" -print_final_stats=1)
if [ "$keep_going" -eq 1 ]; then
  options+=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
fi
echo "fuzz: $seconds s on the scene reader; corpus $work/corpus" >&2
status=0
VDEC_FUZZ_SCENE_DIR=$work/sandbox/scene \
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1} \
  "$fuzzer" "${options[@]}" "${extra[@]}" "$work/corpus" "$work/seeds" "$regressions" >"$work/fuzz.log" 2>&1 || status=$?

findings=$(find "$work/findings" -type f | sort)
if [ -n "$findings" ]; then
  echo "fuzz: FAIL: the scene reader failed on these inputs (new ones copied to tests/fuzz/regressions: commit them):" >&2
  for f in $findings; do
    kept=""
    for old in "$regressions"/*; do
      if [ -f "$old" ] && cmp -s "$f" "$old"; then kept=$old; break; fi
    done
    if [ -z "$kept" ]; then
      kept=$regressions/$(basename "$f")
      cp "$f" "$kept"
    fi
    echo "  ${kept#"$root"/}" >&2
  done
  grep -E '^(fuzz: scene reader defect|==[0-9]+==ERROR|SUMMARY|.*runtime error)' "$work/fuzz.log" | head -20 >&2 || true
  echo "fuzz: log in $work/fuzz.log" >&2
  exit 1
fi
if [ "$status" -ne 0 ]; then
  tail -20 "$work/fuzz.log" >&2
  echo "fuzz: libFuzzer exited $status without a finding; log in $work/fuzz.log" >&2
  exit 1
fi
grep -E '^stat::number_of_executed_units|^stat::new_units_added' "$work/fuzz.log" | sed 's/^/fuzz: /' >&2 || true
echo "fuzz: PASS: no finding (time limit $seconds s; inputs run as counted above)" >&2
