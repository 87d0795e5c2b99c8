# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""The Metaballs representation rendered by a client from two pvserver ranks.

    pvpython TestPointSurfacesClient.py PLUGIN DATA_DIR BASELINE_DIR OUT_DIR PORT

Run by RunClientServer.sh beside `mpiexec -n 2 pvserver`. The protein chain
of TestPointSurfacesPlugin.py is split between the server ranks
(RedistributeDataSet), each rank adds the other's balls that reach its own
(vtkMetaballGhostBalls), and the view renders on the client: the geometry of
both ranks, ghosts included, is delivered to one process. The client must
leave the ghosts out, or they count twice beside their owners (1.9 % of the
pixels differed when it did not). The picture is compared with the serial
baseline: at most 0.1 % of the pixels may differ by more than 40/255.
"""
import os
import sys

# The unpacked pvpython finds its prefix at "/" and puts Debian's VTK 9.1
# modules (//lib/python3/dist-packages) before ParaView's: drop that entry.
sys.path = [p for p in sys.path if p != "//lib/python3/dist-packages"]

from paraview.simple import *  # noqa: E402,F401,F403
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402

plugin, data, baselines, out, port = sys.argv[1:6]
os.makedirs(out, exist_ok=True)
failures = []


def check(ok, what):
    print(("ok:     " if ok else "FAILED: ") + what, flush=True)
    if not ok:
        failures.append(what)


def pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    return image.GetDimensions(), vtk_to_numpy(image.GetPointData().GetScalars()).astype(int)[:, :3]


Connect("localhost", int(port))
LoadPlugin(plugin, remote=True, ns=globals())
LoadPlugin(plugin, remote=False, ns=globals())
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
check(ranks == 2, "two server ranks (%d)" % ranks)

view = CreateRenderView()
view.ViewSize = [320, 320]
view.OrientationAxesVisibility = 0
view.Background = [0.32, 0.34, 0.43]
view.UseColorPaletteForBackground = 0
view.UseFXAA = 0
view.RemoteRenderThreshold = 1e9  # geometry to the client, rendered there

atoms = PDBReader(FileName=os.path.join(data, "hemoglobin_chainA.pdb"))
balls = Show(RedistributeDataSet(Input=atoms), view)
balls.SetRepresentationType("Metaballs")
balls.MetaballRadiusArray = "radius"
balls.MetaballRadiusScale = 2.0
ColorBy(balls, ("POINTS", "rgb_colors"))
balls.MapScalars = 0
b = atoms.GetDataInformation().GetBounds()
centre = [0.5 * (b[2 * k] + b[2 * k + 1]) for k in range(3)]
plane = Plane(Origin=[b[0] - 5, b[2] - 5, centre[2]], Point1=[b[1] + 5, b[2] - 5, centre[2]],
              Point2=[b[0] - 5, b[3] + 5, centre[2]])
plane_display = Show(plane, view)
plane_display.DiffuseColor = [0.8, 0.8, 0.8]
Render(view)
view.CameraFocalPoint = centre
view.CameraPosition = [centre[0] + 50, centre[1] - 75, centre[2] + 75]
view.CameraViewUp = [0, 0, 1]
Render(view)

path = os.path.join(out, "PluginMetaballs.client.png")
SaveScreenshot(path, view, ImageResolution=[320, 320])
(dims, a), (dims_b, b_) = pixels(path), pixels(os.path.join(baselines, "PluginMetaballs.png"))
if dims != dims_b:
    check(False, "image size %s, baseline %s" % (dims, dims_b))
else:
    differ = (abs(a - b_).max(axis=1) > 40).mean()
    check(differ <= 0.001, "client render of two ranks' metaballs: %.3f %% of the pixels differ "
          "from the serial baseline (at most 0.1 %%)" % (100 * differ))
print("TestPointSurfacesClient: %d failure(s)" % len(failures), flush=True)
Delete(view)
del view
Disconnect()
