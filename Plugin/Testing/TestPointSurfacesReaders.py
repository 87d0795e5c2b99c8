# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Every reader of the plugin, from files named as their codes name them, shown
as Metaballs with the defaults (pvbatch).

    pvbatch TestPointSurfacesReaders.py PLUGIN DATA_DIR BASELINE_DIR OUT_DIR IO_DATA_DIR [--mpi]

- OpenDataFile (the reader factory behind File > Open) must pick the
  plugin's reader for `dump.meoh`, `dump.1000.melt`, `melt.lammpstrj`,
  `confout.gro`, `traj_comp.xtc`, `snapshot_000.hdf5`, `snap_000.0.hdf5`,
  `output_0000.hdf5`, `points.vdb` and `cloud.off` (copies of the test data
  under those names, and a lattice of points written here), and
  `sphere.psplat`, a splat file the Streaming Splat Fitter writes here,
  which shows as Streaming Splats (the file drawn as the view needs it,
  however little the reader loaded) matching the whole file drawn as
  Algebraic Splats, within a GPU budget, and asynchronously; and, polled
  as ParaView's GUI polls a live source, renders that never wait for pages
  and sharpen poll by poll without the reader reading again;
- a .vdb on which OpenVDB aborts reads as empty (in the reader's child
  process) and the session goes on;
- each reader's output, shown as Metaballs with no property touched (the
  radii come from the data: the readers' `radius` or `SmoothingLength`
  arrays, else a multiple of the mean nearest-neighbour spacing), is compared
  with a baseline picture, and must cover a sane share of the view: balls of
  one unit, whatever the data's scale, filled the view with one blob or
  vanished (a GROMACS box is 3 nm across, a Gadget subset 2e4 kpc).

With --mpi (pvbatch --symmetric under mpiexec -n 2) the particles are split
between the ranks first; the automatic radius is the same on every rank
(vtkMetaballGhostBalls reduces the spacing over the ranks), so the pictures
match the serial baselines.
"""
import os
import shutil
import sys

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pointsurfaces_plugin_test import Checks, SIZE, compare_baseline, new_view, pixels  # noqa: E402

plugin, data, baselines, out, io_data = sys.argv[1:6]
mpi = "--mpi" in sys.argv[6:]
RANK = servermanager.vtkProcessModule.GetProcessModule().GetPartitionId()
os.makedirs(out, exist_ok=True)
check = Checks(RANK)


LoadPlugin(plugin, ns=globals())

# The test data under the names the codes give their files.
named = os.path.join(out, "named")
os.makedirs(named, exist_ok=True)
COPIES = {
    "dump.meoh": os.path.join(io_data, "lammps", "melt.lammpstrj"),
    "dump.1000.melt": os.path.join(io_data, "lammps", "melt.lammpstrj"),
    "melt.lammpstrj": os.path.join(io_data, "lammps", "melt.lammpstrj"),
    "confout.gro": os.path.join(io_data, "gromacs", "water_traj.gro"),
    "traj_comp.xtc": os.path.join(io_data, "gromacs", "water_p3.xtc"),
    "snapshot_000.hdf5": os.path.join(io_data, "gadget", "lcdm_gas_z5_subset.hdf5"),
    "snap_000.0.hdf5": os.path.join(io_data, "gadget", "lcdm_gas_z5_subset.hdf5"),
    "output_0000.hdf5": os.path.join(io_data, "gadget", "lcdm_gas_z5_subset.hdf5"),
    "points.vdb": os.path.join(data, "..", "Fuzz", "Corpus", "OpenVDBPoints", "points-blosc.vdb"),
    # Found by fuzzing: Debian's OpenVDB aborts on it (an assertion).
    "damaged.vdb": os.path.join(io_data, "openvdb", "page-without-mapped-file.vdb"),
}
if RANK == 0:
    for name, source in COPIES.items():
        shutil.copyfile(source, os.path.join(named, name))
    # A point cloud without radii: a 6 x 6 x 3 lattice of spacing 0.02 with
    # every second point of its top layer missing, so the radius comes from
    # the spacing rule.
    with open(os.path.join(named, "cloud.off"), "w") as f:
        cloud = [(0.02 * i, 0.02 * j, 0.02 * k) for i in range(6) for j in range(6)
                 for k in range(3) if k < 2 or (i + j) % 2 == 0]
        f.write("OFF\n%d 0 0\n" % len(cloud))
        f.writelines("%g %g %g\n" % p for p in cloud)
if mpi:
    servermanager.vtkProcessModule.GetProcessModule().GetGlobalController().Barrier()

READERS = {
    "dump.meoh": "LAMMPSDumpReader",
    "dump.1000.melt": "LAMMPSDumpReader",
    "melt.lammpstrj": "LAMMPSDumpReader",
    "confout.gro": "GromacsGroReader",
    "traj_comp.xtc": "GromacsXtcReader",
    "snapshot_000.hdf5": "GadgetHDF5Reader",
    "snap_000.0.hdf5": "GadgetHDF5Reader",
    "output_0000.hdf5": "GadgetHDF5Reader",
    "points.vdb": "OpenVDBPointsReader",
    "cloud.off": "OpenMeshReader",
}
opened = {}
for name, expected in READERS.items():
    reader = OpenDataFile(os.path.join(named, name))
    got = reader.GetXMLName() if reader is not None else None
    check(got == expected, "%s opens with %s (%s)" % (name, expected, got))
    opened[name] = reader

view = new_view()


def show_defaults(name, label, setup=None):
    """`name`'s reader output as Metaballs with the defaults, against a baseline."""
    source = opened[name]
    if source is None:
        return
    if setup:
        setup(source)
    source.UpdatePipeline()
    bounds = source.GetDataInformation().GetBounds()
    shown = RedistributeDataSet(Input=source) if mpi else source
    display = Show(shown, view)
    display.SetRepresentationType("Metaballs")
    display.MetaballRayCaster = 2  # the native CPU caster: llvmpipe, as in CI
    display.ColorArrayName = ["POINTS", ""]
    display.AmbientColor = display.DiffuseColor = [0.9, 0.85, 0.75]
    Render(view)
    # One camera for serial and split runs: from the reader's whole bounds.
    centre = [0.5 * (bounds[2 * k] + bounds[2 * k + 1]) for k in range(3)]
    size = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4], 1e-30)
    view.CameraFocalPoint = centre
    # Far enough for balls of a few spacings beyond the points' bounds.
    view.CameraPosition = [centre[0] + 2.0 * size, centre[1] - 2.7 * size, centre[2] + 1.9 * size]
    view.CameraViewUp = [0, 0, 1]
    view.CameraViewAngle = 30
    Render(view)
    path = os.path.join(out, label + (".mpi" if mpi else "") + ".png")
    SaveScreenshot(path, view, ImageResolution=SIZE)
    Hide(shown, view)
    if RANK != 0:
        return
    dims, image = pixels(path)
    background = [round(255 * c) for c in view.Background]
    covered = (abs(image - background).max(axis=1) > 12).mean()
    check(0.01 < covered < 0.8,
          "%s as Metaballs with the defaults covers %.1f %% of the view" % (name, 100 * covered))
    compare_baseline(check, path, baselines, label, mpi, 0.002 if mpi else 0.001)


