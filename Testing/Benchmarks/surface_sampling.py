# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Dense scans for the benchmarks: points sampled uniformly on a triangle mesh."""
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy


def sample_surface(mesh, n, seed=1):
    """n points (an n x 3 array) uniformly by area on the triangles of a vtkPolyData."""
    xyz = vtk_to_numpy(mesh.GetPoints().GetData()).astype(np.float64)
    tri = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    a, b, c = xyz[tri[:, 0]], xyz[tri[:, 1]], xyz[tri[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    rng = np.random.default_rng(seed)
    pick = rng.choice(len(tri), size=n, p=area / area.sum())
    r1, r2 = np.sqrt(rng.random(n))[:, None], rng.random(n)[:, None]
    return (1 - r1) * a[pick] + r1 * (1 - r2) * b[pick] + r1 * r2 * c[pick]
