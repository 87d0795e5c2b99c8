#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""The SPH density surface of a Gadget or SWIFT snapshot's gas: frame time and ray work per threshold.

    bench_sph_density.py [SNAPSHOT] [--data DIR] [--over 1.5 2.5 4 20] [--size 512]
                         [--frames 3] [--out DIR] [--smoke]

The gas (PartType0) drawn by vtkMetaballMapper's CPU ray caster as an
iso-surface of its SPH density: the cubic-spline kernel, SmoothingLength as
the support (Gadget's convention), Masses as the strengths, the threshold at
each overdensity times the mean of the Density array. Every ray crosses
hundreds of overlapping supports, and at a high threshold most of them are
far below it: the case the caster's per-block field bounds are for. Sphere
imposters (vtkOpenGLSphereMapper) of the same particles, at half their
smoothing length, give the frame-time yardstick of the same run.

Per threshold: dynamic frame time (the particles marked modified before
each frame), grid build and ray-cast times, hits, and per ray the support
tests, samples and kernel terms (the mapper's statistics). CSV to stdout and
<out>/sph_density.csv.

The snapshot: SNAPSHOT (any Gadget or SWIFT HDF5 file); else, with --data DIR,
the full-size gadget4_lcdm_gas_z5.hdf5 in DIR (or a folder one level below it;
without it the run is skipped with one line on stderr); else the committed
2 000-particle subset of it, IO/Testing/Data/gadget/lcdm_gas_z5_subset.hdf5.
--smoke (what ctest runs): 96 x 96, one frame.
"""
import argparse
import os
import sys

import numpy as np

import pointsurfaces
from pointsurfaces import vtkMetaballMapper
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkRenderingCore import vtkActor

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from bench_csv import IO_DATA, find_input, write_rows  # noqa: E402
from bench_metaballs import LONE_ISO, Scene, imposters, material  # noqa: E402

SNAPSHOT = "gadget4_lcdm_gas_z5.hdf5"  # the full-size snapshot's name in --data
SUBSET = os.path.join(IO_DATA, "gadget", "lcdm_gas_z5_subset.hdf5")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("snapshot", nargs="?", metavar="SNAPSHOT",
                        help="a Gadget/SWIFT HDF5 snapshot (default: see --data)")
    parser.add_argument("--data", metavar="DIR",
                        help="folder of the full-size %s (default: the committed subset "
                             "IO/Testing/Data/gadget/lcdm_gas_z5_subset.hdf5)" % SNAPSHOT)
    parser.add_argument("--over", type=float, nargs="+", default=[1.5, 2.5, 4.0, 20.0],
                        help="thresholds, as multiples of the mean density")
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--frames", type=int, default=3)
    parser.add_argument("--out", default="bench-results", help="folder for sph_density.csv")
    parser.add_argument("--smoke", action="store_true", help="96 x 96, one frame (ctest)")
    args = parser.parse_args()
    path = args.snapshot or (find_input(args.data, SNAPSHOT, "the Gadget snapshot")
                             if args.data else SUBSET)
    if path is None:
        return 0
    if not os.path.isfile(path):
        sys.exit("bench_sph_density.py: no such file: " + path)
    size = 96 if args.smoke else args.size
    frames = 1 if args.smoke else args.frames
    os.makedirs(args.out, exist_ok=True)

    reader = pointsurfaces.vtkGadgetHDF5Reader()
    reader.SetFileName(path)
    reader.Update()
    poly = reader.GetOutput()
    if poly.GetNumberOfPoints() == 0:
        sys.exit("bench_sph_density.py: no gas particles in " + path)
    pd = poly.GetPointData()
    xyz = vtk_to_numpy(poly.GetPoints().GetData()).astype(np.float64)
    h = vtk_to_numpy(pd.GetArray("SmoothingLength")).astype(np.float64)
    rho = vtk_to_numpy(pd.GetArray("Density")).astype(np.float64)
    bounds = list(np.ravel(np.column_stack([(xyz - h[:, None]).min(axis=0),
                                            (xyz + h[:, None]).max(axis=0)])))
    scene = Scene((size, size))
    # Imposters at half the smoothing length (their "iso-radius" is LONE_ISO R).
    yardstick = imposters(scene, poly, 0.5 * h / LONE_ISO, bounds, frames)

    rows = []
    for over in args.over:
        mapper = vtkMetaballMapper()
        mapper.SetRayCaster(vtkMetaballMapper.CPU)
        mapper.SetInputDataObject(poly)
        field = mapper.GetField()
        field.SetKernel(field.CubicSpline)
        field.SetRadiusArrayName("SmoothingLength")
        field.SetStrengthArrayName("Masses")
        field.SetThreshold(over * float(rho.mean()))
        actor = material(vtkActor())
        actor.SetMapper(mapper)
        scene.show(actor, bounds)
        scene.image()
        mapper.CollectStatisticsOn()
        scene.image()
        rays = max(mapper.GetNumberOfRays(), 1)
        stats = dict(hits=mapper.GetNumberOfHits(),
                     tests_per_ray="%.1f" % (mapper.GetNumberOfSupportTests() / rays),
                     samples_per_ray="%.2f" % ((mapper.GetNumberOfSamples() +
                                                mapper.GetNumberOfBisectionSamples()) / rays),
                     terms_per_ray="%.1f" % (mapper.GetNumberOfKernelTerms() / rays),
                     empty_visits="%.3f" % (mapper.GetNumberOfEmptyVoxelVisits() /
                                            max(mapper.GetNumberOfVoxelVisits(), 1)))
        mapper.CollectStatisticsOff()
        ms = scene.frame_ms(frames, before=poly.GetPoints().Modified)
        rows.append(dict(snapshot=os.path.basename(path), particles=len(xyz),
                         size="%dx%d" % (size, size), overdensity=over,
                         frame_ms="%.1f" % ms, build_ms="%.2f" % mapper.GetGridBuildTime(),
                         cast_ms="%.1f" % mapper.GetRayCastTime(),
                         imposters_ms="%.1f" % yardstick,
                         vs_imposters="%.1f" % (ms / yardstick), **stats))
    write_rows(os.path.join(args.out, "sph_density.csv"), rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
