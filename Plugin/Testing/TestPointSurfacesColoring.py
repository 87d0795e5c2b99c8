# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Colour maps on both representations, as ParaView's panels set them (pvbatch).

    pvbatch TestPointSurfacesColoring.py PLUGIN DATA_DIR BASELINE_DIR OUT_DIR [--mpi]

Two scenes whose colours are known pixel by pixel:

- Metaballs: five balls on a line, far enough apart to stay separate, with a
  scalar `s` (0 to 4), a vector `v` whose magnitude and X component differ
  from `s`, and an unsigned-char RGB array `rgb`;
- Algebraic Splats: a sphere of points fitted to splats (vtkAlgebraicSplatFitter),
  whose upper half has s = 4 and whose lower half has s = 0 (and `v`, `rgb`
  the same way);
- Streaming Splats: the same sphere's points with the same arrays, written to
  a splat file by the Streaming Splat Fitter, opened as File > Open opens it
  and drawn from the file (the reader's output is a preview of a few splats).

For each representation the test colours by the scalar, by the vector's
magnitude and by one component (with a colour map and its range), by the RGB
array with MapScalars off (direct colours), with a solid colour, and with
opacity 0.5 (both representations draw opaque surfaces and say so: their
own passes take no part in ParaView's depth peeling); every setting with InterpolateScalarsBeforeMapping
on (ParaView's default for every display) and off. It reads the picture
back and checks each ball's (or half-sphere's) pixels: their chromaticity (the
colour over its largest channel, so that lighting falls out) must match the
colour map's colour of the known value within a few degrees, and be nearer
to it than to any other ball's colour. A white, grey or missing surface
fails, and so does the crash this test was written for (colouring splats
with InterpolateScalarsBeforeMapping on died in vtkOpenGLPolyDataMapper).

Selection as a user drags a rectangle (SelectSurfacePoints, then
ExtractSelection): around each ball's centre it holds that ball alone, and
around a sample of each half-sphere only splats of that half (serially:
under pvbatch --symmetric the selection's fetch did not return, which is
left open).

With --mpi (pvbatch --symmetric under mpiexec -n 2) both data sets are split
between the ranks first (RedistributeDataSet), and the same checks hold on
the composited picture.
"""
import builtins  # paraview.simple brings numpy-style min, max and sum
import math
import os
import sys

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403


sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pointsurfaces_plugin_test import Checks, SIZE, new_view, pixels  # noqa: E402

plugin, data, baselines, out = sys.argv[1:5]
mpi = "--mpi" in sys.argv[5:]
RANK = servermanager.vtkProcessModule.GetProcessModule().GetPartitionId()
os.makedirs(out, exist_ok=True)
check = Checks(RANK)


# ns=globals(): the plugin's proxies as names here; ParaView refreshes that namespace
# later (with numpy-style min, max, sum and angle), so helpers use other names.
LoadPlugin(plugin, ns=globals())

# Five balls along x at -6, -3, 0, 3, 6, support radius 2 (each shows as a
# sphere of radius about 1). Values: s = index; v = (4 - s, 1, 0) so that
# |v| and v_x order the balls differently from s; rgb distinct primaries.
BALLS = ProgrammableSource(OutputDataSetType="vtkPolyData")
BALLS.Script = """
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray
out = self.GetPolyDataOutput()
x = np.array([-6.0, -3.0, 0.0, 3.0, 6.0])
points = vtkPoints()
points.SetData(numpy_to_vtk(np.c_[x, np.zeros(5), np.zeros(5)], deep=1))
out.SetPoints(points)
verts = vtkCellArray()
for i in range(5):
    verts.InsertNextCell(1)
    verts.InsertCellPoint(i)
out.SetVerts(verts)
s = numpy_to_vtk(np.arange(5.0), deep=1)
s.SetName("s")
v = numpy_to_vtk(np.c_[4.0 - np.arange(5.0), np.ones(5), np.zeros(5)], deep=1)
v.SetName("v")
rgb = numpy_to_vtk(np.array([[255, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 0],
                             [0, 255, 255]], dtype=np.uint8), deep=1)
rgb.SetName("rgb")
for a in (s, v, rgb):
    out.GetPointData().AddArray(a)
"""
BALL_X = [-6.0, -3.0, 0.0, 3.0, 6.0]
BALL_S = [0.0, 1.0, 2.0, 3.0, 4.0]
BALL_V = [(4.0 - k, 1.0, 0.0) for k in range(5)]
BALL_RGB = [(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 0), (0, 255, 255)]

# A sphere of points to splats; arrays by the half a splat lies in.
sphere = Sphere(Radius=1.0, ThetaResolution=96, PhiResolution=96)
fitter = AlgebraicSplatFitter(Input=sphere)
SPLATS = ProgrammableFilter(Input=fitter)
SPLATS.Script = """
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
inp = self.GetInput()
out = self.GetOutput()
out.ShallowCopy(inp)
if inp.GetNumberOfPoints() > 0:
    z = vtk_to_numpy(inp.GetPoints().GetData())[:, 2]
    top = z > 0
    s = numpy_to_vtk(np.where(top, 4.0, 0.0), deep=1)
    s.SetName("s")
    v = numpy_to_vtk(np.where(top[:, None], [[0.0, 1.0, 0.0]], [[4.0, 1.0, 0.0]]), deep=1)
    v.SetName("v")
    rgb = numpy_to_vtk(np.where(top[:, None], [[255, 255, 0]], [[0, 0, 255]]).astype(np.uint8),
                       deep=1)
    rgb.SetName("rgb")
    for a in (s, v, rgb):
        out.GetPointData().AddArray(a)
"""
# Sample points (world x, z) and their values: well inside each half.
HALF_Z = [0.55, -0.55]
HALF_S = [4.0, 0.0]
HALF_V = [(0.0, 1.0, 0.0), (4.0, 1.0, 0.0)]
HALF_RGB = [(255, 255, 0), (0, 0, 255)]

view = new_view()
view.Background = [1.0, 1.0, 1.0]
view.CameraParallelProjection = 1


def set_camera(centre, scale):
    """Look along +y at `centre` (x right, z up), parallel, half-height `scale`."""
    Render(view)  # the first render after Show resets the camera: set it after
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[0], centre[1] - 20.0, centre[2]]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraParallelScale = scale
    Render(view)


def pixel_of(x, z, centre, scale):
    """The pixel (column, row from the bottom) of world (x, z) under set_camera."""
    half = SIZE[1] / 2.0
    return (int(round(SIZE[0] / 2.0 + (x - centre[0]) / scale * half)),
            int(round(half + (z - centre[2]) / scale * half)))


def lut_colour(lut, value):
    rgb = [0.0, 0.0, 0.0]
    lut.GetClientSideObject().GetColor(value, rgb)
    return [255.0 * c for c in rgb]


def colour_angle(a, b):
    """Degrees between two colours seen as directions (lighting scales a colour)."""
    na = math.sqrt(builtins.sum(c * c for c in a))
    nb = math.sqrt(builtins.sum(c * c for c in b))
    if na < 1e-6 or nb < 1e-6:
        return 180.0
    cosine = builtins.sum(x * y for x, y in zip(a, b)) / (na * nb)
    return math.degrees(math.acos(builtins.max(-1.0, builtins.min(1.0, cosine))))


def mean_colour(image, dims, column, row, half=3):
    """The mean RGB of the (2 half + 1)^2 pixels around (column, row)."""
    total = [0.0, 0.0, 0.0]
    count = 0
    for r in range(row - half, row + half + 1):
        for c in range(column - half, column + half + 1):
            p = image[r * dims[0] + c]
            total = [t + float(x) for t, x in zip(total, p)]
            count += 1
    return [t / count for t in total]


def check_colours(name, samples, expected, tolerance=9.0):
    """Each sample pixel's colour direction within `tolerance` degrees of its own
    expected colour and nearer to it than to any other sample's colour."""
    path = os.path.join(out, name + (".mpi" if mpi else "") + ".png")
    SaveScreenshot(path, view, ImageResolution=SIZE)
    if RANK != 0:
        return
    dims, image = pixels(path)
    worst = 0.0
    for k, ((column, row), want) in enumerate(zip(samples, expected)):
        got = mean_colour(image, dims, column, row)
        if builtins.max(got) < 10.0 and builtins.max(want) > 10.0:
            check(False, "%s: sample %d is black or missing (%s)" % (name, k, got))
            return
        a = colour_angle(got, want)
        worst = builtins.max(worst, a)
        nearest = builtins.min(range(len(expected)), key=lambda j: colour_angle(got, expected[j]))
        if a > tolerance or (colour_angle(got, expected[nearest]) < a - 1e-9):
            check(False, "%s: sample %d has colour %s, %.1f degrees from the colour map's %s"
                  % (name, k, [round(g) for g in got], a, [round(w) for w in want]))
            return
    check(True, "%s: %d samples within %.1f degrees of their colours" % (name, len(samples), worst))


def exercise(display, label, samples, values, vectors, colours):
    """Every colouring setting on `display`, with InterpolateScalarsBeforeMapping on and off."""
    for interpolate in (1, 0):
        display.InterpolateScalarsBeforeMapping = interpolate
        tag = "%s-isbm%d" % (label, interpolate)
        display.Opacity = 1.0
        # A scalar through a colour map and its range.
        display.MapScalars = 1
        ColorBy(display, ("POINTS", "s"))
        lut = GetColorTransferFunction("s")
        lut.ApplyPreset("Rainbow Uniform", True)
        lut.RescaleTransferFunction(0.0, 4.0)
        Render(view)
        check_colours(tag + "-scalar", samples, [lut_colour(lut, s) for s in values])
        # A vector's magnitude, then its X component.
        ColorBy(display, ("POINTS", "v", "Magnitude"))
        vlut = GetColorTransferFunction("v")
        vlut.ApplyPreset("Rainbow Uniform", True)
        vlut.RescaleTransferFunction(1.0, math.sqrt(17.0))
        Render(view)
        check_colours(tag + "-magnitude", samples,
                      [lut_colour(vlut, math.sqrt(builtins.sum(c * c for c in v))) for v in vectors])
        ColorBy(display, ("POINTS", "v", "X"))
        vlut.RescaleTransferFunction(0.0, 4.0)
        Render(view)
        check_colours(tag + "-component", samples, [lut_colour(vlut, v[0]) for v in vectors])
        # Direct colours from an unsigned char array.
        ColorBy(display, ("POINTS", "rgb"))
        display.MapScalars = 0
        Render(view)
        check_colours(tag + "-direct", samples, [list(map(float, c)) for c in colours])
        display.MapScalars = 1
        # A solid colour.
        ColorBy(display, None)
        display.AmbientColor = display.DiffuseColor = [0.9, 0.3, 0.1]
        Render(view)
        check_colours(tag + "-solid", samples, [[229.5, 76.5, 25.5]] * len(samples))
        # Opacity below 1: both representations draw opaque surfaces (they warn),
        # never the stripes and holes that ParaView's depth peeling made of them.
        ColorBy(display, ("POINTS", "s"))
        lut.RescaleTransferFunction(0.0, 4.0)
        display.Opacity = 0.5
        Render(view)
        check_colours(tag + "-opacity", samples, [lut_colour(lut, s) for s in values])
        display.Opacity = 1.0


# Metaballs.
balls_input = RedistributeDataSet(Input=BALLS) if mpi else BALLS
balls = Show(balls_input, view)
balls.SetRepresentationType("Metaballs")
balls.MetaballRadiusArray = ""
balls.MetaballRadius = 2.0
balls.MetaballRayCaster = 2  # the native CPU caster: llvmpipe, as in CI
ball_centre = [0.0, 0.0, 0.0]
set_camera(ball_centre, 8.0)
ball_samples = [pixel_of(x, 0.0, ball_centre, 8.0) for x in BALL_X]


exercise(balls, "metaballs", ball_samples, BALL_S, BALL_V, BALL_RGB)


def check_selection(name, source, rectangle, values):
    """Select surface points in `rectangle` (pixels) as a user drags; the
    extracted points' `s` values must be exactly `values` (point ids are
    not compared: RedistributeDataSet renumbers them per rank)."""
    SelectSurfacePoints(Rectangle=rectangle, View=view)
    extracted = ExtractSelection(Input=source)
    result = servermanager.Fetch(extracted)
    got = set()
    if result is not None:
        from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet, vtkDataSet

        pieces = []
        if isinstance(result, vtkCompositeDataSet):
            it = result.NewIterator()
            it.InitTraversal()
            while not it.IsDoneWithTraversal():
                pieces.append(it.GetCurrentDataObject())
                it.GoToNextItem()
        elif isinstance(result, vtkDataSet):
            pieces.append(result)
        for piece in pieces:
            array = piece.GetPointData().GetArray("s")
            if array is not None:
                got.update(array.GetValue(i) for i in range(array.GetNumberOfTuples()))
    ClearSelection(source)
    Delete(extracted)
    check(got == set(values), "%s: the selection holds s = %s (%s expected)"
          % (name, sorted(got), sorted(values)))


# Picking: a drag around each ball's centre selects that ball alone. Serial
# only: under pvbatch --symmetric the selection's fetch did not return.
balls.Opacity = 1.0
ColorBy(balls, ("POINTS", "s"))
Render(view)
for k in (() if mpi else (0, 2, 4)):
    column, row = ball_samples[k]
    check_selection("metaballs: rectangle on ball %d" % k, balls_input,
                    [column - 4, row - 4, column + 4, row + 4], [BALL_S[k]])
Hide(balls_input, view)

# Algebraic splats. Under MPI, RedistributeDataSet gives each rank a piece
# that still carries the whole fit's octree, which no longer indexes it: the
# mapper builds its own (LOD and culling kept) instead of warning at every
# rebuild and drawing everything. Its warnings are captured to check that.
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
usual_window = vtkOutputWindow.GetInstance()
captured = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(captured)
splats_input = RedistributeDataSet(Input=SPLATS) if mpi else SPLATS
splats = Show(splats_input, view)
splats.SetRepresentationType("Algebraic Splats")
splat_centre = [0.0, 0.0, 0.0]
set_camera(splat_centre, 1.3)
splat_samples = [pixel_of(0.0, z, splat_centre, 1.3) for z in HALF_Z]


exercise(splats, "splats", splat_samples, HALF_S, HALF_V, HALF_RGB)
splats.Opacity = 1.0
Render(view)
for k in (() if mpi else (0, 1)):
    column, row = splat_samples[k]
    check_selection("splats: rectangle on the %s half" % ("upper" if k == 0 else "lower"),
                    splats_input, [column - 4, row - 4, column + 4, row + 4], [HALF_S[k]])

Hide(splats_input, view)
vtkOutputWindow.SetInstance(usual_window)
said = captured.GetOutput() or ""
if said:
    print(said, flush=True)
check("does not index" not in said and "does not hold" not in said,
      "Algebraic Splats of %s draw with an octree, without a stale-octree warning"
      % ("RedistributeDataSet's pieces" if mpi else "the fit"))

# Streaming Splats: the sphere's points with the same arrays, fitted into a
# splat file by the Streaming Splat Fitter and opened as File > Open does; the
# file itself is drawn, its attributes in their types (the RGB array stays
# unsigned char: direct colours). Under MPI both ranks name the same file:
# rank 0 alone fits and writes it (two ranks writing one file raced, and
# HDF5 refused one of them), and rank 0 draws it. The
# reader shares its preview between the ranks: a rank without the arrays
# skipped the colour range's reduction under ParaView 6.1 and ColorBy hung.
POINTS = ProgrammableSource(OutputDataSetType="vtkPolyData")
POINTS.Script = """
from vtkmodules.vtkFiltersSources import vtkSphereSource
whole = vtkSphereSource()
whole.SetRadius(1.0)
whole.SetThetaResolution(96)
whole.SetPhiResolution(96)
whole.Update()
inp = whole.GetOutput()
""" + SPLATS.Script.replace("inp = self.GetInput()", "").replace(
    "self.GetOutput()", "self.GetPolyDataOutput()")
streamed = StreamingSplatFitter(Input=POINTS)
streamed.FileName = os.path.join(out, "coloured%s.psplat" % (".mpi" if mpi else ""))
streamed.PageSize = 256  # pages small enough for a preview of some of them
fitter_said = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(fitter_said)
streamed.UpdatePipeline()
vtkOutputWindow.SetInstance(usual_window)
fitted = streamed.GetDataInformation().GetNumberOfPoints()
said = fitter_said.GetOutput() or ""
if said:
    print(said, flush=True)
check(fitted > 0 and "cannot be" not in said,
      "the Streaming Splat Fitter writes its file once and reads back %d splats" % fitted)
Delete(streamed)
splat_file = OpenDataFile(os.path.join(out, "coloured%s.psplat" % (".mpi" if mpi else "")))
splat_file.MemoryBudget = 0.1  # a preview of some pages: what is drawn is the file
stream = Show(splat_file, view)
check(stream.Representation == "Streaming Splats",
      "the splat file shows as Streaming Splats (%s)" % stream.Representation)
set_camera(splat_centre, 1.3)
ranks_with_arrays = 1
if mpi:
    from vtkmodules.vtkCommonCore import vtkIntArray
    from vtkmodules.vtkParallelCore import vtkCommunicator
    here, least = vtkIntArray(), vtkIntArray()
    here.InsertNextValue(0 if splat_file.PointData.GetArray("s") is None else 1)
    servermanager.vtkProcessModule.GetProcessModule().GetGlobalController().AllReduce(
        here, least, vtkCommunicator.MIN_OP)
    ranks_with_arrays = least.GetValue(0)
    check(ranks_with_arrays == 1, "every rank's piece of the file has its arrays")
if not mpi:
    preview = splat_file.GetDataInformation().GetNumberOfPoints()
    stream.UpdatePropertyInformation()
    drawn = stream.GetPropertyValue("SplatStreamingResidentSplats")
    whole = stream.GetPropertyValue("SplatStreamingFileSplats")
    check(0 < preview < drawn == whole,
          "the file's %d splats are drawn, not the reader's %d" % (drawn, preview))
if ranks_with_arrays:  # else ParaView 6.1's ColorBy waits for the rank without them
    exercise(stream, "streaming", splat_samples, HALF_S, HALF_V, HALF_RGB)

if RANK == 0:
    print("TestPointSurfacesColoring: %d failure(s)" % len(check.failures), flush=True)
Delete(view)
del view
