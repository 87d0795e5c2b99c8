#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""The streaming splat fit against the in-memory one, and a cloud larger than memory.

    bench_splat_stream.py [MESH] [--points N ...] [--noise F] [--chunk-points N]
                          [--memory-limit N] [--budget MB] [--size PX] [--out DIR]
                          [--scratch DIR] [--set NAME=VALUE ...] [--smoke]

MESH (default: Testing/Data/bunny.vtp) is any triangle mesh pointsurfaces.scanio
reads. For each N, N points are sampled uniformly by area on its triangles
(surface_sampling.py, in blocks of 5M so that the sample never sits in
memory whole), moved by Gaussian noise of F times the bounding-box diagonal,
and written as a binary PLY (float x, y, z) in --scratch; the PLY is
deleted afterwards. Then, each in a child process of its own (its peak
resident memory, VmHWM, which the child reports):

- in memory (N up to --memory-limit): vtkPLYScanReader, vtkAlgebraicSplatFitter
  at the defaults, the splats written with vtkSplatFileWriter;
- streamed: vtkPLYScanReader with SplitPoints (one piece a million points),
  vtkStreamingSplatFitter at the same defaults (ChunkPoints --chunk-points),
  writing the splat file.

--set gives fitter properties beyond the defaults to both (for example
ToleranceUnit=1 MaximumFeatureScale=4 NumberOfLevels=3: the noise-aware
tolerance, wider splats where the surface allows, three levels of detail).

Each file is then opened with vtkSplatFileReader: the time to the first
picture (open, load within --first-budget MB with the first view's camera,
draw one frame with vtkAlgebraicSplatMapper's LOD at 1 pixel), then the
frame time of a 12-step orbit that reloads pages for each view within
--budget MB,
and, for files up to 5M splats, the masked SSIM, RMSE and coverage IoU of
the whole file's splats against the mesh in three views (as
bench_splat_quality.py scores them).

Output in --out: splat_stream.csv (one row per sample and method: points,
splats, fit seconds, peak memory, file bytes per point, first picture
seconds, orbit frame milliseconds, scores) and splat_stream.png. Timings
are wall-clock on whatever this runs on: compare the two methods within one
run, as ratios.
"""
import argparse
import json
import os
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_splat_quality as quality  # noqa: E402
from bench_csv import TEST_DATA, peak_resident_gib, run_json_child, write_rows  # noqa: E402
from surface_sampling import sample_surface  # noqa: E402

import pointsurfaces  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkActor  # noqa: E402

VIEWS = [(0, 15), (120, -10), (240, 30)]
SAMPLE_BLOCK = 5_000_000


def write_sample(mesh, n, noise, diagonal, path):
    """n points on the mesh with noise, as a binary little-endian PLY of float x y z."""
    with open(path, "wb") as out:
        out.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
                   "property float x\nproperty float y\nproperty float z\nend_header\n" % n).encode())
        rng = np.random.default_rng(7)
        for block, first in enumerate(range(0, n, SAMPLE_BLOCK)):
            count = min(SAMPLE_BLOCK, n - first)
            xyz = sample_surface(mesh, count, seed=1 + block)
            if noise > 0:
                xyz += rng.normal(0.0, noise * diagonal, xyz.shape)
            out.write(xyz.astype("<f4").tobytes())


def settings(pairs):
    """NAME=VALUE pairs as fitter setters and numbers."""
    out = {}
    for pair in pairs:
        name, value = pair.split("=", 1)
        out[name] = float(value) if "." in value or "e" in value else int(value)
    return out


def configure(fitter, pairs):
    for name, value in settings(pairs).items():
        getattr(fitter, "Set" + name)(value)


def child(args):
    """One fit in this process (run by the parent as a child): prints its timings as JSON."""
    reader = pointsurfaces.vtkPLYScanReader()
    reader.SetFileName(args.child_ply)
    start = time.perf_counter()
    if args.child == "memory":
        fitter = pointsurfaces.vtkAlgebraicSplatFitter()
        fitter.SetInputConnection(reader.GetOutputPort())
        configure(fitter, args.set)
        fitter.Update()
        fit_s = time.perf_counter() - start
        writer = pointsurfaces.vtkSplatFileWriter()
        writer.SetInputConnection(fitter.GetOutputPort())
        writer.SetFileName(args.child_out)
        writer.Write()
        extra = {}
    else:
        reader.SplitPointsOn()
        fitter = pointsurfaces.vtkStreamingSplatFitter()
        fitter.SetInputConnection(reader.GetOutputPort())
        configure(fitter, args.set)
        fitter.SetNumberOfPieces(max(1, args.child_points // 1_000_000))
        fitter.SetChunkPoints(args.chunk_points)
        fitter.SetFileName(args.child_out)
        fitter.SetOutputMemoryBudget(1)  # the output is not what is measured here
        if args.scratch:
            fitter.SetScratchDirectory(args.scratch)
        fitter.Update()
        fit_s = time.perf_counter() - start
        extra = dict(chunks=fitter.GetNumberOfChunks(), halo_points=fitter.GetNumberOfHaloPoints(),
                     largest_chunk=fitter.GetLargestChunk())
    total_s = time.perf_counter() - start
    print(json.dumps(dict(fit_s=fit_s, total_s=total_s, peak_gib=peak_resident_gib(), **extra)))
    return 0


def run_child(args, method, ply, out, n):
    """Runs one fit in a child process; its JSON, with its peak resident memory (peak_gib, which
    the child reports: wait4's ru_maxrss would count the pages it shared with this process until
    exec)."""
    command = [sys.executable, os.path.abspath(__file__), "--child", method, "--child-ply", ply,
               "--child-out", out, "--child-points", str(n), "--chunk-points", str(args.chunk_points)]
    if args.scratch:
        command += ["--scratch", args.scratch]
    if args.set:
        command += ["--set"] + args.set
    return run_json_child(command, "%s fit of %d points" % (method, n))


def reader_for(path, budget):
    reader = pointsurfaces.vtkSplatFileReader()
    reader.SetFileName(path)
    reader.SetMemoryBudget(budget)
    return reader


def show(scene, mapper):
    """`mapper` as the scene's only actor, in the shared material, LOD at 1 pixel, no scalars."""
    mapper.SetLODPixelError(1.0)
    mapper.ScalarVisibilityOff()
    actor = quality.material(vtkActor())
    actor.SetMapper(mapper)
    scene.renderer.RemoveAllViewProps()
    scene.renderer.AddActor(actor)


