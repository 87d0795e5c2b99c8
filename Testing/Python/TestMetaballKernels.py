# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""The benchmarks' numpy kernels (Testing/Benchmarks/metaball_kernels.py)
against the definition (psMetaballKernels.h, through
vtkMetaballField.EvaluateKernel and EvaluateKernelDerivative): every kernel,
value and d/dx, at 2001 values of x = r^2 / R^2 from -0.1 to 1.1, to 1e-12.
A wrong formula must be caught: each numpy kernel against the next
definition must differ."""
import os
import sys

import numpy as np

import pointsurfaces  # noqa: F401
from pointsurfaces import vtkMetaballField
from pstesting import fail

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Benchmarks"))
import metaball_kernels  # noqa: E402

ENUM = ["Wyvill", "Quartic", "Gaussian", "CubicSpline", "WendlandC2", "WendlandC4"]
if len(ENUM) != len(metaball_kernels.NAMES):
    fail("metaball_kernels.py has %d kernels, vtkMetaballField %d"
         % (len(metaball_kernels.NAMES), len(ENUM)))

xs = np.linspace(-0.1, 1.1, 2001)


def definition(index):
    value = np.array([vtkMetaballField.EvaluateKernel(index, x) for x in xs])
    slope = np.array([vtkMetaballField.EvaluateKernelDerivative(index, x) for x in xs])
    return value, slope


def differs(index, name):
    value, slope = metaball_kernels.kernel(name, xs, derivative=True)
    ref_value, ref_slope = definition(index)
    return (np.abs(value - ref_value).max(), np.abs(slope - ref_slope).max())


for index, enum_name in enumerate(ENUM):
    if getattr(vtkMetaballField, enum_name) != index:
        fail("vtkMetaballField.%s is %d, not %d" % (enum_name, getattr(vtkMetaballField, enum_name),
                                                    index))
    name = metaball_kernels.NAMES[index]
    dv, ds = differs(index, name)
    print("%-12s value %.2e  d/dx %.2e" % (name, dv, ds))
    if not (dv <= 1e-12 and ds <= 1e-11):
        fail("numpy %s differs from the definition: %.3g in value, %.3g in d/dx" % (name, dv, ds))
    other = metaball_kernels.NAMES[(index + 1) % len(ENUM)]
    if max(differs(index, other)) < 1e-3:
        fail("numpy %s matches kernel %d: the check cannot tell kernels apart" % (other, index))
print("numpy kernels agree with psMetaballKernels.h")
