# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Fit the Stanford Bunny (Testing/Data/bunny.vtp) from Python: the splat
count at s = 1 against Table 4.7 of N. K. R. Bolla, "High Quality Rendering
of Large Point-based Surfaces", M.S. thesis, IIIT Hyderabad, 2010
([Bolla 2010]), the error falling with the degree, and the data model's
arrays."""
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
print("TestFitBunny: passed")