def picture_and_orbit(scene, model, path, first_budget, budget, frames=12):
    """Seconds to the first picture from a fresh reader, and the orbit's median frame ms."""
    start = time.perf_counter()
    reader = reader_for(path, first_budget)
    camera = scene.renderer.GetActiveCamera()
    scene.use(model["cameras"][0])
    reader.SetCamera(camera)
    size = scene.window.GetSize()
    reader.SetViewportSize(size[0], size[1])
    reader.SetPixelError(1.0)
    mapper = pointsurfaces.vtkAlgebraicSplatMapper()
    mapper.SetInputConnection(reader.GetOutputPort())
    show(scene, mapper)
    scene.window.Render()
    first = time.perf_counter() - start
    loaded = reader.GetNumberOfLoadedSplats()
    reader.SetMemoryBudget(budget)
    scene.window.Render()
    times = []
    for k in range(frames):
        camera.Azimuth(360.0 / frames)
        t = time.perf_counter()
        scene.window.Render()  # the reader reloads for the moved camera within its budget
        times.append(1000.0 * (time.perf_counter() - t))
    scene.renderer.RemoveAllViewProps()
    return first, float(np.median(times)), loaded


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, mid, right) = plt.subplots(1, 3, figsize=(13, 4))
    for method in ("memory", "streamed"):
        mine = sorted((r for r in rows if r["method"] == method), key=lambda r: r["points"])
        if not mine:
            continue
        xs = [r["points"] for r in mine]
        left.plot(xs, [r["fit_s"] for r in mine], marker="o", label=method)
        mid.plot(xs, [r["peak_gb"] for r in mine], marker="o", label=method)
        scored = [r for r in mine if r["masked_ssim"] != ""]
        right.plot([r["points"] for r in scored], [r["masked_ssim"] for r in scored], marker="o",
                   label=method)
    for axis, title in ((left, "fit (s)"), (mid, "peak resident memory (GiB)"),
                        (right, "masked SSIM against the mesh")):
        axis.set_xscale("log")
        axis.set_xlabel("points")
        axis.set_title(title)
        axis.legend(fontsize=8)
    left.set_yscale("log")
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mesh", nargs="?", default=os.path.join(TEST_DATA, "bunny.vtp"))
    parser.add_argument("--points", type=float, nargs="+", default=[1e6])
    parser.add_argument("--noise", type=float, default=1e-4)
    parser.add_argument("--chunk-points", type=int, default=2_000_000)
    parser.add_argument("--memory-limit", type=float, default=1e7,
                        help="largest N also fitted in memory")
    parser.add_argument("--budget", type=float, default=512.0, help="reader's budget in the orbit, MB")
    parser.add_argument("--first-budget", type=float, default=64.0,
                        help="reader's budget for the first picture, MB")
    parser.add_argument("--keep", action="store_true", help="keep the splat files in --scratch")
    parser.add_argument("--size", type=int, default=300, help="image side, pixels")
    parser.add_argument("--up", choices=("x", "y", "z"))
    parser.add_argument("--scratch", default="", help="where the PLY and scratch files go")
    parser.add_argument("--set", nargs="*", default=[], metavar="NAME=VALUE",
                        help="fitter properties beyond the defaults, for both fits")
    parser.add_argument("--out", default="bench-results")
    parser.add_argument("--smoke", action="store_true", help="50 000 points, 96 pixels")
    parser.add_argument("--child", choices=("memory", "streamed"), help=argparse.SUPPRESS)
    parser.add_argument("--child-ply", help=argparse.SUPPRESS)
    parser.add_argument("--child-out", help=argparse.SUPPRESS)
    parser.add_argument("--child-points", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        return child(args)
    if args.smoke:
        args.points, args.size, args.chunk_points = [5e4], 96, 20000
    os.makedirs(args.out, exist_ok=True)
    scratch = args.scratch or tempfile.mkdtemp(prefix="bench-splat-stream-")
    os.makedirs(scratch, exist_ok=True)
    mesh = quality.load_mesh(args.mesh)
    b = mesh.GetBounds()
    diagonal = ((b[1] - b[0]) ** 2 + (b[3] - b[2]) ** 2 + (b[5] - b[4]) ** 2) ** 0.5
    stem = os.path.basename(args.mesh).split(".")[0]
    up = args.up or quality.UP_AXIS.get(stem.split("_")[0], "y")
    scene = quality.Scene((args.size, args.size))
    cameras = scene.cameras(mesh, up, VIEWS)
    model = dict(name=stem, cameras=cameras, views=VIEWS,
                 references=[scene.image(c) for c in cameras])
    rows = []
    for n in [int(p) for p in args.points]:
        ply = os.path.join(scratch, "%s-%d.ply" % (stem, n))
        start = time.perf_counter()
        write_sample(mesh, n, args.noise, diagonal, ply)
        print("# sampled %d points in %.1f s" % (n, time.perf_counter() - start), flush=True)
        methods = ["memory", "streamed"] if n <= args.memory_limit else ["streamed"]
        for method in methods:
            path = os.path.join(scratch, "%s-%d-%s.psplat" % (stem, n, method))
            result = run_child(args, method, ply, path, n)
            splats = reader_for(path, 1)
            splats.Update()
            count = splats.GetNumberOfSplats()
            first, orbit, loaded = picture_and_orbit(scene, model, path, args.first_budget,
                                                     args.budget)
            row = dict(model=stem, points=n, noise=args.noise, method=method,
                       settings=" ".join(args.set) or "defaults", splats=count,
                       fit_s=round(result["fit_s"], 2), peak_gb=round(result["peak_gib"], 3),
                       file_bytes_per_point=round(os.path.getsize(path) / n, 2),
                       chunks=result.get("chunks", ""), largest_chunk=result.get("largest_chunk", ""),
                       first_budget_mb=args.first_budget, budget_mb=args.budget,
                       first_picture_s=round(first, 2),
                       first_picture_splats=loaded, orbit_frame_ms=round(orbit, 1),
                       masked_ssim="", masked_rmse="", coverage_iou="")
            if count <= 5_000_000:
                whole = reader_for(path, 0)
                whole.Update()
                scores = quality.score_actor(scene, model, quality.splat_actor(whole.GetOutput()), 0)
                for key in ("masked_ssim", "masked_rmse", "coverage_iou"):
                    row[key] = round(float(np.mean([s[key] for s in scores])), 4)
            rows.append(row)
            print("# %s" % row, flush=True)
            if not args.keep:
                os.remove(path)
        os.remove(ply)
    write_rows(os.path.join(args.out, "splat_stream.csv"), rows)
    plot(rows, os.path.join(args.out, "splat_stream.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
