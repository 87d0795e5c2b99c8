# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""The metaball and SPH kernels in numpy, for the benchmarks' peers.

The formulas of Filters/Core/Metaballs/psMetaballKernels.h (the definition), as
functions of x = r^2 / R^2 with peak 1 at x = 0 and 0 from x = 1, in the
order of vtkMetaballField.Kernels. TestMetaballKernels checks every one
against vtkMetaballField.EvaluateKernel and EvaluateKernelDerivative.
"""
import numpy as np

GAUSSIAN_SHARPNESS = 4.0
GAUSSIAN_FLOOR = np.exp(-GAUSSIAN_SHARPNESS)


def _wyvill(x, q):
    value = ((-4.0 / 9.0 * x + 17.0 / 9.0) * x - 22.0 / 9.0) * x + 1.0
    slope = (-4.0 / 3.0 * x + 34.0 / 9.0) * x - 22.0 / 9.0
    return value, slope


def _quartic(x, q):
    return (1.0 - x) ** 2, -2.0 * (1.0 - x)


def _gaussian(x, q):
    e = np.exp(-GAUSSIAN_SHARPNESS * x)
    scale = 1.0 - GAUSSIAN_FLOOR
    return (e - GAUSSIAN_FLOOR) / scale, -GAUSSIAN_SHARPNESS * e / scale


def _cubic_spline(x, q):
    u = 1.0 - q
    inner = q < 0.5
    value = np.where(inner, 1.0 - 6.0 * x + 6.0 * x * q, 2.0 * u ** 3)
    with np.errstate(divide="ignore", invalid="ignore"):
        slope = np.where(inner, -6.0 + 9.0 * q, -3.0 * u * u / q)
    return value, slope


def _wendland_c2(x, q):
    u = 1.0 - q
    return u ** 4 * (1.0 + 4.0 * q), -10.0 * u ** 3


def _wendland_c4(x, q):
    u = 1.0 - q
    return (u ** 6 * (1.0 + 6.0 * q + 35.0 / 3.0 * x),
            -28.0 / 3.0 * (1.0 + 5.0 * q) * u ** 5)


# In vtkMetaballField.Kernels order: Wyvill, Quartic, Gaussian, CubicSpline,
# WendlandC2, WendlandC4.
KERNELS = {"wyvill": _wyvill, "quartic": _quartic, "gaussian": _gaussian,
           "cubic_spline": _cubic_spline, "wendland_c2": _wendland_c2,
           "wendland_c4": _wendland_c4}
NAMES = list(KERNELS)


def kernel(name, x, derivative=False):
    """K(x) for the kernel `name` (a NAMES entry or its index), with dK/dx
    as a second array when `derivative`; 0 outside [0, 1)."""
    if not isinstance(name, str):
        name = NAMES[name]
    x = np.asarray(x, dtype=np.float64)
    inside = x < 1.0
    xc = np.clip(x, 0.0, 1.0)
    value, slope = KERNELS[name](xc, np.sqrt(xc))
    value = np.where(inside, value, 0.0)
    slope = np.where(inside, slope, 0.0)
    return (value, slope) if derivative else value


def wyvill(x):
    """Wyvill's kernel (thesis eq. 1.4), the benchmarks' default."""
    return kernel("wyvill", x)
