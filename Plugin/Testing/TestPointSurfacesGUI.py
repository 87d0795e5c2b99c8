# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""The plugin in ParaView's GUI client, as a user clicks through it.

Run by RunGUI.sh as `paraview --dr --script=THIS --exit` under Xvfb;
the paths come in the environment (POINTSURFACES_PLUGIN, POINTSURFACES_DATA,
POINTSURFACES_IO_DATA, POINTSURFACES_OUT). In the GUI's own Python:

- loads the plugin;
- opens a LAMMPS dump named as LAMMPS names them (`dump.melt`) and a scan
  (the Bunny written as an .off point cloud, read by the plugin's OpenMesh
  reader) through OpenDataFile, that is through the reader factory that the
  File > Open dialog uses;
- shows the dump as Metaballs with the default radii and colours it by `id`;
  fits the scan to splats, shows them as Algebraic Splats and colours them
  by SplatRadius (this crashed the client before: ParaView turns
  InterpolateScalarsBeforeMapping on for every display);
- saves a screenshot of each view and checks it: enough surface pixels, and
  many colours on them (a white or single-coloured surface fails).

It writes its verdicts to OUT/gui-result.txt; RunGUI.sh prints that file,
and a crash leaves it without its last line.
"""
import os

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

plugin = os.environ["POINTSURFACES_PLUGIN"]
data = os.environ["POINTSURFACES_DATA"]
io_data = os.environ["POINTSURFACES_IO_DATA"]
out = os.environ["POINTSURFACES_OUT"]
os.makedirs(out, exist_ok=True)
result = open(os.path.join(out, "gui-result.txt"), "w")
failures = []


def check(ok, what):
    result.write(("ok:     " if ok else "FAILED: ") + what + "\n")
    result.flush()
    if not ok:
        failures.append(what)


def inspect(path, background, name):
    """The share of surface pixels and the number of distinct colours among them."""
    import numpy as np

    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    rgb = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)
    surface = np.abs(rgb - np.array(background)).max(axis=1) > 12
    share = surface.mean()
    # Colours quantised to 5 bits per channel, counted over the surface.
    q = rgb[surface] // 8
    colours = len(np.unique(q[:, 0] * 1024 + q[:, 1] * 32 + q[:, 2])) if surface.any() else 0
    # Chromatic pixels: a channel spread of more than 40 (white or grey is not).
    chromatic = (rgb[surface].max(axis=1) - rgb[surface].min(axis=1) > 40).mean() \
        if surface.any() else 0.0
    check(share > 0.02, "%s: %.1f %% of the pixels show the surface" % (name, 100 * share))
    check(colours >= 40 and chromatic > 0.5,
          "%s: %d colours, %.0f %% of the surface chromatic (a colour map, not white)"
          % (name, colours, 100 * chromatic))


LoadPlugin(plugin, remote=False, ns=globals())
check(True, "the plugin loaded")

# A LAMMPS dump as LAMMPS names it.
dump_path = os.path.join(out, "dump.melt")
with open(os.path.join(io_data, "lammps", "melt.lammpstrj")) as src, open(dump_path, "w") as dst:
    dst.write(src.read())
dump = OpenDataFile(dump_path)
check(dump is not None and dump.GetXMLName() == "LAMMPSDumpReader",
      "dump.melt opens with the LAMMPS dump reader (%s)" % (dump.GetXMLName() if dump else None))

# The Bunny as an .off point cloud.
reader = vtkXMLPolyDataReader()
reader.SetFileName(os.path.join(data, "bunny.vtp"))
reader.Update()
points = vtk_to_numpy(reader.GetOutput().GetPoints().GetData())
off_path = os.path.join(out, "bunny-cloud.off")
with open(off_path, "w") as f:
    f.write("OFF\n%d 0 0\n" % len(points))
    for p in points:
        f.write("%.7g %.7g %.7g\n" % tuple(p))
scan = OpenDataFile(off_path)
check(scan is not None and scan.GetXMLName() == "OpenMeshReader",
      "bunny-cloud.off opens with the OpenMesh reader (%s)" % (scan.GetXMLName() if scan else None))

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [400, 400]
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = [1.0, 1.0, 1.0]



def show_coloured(source, representation, array, name):
    """`source` as `representation` coloured by `array`, screenshot checked."""
    display = Show(source, view)
    display.SetRepresentationType(representation)
    ColorBy(display, ("POINTS", array))
    display.RescaleTransferFunctionToDataRange(True, False)
    # A map without a grey middle: under the default Cool to Warm, values
    # near the middle of the range (most splat radii) are light grey, and
    # the check below could not tell them from white. ParaView 6 renamed
    # the preset (and raises where 5.11 returns False).
    lut = GetColorTransferFunction(array)
    applied = False
    for preset in ("Viridis (matplotlib)", "Viridis"):
        try:
            applied = lut.ApplyPreset(preset, True) is not False
        except RuntimeError:
            applied = False
        if applied:
            break
    check(applied, "%s: the Viridis colour map applied" % array)
    view.ResetCamera()
    Render(view)
    path = os.path.join(out, name + ".png")
    SaveScreenshot(path, view, ImageResolution=[400, 400])
    inspect(path, [255, 255, 255], "%s coloured by %s" % (representation, array))
    Hide(source, view)


if dump is not None:
    show_coloured(dump, "Metaballs", "id", "gui-metaballs")
if scan is not None:
    show_coloured(AlgebraicSplatFitter(Input=scan), "Algebraic Splats", "SplatRadius", "gui-splats")

result.write("TestPointSurfacesGUI: %d failure(s)\n" % len(failures))
result.close()
