# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Run the Python examples headless on small inputs: each must exit 0, print
its report and write a non-empty PNG that is not a blank background (the
sweep's PNG is its plot)."""
import os
import subprocess
import sys

from pstesting import data_file, fail
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, "..", "..", "Examples", "Python")
TEMP = os.environ.get("POINTSURFACES_TEMP_DIR", ".")
os.makedirs(TEMP, exist_ok=True)

def temp(name):
    path = os.path.join(TEMP, name)
    if os.path.exists(path):
        os.remove(path)
    return path


frames = os.path.join(TEMP, "animation")
# (script, arguments, text the report must hold, the image it must write)
runs = [
    ("render_scan.py", [data_file("bunny.vtp"), temp("render_scan.png"), "--size", "160"],
     "splats:", os.path.join(TEMP, "render_scan.png")),
    ("molecule_metaballs.py", [data_file("hemoglobin_chainA.pdb"), temp("molecule_metaballs.png"),
                               "--size", "160", "--shadows"],
     "atoms:        1079", os.path.join(TEMP, "molecule_metaballs.png")),
    ("particle_animation.py", ["--out", frames, "--frames", "3", "--particles", "2000",
                               "--size", "160", "--vdb"],
     "uploads:      3", os.path.join(frames, "frame_0002.png")),
    ("speed_accuracy_sweep.py", [data_file("hemoglobin_chainA.pdb"), temp("sweep.png"),
                                 "--size", "96", "--steps", "0.4,0.1", "--bisections", "0,5"],
     "sweep:        4 settings", os.path.join(TEMP, "sweep.png")),
]
for script, arguments, expected, out in runs:
    if os.path.exists(out):
        os.remove(out)
    args = [sys.executable, os.path.join(EXAMPLES, script)] + arguments
    result = subprocess.run(args, capture_output=True, text=True, timeout=600)
    if result.returncode != 0 or expected not in result.stdout:
        fail("%s failed (%d):\n%s\n%s" % (script, result.returncode, result.stdout, result.stderr))
    reader = vtkPNGReader()
    reader.SetFileName(out)
    reader.Update()
    pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())
    if pixels.size == 0 or (pixels.max(axis=0) - pixels.min(axis=0)).max() < 50:
        fail("%s wrote a blank image" % script)
    print("%s: %s" % (script, result.stdout.splitlines()[0]))
# The animation's level sets are OpenVDB files that its reader side accepts as VDB.
import pointsurfaces  # noqa: E402
if not pointsurfaces.vtkOpenVDBPointsReader.CanReadFile(os.path.join(frames, "frame_0002.vdb")):
    fail("particle_animation.py --vdb wrote no OpenVDB file")
print("TestPythonExamples: passed")