show_defaults("dump.meoh", "ReaderDefaultsLAMMPS")
show_defaults("confout.gro", "ReaderDefaultsGRO")


def structure(xtc):
    xtc.StructureFile = os.path.join(named, "confout.gro")


show_defaults("traj_comp.xtc", "ReaderDefaultsXTC", structure)
show_defaults("snapshot_000.hdf5", "ReaderDefaultsGadget")
show_defaults("points.vdb", "ReaderDefaultsOpenVDB")
show_defaults("cloud.off", "ReaderDefaultsOpenMesh")

# A .vdb on which OpenVDB aborts: the reader reads it in a child process, so
# the error is the reader's and the session goes on.
damaged = OpenDataFile(os.path.join(named, "damaged.vdb"))
damaged.UpdatePipeline()
check(damaged.GetDataInformation().GetNumberOfPoints() == 0,
      "a .vdb on which OpenVDB aborts reads as empty, and the session goes on")
check(damaged.ReadInChildProcess == 1, "ReadInChildProcess is on by default")
Delete(damaged)
opened["points.vdb"].UpdatePipeline()
check(opened["points.vdb"].GetDataInformation().GetNumberOfPoints() > 0,
      "a good .vdb reads after the damaged one")

import builtins  # noqa: E402  (paraview.simple brings numpy-style all, min and max)
import time  # noqa: E402
from vtkmodules.vtkCommonCore import vtkIdTypeArray, vtkIntArray  # noqa: E402
from vtkmodules.vtkParallelCore import vtkCommunicator  # noqa: E402

