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

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pointsurfaces_plugin_test import SIZE, differing_pixels, new_view, show_protein  # noqa: E402

plugin, data, baselines, out, port = sys.argv[1:6]
os.makedirs(out, exist_ok=True)
failures = []


def check(ok, what):
    print(("ok:     " if ok else "FAILED: ") + what, flush=True)
    if not ok:
        failures.append(what)


Connect("localhost", int(port))
LoadPlugin(plugin, remote=True, ns=globals())
LoadPlugin(plugin, remote=False, ns=globals())
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
check(ranks == 2, "two server ranks (%d)" % ranks)

view = new_view()
view.RemoteRenderThreshold = 1e9  # geometry to the client, rendered there
show_protein(view, data, split=True)

path = os.path.join(out, "PluginMetaballs.client.png")
SaveScreenshot(path, view, ImageResolution=SIZE)
differ, why = differing_pixels(path, os.path.join(baselines, "PluginMetaballs.png"))
check(why is None and differ <= 0.001,
      why or "client render of two ranks' metaballs: %.3f %% of the pixels differ from the "
      "serial baseline (at most 0.1 %%)" % (100 * differ))
print("TestPointSurfacesClient: %d failure(s)" % len(failures), flush=True)
Delete(view)
del view
Disconnect()
