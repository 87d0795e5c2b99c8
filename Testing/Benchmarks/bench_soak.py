#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""A soak of the time-series paths: memory, frame times and warnings over thousands of frames.

    bench_soak.py [--metaball-frames N] [--splat-frames N] [--particles N]
                  [--points N] [--size N] [--out DIR] [--smoke]

1. Metaballs: writes a LAMMPS dump of --metaball-frames snapshots of
   --particles atoms (the vortex of Examples/Python/particle_animation.py;
   made here in a scratch folder under DIR and deleted after, not
   committed), and plays it through one vtkLAMMPSDumpReader and one
   vtkMetaballMapper on the CPU ray caster, one time step a frame.
2. Splats: --splat-frames frames of a wobbling torus of --points points,
   new coordinates every frame, through one vtkAlgebraicSplatFitter and one
   vtkAlgebraicSplatMapper.

Per frame it records the wall time, the process's resident memory and the
warnings and errors VTK reported. It prints, per part: resident memory
after the warm-up (the first tenth) and at the end, the median frame time
of the last tenth against the first tenth (after the first frame), and the
warnings: how many, and whether any text came back frame after frame.
Writes <out>/soak_metaballs.csv, <out>/soak_splats.csv (per frame),
<out>/soak_summary.csv (those figures) and <out>/soak.png.
Exit status 1 when memory grew by more than 10 % after the warm-up or a
warning repeated on more than a tenth of the frames (a benchmark: run it by
hand, `ctest -L bench` runs only its smoke size).
"""
import argparse
import os
import shutil
import statistics
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "Examples", "Python"))

import pointsurfaces  # noqa: E402
from vtkmodules.util.misc import calldata_type  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402
from vtkmodules.util.vtkConstants import VTK_STRING  # noqa: E402
from vtkmodules.vtkCommonCore import vtkCommand, vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkPolyData  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow  # noqa: E402
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401,E402

from particle_animation import Vortex, spacing_radius  # noqa: E402
from bench_csv import write_rows  # noqa: E402


def resident_mb():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2.0 ** 20


class Messages:
    """Counts the warnings and errors of the observed objects, per frame and by text."""

    def __init__(self, *objects):
        self.frame = []
        self.frames_by_text = {}

        @calldata_type(VTK_STRING)
        def seen(obj, event, text):
            # The text without its "ERROR: In file, line N" prefix line.
            self.frame.append(obj.GetClassName() + " " + event + ": " +
                              (text or "").strip().split("\n")[-1])

        for obj in objects:
            obj.AddObserver(vtkCommand.WarningEvent, seen)
            obj.AddObserver(vtkCommand.ErrorEvent, seen)

    def end_frame(self):
        """The number of messages of the frame just drawn."""
        count = len(self.frame)
        for text in set(self.frame):
            self.frames_by_text[text] = self.frames_by_text.get(text, 0) + 1
        self.frame = []
        return count


class Record:
    """Per-frame figures in arrays allocated up front, so that the soak's own
    bookkeeping does not grow the memory it measures."""

    def __init__(self, frames, count_name):
        self.count_name = count_name
        self.values = np.zeros((frames, 4))  # frame ms, resident MB, count, messages

    def add(self, k, ms, count, messages):
        self.values[k] = (ms, resident_mb(), count, messages)

    def rows(self):
        return [dict([("frame", k), ("frame_ms", "%.2f" % v[0]), ("resident_mb", "%.1f" % v[1]),
                      (self.count_name, int(v[2])), ("messages", int(v[3]))])
                for k, v in enumerate(self.values)]


def write_lammps(path, frames, particles):
    """A LAMMPS dump of the vortex: `frames` snapshots of `particles` atoms."""
    vortex = Vortex(particles)
    ids = np.arange(1, particles + 1)
    with open(path, "w") as f:
        for k in range(frames):
            vortex.step()
            f.write("ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n%d\n" % (k, particles))
            f.write("ITEM: BOX BOUNDS ss ss ss\n-1.5 1.5\n-1.5 1.5\n-1.5 1.5\n")
            f.write("ITEM: ATOMS id type x y z\n")
            block = np.column_stack([ids, np.ones(particles), vortex.xyz])
            np.savetxt(f, block, fmt="%d %d %.5f %.5f %.5f")


def window_for(actor, size):
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    window = vtkRenderWindow()
    window.SetSize(size, size)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)
    return window, renderer


def frame(window):
    """Renders and waits for it; milliseconds."""
    t0 = time.perf_counter()
    window.Render()
    window.GetZbufferDataAtPoint(0, 0)
    return 1000.0 * (time.perf_counter() - t0)


def soak_metaballs(args, scratch):
    dump = os.path.join(scratch, "vortex.lammpstrj")
    write_lammps(dump, args.metaball_frames, args.particles)
    reader = pointsurfaces.vtkLAMMPSDumpReader()
    reader.SetFileName(dump)
    reader.UpdateInformation()
    mapper = pointsurfaces.vtkMetaballMapper()
    mapper.SetInputConnection(reader.GetOutputPort())
    mapper.SetRayCasterToCPU()
    mapper.GetField().SetRadius(spacing_radius(Vortex(args.particles).xyz))
    actor = vtkActor()
    actor.SetMapper(mapper)
    window, renderer = window_for(actor, args.size)
    messages = Messages(reader, mapper)
    record = Record(args.metaball_frames, "hits")
    for k in range(args.metaball_frames):
        reader.UpdateTimeStep(float(k))
        if k == 0:
            camera = renderer.GetActiveCamera()
            camera.SetPosition(0.0, -4.0, 1.2)
            camera.SetViewUp(0.0, 0.0, 1.0)
            renderer.ResetCamera()
        ms = frame(window)
        record.add(k, ms, mapper.GetNumberOfHits(), messages.end_frame())
    os.remove(dump)
    return record.rows(), messages


def wobbling_torus(n, k, rng_points):
    """A torus (R = 1, r = 0.35) whose tube radius ripples with the frame `k`."""
    u, v = rng_points
    r = 0.35 * (1.0 + 0.15 * np.sin(3.0 * u + 0.05 * k))
    return np.column_stack([(1.0 + r * np.cos(v)) * np.cos(u), (1.0 + r * np.cos(v)) * np.sin(u),
                            r * np.sin(v)])


def soak_splats(args):
    rng = np.random.default_rng(5)
    uv = (rng.uniform(0.0, 2.0 * np.pi, args.points), rng.uniform(0.0, 2.0 * np.pi, args.points))
    poly = vtkPolyData()
    fitter = pointsurfaces.vtkAlgebraicSplatFitter()
    fitter.SetInputData(poly)
    mapper = pointsurfaces.vtkAlgebraicSplatMapper()
    mapper.SetInputConnection(fitter.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    window, renderer = window_for(actor, args.size)
    messages = Messages(fitter, mapper)
    record = Record(args.splat_frames, "splats")
    for k in range(args.splat_frames):
        points = vtkPoints()
        points.SetData(numpy_to_vtk(wobbling_torus(args.points, k, uv), deep=True))
        poly.SetPoints(points)
        poly.Modified()
        if k == 0:
            renderer.GetActiveCamera().SetPosition(0.0, -3.0, 2.0)
            renderer.ResetCamera()
        ms = frame(window)
        record.add(k, ms, fitter.GetOutput().GetNumberOfPoints(), messages.end_frame())
    return record.rows(), messages


def summarise(name, rows, messages):
    """Prints the part's figures; returns them as a row of soak_summary.csv."""
    n = len(rows)
    tenth = max(2, n // 10)
    times = [float(r["frame_ms"]) for r in rows]
    memory = [float(r["resident_mb"]) for r in rows]
    first, last = statistics.median(times[1:tenth + 1]), statistics.median(times[-tenth:])
    growth = (memory[-1] - memory[tenth - 1]) / memory[tenth - 1]
    repeated = max(messages.frames_by_text.values(), default=0)
    print("# %s: %d frames; resident %.1f MB after %d frames (warm-up), %.1f MB at the end (%+.1f %%)"
          % (name, n, memory[tenth - 1], tenth, memory[-1], 100.0 * growth))
    print("# %s: median frame %.2f ms in the first tenth, %.2f ms in the last (ratio %.3f)"
          % (name, first, last, last / first))
    print("# %s: %d messages; the most frequent came in %d of %d frames%s"
          % (name, sum(int(r["messages"]) for r in rows), repeated, n,
             "" if not messages.frames_by_text else
             " (%s)" % max(messages.frames_by_text, key=messages.frames_by_text.get)))
    return dict(part=name, frames=n, warmup_frames=tenth, warmup_mb="%.1f" % memory[tenth - 1],
                end_mb="%.1f" % memory[-1], growth_percent="%.2f" % (100.0 * growth),
                first_tenth_ms="%.2f" % first, last_tenth_ms="%.2f" % last,
                time_ratio="%.3f" % (last / first),
                messages=sum(int(r["messages"]) for r in rows), most_repeated_frames=repeated)


def plot(out, parts):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, len(parts), figsize=(5.0 * len(parts), 5), squeeze=False)
    for column, (name, rows) in enumerate(parts):
        x = [int(r["frame"]) for r in rows]
        axes[0][column].plot(x, [float(r["frame_ms"]) for r in rows], lw=0.5)
        axes[0][column].set_title(name)
        axes[0][column].set_ylabel("frame ms")
        axes[0][column].set_yscale("log")
        axes[1][column].plot(x, [float(r["resident_mb"]) for r in rows], color="k", lw=1)
        axes[1][column].set_ylabel("resident MB")
        axes[1][column].set_xlabel("frame")
        for ax in axes[:, column]:
            ax.grid(True, alpha=0.3)
    fig.tight_layout()
    png = os.path.join(out, "soak.png")
    fig.savefig(png, dpi=100)
    print("# wrote " + png)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--metaball-frames", type=int, default=10000)
    parser.add_argument("--splat-frames", type=int, default=1000)
    parser.add_argument("--particles", type=int, default=400, help="atoms of the LAMMPS series")
    parser.add_argument("--points", type=int, default=4000, help="points of the splat series")
    parser.add_argument("--size", type=int, default=160)
    parser.add_argument("--out", default="bench-results")
    parser.add_argument("--smoke", action="store_true", help="40 and 20 frames")
    args = parser.parse_args()
    if args.smoke:
        args.metaball_frames, args.splat_frames, args.particles, args.points = 40, 20, 200, 1500
    os.makedirs(args.out, exist_ok=True)
    if not os.environ.get("DISPLAY"):
        pointsurfaces.use_egl()
    scratch = os.path.join(args.out, "soak-scratch")
    os.makedirs(scratch, exist_ok=True)
    try:
        metaballs, metaball_messages = soak_metaballs(args, scratch)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    write_rows(os.path.join(args.out, "soak_metaballs.csv"), metaballs)
    splats, splat_messages = soak_splats(args)
    write_rows(os.path.join(args.out, "soak_splats.csv"), splats)
    results = [summarise("metaballs (LAMMPS reader, CPU caster)", metaballs, metaball_messages),
               summarise("splats (fitter and mapper)", splats, splat_messages)]
    write_rows(os.path.join(args.out, "soak_summary.csv"), results)
    plot(args.out, [("metaballs: LAMMPS reader, CPU caster", metaballs),
                    ("splats: fitter and mapper", splats)])
    if args.smoke:
        return 0  # too few frames for the verdicts
    ok = all(float(r["growth_percent"]) <= 10.0 and r["most_repeated_frames"] <= r["frames"] / 10
             for r in results)
    print("# verdict: %s" % ("flat memory, no warning repeated per frame" if ok else "FAILED"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
