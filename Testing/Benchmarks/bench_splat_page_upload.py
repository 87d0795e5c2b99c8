#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""What pages arriving cost vtkStreamingSplatMapper's render thread: uploading
what arrives (IncrementalUpload, the default) against gathering and uploading
the whole resident set on each arrival (the former method).

    bench_splat_page_upload.py [MESH] [--file PSPLAT] [--points N] [--page-size N]
                               [--budgets MB ...] [--frames N] [--size PX] [--out DIR] [--smoke]

The splat file is --file, or else made here as bench_splat_paging.py makes
it: N points (default 4M) sampled by area on MESH (default
Testing/Data/bunny.vtp) with noise of 1e-4 of its diagonal, fitted with
three levels, written in pages of --page-size splats (default: the
writer's, 16 384) to a temporary folder and deleted afterwards.

For each budget (MB of GPU buffers), both modes in this process, along the
same path: the first of bench_splat_quality.py's views zoomed in 2.5 times,
then an orbit of --frames steps (30 degrees of azimuth and 15 of elevation,
alternately up and down), so that pages leave the view and others come.
Each step renders once (the loading thread is asked for the new view's
pages), waits until they are read, and renders again: that second render
brings the arrivals into the buffers. Per step the CSV has the splats
resident, uploaded (GetNumberOfUploadedSplats) and drawn, the render
thread's seconds spent bringing pages in (GetUploadSeconds: writing or
gathering them, converting, uploading) and the whole second render's
wall time. The window is small (--size, default 32 pixels) with LOD off:
every level of every page in view is wanted, as in a large window, while
llvmpipe's per-pixel work stays small.

