#!/usr/bin/env bash
# The whole test suite from nothing, on Debian 12, 13 or forky: install that
# release's packages (scripts/install-deps.sh), configure, build and run
# ctest (which also installs into a scratch prefix, builds the C++ example
# against the installed package and imports the installed Python package).
#
# Usage: scripts/test.sh [PRESET] [-- extra ctest arguments]
#   PRESET: vtk (default), debug, asan (the unit tests only), fuzz (the
#           readers' libFuzzer smoke runs) or paraview (the plugin against
#           Debian's ParaView, in pvbatch, serial and over two MPI ranks,
#           and a pvpython client of two pvserver ranks)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
preset=vtk
if [ $# -gt 0 ] && [ "$1" != "--" ]; then
  preset=$1
  shift
fi
[ "${1:-}" = "--" ] && shift

if [ "$preset" = paraview ]; then
  "$root/scripts/install-deps.sh" --paraview
else
  "$root/scripts/install-deps.sh"
fi
cmake --preset "$preset"
cmake --build --preset "$preset"
ctest --preset "$preset" "$@"
