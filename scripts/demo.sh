#!/usr/bin/env bash
# The main job: on a fresh Debian 12, 13 or forky machine, install what the
# libraries need (install-deps.sh --demo), build the libraries and the Python
# package (the `demo` preset, in build/demo: not the tests, which
# scripts/test.sh builds in build/vtk), then render a real scan headless to a
# PNG and print what it cost.
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
# The `demo` preset: the libraries and the Python package alone, in their own
# tree (build/demo), without the tests, benchmarks and examples that
# scripts/test.sh builds, and without the modules of optional libraries,
# except the one that reads this input.
reader=()
case "${input,,}" in
  *.pcd) reader=(-DPOINTSURFACES_USE_PCL_IO=ON) ;;
  *.obj | *.off | *.om | *.stl) reader=(-DPOINTSURFACES_USE_OPENMESH=ON) ;;
esac
if [ ! -f "$root/build/demo/build.ninja" ] || [ ${#reader[@]} -gt 0 ]; then
  (cd "$root" && cmake --preset demo "${reader[@]}") >&2
fi
cmake --build --preset demo >&2
export PYTHONPATH="$root/build/demo/$(cd "$root/build/demo" && sed -n 's/^POINTSURFACES_PYTHON_SITE_PACKAGES:STRING=//p' CMakeCache.txt)${PYTHONPATH:+:$PYTHONPATH}"
exec /usr/bin/python3 "$root/Examples/Python/render_scan.py" "$input" "$output"
