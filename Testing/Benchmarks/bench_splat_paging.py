#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Drawing a splat file within a memory budget: vtkStreamingSplatMapper against the reader.

    bench_splat_paging.py [MESH] [--file PSPLAT] [--points N] [--budgets MB ...]
                          [--frames N] [--size PX] [--out DIR] [--smoke]

The splat file is --file (for example one that bench_splat_stream.py --keep
left: a 100M-point fit), or else made here: N points (default 1M) sampled
by area on MESH (default Testing/Data/bunny.vtp) with noise of 1e-4 of its
diagonal, fitted in memory with three levels and written with
vtkSplatFileWriter in a temporary folder, deleted afterwards.

For each budget (MB of the mapper's GPU buffers; the reader gets the budget
of its own output that holds as many splats), both ways of drawing the file,
in this process, with LOD at 1 pixel, from the first of
bench_splat_quality.py's views and then an orbit of --frames steps around
it:

- reader: vtkSplatFileReader with the camera (it reloads the pages of each
  view within the budget, on the render's thread) and vtkAlgebraicSplatMapper,
  as bench_splat_stream.py measures it;
- streaming: vtkStreamingSplatMapper (its pages loaded by a thread,
  MemoryBudget the budget): the first frame (it returns without waiting),
  the time to the first picture with splats in it, the time until the
  thread has read all the view wants, and to the frame that draws it all;
  then the orbit rendered frame after frame without waiting: the median and
  the longest frame, and the share of what each view wants that is in
  memory when it is drawn.

Output in --out: splat_paging.csv (one row per budget and method) and
splat_paging.png (frame times along the orbit). Timings are wall-clock on
whatever this runs on (llvmpipe here): compare the two methods within one
run, as ratios.
"""
import argparse
import os
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_splat_quality as quality  # noqa: E402
import bench_splat_stream as stream  # noqa: E402
from bench_csv import TEST_DATA, write_rows  # noqa: E402

import pointsurfaces  # noqa: E402


def make_file(mesh, n, path, page_size=None):
    """n noisy points on `mesh`, fitted in memory with three levels, as a splat file
    (pages of `page_size` splats; None: the writer's default)."""
    b = mesh.GetBounds()
    diagonal = ((b[1] - b[0]) ** 2 + (b[3] - b[2]) ** 2 + (b[5] - b[4]) ** 2) ** 0.5
    ply = path + ".ply"
    stream.write_sample(mesh, n, 1e-4, diagonal, ply)
    reader = pointsurfaces.vtkPLYScanReader()
    reader.SetFileName(ply)
    fitter = pointsurfaces.vtkAlgebraicSplatFitter()
    fitter.SetInputConnection(reader.GetOutputPort())
    fitter.SetNumberOfLevels(3)
    writer = pointsurfaces.vtkSplatFileWriter()
    writer.SetInputConnection(fitter.GetOutputPort())
    writer.SetFileName(path)
    if page_size:
        writer.SetPageSize(page_size)
    writer.Write()
    os.remove(ply)


def splat_file(args, mesh, stem, prefix, page_size=None):
    """args.file, or a file of args.points points on `mesh` made here (make_file) in a new
    temporary folder: (path, that folder or None)."""
    if args.file:
        return args.file, None
    scratch = tempfile.mkdtemp(prefix=prefix)
    path = os.path.join(scratch, "%s-%d.psplat" % (stem, int(args.points)))
    make_file(mesh, int(args.points), path, page_size)
    return path, scratch


def remove_made(path, scratch):
    """Delete what splat_file made (nothing when it was given a file)."""
    if scratch:
        os.remove(path)
        os.rmdir(scratch)


def file_header(path):
    """vtkSplatFileReader on `path`, updated within a budget that holds no page: its header."""
    info = pointsurfaces.vtkSplatFileReader()
    info.SetFileName(path)
    info.SetMemoryBudget(1e-6)
    info.GlobalWarningDisplayOff()  # the tiny budget's warning: only the header is wanted
    info.Update()
    return info


def streaming(scene, model, path, budget, frames):
    """vtkStreamingSplatMapper: first picture, whole view, and the orbit without waiting."""
    mapper = pointsurfaces.vtkStreamingSplatMapper()
    mapper.SetFileName(path)
    mapper.SetMemoryBudget(budget)
    stream.show(scene, mapper)
    scene.use(model["cameras"][0])
    start = time.perf_counter()
    scene.window.Render()
    first_frame_ms = 1000.0 * (time.perf_counter() - start)
    while mapper.GetNumberOfResidentSplats() == 0 and mapper.GetLoading():
        mapper.WaitForPages(0.01)
        scene.window.Render()
    first = time.perf_counter() - start
    first_splats = mapper.GetNumberOfResidentSplats()
    mapper.WaitForPages()  # the rest of this view, read by the thread
    loaded = time.perf_counter() - start
    scene.window.Render()
    complete = time.perf_counter() - start
    camera = scene.renderer.GetActiveCamera()
    times, shares = [], []
    for _ in range(frames):
        camera.Azimuth(360.0 / frames)
        t = time.perf_counter()
        scene.window.Render()
        times.append(1000.0 * (time.perf_counter() - t))
        wanted = mapper.GetNumberOfWantedSplats()
        shares.append(min(1.0, mapper.GetNumberOfResidentSplats() / wanted) if wanted else 1.0)
    scene.renderer.RemoveAllViewProps()
    return dict(first_frame_ms=round(first_frame_ms, 1), first_picture_s=round(first, 3),
                first_picture_splats=first_splats, loaded_s=round(loaded, 2),
                complete_s=round(complete, 2),
                resident_splats=mapper.GetNumberOfResidentSplats(),
                gpu_bytes_per_splat=round(mapper.GetBytesPerSplat(), 1),
                orbit_frame_ms=round(float(np.median(times)), 1),
                longest_frame_ms=round(max(times), 1),
                resident_share=round(float(np.mean(shares)), 3)), times


def reader(scene, model, path, budget, frames):
    """vtkSplatFileReader with the camera: every view loads on the render's thread."""
    first, orbit, loaded = stream.picture_and_orbit(scene, model, path, budget, budget, frames)
    return dict(first_frame_ms="", first_picture_s=round(first, 3), first_picture_splats=loaded,
                loaded_s="", complete_s=round(first, 2), resident_splats=loaded, gpu_bytes_per_splat="",
                orbit_frame_ms=round(orbit, 1), longest_frame_ms="", resident_share=1.0)


def plot(series, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axis = plt.subplots(figsize=(7, 4))
    for label, times in series:
        axis.plot(range(1, len(times) + 1), times, marker="o", label=label)
    axis.set_xlabel("orbit step")
    axis.set_ylabel("frame (ms)")
    axis.set_yscale("log")
    axis.set_title("vtkStreamingSplatMapper: frames while pages load")
    axis.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mesh", nargs="?", default=os.path.join(TEST_DATA, "bunny.vtp"))
    parser.add_argument("--file", help="a splat file to draw (default: one made here)")
    parser.add_argument("--points", type=float, default=1e6)
    parser.add_argument("--budgets", type=float, nargs="+", default=[16.0, 64.0, 256.0])
    parser.add_argument("--frames", type=int, default=24)
    parser.add_argument("--size", type=int, default=400, help="image side, pixels")
    parser.add_argument("--up", choices=("x", "y", "z"))
    parser.add_argument("--out", default="bench-results")
    parser.add_argument("--smoke", action="store_true", help="30 000 points, 96 pixels, 4 frames")
    args = parser.parse_args()
    if args.smoke:
        args.points, args.size, args.frames, args.budgets = 3e4, 96, 4, [0.5, 64.0]
    os.makedirs(args.out, exist_ok=True)
    mesh = quality.load_mesh(args.mesh)
    stem = os.path.basename(args.mesh).split(".")[0]
    up = args.up or quality.UP_AXIS.get(stem.split("_")[0], "y")
    scene = quality.Scene((args.size, args.size))
    model = dict(name=stem, cameras=scene.cameras(mesh, up, stream.VIEWS[:1]))
    path, scratch = splat_file(args, mesh, stem, "bench-splat-paging-")
    info = file_header(path)
    rows, series = [], []
    for budget in args.budgets:
        # The reader's budget counts its output's bytes (double arrays), the
        # mapper's its GPU buffers: the reader gets the budget that holds as
        # many splats.
        row, times = streaming(scene, model, path, budget, args.frames)
        series.append(("streaming, %g MB" % budget, times))
        reader_budget = budget * info.GetBytesPerSplat() / row["gpu_bytes_per_splat"]
        peer = reader(scene, model, path, reader_budget, args.frames)
        for method, values, mb in (("reader", peer, reader_budget), ("streaming", row, budget)):
            rows.append(dict(model=stem, file_splats=info.GetNumberOfSplats(),
                             file_mb=round(os.path.getsize(path) / 1e6, 1), budget_mb=budget,
                             method=method, method_budget_mb=round(mb, 1), **values))
            print("# %s" % rows[-1], flush=True)
    write_rows(os.path.join(args.out, "splat_paging.csv"), rows)
    plot(series, os.path.join(args.out, "splat_paging.png"))
    remove_made(path, scratch)
    return 0


if __name__ == "__main__":
    sys.exit(main())
