# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Fit the Stanford Bunny (Testing/Data/bunny.vtp) from Python: the splat
count at s = 1 of the unbounded fit against Table 4.7 of N. K. R. Bolla,
"High Quality Rendering of Large Point-based Surfaces", M.S. thesis, IIIT
Hyderabad, 2010 ([Bolla 2010]), the error falling with the degree, and the
data model's arrays; then the default, error-bounded fit: its reported
deviations, a scan repeated three times over (as an OBJ export with one
vertex per face corner is) giving the splats of the unique points, and the
splat mapper's bounds framing the splats as the points are framed."""
import math

import pointsurfaces
from pstesting import data_file, fail
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

reader = vtkXMLPolyDataReader()
reader.SetFileName(data_file("bunny.vtp"))
reader.Update()
bunny = reader.GetOutput()
n = bunny.GetNumberOfPoints()
diagonal = bunny.GetLength()

fitter = pointsurfaces.vtkAlgebraicSplatFitter()
fitter.SetInputConnection(reader.GetOutputPort())
fitter.SetMaximumDeviation(0.0)  # the unbounded fit of the thesis,
fitter.SetFeatureSizeNeighbors(120)  # with h calibrated on its Table 4.7
metric = pointsurfaces.vtkSplatErrorMetric()
metric.SetInputConnection(reader.GetOutputPort())
metric.SetSplatConnection(fitter.GetOutputPort())

previous = None
for degree in (1, 2, 3, 4):
    fitter.SetDegree(degree)
    metric.Update()
    splats = fitter.GetOutput()
    count = splats.GetNumberOfPoints()
    rms = metric.GetRMSDistance() / diagonal
    print("degree %d: %d splats (%.2f%% of %d), RMS %.2e of the diagonal, %d uncovered"
          % (degree, count, 100.0 * count / n, n, rms, metric.GetNumberOfUncoveredPoints()))
    # [Bolla 2010] Table 4.7: 1315 splats at s = 1 for the Bunny.
    if abs(count - 1315) > 0.05 * 1315:
        fail("%d splats at s = 1, the thesis has 1315" % count)
    if previous is not None and rms > previous * 1.02:
        fail("degree %d is less accurate than degree %d" % (degree, degree - 1))
    previous = rms
    coefficients = splats.GetPointData().GetArray("SplatCoefficients")
    if coefficients.GetNumberOfComponents() != (degree + 1) * (degree + 2) // 2:
        fail("SplatCoefficients has %d components" % coefficients.GetNumberOfComponents())
    for i in range(coefficients.GetNumberOfTuples()):
        if not all(math.isfinite(v) for v in coefficients.GetTuple(i)):
            fail("non-finite coefficient at splat %d" % i)
    if splats.GetFieldData().GetArray("SplatDegree").GetValue(0) != degree:
        fail("SplatDegree is not %d" % degree)

if previous > 1e-3:
    fail("quartic splats are %.2e of the diagonal away from the scan" % previous)


def fit(data, **settings):
    f = pointsurfaces.vtkAlgebraicSplatFitter()
    f.SetInputData(data)
    for key, value in settings.items():
        getattr(f, "Set" + key)(value)
    m = pointsurfaces.vtkSplatErrorMetric()
    m.SetInputData(data)
    m.SetSplatConnection(f.GetOutputPort())
    m.Update()
    return f, m


# The default fit is error-bounded: every splat reports its largest deviation.
bounded, bounded_metric = fit(bunny)
splats = bounded.GetOutput()
deviation = splats.GetPointData().GetArray("SplatMaxDeviation")
if deviation is None or deviation.GetNumberOfTuples() != splats.GetNumberOfPoints():
    fail("no SplatMaxDeviation array")
largest = deviation.GetRange()[1]
print("bounded, degree 3: %d splats, RMS %.2e, largest reported deviation %.2e of the diagonal,"
      " %d uncovered" % (splats.GetNumberOfPoints(), bounded_metric.GetRMSDistance() / diagonal,
                         largest / diagonal, bounded_metric.GetNumberOfUncoveredPoints()))
if not 0.0 < largest < 5e-3 * diagonal:
    fail("largest reported deviation %.2e of the diagonal" % (largest / diagonal))

# Duplicates: each point three times, two of them moved by 1e-9 of the diagonal.
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
unique = vtkPolyData()
unique.SetPoints(bunny.GetPoints())
repeated_points = vtkPoints()
repeated_points.SetDataTypeToDouble()
for copy in range(3):
    for i in range(n):
        x, y, z = bunny.GetPoint(i)
        repeated_points.InsertNextPoint(x + copy * 1e-9 * diagonal, y, z)
repeated = vtkPolyData()
repeated.SetPoints(repeated_points)
for degree in (2, 3):
    one, one_metric = fit(unique, Degree=degree)
    three, three_metric = fit(repeated, Degree=degree)
    a, b = one.GetOutput().GetNumberOfPoints(), three.GetOutput().GetNumberOfPoints()
    ra, rb = one_metric.GetRMSDistance(), three_metric.GetRMSDistance()
    print("degree %d: unique points %d splats (RMS %.3e, %d reduced), three times over %d splats"
          " (RMS %.3e, %d reduced, %d merged)"
          % (degree, a, ra, one.GetNumberOfReducedDegreeSplats(), b, rb,
             three.GetNumberOfReducedDegreeSplats(), three.GetNumberOfMergedPoints()))
    if three.GetNumberOfMergedPoints() != 2 * n:
        fail("%d points merged, expected %d" % (three.GetNumberOfMergedPoints(), 2 * n))
    if abs(b - a) > 0.01 * a or abs(rb - ra) > 0.01 * ra:
        fail("duplicates change the splats: %d against %d, RMS %.3e against %.3e" % (b, a, rb, ra))
    if three.GetNumberOfReducedDegreeSplats() > one.GetNumberOfReducedDegreeSplats():
        fail("duplicates lower the degree")

# Tight bounds: the mapper's bounds are the splats' own, within 5 % of the points' extent.
mapper = pointsurfaces.vtkAlgebraicSplatMapper()
mapper.SetInputData(splats)
got, want = mapper.GetBounds(), bunny.GetBounds()
for axis in range(3):
    extent = want[2 * axis + 1] - want[2 * axis]
    for side in (0, 1):
        gap = abs(got[2 * axis + side] - want[2 * axis + side])
        if gap > 0.05 * extent:
            fail("mapper bounds %s against the points' %s" % (got, want))
print("mapper bounds %s, points %s" % (tuple(round(v, 4) for v in got), tuple(round(v, 4) for v in want)))
print("TestFitBunny: passed")
