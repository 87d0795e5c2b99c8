#!/usr/bin/env bash
# The main job: on a fresh Debian 12, 13 or forky machine, install what the
# libraries need (install-deps.sh --demo), build the libraries and the Python
# package (not the tests: scripts/test.sh builds those), then render a real
# scan headless to a PNG and print what it cost.
#
# Usage: scripts/demo.sh [input.{ply,vtp,pcd,xyz,obj,off,om,stl}] [output.png]
#   default input: Testing/Data/bunny.vtp (the Stanford Bunny), output: bunny.png
#   Examples/Python/render_scan.py reads the scan (pointsurfaces.scanio); a file
#   it cannot read stops it with one line naming the file and exit status 1.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
input="${1:-$root/Testing/Data/bunny.vtp}"
[ -f "$input" ] || { echo "demo.sh: no such file: $input" >&2; exit 2; }
input=$(realpath "$input")
output=$(realpath -m "${2:-bunny.png}")

"$root/scripts/install-deps.sh" --demo >&2
if [ ! -f "$root/build/vtk/build.ninja" ]; then
  (cd "$root" && cmake --preset vtk) >&2
fi
# The libraries and the Python package only: scripts/test.sh builds the tests,
# benchmarks and examples in the same tree.
cmake --build "$root/build/vtk" --target pointsurfaces-libraries >&2
export PYTHONPATH="$root/build/vtk/$(cd "$root/build/vtk" && sed -n 's/^POINTSURFACES_PYTHON_SITE_PACKAGES:STRING=//p' CMakeCache.txt)${PYTHONPATH:+:$PYTHONPATH}"
exec /usr/bin/python3 "$root/Examples/Python/render_scan.py" "$input" "$output"
