#!/usr/bin/env bash
# Install every Debian 12 package that the `vtk` preset, its tests, benchmarks and
# examples need. Idempotent: one `apt-get update`, and a no-op when all is present.
# Runs as root, or through sudo otherwise. Never installs python3-paraview, which
# conflicts with python3-vtk9 (see the README's ParaView section).
#
# Usage: scripts/install-deps.sh [--dry-run] [--paraview]
#   --dry-run   only list the packages that are missing
#   --paraview  also what the `paraview` preset needs: paraview, paraview-dev
#               and Qt's xmlpatterns (the plugin's help pages); and
#               python3-paraview, downloaded and unpacked into
#               build/paraview-sdk/root (it can never be installed beside
#               python3-vtk9)
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git clang-format
  # VTK 9.1 (X11 build, system GLEW) and its Python bindings
  libvtk9-dev python3-vtk9 vtk9 python3-numpy
  # numerics and readers (PCL: kd-trees, PCD files; Ceres: robust fits;
  # OpenMesh: OFF, OBJ, OM and STL meshes; OpenVDB: point grids and level sets)
  libeigen3-dev libpcl-dev libceres-dev libopenmesh-dev libopenvdb-dev
  # HDF5's C API (Gadget and SWIFT snapshots, through VTK's VTK::hdf5)
  libhdf5-dev
  # benchmark peers (CGAL's WLOP; PCL's MLS comes with libpcl-dev)
  libcgal-dev
  # headless GL: Mesa llvmpipe through EGL (surfaceless) or GLX under Xvfb
  libegl-dev libegl-mesa0 libgl1-mesa-dri libgl-dev xvfb xauth
  # benchmark plots, image metrics (SSIM) and k-nearest neighbours (SPH lengths)
  python3-matplotlib python3-skimage python3-scipy
  # the fuzz preset: clang with libFuzzer and the sanitizer runtimes
  clang libclang-rt-14-dev
  # mpiexec: the ghost-ball test runs over three MPI ranks
  openmpi-bin
  # the GPU bundle (scripts/gpu-bundle.sh): xz, objdump and strip, unshare
  xz-utils binutils util-linux
)
dryrun=0
paraview=0
for arg in "$@"; do
  case "$arg" in
    --dry-run) dryrun=1 ;;
    --paraview) paraview=1 ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) echo "install-deps.sh: unknown argument '$arg'" >&2; exit 2 ;;
  esac
done
if [ "$paraview" = 1 ]; then
  packages+=(paraview paraview-dev qtxmlpatterns5-dev-tools)
fi
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

root=$(cd "$(dirname "$0")/.." && pwd)
sdk="$root/build/paraview-sdk"
need_sdk=0
if [ "$paraview" = 1 ] && [ ! -f "$sdk/root/usr/lib/python3/dist-packages/paraview/simple.py" ]; then
  need_sdk=1
fi
if [ "${#missing[@]}" -eq 0 ] && [ "$need_sdk" = 0 ]; then
  echo "install-deps.sh: all ${#packages[@]} packages present"
  exit 0
fi
[ "${#missing[@]}" -gt 0 ] && echo "install-deps.sh: installing ${missing[*]}"
[ "$need_sdk" = 1 ] && echo "install-deps.sh: unpacking python3-paraview into $sdk/root"
[ "$dryrun" = 1 ] && exit 0

SUDO=""
if [ "$(id -u)" != 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps.sh: not root and no sudo" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
updated=0
if [ "${#missing[@]}" -gt 0 ]; then
  $SUDO apt-get update -qq
  updated=1
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
if [ "$need_sdk" = 1 ]; then
  # Download only (never install) the package whose files ParaView's CMake
  # package and pvbatch need, and unpack it where the preset looks.
  [ "$updated" = 1 ] || $SUDO apt-get update -qq
  rm -rf "$sdk" && mkdir -p "$sdk"
  (cd "$sdk" && $SUDO apt-get download -qq python3-paraview)
  dpkg-deb -x "$sdk"/python3-paraview_*.deb "$sdk/root"
fi
if dpkg-query -W -f='${Status}' python3-paraview 2>/dev/null | grep -q "install ok installed"; then
  echo "install-deps.sh: warning: python3-paraview is installed and conflicts with python3-vtk9" >&2
fi
