#!/usr/bin/env bash
# Install every Debian package that the `vtk` preset, its tests, benchmarks and
# examples need, by this Debian release's names: 12 bookworm (VTK 9.1,
# ParaView 5.11), 13 trixie (VTK 9.3, ParaView 5.13) or forky (VTK 9.6,
# ParaView 6.1). Idempotent: one `apt-get update`, and a no-op when all is
# present. Runs as root, or through sudo otherwise.
#
# Usage: scripts/install-deps.sh [--dry-run] [--demo] [--paraview] [--release=NAME]
#   --dry-run   only list the packages that are missing
#   --demo      only what the libraries, the Python package and a headless
#               render need (scripts/demo.sh; scripts/test.sh adds the rest)
#   --paraview  also what the `paraview` preset needs: paraview, paraview-dev
#               and an XSLT tool for the plugin's help pages (Qt's
#               xmlpatterns on bookworm, xsltproc on trixie and forky, and
#               on forky Qt 6 Help, which ParaView 6.1's plugin macros ask for).
#               Where python3-paraview conflicts with python3-vtk9 (bookworm
#               and trixie: ParaView bundles its own VTK there) it is
#               downloaded and unpacked into build/paraview-sdk/root, never
#               installed; on forky ParaView uses Debian's VTK and
#               python3-paraview is installed as usual.
#   --release=NAME  the package names of this release (default: this machine's,
#               from /etc/os-release; an unknown one gets forky's)
set -euo pipefail

release=""
for arg in "$@"; do
  case "$arg" in
    --release=*) release=${arg#--release=} ;;
  esac
done
if [ -z "$release" ]; then
  release=$(. /etc/os-release 2>/dev/null && echo "${VERSION_CODENAME:-}")
fi
case "$release" in
  bookworm|trixie|forky) ;;
  *)
    echo "install-deps.sh: warning: Debian release '${release:-unknown}' is not bookworm, trixie or forky: trying forky's package names" >&2
    release=forky ;;
esac

demo=0
for arg in "$@"; do
  [ "$arg" = --demo ] && demo=1
done
# What the libraries, the Python package and a headless render need
# (scripts/demo.sh installs only these).
packages=(
  build-essential cmake ninja-build pkg-config
  # VTK and its Python bindings (bookworm: 9.1, trixie: 9.3, forky: 9.6)
  libvtk9-dev python3-vtk9 vtk9 python3-numpy
  # numerics and readers (nanoflann: kd-trees; PCL: PCD files; Ceres: robust fits;
  # OpenMesh: OFF, OBJ, OM and STL meshes)
  libeigen3-dev libnanoflann-dev libpcl-dev libceres-dev libopenmesh-dev
  # HDF5's C API (Gadget and SWIFT snapshots, through VTK's VTK::hdf5)
  libhdf5-dev
  # headless GL: Mesa llvmpipe through EGL (surfaceless)
  libegl-dev libegl-mesa0 libgl1-mesa-dri libgl-dev
)
if [ "$demo" = 0 ]; then
  packages+=(
    # OpenVDB: point grids and level sets (PointSurfaces::IOOpenVDB and
    # FiltersOpenVDB; the demo builds without them)
    libopenvdb-dev
    # the format check, and the Debian roots of scripts/test-release.sh
    git clang-format debootstrap
    # benchmark peers (CGAL's WLOP; PCL's MLS comes with libpcl-dev)
    libcgal-dev
    # the X leg of the render tests
    xvfb xauth
    # benchmark plots, image metrics (SSIM) and k-nearest neighbours (SPH lengths)
    python3-matplotlib python3-skimage python3-scipy
    # the fuzz preset: clang with libFuzzer and the sanitizer runtimes
    clang
    # mpiexec: the ghost-ball test runs over three MPI ranks
    openmpi-bin
    # the GPU bundle (scripts/gpu-bundle.sh): xz, objdump and strip, unshare
    xz-utils binutils util-linux
    # the API reference (the `docs` target and its warning test)
    doxygen
  )
  case "$release" in
    bookworm) packages+=(libclang-rt-14-dev) ;;
    *) packages+=(libclang-rt-dev) ;;
  esac
  # LAS and LAZ lidar files (PointSurfaces::IOLAS): LASzip, which Debian 12
  # does not package (nor PDAL or libLAS)
  case "$release" in
    bookworm) ;;
    *) packages+=(liblaszip-dev) ;;
  esac
fi
dryrun=0
paraview=0
for arg in "$@"; do
  case "$arg" in
    --dry-run) dryrun=1 ;;
    --paraview) paraview=1 ;;
    --demo|--release=*) ;;
    -h|--help) sed -n '2,22p' "$0"; exit 0 ;;
    *) echo "install-deps.sh: unknown argument '$arg'" >&2; exit 2 ;;
  esac
done
# Where python3-paraview conflicts with python3-vtk9, it is unpacked, not installed.
pv_unpack=0
if [ "$paraview" = 1 ]; then
  packages+=(paraview paraview-dev)
  case "$release" in
    bookworm) packages+=(qtxmlpatterns5-dev-tools); pv_unpack=1 ;;
    trixie) packages+=(xsltproc); pv_unpack=1 ;;
    *) packages+=(python3-paraview xsltproc qt6-tools-dev qt6-tools-dev-tools) ;;
  esac
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
if [ "$pv_unpack" = 1 ] && [ ! -f "$sdk/root/usr/lib/python3/dist-packages/paraview/simple.py" ]; then
  need_sdk=1
fi
if [ "${#missing[@]}" -eq 0 ] && [ "$need_sdk" = 0 ]; then
  echo "install-deps.sh: all ${#packages[@]} packages of $release present"
  exit 0
fi
[ "${#missing[@]}" -gt 0 ] && echo "install-deps.sh: installing ($release) ${missing[*]}"
[ "$need_sdk" = 1 ] && echo "install-deps.sh: unpacking python3-paraview into $sdk/root"
[ "$dryrun" = 1 ] && exit 0

SUDO=""
if [ "$(id -u)" != 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps.sh: not root and no sudo" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
fail() { echo "install-deps.sh: Debian $release: step '$1' failed (packages unreachable or not in this release?)" >&2; exit 1; }
updated=0
if [ "${#missing[@]}" -gt 0 ]; then
  $SUDO apt-get update -qq || fail "apt-get update"
  updated=1
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" || fail "apt-get install"
fi
if [ "$need_sdk" = 1 ]; then
  # Download only (never install) the package whose files ParaView's CMake
  # package and pvbatch need, and unpack it where the preset looks.
  [ "$updated" = 1 ] || $SUDO apt-get update -qq || fail "apt-get update"
  rm -rf "$sdk" && mkdir -p "$sdk"
  (cd "$sdk" && $SUDO apt-get download -qq python3-paraview) || fail "apt-get download python3-paraview"
  dpkg-deb -x "$sdk"/python3-paraview_*.deb "$sdk/root"
fi
if [ "$release" != forky ] && dpkg-query -W -f='${Status}' python3-paraview 2>/dev/null | grep -q "install ok installed"; then
  echo "install-deps.sh: warning: python3-paraview is installed and conflicts with python3-vtk9" >&2
fi
