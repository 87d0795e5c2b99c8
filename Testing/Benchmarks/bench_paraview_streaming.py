# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""A splat file in ParaView: Streaming Splats against the reader's output as Algebraic Splats (pvbatch).

    pvbatch bench_paraview_streaming.py PLUGIN [FILE] [--budgets MB ...] [--peer-budget MB]
                                        [--reader-budgets MB ...] [--no-peer]
                                        [--frames N] [--size PX] [--out DIR] [--smoke]

FILE is a splat file (`.psplat`, from vtkStreamingSplatFitter or
`bench_splat_stream.py --keep`); with --smoke, a small one is fitted here
from a sphere. In one pvbatch process, for each --budgets value:

- **streaming**: *File > Open* (the Splat File Reader at its defaults)
  shown as Streaming Splats with SplatStreamingBudget MB of GPU buffers,
  asynchronous and, as in the GUI, never waiting (SplatStreamingBatchWait
  0; pvbatch's default waits for each view's pages): the time the reader's update takes, the first render, the
  first picture with splats and the picture with all the view wants (each
  from the moment the file was named), then an orbit of --frames steps,
  each frame rendered at once (pages arrive between frames);
- with --reader-budgets, the same with the reader's own output (what
  other filters see) held to those MB instead of its default;
- **reader** (the peer, what ParaView drew before Streaming Splats): the
  Splat File Reader with MemoryBudget --peer-budget MB (1024, its former
  default) shown as Algebraic Splats: the first picture after the reader
  loaded, then the same orbit.