# The Streaming Splat Fitter writes a splat file, which File > Open opens
# with the Splat File Reader and shows as Streaming Splats: the file itself,
# drawn as the view needs it, whatever the reader loaded. Under MPI both
# ranks name the same file: rank 0 alone writes it (two ranks writing one
# file raced), each rank's output is its piece of the file read back (their
# sum is the file), and rank 0 draws it for both.
controller = servermanager.vtkProcessModule.GetProcessModule().GetGlobalController()
sphere = Sphere(ThetaResolution=160, PhiResolution=160)
streamed = StreamingSplatFitter(Input=sphere)
streamed.FileName = os.path.join(named, "sphere%s.psplat" % (".mpi" if mpi else ""))
streamed.NumberOfPieces = 3
streamed.ChunkPoints = 5000
streamed.PageSize = 256  # many pages, so that a budget can hold some of them
streamed.UpdatePipeline()
written = streamed.GetDataInformation().GetNumberOfPoints()  # this rank's piece
if mpi:
    piece, pieces = vtkIdTypeArray(), vtkIdTypeArray()
    piece.InsertNextValue(written)
    controller.AllReduce(piece, pieces, vtkCommunicator.SUM_OP)
    check(0 < written < pieces.GetValue(0), "rank %d reads back %d of the file's %d splats"
          % (RANK, written, pieces.GetValue(0)))
    written = pieces.GetValue(0)
check(written > 100, "the Streaming Splat Fitter writes a splat file (%d splats)" % written)
Delete(streamed)
if mpi:
    # The same sphere spread over the ranks: each rank sends rank 0 its own
    # points, and the fit is whole (before, only rank 0's half was fitted).
    spread = RedistributeDataSet(Input=sphere)
    gathered = StreamingSplatFitter(Input=spread)
    gathered.FileName = os.path.join(named, "sphere-spread.mpi.psplat")
    gathered.NumberOfPieces = 3
    gathered.ChunkPoints = 5000
    gathered.PageSize = 256
    gathered.UpdatePipeline()
    piece.SetValue(0, gathered.GetDataInformation().GetNumberOfPoints())
    controller.AllReduce(piece, pieces, vtkCommunicator.SUM_OP)
    check(abs(pieces.GetValue(0) - written) <= 0.02 * written,
          "the sphere spread over the ranks fits into %d splats (%d when every rank has it all)"
          % (pieces.GetValue(0), written))
    Delete(gathered)
    Delete(spread)
Delete(sphere)
splat_path = os.path.join(named, "sphere%s.psplat" % (".mpi" if mpi else ""))
splat_file = OpenDataFile(splat_path)
got = splat_file.GetXMLName() if splat_file is not None else None
check(got == "SplatFileReader", "sphere.psplat opens with SplatFileReader (%s)" % got)


def streaming_picture(display, label, near=1.0):
    """The whole sphere (or `near` times as far: part of it) as `display` draws it; rank 0's pixels."""
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraPosition = [1.8 * near, -2.4 * near, 1.6 * near]
    view.CameraViewUp = [0, 0, 1]
    view.CameraViewAngle = 30
    path = os.path.join(out, label + (".mpi" if mpi else "") + ".png")
    SaveScreenshot(path, view, ImageResolution=SIZE)
    if RANK != 0:
        return None
    return pixels(path)[1]


