#!/usr/bin/env bash
# Regenerate regression baselines from the images that tests wrote.
#
# Usage: scripts/update-baseline.sh [--build DIR] [--run] [--alternate] TestName...
#   --build DIR   build tree (default: build/vtk)
#   --run         run the EGL variant of each test first (ctest -R egl-TestName)
#   --alternate   add the image as the next alternate (TestName_1.png, _2, ...)
#                 instead of replacing TestName.png
# The image <build>/Testing/Temporary/TestName.png is copied to
# <Module>/Testing/Data/Baseline/, next to the test's source. Look at the
# image before you commit it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build/vtk"
run=0
alternate=0
tests=()
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build=$(cd "$2" && pwd); shift 2 ;;
    --run) run=1; shift ;;
    --alternate) alternate=1; shift ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) tests+=("$1"); shift ;;
  esac
done
[ "${#tests[@]}" -gt 0 ] || { echo "update-baseline.sh: name at least one test" >&2; exit 2; }

for t in "${tests[@]}"; do
  src=$(cd "$root" && git ls-files -co --exclude-standard "*Testing/Cxx/$t.cxx" "*Testing/Python/$t.py" | head -n 1)
  if [ -z "$src" ]; then
    echo "update-baseline.sh: no source Testing/Cxx/$t.cxx or Testing/Python/$t.py" >&2
    exit 1
  fi
  image="$build/Testing/Temporary/$t.png"
  if [ "$run" = 1 ]; then
    # VTK writes the test's image only when the comparison fails: compare it
    # against an empty baseline, so that the image is always the new one.
    baseline=$(cd "$root" && git ls-files -co --exclude-standard "*Testing/Data/Baseline/$t.png" | head -n 1)
    rm -f "$image"
    [ -n "$baseline" ] && mv "$root/$baseline" "$root/$baseline.saved" && : >"$root/$baseline"
    (cd "$build" && ctest -R "(egl-|Python-)$t\$" >/dev/null) || true
    [ -n "$baseline" ] && mv "$root/$baseline.saved" "$root/$baseline"
  fi
  [ -f "$image" ] || { echo "update-baseline.sh: $image not found: run the test (or use --run)" >&2; exit 1; }
  dir="$root/$(dirname "$(dirname "$src")")/Data/Baseline"
  mkdir -p "$dir"
  dest="$dir/$t.png"
  if [ "$alternate" = 1 ] && [ -f "$dest" ]; then
    n=1
    while [ -f "$dir/${t}_$n.png" ]; do n=$((n + 1)); done
    dest="$dir/${t}_$n.png"
  fi
  cp "$image" "$dest"
  echo "update-baseline.sh: $image -> ${dest#"$root"/}"
done
