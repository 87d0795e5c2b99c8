#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""What vtkMetaballMapper's LevelOfDetailPixels saves and costs, against the exact frame.

    bench_metaball_lod.py [--balls N ...] [--levels P ...] [--size N] [--frames N]
                          [--out DIR] [--smoke]

A cloud of --balls balls fills a sphere of radius 1 (radius 2.5 mean
spacings: one closed body), seen whole at --size² by the GPU ray caster,
every frame dynamic (all balls move a little and are uploaded again). For
each ball count it draws the exact frame (level 0) and one per --levels
value, in the same process, and reports per frame: the median wall time,
the kernel terms the rays summed, the grid's (voxel, ball) pairs, the
merged balls and the balls they stand for, and against the exact frame the
pixels whose hit or miss differs (as a share of the exact hits) and the
view-distance error of the common hits in cells' depth (p95 and maximum).
The point: with a level, the terms of a frame follow the pixels, not the
balls. On a software renderer (llvmpipe) the times are the CPU's; the kernel
terms are what a GPU's time follows too. The error is measured against the
CPU ray caster's exact frame: a software renderer cuts the GPU path's
longest loops short (`incomplete_rays`), so its level-0 frame has holes
where voxels hold the most balls. Writes <out>/metaball_lod.csv and
<out>/metaball_lod.png.
"""
import argparse
import math
import os
import statistics
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "Examples", "Python"))

import pointsurfaces  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkPolyData  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow  # noqa: E402
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401,E402

from bench_csv import write_rows  # noqa: E402


def cloud(n, rng):
    """n points uniform in the unit ball."""
    points = np.empty((0, 3), dtype=np.float32)
    while len(points) < n:
        p = rng.uniform(-1.0, 1.0, (2 * n, 3)).astype(np.float32)
        points = np.concatenate([points, p[(p * p).sum(axis=1) <= 1.0]])
    return np.ascontiguousarray(points[:n])


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--balls", type=int, nargs="+", default=[30000, 300000])
    parser.add_argument("--levels", type=float, nargs="+", default=[2.0, 4.0, 8.0])
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--frames", type=int, default=3)
    parser.add_argument("--out", default="bench-results")
    parser.add_argument("--smoke", action="store_true", help="3 000 balls at 96², levels 4")
    args = parser.parse_args()
    if args.smoke:
        args.balls, args.levels, args.size, args.frames = [3000], [4.0], 96, 2
    os.makedirs(args.out, exist_ok=True)
    if not os.environ.get("DISPLAY"):
        pointsurfaces.use_egl()

    rows = []
    view_angle = 30.0
    distance = 4.0
    per_unit = 0.5 * args.size / math.tan(math.radians(view_angle / 2))  # pixels at distance 1
    for n in args.balls:
        rng = np.random.default_rng(5)
        xyz = cloud(n, rng)
        points = vtkPoints()
        points.SetData(numpy_to_vtk(xyz, deep=False))
        poly = vtkPolyData()
        poly.SetPoints(points)
        spacing = 0.55 * (4.0 / 3.0 * math.pi / n) ** (1.0 / 3.0)
        mapper = pointsurfaces.vtkMetaballMapper()
        mapper.SetInputData(poly)
        mapper.SetRayCaster(mapper.GPU)
        mapper.CollectStatisticsOn()  # this frame's terms and merged balls
        mapper.GetField().SetRadius(2.5 * spacing)
        actor = vtkActor()
        actor.SetMapper(mapper)
        renderer = vtkRenderer()
        renderer.AddActor(actor)
        window = vtkRenderWindow()
        window.SetSize(args.size, args.size)
        window.SetMultiSamples(0)
        window.AddRenderer(renderer)
        camera = renderer.GetActiveCamera()
        camera.SetViewAngle(view_angle)
        camera.SetPosition(0.3, 0.4, distance)
        camera.SetFocalPoint(0.0, 0.0, 0.0)
        camera.SetClippingRange(distance - 1.5, distance + 1.5)
        ball_pixels = 2.5 * spacing * per_unit / distance

        start = xyz.copy()

        def draw(level, caster=mapper.GPU):
            # The same motion for every level: the last frames compare ball for ball.
            mapper.SetRayCaster(caster)
            mapper.SetLevelOfDetailPixels(level)
            xyz[:] = start
            motion = np.random.default_rng(7)
            times = []
            for _ in range(args.frames):
                xyz[:] += np.asarray(motion.normal(0.0, 1e-4, 3), dtype=np.float32)
                points.Modified()
                t0 = time.perf_counter()
                window.Render()
                window.GetZbufferDataAtPoint(0, 0)
                times.append(1000.0 * (time.perf_counter() - t0))
            z = vtkFloatArray()
            window.GetZbufferData(0, 0, args.size - 1, args.size - 1, z)
            depth = vtk_to_numpy(z).copy()
            return dict(ms=statistics.median(times[1:] or times), terms=mapper.GetNumberOfKernelTerms(),
                        incomplete=mapper.GetNumberOfIncompleteRays(),
                        pairs=mapper.GetNumberOfPairs(), merged=mapper.GetNumberOfMergedBalls(),
                        represented=mapper.GetNumberOfBallsMerged(), depth=depth)

        # The reference: the CPU ray caster's frame (every ray complete: a
        # software renderer cuts the GPU path's longest loops short).
        reference = draw(0.0, mapper.CPU)
        exact = None  # the GPU caster's exact frame: level 0
        for level in [0.0] + args.levels:
            frame = draw(level)
            exact = exact or frame
            hit_exact, hit = reference["depth"] < 1.0, frame["depth"] < 1.0
            differ = int(np.count_nonzero(hit_exact != hit))
            both = hit_exact & hit
            # Window depth to view distance (perspective, the clipping range above).
            near, far = distance - 1.5, distance + 1.5

            def view_distance(z):
                return near * far / (far - z * (far - near))
            error = np.abs(view_distance(frame["depth"][both]) - view_distance(reference["depth"][both]))
            cell_depth = (level if level > 0 else 1.0) * view_distance(reference["depth"][both]) / per_unit
            cells = error / cell_depth if error.size else np.zeros(1)
            rows.append(dict(
                balls=n, ball_pixels="%.2f" % ball_pixels, level_pixels=level,
                frame_ms="%.1f" % frame["ms"],
                vs_exact_ms="%.3f" % (frame["ms"] / exact["ms"]), kernel_terms=frame["terms"],
                terms_vs_exact="%.3f" % (frame["terms"] / max(1, exact["terms"])),
                incomplete_rays=frame["incomplete"],
                pairs=frame["pairs"], merged_balls=frame["merged"], balls_merged=frame["represented"],
                hits=int(np.count_nonzero(hit_exact)),
                differ_pct="%.2f" % (100.0 * differ / max(1, np.count_nonzero(hit_exact))),
                depth_p95_cells="%.2f" % float(np.percentile(cells, 95)),
                depth_max_cells="%.2f" % float(cells.max())))
        window.Finalize()
    write_rows(os.path.join(args.out, "metaball_lod.csv"), rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (terms, error) = plt.subplots(1, 2, figsize=(9, 3.8))
    for n in args.balls:
        mine = [r for r in rows if r["balls"] == n]
        x = [r["level_pixels"] for r in mine]
        terms.plot(x, [r["kernel_terms"] for r in mine], marker="o", label="%d balls" % n)
        error.plot(x[1:], [float(r["differ_pct"]) for r in mine[1:]], marker="o",
                   label="%d balls: hit/miss differs, %% of hits" % n)
        error.plot(x[1:], [float(r["depth_p95_cells"]) for r in mine[1:]], marker="s", ls="--",
                   label="%d balls: depth error p95, cells" % n)
    terms.set_xlabel("LevelOfDetailPixels (0: exact)")
    terms.set_ylabel("kernel terms per frame")
    terms.set_yscale("log")
    terms.legend(fontsize=7)
    terms.grid(True, alpha=0.3)
    error.set_xlabel("LevelOfDetailPixels")
    error.legend(fontsize=7)
    error.grid(True, alpha=0.3)
    fig.suptitle("Metaball level of detail at %d²: work against error" % args.size)
    fig.tight_layout()
    png = os.path.join(args.out, "metaball_lod.png")
    fig.savefig(png, dpi=100)
    print("# wrote " + png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
