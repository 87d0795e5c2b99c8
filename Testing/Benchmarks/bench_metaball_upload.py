#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""The metaball upload's host time per million balls, and the read-backs per frame.

    bench_metaball_upload.py [--balls N ...] [--frames N] [--out DIR] [--smoke]

Every frame of a time series changes every ball, so vtkMetaballMapper's
upload is on the per-frame path. For float and double points, with one
radius or a float radius array, this plays --frames frames of --balls balls
(new positions each frame, as a simulation writes them) through two mappers
in the same process:

- `gpu`: the GPU ray caster's upload (vtkMetaballUploader): the arrays go
  to the GPU as the input holds them (float as it is, double converted in
  parallel in one pass) and a compute pass assembles the balls;
- `host` (the peer): the CPU ray caster's upload, the path every frame took
  before: the balls extracted in double, converted to float vec4 on the
  host, then copied to the GPU.

Per configuration it reports the median of the mapper's GetUploadTime (ms,
host wall time of the whole upload), of GetUploadCopyTime (the `gpu` path's
writes into the mapped buffers: its one host copy), both per million balls,
the bytes a ball sent, the host's copy rate in GB/s, the `gpu` upload's
time as a fraction of the `host` one, and the read-backs that waited for the
GPU in the frames after the first (GetNumberOfReadBacks; CollectStatistics
off). On a software renderer (llvmpipe) the assembly pass runs on the CPU
inside the upload's time; on a GPU it does not. Writes <out>/metaball_upload.csv
and <out>/metaball_upload.png.
"""
import argparse
import os
import statistics
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "Examples", "Python"))

import pointsurfaces  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkPolyData  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow  # noqa: E402
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401,E402

from bench_csv import write_rows  # noqa: E402


def play(n, dtype, radius_array, path, frames, size):
    """Median upload times of `frames` dynamic frames of n balls on one path."""
    rng = np.random.default_rng(3)
    xyz = rng.uniform(-1.0, 1.0, (n, 3)).astype(dtype)
    points = vtkPoints()
    points.SetData(numpy_to_vtk(xyz, deep=False))
    poly = vtkPolyData()
    poly.SetPoints(points)
    radius = 1.5 / n ** (1.0 / 3.0)
    mapper = pointsurfaces.vtkMetaballMapper()
    if radius_array:
        radii = numpy_to_vtk(rng.uniform(0.5 * radius, radius, n).astype(np.float32), deep=True)
        radii.SetName("Radius")
        poly.GetPointData().AddArray(radii)
        mapper.GetField().SetRadiusArrayName("Radius")
    else:
        mapper.GetField().SetRadius(radius)
    mapper.SetInputData(poly)
    mapper.SetRayCaster(mapper.GPU if path == "gpu" else mapper.CPU)
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    window = vtkRenderWindow()
    window.SetSize(size, size)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)
    renderer.GetActiveCamera().SetPosition(0.0, 0.0, 40.0)  # small on screen: the upload dominates
    renderer.ResetCameraClippingRange()
    upload, copy, readbacks = [], [], None
    for frame in range(frames):
        xyz += np.asarray(rng.normal(0.0, 1e-3, 3), dtype=dtype)  # every ball moves
        points.Modified()
        window.Render()
        window.GetZbufferDataAtPoint(0, 0)
        if frame == 0:
            readbacks = mapper.GetNumberOfReadBacks()
        else:
            upload.append(mapper.GetUploadTime())
            copy.append(mapper.GetUploadCopyTime())
    per_frame = (mapper.GetNumberOfReadBacks() - readbacks) / max(1, frames - 1)
    bytes_per_ball = mapper.GetUploadedBytes() / n
    window.Finalize()
    return statistics.median(upload), statistics.median(copy), bytes_per_ball, per_frame


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--balls", type=int, nargs="+", default=[1000000, 4000000])
    parser.add_argument("--frames", type=int, default=6)
    parser.add_argument("--size", type=int, default=64)
    parser.add_argument("--out", default="bench-results")
    parser.add_argument("--smoke", action="store_true", help="3 frames of 20 000 balls")
    args = parser.parse_args()
    if args.smoke:
        args.balls, args.frames = [20000], 3
    os.makedirs(args.out, exist_ok=True)
    if not os.environ.get("DISPLAY"):
        pointsurfaces.use_egl()

    rows = []
    for n in args.balls:
        for dtype, type_name in ((np.float32, "float"), (np.float64, "double")):
            for radius_array in (False, True):
                host = None
                for path in ("host", "gpu"):
                    ms, copy_ms, bytes_per_ball, readbacks = play(
                        n, dtype, radius_array, path, args.frames, args.size)
                    host = ms if path == "host" else host
                    million = n / 1e6
                    rows.append(dict(
                        balls=n, points=type_name,
                        radii="float array" if radius_array else "one radius", path=path,
                        upload_ms="%.2f" % ms, upload_ms_per_million="%.2f" % (ms / million),
                        copy_ms_per_million="%.2f" % (copy_ms / million) if path == "gpu" else "",
                        bytes_per_ball="%.0f" % bytes_per_ball,
                        copy_gb_s="%.2f" % (bytes_per_ball * n / copy_ms / 1e6)
                        if path == "gpu" and copy_ms > 0 else "",
                        vs_host="%.2f" % (ms / host),
                        readbacks_per_frame="%.2f" % readbacks))
    write_rows(os.path.join(args.out, "metaball_upload.csv"), rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 5))
    labels = sorted({(r["points"], r["radii"]) for r in rows})
    width = 0.8 / (2 * len(args.balls))
    for j, n in enumerate(args.balls):
        for k, path in enumerate(("host", "gpu")):
            picked = [next(r for r in rows if r["balls"] == n and r["path"] == path
                           and (r["points"], r["radii"]) == label) for label in labels]
            total = [float(r["upload_ms_per_million"]) for r in picked]
            x = [i + (2 * j + k) * width for i in range(len(labels))]
            name = "%.0fM" % (n / 1e6) if n >= 1e6 else "%d" % n
            if path == "host":
                ax.bar(x, total, width, color="C%d" % (2 * j), label="host path, %s balls" % name)
            else:
                copy = [float(r["copy_ms_per_million"]) for r in picked]
                ax.bar(x, copy, width, color="C%d" % (2 * j + 1),
                       label="GPU caster: host copy, %s balls" % name)
                ax.bar(x, [t - c for t, c in zip(total, copy)], width, bottom=copy,
                       color="C%d" % (2 * j + 1), alpha=0.35, hatch="//",
                       label="GPU caster: assembly pass and driver, %s balls" % name)
    ax.set_xticks([i + 0.4 - width / 2 for i in range(len(labels))])
    ax.set_xticklabels(["%s points\n%s" % label for label in labels], fontsize=8)
    ax.set_ylabel("upload ms per million balls")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3)
    ax.grid(True, axis="y", alpha=0.3)
    fig.suptitle("vtkMetaballMapper upload per million balls (hatched: the assembly pass,\n"
                 "which a software renderer runs on the CPU)", fontsize=10)
    fig.tight_layout()
    png = os.path.join(args.out, "metaball_upload.png")
    fig.savefig(png, dpi=100)
    print("# wrote " + png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
