#!/usr/bin/env bash
# Reruns every worked example at full size and redraws its pictures into examples/NAME/pictures/.
#   examples/render.sh [BUILD_DIR]        (default build/; BUILD_DIR/vdec is used)
# The commands are read from the documents that show them, so that a picture is always what its
# command draws: the `vdec run` and `vdec plot` lines of the ```sh blocks of examples/NAME/README.md
# (and, for the tutorial, of docs/user-manual/tutorial.md), run in document order in a scratch
# folder that sees the repository's examples/ as ./examples. Each example's old pictures are
# removed first; every PNG its commands write is moved into examples/NAME/pictures/.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

build=${1:-build}
[ $# -le 1 ] || { echo "render.sh: usage: examples/render.sh [BUILD_DIR]" >&2; exit 2; }
vdec=$(cd "$build" 2>/dev/null && pwd)/vdec
[ -x "$vdec" ] || { echo "render.sh: $build/vdec not found or not executable; build vdec first or give its build folder" >&2; exit 2; }

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# The `vdec run` and `vdec plot` commands of the ```sh blocks of the markdown files given, a
# command continued over lines with a trailing backslash joined into one line.
commands_of() {
  awk '/^```sh$/ { inside = 1; next }
       /^```/ { inside = 0; next }
       inside { line = pending $0; pending = ""
                if (line ~ /\\$/) { pending = substr(line, 1, length(line) - 1); next }
                if (line ~ /^vdec (run|plot) /) print line }' "$@"
}

for readme in examples/*/README.md; do
  name=$(basename "$(dirname "$readme")")
  documents=("$readme")
  [ "$name" = tutorial ] && documents+=(docs/user-manual/tutorial.md)
  mapfile -t commands < <(commands_of "${documents[@]}")
  [ ${#commands[@]} -gt 0 ] || continue
  work=$scratch/$name
  mkdir -p "$work"
  ln -s "$root/examples" "$work/examples"
  echo "== $name"
  for command in "${commands[@]}"; do
    echo "   $command"
    # The README's own words, with `vdec` the build's; eval keeps their quoting and drops their comments.
    (cd "$work" && eval "\"\$vdec\" ${command#vdec }") >/dev/null
  done
  mkdir -p "examples/$name/pictures"
  rm -f "examples/$name/pictures/"*.png
  shopt -s nullglob
  pictures=("$work"/*.png)
  shopt -u nullglob
  [ ${#pictures[@]} -eq 0 ] || mv "${pictures[@]}" "examples/$name/pictures/"
done

# A 256-colour palette keeps the meshes' pictures at a third of their size, with no visible change:
# Pillow, which matplotlib depends on, does it.
/usr/bin/python3 - examples/*/pictures/*.png <<'PYTHON'
import sys
from PIL import Image
for path in sys.argv[1:]:
    Image.open(path).convert("RGB").quantize(256, dither=Image.Dither.NONE).save(path, optimize=True)
PYTHON