LOD is at 1 pixel for both. Output in --out: paraview_streaming.csv (one
row per budget and method) and paraview_streaming.png. Timings are
wall-clock: compare the methods within one run, as ratios.
"""
import argparse
import os
import statistics
import sys
import time

from paraview.simple import (CreateRenderView, Delete, GetActiveCamera, Hide, LoadPlugin,
                             OpenDataFile, Render, ResetCamera, Show, Sphere)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_csv import write_rows  # noqa: E402


def make_smoke_file(path):
    sphere = Sphere(ThetaResolution=160, PhiResolution=160)
    fit = globals()["StreamingSplatFitter"](Input=sphere)  # from the plugin
    fit.FileName = path
    fit.ChunkPoints = 5000
    fit.NumberOfLevels = 2
    fit.PageSize = 256
    fit.UpdatePipeline()
    Delete(fit)
    Delete(sphere)


def orbit(view, frames):
    """Frame times (ms) of `frames` renders, the camera a step further round each time."""
    times = []
    camera = GetActiveCamera()
    for _ in range(frames):
        camera.Azimuth(360.0 / frames)
        start = time.perf_counter()
        Render(view)
        times.append(1e3 * (time.perf_counter() - start))
    return times


def info(display, name):
    display.UpdatePropertyInformation()
    return display.GetPropertyValue(name)


def run_streaming(view, path, budget, frames, reader_budget):
    start = time.perf_counter()
    reader = OpenDataFile(path)
    if reader_budget is not None:
        reader.MemoryBudget = reader_budget
    reader.UpdatePipeline()
    reader_s = time.perf_counter() - start
    display = Show(reader, view)
    display.SetRepresentationType("Streaming Splats")
    display.SplatLODPixelError = 1.0
    display.SplatStreamingBudget = budget
    display.SplatStreamingAsynchronous = 1
    display.SplatStreamingBatchWait = 0  # as in the GUI: renders never wait for the disk
    ResetCamera(view)
    first = time.perf_counter()
    Render(view)
    first_frame_ms = 1e3 * (time.perf_counter() - first)
    first_picture_s = None
    first_splats = 0
    deadline = time.perf_counter() + 600
    while time.perf_counter() < deadline:
        resident = info(display, "SplatStreamingResidentSplats")
        if resident > 0 and first_picture_s is None:
            first_picture_s = time.perf_counter() - start
            first_splats = resident
        if not info(display, "SplatStreamingLoading"):
            break
        time.sleep(0.01)
        Render(view)
    Render(view)
    complete_s = time.perf_counter() - start
    wanted = info(display, "SplatStreamingWantedSplats")
    resident = info(display, "SplatStreamingResidentSplats")
    times = orbit(view, frames)
    method = "streaming" if reader_budget is None else "streaming_reader_%g" % reader_budget
    row = dict(budget_mb=budget, method=method, file_splats=info(display, "SplatStreamingFileSplats"),
               reader_s=round(reader_s, 3), first_frame_ms=round(first_frame_ms, 1),
               first_picture_s=round(first_picture_s or complete_s, 3), first_picture_splats=first_splats,
               complete_s=round(complete_s, 3), drawn_splats=max(wanted, resident),
               orbit_frame_ms=round(statistics.median(times), 1), longest_frame_ms=round(max(times), 1))
    Hide(reader, view)
    Delete(reader)
    return row


def run_reader(view, path, budget, peer_budget, frames):
    start = time.perf_counter()
    reader = OpenDataFile(path)
    reader.MemoryBudget = peer_budget
    reader.UpdatePipeline()
    reader_s = time.perf_counter() - start
    display = Show(reader, view)
    display.SetRepresentationType("Algebraic Splats")
    display.SplatLODPixelError = 1.0
    ResetCamera(view)
    first = time.perf_counter()
    Render(view)
    first_frame_ms = 1e3 * (time.perf_counter() - first)
    complete_s = time.perf_counter() - start
    loaded = reader.GetDataInformation().GetNumberOfPoints()
    times = orbit(view, frames)
    row = dict(budget_mb=budget, method="reader_%g" % peer_budget, file_splats="",
               reader_s=round(reader_s, 3), first_frame_ms=round(first_frame_ms, 1),
               first_picture_s=round(complete_s, 3), first_picture_splats=loaded,
               complete_s=round(complete_s, 3), drawn_splats=loaded,
               orbit_frame_ms=round(statistics.median(times), 1), longest_frame_ms=round(max(times), 1))
    Hide(reader, view)
    Delete(reader)
    return row


def plot(rows, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("bench_paraview_streaming.py: no matplotlib: no plot", file=sys.stderr)
        return
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for method in sorted({r["method"] for r in rows}):
        mine = [r for r in rows if r["method"] == method]
        x = [r["budget_mb"] for r in mine]
        axes[0].plot(x, [r["first_picture_s"] for r in mine], marker="o", label=method + " first picture")
        axes[0].plot(x, [r["complete_s"] for r in mine], marker="s", linestyle="--",
                     label=method + " complete")
        axes[1].plot(x, [r["orbit_frame_ms"] for r in mine], marker="o", label=method)
    axes[0].set_ylabel("seconds from File > Open")
    axes[1].set_ylabel("median orbit frame, ms")
    for ax in axes:
        ax.set_xlabel("Streaming Splats budget, MB")
        ax.set_xscale("log")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("plugin")
    parser.add_argument("file", nargs="?")
    parser.add_argument("--budgets", type=float, nargs="+", default=[64.0, 256.0])
    parser.add_argument("--peer-budget", type=float, default=1024.0)
    parser.add_argument("--reader-budgets", type=float, nargs="+", default=[],
                        help="also Streaming Splats with the reader's MemoryBudget at these MB")
    parser.add_argument("--no-peer", action="store_true", help="Streaming Splats only")
    parser.add_argument("--frames", type=int, default=12)
    parser.add_argument("--size", type=int, default=600)
    parser.add_argument("--out", default="bench-results")
    parser.add_argument("--smoke", action="store_true", help="a sphere's file, 0.2 and 1 MB, 4 frames")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    LoadPlugin(args.plugin, ns=globals())
    path = args.file
    if args.smoke:
        path = os.path.join(args.out, "paraview_streaming_smoke.psplat")
        make_smoke_file(path)
        args.budgets, args.frames, args.size, args.peer_budget = [0.2, 1.0], 4, 96, 0.5
    if not path or not os.path.isfile(path):
        parser.error("no splat file (give FILE, or --smoke)")
    view = CreateRenderView()
    view.ViewSize = [args.size, args.size]
    view.OrientationAxesVisibility = 0
    rows = []
    for budget in args.budgets:
        rows.append(run_streaming(view, path, budget, args.frames, None))
        for reader_budget in args.reader_budgets:
            rows.append(run_streaming(view, path, budget, args.frames, reader_budget))
        if not args.no_peer:
            rows.append(run_reader(view, path, budget, args.peer_budget, args.frames))
    name = "paraview_streaming" + ("_smoke" if args.smoke else "")
    write_rows(os.path.join(args.out, name + ".csv"), rows)
    plot(rows, os.path.join(args.out, name + ".png"))
    Delete(view)  # before pvbatch's exit tears the context down
    del view
    if any(r["drawn_splats"] == 0 for r in rows):
        print("bench_paraview_streaming.py: a method drew nothing", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
