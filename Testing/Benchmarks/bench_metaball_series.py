#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Per-frame cost of vtkMetaballMapper over a time series: upload, grid, ray cast, memory.

    bench_metaball_series.py [TRAJECTORY] [--frames N] [--particles N] [--size N]
                             [--caster cpu|gpu|auto] [--out DIR] [--smoke]

Plays a time series through one mapper, new positions every frame as a
simulation writes them: by default the vortex of Examples/Python/
particle_animation.py (--particles falling into a swirl, --frames frames),
or every snapshot of a LAMMPS dump or GROMACS .gro trajectory given as
TRAJECTORY. Per frame it records the frame's wall time, the mapper's upload,
grid build and ray-cast times (GetUploadTime, GetGridBuildTime,
GetRayCastTime) and the process's resident memory. It prints the CSV and a
summary: medians, the 95th percentile, the drift of the median frame time
from the first to the last quarter of the series, and the growth of resident
memory after the first tenth. Writes <out>/series.csv and <out>/series.png.
"""
import argparse
import os
import statistics
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "Examples", "Python"))

import pointsurfaces  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkPolyData  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow  # noqa: E402
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401,E402

from particle_animation import Vortex, expand_steps, read_step, spacing_radius  # noqa: E402
from bench_csv import write_rows  # noqa: E402


def resident_mb():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2.0 ** 20


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("trajectory", nargs="?", help="a .lammpstrj, .dump or .gro (default: vortex)")
    parser.add_argument("--frames", type=int, default=200)
    parser.add_argument("--particles", type=int, default=20000)
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--caster", choices=("auto", "cpu", "gpu"), default="auto")
    parser.add_argument("--out", default="bench-results")
    parser.add_argument("--smoke", action="store_true", help="20 frames of 2000 particles at 96²")
    args = parser.parse_args()
    if args.smoke:
        args.frames, args.particles, args.size = 20, 2000, 96
    os.makedirs(args.out, exist_ok=True)
    if not os.environ.get("DISPLAY"):
        pointsurfaces.use_egl()

    steps = expand_steps([args.trajectory]) if args.trajectory else None
    vortex = None if steps else Vortex(args.particles)
    frames = len(steps) if steps else args.frames

    poly = vtkPolyData()
    mapper = pointsurfaces.vtkMetaballMapper()
    mapper.SetInputData(poly)
    mapper.GetField().SetRadiusArrayName("Radius")  # every frame gets one (below)
    mapper.SetRayCaster({"auto": mapper.AUTOMATIC, "cpu": mapper.CPU, "gpu": mapper.GPU}[args.caster])
    mapper.CollectStatisticsOn()  # this frame's times, waited for
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    window = vtkRenderWindow()
    window.SetSize(args.size, args.size)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)

    rows = []
    radius = None
    for k in range(frames):
        if vortex:
            vortex.step()
            xyz, radii = vortex.xyz, None
        else:
            xyz, radii = read_step(*steps[k])
        if radii is None:
            if radius is None:
                radius = spacing_radius(xyz)
            radii = np.full(len(xyz), radius)
        points = vtkPoints()
        points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz, dtype=np.float64), deep=True))
        poly.SetPoints(points)
        r = numpy_to_vtk(np.asarray(radii, dtype=np.float64), deep=True)
        r.SetName("Radius")
        poly.GetPointData().AddArray(r)
        if k == 0:
            camera = renderer.GetActiveCamera()
            camera.SetFocalPoint(0.0, 0.0, 0.0)
            camera.SetPosition(0.0, -4.0, 1.2)
            camera.SetViewUp(0.0, 0.0, 1.0)
            renderer.ResetCamera()
        t0 = time.perf_counter()
        window.Render()
        window.GetZbufferDataAtPoint(0, 0)
        ms = 1000.0 * (time.perf_counter() - t0)
        rows.append(dict(frame=k, balls=len(xyz), frame_ms="%.2f" % ms,
                         upload_ms="%.3f" % mapper.GetUploadTime(),
                         grid_ms="%.3f" % mapper.GetGridBuildTime(),
                         cast_ms="%.3f" % mapper.GetRayCastTime(),
                         hits=mapper.GetNumberOfHits(), uploads=mapper.GetNumberOfUploads(),
                         resident_mb="%.1f" % resident_mb(),
                         caster="cpu" if mapper.GetRayCasterInUse() == mapper.CPU else "gpu"))

    write_rows(os.path.join(args.out, "series.csv"), rows)

    def column(name, part=slice(None)):
        return [float(r[name]) for r in rows[part]]

    quarter = max(1, frames // 4)
    first, last = column("frame_ms", slice(1, quarter + 1)), column("frame_ms", slice(-quarter, None))
    tenth = max(1, frames // 10)
    memory = column("resident_mb")
    print("# %d frames of %d balls at %d², %s ray caster (%s)" % (
        frames, int(rows[-1]["balls"]), args.size, rows[-1]["caster"],
        args.trajectory or "vortex"))
    print("# median ms: frame %.1f, upload %.2f, grid %.2f, ray cast %.1f; frame p95 %.1f" % (
        statistics.median(column("frame_ms", slice(1, None)) or column("frame_ms")),
        statistics.median(column("upload_ms")), statistics.median(column("grid_ms")),
        statistics.median(column("cast_ms")),
        float(np.percentile(column("frame_ms"), 95))))
    print("# drift: median frame of the last quarter / of the first %.3f" % (
        statistics.median(last) / statistics.median(first)))
    print("# resident memory: %.1f MB after %d frames, %.1f MB at the end (%+.1f MB)" % (
        memory[tenth - 1], tenth, memory[-1], memory[-1] - memory[tenth - 1]))
    print("# uploads: %d for %d frames" % (int(rows[-1]["uploads"]), frames))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, mem) = plt.subplots(2, 1, figsize=(6.5, 5), sharex=True)
    x = column("frame")
    for name in ("frame_ms", "upload_ms", "grid_ms", "cast_ms"):
        ax.plot(x, column(name), label=name.replace("_ms", ""), lw=1)
    ax.set_ylabel("ms")
    ax.set_yscale("log")
    ax.legend(fontsize=7, ncol=4)
    ax.grid(True, alpha=0.3)
    mem.plot(x, memory, color="k", lw=1)
    mem.set_ylabel("resident MB")
    mem.set_xlabel("frame")
    mem.grid(True, alpha=0.3)
    fig.suptitle("vtkMetaballMapper over a time series (%s, %s)" % (
        args.trajectory and os.path.basename(args.trajectory) or "vortex", rows[-1]["caster"]))
    fig.tight_layout()
    png = os.path.join(args.out, "series.png")
    fig.savefig(png, dpi=100)
    print("# wrote " + png)
    return 0


if __name__ == "__main__":
    sys.exit(main())
