#!/usr/bin/env bash
# The whole test suite from nothing: install the Debian packages, configure,
# build and run ctest (which also installs into a scratch prefix, builds the
# C++ example against the installed package and imports the installed Python
# package).
#
# Usage: scripts/test.sh [PRESET] [-- extra ctest arguments]
#   PRESET: vtk (default), debug, asan (the unit tests only) or fuzz (the
#           readers' libFuzzer smoke runs)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
preset=vtk
if [ $# -gt 0 ] && [ "$1" != "--" ]; then
  preset=$1
  shift
fi
[ "${1:-}" = "--" ] && shift

"$root/scripts/install-deps.sh"
cmake --preset "$preset"
cmake --build --preset "$preset"
ctest --preset "$preset" "$@"