Output in --out: splat_page_upload.csv (one row per budget, mode and step),
splat_page_upload_summary.csv (per budget and mode, the medians over the
orbit's arrivals, and the incremental median's ratio to the gathered one)
and splat_page_upload.png (upload ms per arrival against the splats
resident). Timings are wall-clock on whatever this runs on: compare the two
modes within one run, as ratios.
"""
import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_splat_paging as paging  # noqa: E402
import bench_splat_quality as quality  # noqa: E402
import bench_splat_stream as stream  # noqa: E402
from bench_csv import TEST_DATA, write_rows  # noqa: E402

import pointsurfaces  # noqa: E402

MODES = (("incremental", True), ("gathered", False))


def orbit(scene, model, path, budget, incremental, frames):
    """The rows of one mode: the path's steps, each rendered after its pages arrived."""
    mapper = pointsurfaces.vtkStreamingSplatMapper()
    mapper.SetFileName(path)
    mapper.SetMemoryBudget(budget)
    mapper.SetIncrementalUpload(incremental)
    mapper.SetRenderWhileLoading(False)
    stream.show(scene, mapper)
    mapper.SetLODPixelError(0.0)
    scene.use(model["cameras"][0])
    camera = scene.renderer.GetActiveCamera()
    camera.Zoom(2.5)
    rows = []
    for step in range(frames + 1):
        if step > 0:
            camera.Azimuth(30.0)
            camera.Elevation(15.0 if step % 2 else -15.0)
            camera.OrthogonalizeViewUp()
        scene.renderer.ResetCameraClippingRange()
        scene.window.Render()  # asks for this view's pages
        mapper.WaitForPages()
        start = time.perf_counter()
        scene.window.Render()  # brings them in
        render_ms = 1000.0 * (time.perf_counter() - start)
        rows.append(dict(step=step, resident_splats=mapper.GetNumberOfResidentSplats(),
                         allocated_splats=mapper.GetNumberOfAllocatedSplats(),
                         uploaded_splats=mapper.GetNumberOfUploadedSplats(),
                         drawn_splats=mapper.GetNumberOfRenderedSplats(),
                         upload_ms=round(1000.0 * mapper.GetUploadSeconds(), 2),
                         render_ms=round(render_ms, 1)))
    scene.renderer.RemoveAllViewProps()
    return rows


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axis = plt.subplots(figsize=(7, 4))
    for budget in sorted({r["budget_mb"] for r in rows}):
        for mode, marker in (("incremental", "o"), ("gathered", "s")):
            points = [(r["resident_splats"], r["upload_ms"]) for r in rows
                      if r["budget_mb"] == budget and r["mode"] == mode and r["step"] > 0
                      and r["uploaded_splats"] > 0]
            if points:
                x, y = zip(*points)
                axis.scatter(x, y, marker=marker, s=18, label="%s, %g MB" % (mode, budget))
    axis.set_xlabel("splats resident")
    axis.set_ylabel("render thread per arrival (ms)")
    axis.set_yscale("log")
    axis.set_title("vtkStreamingSplatMapper: pages arriving")
    axis.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mesh", nargs="?", default=os.path.join(TEST_DATA, "bunny.vtp"))
    parser.add_argument("--file", help="a splat file to draw (default: one made here)")
    parser.add_argument("--points", type=float, default=4e6)
    parser.add_argument("--page-size", type=int)
    parser.add_argument("--budgets", type=float, nargs="+", default=[16.0, 32.0, 64.0])
    parser.add_argument("--frames", type=int, default=12)
    parser.add_argument("--size", type=int, default=32, help="image side, pixels")
    parser.add_argument("--up", choices=("x", "y", "z"))
    parser.add_argument("--out", default="bench-results")
    parser.add_argument("--smoke", action="store_true",
                        help="30 000 points in pages of 256, 3 frames")
    args = parser.parse_args()
    if args.smoke:
        args.points, args.page_size, args.frames, args.budgets = 3e4, 256, 3, [0.2]
    os.makedirs(args.out, exist_ok=True)
    mesh = quality.load_mesh(args.mesh)
    stem = os.path.basename(args.mesh).split(".")[0]
    up = args.up or quality.UP_AXIS.get(stem.split("_")[0], "y")
    scene = quality.Scene((args.size, args.size))
    model = dict(name=stem, cameras=scene.cameras(mesh, up, stream.VIEWS[:1]))
    path, scratch = paging.splat_file(args, mesh, stem, "bench-splat-page-upload-", args.page_size)
    info = paging.file_header(path)
    rows, summary = [], []
    for budget in args.budgets:
        medians = {}
        for mode, incremental in MODES:
            steps = orbit(scene, model, path, budget, incremental, args.frames)
            for row in steps:
                rows.append(dict(model=stem, file_splats=info.GetNumberOfSplats(),
                                 budget_mb=budget, mode=mode, **row))
            # Arrivals along the orbit (the first view's buffers are made anew either way).
            arrivals = [r for r in steps if r["step"] > 0 and r["uploaded_splats"] > 0]
            median = (lambda key: float(np.median([r[key] for r in arrivals])) if arrivals else 0.0)
            medians[mode] = median("upload_ms")
            summary.append(dict(model=stem, file_splats=info.GetNumberOfSplats(), budget_mb=budget,
                                mode=mode, arrivals=len(arrivals),
                                resident_splats=int(median("resident_splats")),
                                uploaded_splats=int(median("uploaded_splats")),
                                upload_ms=round(median("upload_ms"), 2),
                                longest_upload_ms=round(max([r["upload_ms"] for r in arrivals],
                                                            default=0.0), 2),
                                first_view_upload_ms=steps[0]["upload_ms"]))
        for row in summary[-len(MODES):]:
            row["ratio_to_gathered"] = (round(medians[row["mode"]] / medians["gathered"], 3)
                                        if medians["gathered"] else "")
            print("# %s" % row, flush=True)
    write_rows(os.path.join(args.out, "splat_page_upload.csv"), rows)
    write_rows(os.path.join(args.out, "splat_page_upload_summary.csv"), summary)
    plot(rows, os.path.join(args.out, "splat_page_upload.png"))
    paging.remove_made(path, scratch)
    return 0


if __name__ == "__main__":
    sys.exit(main())
