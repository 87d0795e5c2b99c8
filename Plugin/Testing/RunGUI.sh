#!/usr/bin/env bash
# Runs TestPointSurfacesGUI.py inside ParaView's GUI client (`paraview
# --script ... --exit`, under the X server this test is given), then
# prints its verdicts. Fails when the client crashed or hung before its
# last verdict, or when any check failed.
#
# Usage: RunGUI.sh PARAVIEW SCRIPT PLUGIN DATA_DIR IO_DATA_DIR OUT_DIR
set -uo pipefail
paraview=$1 script=$2
export POINTSURFACES_PLUGIN=$3 POINTSURFACES_DATA=$4 POINTSURFACES_IO_DATA=$5 POINTSURFACES_OUT=$6
mkdir -p "$POINTSURFACES_OUT"
result="$POINTSURFACES_OUT/gui-result.txt"
rm -f "$result"
status=0
timeout 300 "$paraview" --dr --script="$script" --exit || status=$?
if [ -f "$result" ]; then
  cat "$result"
else
  echo "FAILED: the GUI test wrote no result (paraview exit status $status)"
  exit 1
fi
if ! grep -q "^TestPointSurfacesGUI: 0 failure" "$result"; then
  echo "FAILED: the GUI client stopped before its last check, or a check failed (exit status $status)"
  exit 1
fi
echo "paraview exit status $status"
