#!/usr/bin/env bash
# The GPU bundle must run from itself alone: make it with
# scripts/gpu-bundle.sh, unpack it, and run its gpu-run.sh --smoke (one test of
# each kind, and the benchmarks at tiny sizes) with
# Mesa's EGL in a mount namespace where every system library of VTK, PCL,
# OpenVDB, OpenMesh, Ceres and TBB, and the build tree's own libraries, are
# hidden (empty files and an empty folder mounted over them). Any library
# the bundle lacks then fails to load, and the run fails.
#
# Usage: Testing/RunGPUBundle.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
root=$1
build=$2
work=$3
rm -rf "$work"
mkdir -p "$work"

# xz -1: a fifth of the default's time, a bundle 15 to 40 % larger, whose size
# gpu-bundle.sh reports but does not hold to the 60 MiB of a real bundle.
POINTSURFACES_BUNDLE_XZ_LEVEL=1 "$root/scripts/gpu-bundle.sh" "$work/out"
mkdir -p "$work/unpacked" "$work/emptydir"
tar -C "$work/unpacked" -xJf "$work/out/pointsurfaces-gpu.tar.xz"
touch "$work/empty"
find /usr/lib/x86_64-linux-gnu -maxdepth 1 -type f \( -name 'libvtk*' -o -name 'libpcl_*' \
  -o -name 'libopenvdb*' -o -name 'libOpenMesh*' -o -name 'libceres*' -o -name 'libtbb*' \) \
  > "$work/hidden.txt"
echo "RunGPUBundle: hiding $(wc -l < "$work/hidden.txt") system libraries and $build/lib"

namespace=(unshare -m --propagation private)
if [ "$(id -u)" != 0 ]; then
  namespace=(unshare -r -m --propagation private)
fi
"${namespace[@]}" bash -euo pipefail -c '
  work=$1
  build=$2
  while read -r f; do
    mount --bind "$work/empty" "$f"
  done < "$work/hidden.txt"
  mount --bind "$work/emptydir" "$build/lib"
  # Proof that the hiding works: the system VTK cannot be loaded any more.
  if python3 -c "import ctypes; ctypes.CDLL(\"libvtkCommonCore-9.1.so.1\")" 2> /dev/null; then
    echo "RunGPUBundle: the system VTK is still loadable" >&2
    exit 1
  fi
  "$work/unpacked/pointsurfaces-gpu/gpu-run.sh" --smoke "$work/results"
' hide "$work" "$build"

csv="$work/results/bench/render.csv"
for scene in splats- metaballs-; do
  if ! grep -q "^$scene" "$csv"; then
    echo "RunGPUBundle: no $scene rows in $csv" >&2
    exit 1
  fi
done
grep -q "ctest -L egl: 0," "$work/results/gpu-run.log"
# All four of gpu-run.sh's smoke tests ran (a renamed test would drop out).
if ! grep -q "0 tests failed out of 4\$" "$work/results/gpu-run.log"; then
  echo "RunGPUBundle: gpu-run.sh --smoke did not run its four EGL tests" >&2
  exit 1
fi
echo "RunGPUBundle: the bundle ran from itself alone ($(stat -c %s "$work/out/pointsurfaces-gpu.tar.xz") bytes)"
