# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Run the Python examples headless on small inputs: each must exit 0, print
its report and write a non-empty PNG that is not a blank background."""
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

runs = [
    ("render_scan.py", [data_file("bunny.vtp")], "splats:"),
    ("molecule_metaballs.py", [data_file("hemoglobin_chainA.pdb"), "--shadows"], "atoms:        1079"),
]
for script, inputs, expected in runs:
    out = os.path.join(TEMP, script.replace(".py", ".png"))
    if os.path.exists(out):
        os.remove(out)
    args = [sys.executable, os.path.join(EXAMPLES, script)] + inputs[:1] + [out, "--size", "160"]
    args += inputs[1:]
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
print("TestPythonExamples: passed")