if splat_file is not None:
    splat_file.UpdatePipeline()
    if not mpi:
        check(splat_file.GetDataInformation().GetNumberOfPoints() == written,
              "the splat file reads back its %d splats" % written)
    whole_radius = tuple(splat_file.PointData["SplatRadius"].GetRange())
    # The whole file as Algebraic Splats of the reader's output: the reference.
    splat_file.MemoryBudget = 0
    whole = Show(splat_file, view)
    check(whole.Representation == "Streaming Splats",
          "a splat file shows as Streaming Splats by default (%s)" % whole.Representation)
    whole.SetRepresentationType("Algebraic Splats")
    Render(view)
    reference = streaming_picture(whole, "SplatFileWhole")
    Hide(splat_file, view)

    # The reader loads almost nothing; Streaming Splats still draw the file.
    splat_file.MemoryBudget = 0.01
    splat_file.UpdatePipeline()
    loaded = splat_file.GetDataInformation().GetNumberOfPoints()
    stream = Show(splat_file, view)  # the display of the reference: back to Streaming Splats
    stream.SetRepresentationType("Streaming Splats")  # asynchronous; in pvbatch each render waits
    Render(view)
    picture = streaming_picture(stream, "SplatFileStreamed")
    stream.UpdatePropertyInformation()
    resident = stream.GetPropertyValue("SplatStreamingResidentSplats")
    check(loaded < written // 10, "the reader's output within 0.01 MB: %d of %d splats" % (loaded, written))
    if RANK == 0:
        check(stream.GetPropertyValue("SplatStreamingFileSplats") == written and resident == written,
              "Streaming Splats draw the file's %d splats (%d in memory)" % (written, resident))
        background = [round(255 * c) for c in view.Background]
        covered = (abs(picture - background).max(axis=1) > 12).mean()
        same = (abs(picture - reference).max(axis=1) > 40).mean()
        check(covered > 0.1 and same < 0.001,
              "Streaming Splats cover %.1f %% of the view and match the whole file drawn as "
              "Algebraic Splats but for %.3f %% of the pixels" % (100 * covered, 100 * same))

    # Where ranks composite by depth, only rank 0 draws the file.
    if mpi:
        elsewhere, most = vtkIdTypeArray(), vtkIdTypeArray()
        elsewhere.InsertNextValue(0 if RANK == 0 else resident)
        controller.AllReduce(elsewhere, most, vtkCommunicator.MAX_OP)
        check(most.GetValue(0) == 0, "over two ranks, rank 1 holds %d splats of the file (rank 0 "
              "draws it)" % most.GetValue(0))

    # The colour map fits the whole file, not the pages read, on every
    # ParaView: 5.11 takes VTK's cached ranges, which the reader sets to the
    # file's; 5.13 and later compute ranges from the values, and the reader
    # also loads the few splats that hold each range's ends (LoadRangeEnds).
    # A coarse preview alone has no small splats: serially, with
    # LoadRangeEnds off, the pages read span less (the check means
    # something). A fetch under --symmetric is avoided, as for selections.
    ColorBy(stream, ("POINTS", "SplatRadius"))
    stream.RescaleTransferFunctionToDataRange(False, True)
    fitted = GetColorTransferFunction("SplatRadius").RGBPoints
    fitted = (fitted[0], fitted[-4])
    reported = tuple(splat_file.PointData["SplatRadius"].GetRange())
    version = (servermanager.vtkSMProxyManager.GetVersionMajor(),
               servermanager.vtkSMProxyManager.GetVersionMinor())

    def near(a, b):
        return builtins.all(abs(x - y) <= 1e-6 * abs(y) for x, y in zip(a, b))

    check(near(fitted, whole_radius) and near(reported, whole_radius),
          "ParaView %d.%d: with %d splats read, the colour map fits the file's SplatRadius range "
          "[%.4g, %.4g] (the reader reports [%.4g, %.4g])"
          % (*version, loaded, fitted[0], fitted[1], *reported))
    if not mpi:
        from vtkmodules.util.numpy_support import vtk_to_numpy

        def own_radius():
            output = servermanager.Fetch(splat_file)
            values = vtk_to_numpy(output.GetPointData().GetArray("SplatRadius"))
            return output.GetNumberOfPoints(), values.min(), values.max()

        count, low, high = own_radius()
        check(near((low, high), whole_radius),
              "the %d splats read hold the file's SplatRadius ends [%.4g, %.4g]" % (count, low, high))
        splat_file.LoadRangeEnds = 0
        pages, low, high = own_radius()
        splat_file.LoadRangeEnds = 1
        splat_file.UpdatePipeline()
        check(low > whole_radius[0] and 0 < count - pages <= 64,
              "without the range ends the %d splats read span [%.4g, %.4g], and the ends add %d "
              "splats (the check means something)" % (pages, low, high, count - pages))
    ColorBy(stream, None)

    # A filter that passes the field data on but moves the splats (a
    # Transform keeps their count) or adds an array (a Calculator keeps the
    # points, and the file has no such array): its output is drawn as data.
    Hide(splat_file, view)
    moved = Transform(Input=splat_file)
    moved.Transform.Translate = [0.5, 0.0, 0.0]
    added = Calculator(Input=splat_file, ResultArrayName="height", Function="coordsZ")
    for label, filtered in (("a Transform", moved), ("a Calculator", added)):
        display = Show(filtered, view)
        display.SetRepresentationType("Streaming Splats")
        Render(view)
        display.UpdatePropertyInformation()
        drawn = display.GetPropertyValue("SplatStreamingFileSplats")
        check(drawn == 0, "the output of %s is drawn as data, not the file (%d of the file's "
              "splats)" % (label, drawn))
        Hide(filtered, view)
    Delete(added)
    Delete(moved)
    stream = Show(splat_file, view)

    # Opened afresh and seen close up, only the pages in view are read.
    Hide(splat_file, view)
    near_file = OpenDataFile(splat_path)
    near_display = Show(near_file, view)
    streaming_picture(near_display, "SplatFileStreamedNear", near=0.3)
    near_display.UpdatePropertyInformation()
    near = near_display.GetPropertyValue("SplatStreamingWantedSplats")
    near_resident = near_display.GetPropertyValue("SplatStreamingResidentSplats")
    if RANK == 0:
        check(0 < near < written * 0.8 and near_resident == near,
              "close up, the view wants %d of the %d splats (the pages in view), %d read"
              % (near, written, near_resident))
    Hide(near_file, view)
    Delete(near_file)
    stream = Show(splat_file, view)

    # A budget for about a fifth of the file: nearest pages first, fewer drawn.
    stream.SplatStreamingBudget = 0.1
    Render(view)
    stream.UpdatePropertyInformation()
    part = stream.GetPropertyValue("SplatStreamingResidentSplats")
    if RANK == 0:
        check(0 < part < written // 2,
              "within 0.1 MB of GPU buffers: %d of the %d splats in memory" % (part, written))

    # Asynchronous: renders return at once and draw what has arrived; the
    # pages come within a few renders. Every rank must render as often
    # (under --symmetric a render is collective), and only rank 0 loads:
    # the ranks go on while any of them is loading.
    stream.SplatStreamingBudget = 512
    stream.SplatStreamingBatchWait = 0  # as the GUI: renders never wait
    view.CameraPosition = [0.54, -0.72, 0.48]
    renders, settled = 0, False
    for renders in range(1, 201):
        Render(view)
        stream.UpdatePropertyInformation()
        loading = vtkIntArray()
        loading.InsertNextValue(stream.GetPropertyValue("SplatStreamingLoading"))
        if mpi:
            anywhere = vtkIntArray()
            controller.AllReduce(loading, anywhere, vtkCommunicator.MAX_OP)
            loading = anywhere
        if not loading.GetValue(0):
            settled = True  # on every rank: rank 1, which leaves the file to rank 0, never loads
            break
        time.sleep(0.02)
    resident = stream.GetPropertyValue("SplatStreamingResidentSplats")
    wanted = stream.GetPropertyValue("SplatStreamingWantedSplats")
    loading = stream.GetPropertyValue("SplatStreamingLoading")
    if RANK == 0:
        check(settled and not loading and resident >= wanted == near,
              "Asynchronous: the %d splats the close view wants are in memory after %d renders "
              "(%d in all)" % (wanted, renders, resident))
    Hide(splat_file, view)

    # ParaView's GUI on a server: no Qt interactor renders again there while
    # pages load, so the GUI polls the reader as a live source (its
    # GetNeedsUpdate, every 100 ms), marks it modified and renders while it
    # says true; the first poll also makes the server's renders stop waiting
    # for pages. Emulated here as pqLiveSourceBehavior does it, on a file
    # opened afresh; the process stays polled after this (the last check).
    if not mpi:
        live_file = OpenDataFile(splat_path)
        live_display = Show(live_file, view)
        live_display.SplatStreamingBatchWait = 60  # a server's default
        live = live_file.GetClientSideObject()

        def loading():
            live_display.UpdatePropertyInformation()
            return live_display.GetPropertyValue("SplatStreamingLoading")

        live_file.SMProxy.InvokeCommand("PollAsGUI")  # the GUI's first poll (GetNeedsUpdate)
        output_time = live.GetOutputDataObject(0).GetMTime()
        view.CameraPosition = [1.8, -2.4, 1.6]
        start = time.perf_counter()
        Render(view)
        first_ms = 1000 * (time.perf_counter() - start)
        live_display.UpdatePropertyInformation()
        first = live_display.GetPropertyValue("SplatStreamingResidentSplats")
        first_loading = loading()
        polls = 0
        while loading() and polls < 200:  # GetNeedsUpdate's answer: pages loading or not drawn
            live_file.SMProxy.InvokeCommand("PollAsGUI")
            live_file.SMProxy.MarkModified(live_file.SMProxy)
            Render(view)
            polls += 1
            time.sleep(0.02)
        live_display.UpdatePropertyInformation()
        resident = live_display.GetPropertyValue("SplatStreamingResidentSplats")
        wanted = live_display.GetPropertyValue("SplatStreamingWantedSplats")
        check(first_loading and first < wanted,
              "polled by a GUI, the first render returns before its pages are read (%.0f ms, "
              "%d of %d splats drawn)" % (first_ms, first, wanted))
        check(0 < polls < 200 and resident == wanted == written and not loading(),
              "the GUI's polls render until every page is drawn: %d polls that said true, %d of "
              "%d splats" % (polls, resident, written))
        check(live.GetOutputDataObject(0).GetMTime() == output_time,
              "the polls render again without the reader reading again")
        Hide(live_file, view)
        Delete(live_file)
    Delete(splat_file)

if RANK == 0:
    print("TestPointSurfacesReaders: %d failure(s)" % len(check.failures), flush=True)
Delete(view)
del view
