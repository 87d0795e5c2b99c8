#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Sweep the metaball ray caster's speed/accuracy knobs and plot error against time.

    speed_accuracy_sweep.py [input.pdb] [output.png] [--size N]
                            [--steps 0.8,0.4,...] [--bisections 0,2,...]

input.pdb is any PDB file (default: Testing/Data/hemoglobin_chainA.pdb, chain
A of hemoglobin 3GQP, 1 079 atoms, which a clone has); output.png defaults to
sweep.png in the current folder.

vtkMetaballMapper marches each ray in steps of StepScale times the smallest
radius (longer where the field is far from T), then refines the crossing by
Bisections halvings. Smaller steps and more bisections cost time and buy
accuracy. For every pair, this renders the molecule (atoms as metaballs, as
molecule_metaballs.py does) and measures against a fine reference (step
0.02, 20 bisections) rendered in the same window:

- depth error: the 99th percentile of |z - z_ref| over the pixels both
  images cover, in units of the smallest atom radius;
- silhouette error: the share of pixels covered by one image but not the
  other;
- frame time: the median of 3 frames.

Writes the plot to output.png and the table to output.csv, and prints it.
"""
import argparse
import csv
import os
import statistics
import sys
import time

import numpy as np

import pointsurfaces
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkIOChemistry import vtkPDBReader
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

HERE = os.path.dirname(os.path.abspath(__file__))
# Chain A of hemoglobin (PDB 3GQP, 1 079 atoms), which a clone has.
DEFAULT_INPUT = os.path.join(HERE, "..", "..", "Testing", "Data", "hemoglobin_chainA.pdb")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input", nargs="?", default=DEFAULT_INPUT,
                        help="any PDB file (default: Testing/Data/hemoglobin_chainA.pdb)")
    parser.add_argument("output", nargs="?", default="sweep.png",
                        help="the plot (default: sweep.png); the table goes beside it as .csv")
    parser.add_argument("--size", type=int, default=400)
    parser.add_argument("--steps", default="0.8,0.4,0.2,0.1,0.05")
    parser.add_argument("--bisections", default="0,2,5,10")
    args = parser.parse_args()
    if not os.path.exists(args.input):
        print("speed_accuracy_sweep.py: no such file: " + args.input)
        return 1
    if not os.environ.get("DISPLAY"):
        pointsurfaces.use_egl()
    steps = [float(v) for v in args.steps.split(",")]
    bisections = [int(v) for v in args.bisections.split(",")]

    reader = vtkPDBReader()
    reader.SetFileName(args.input)
    reader.Update()
    radii = vtk_to_numpy(reader.GetOutput().GetPointData().GetArray("radius"))
    smallest = 2.0 * float(np.min(radii.reshape(len(radii), -1)[:, 0]))  # RadiusScale 2

    mapper = pointsurfaces.vtkMetaballMapper()
    mapper.SetInputConnection(reader.GetOutputPort())
    mapper.GetField().SetRadiusArrayName("radius")
    mapper.GetField().SetRadiusScale(2.0)
    mapper.SetColorModeToDirectScalars()
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("rgb_colors")
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    window = vtkRenderWindow()
    window.SetSize(args.size, args.size)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    camera = renderer.GetActiveCamera()
    camera.Zoom(1.4)

    def render(step, bisect, frames=3):
        mapper.SetStepScale(step)
        mapper.SetBisections(bisect)
        window.Render()
        times = []
        for _ in range(frames):
            t0 = time.perf_counter()
            window.Render()
            window.GetZbufferDataAtPoint(0, 0)
            times.append(1000.0 * (time.perf_counter() - t0))
        z = vtkFloatArray()
        window.GetZbufferData(0, 0, args.size - 1, args.size - 1, z)
        return statistics.median(times), vtk_to_numpy(z).astype(np.float64)

    def view_distance(z):
        # Window depth to distance along the view axis (perspective).
        near, far = camera.GetClippingRange()
        ndc = 2.0 * z - 1.0
        return 2.0 * near * far / (far + near - ndc * (far - near))

    _, z_ref = render(0.02, 20, frames=1)
    covered_ref = z_ref < 1.0
    d_ref = view_distance(z_ref)
    rows = []
    for bisect in bisections:
        for step in steps:
            ms, z = render(step, bisect)
            covered = z < 1.0
            both = covered & covered_ref
            depth = np.abs(view_distance(z[both]) - d_ref[both]) / smallest
            rows.append(dict(step=step, bisections=bisect, frame_ms="%.1f" % ms,
                             depth_p99="%.3g" % (np.percentile(depth, 99) if depth.size else 0),
                             silhouette="%.4f" % (np.count_nonzero(covered != covered_ref)
                                                  / max(1, np.count_nonzero(covered_ref))),
                             incomplete=mapper.GetNumberOfIncompleteRays()))

    base = os.path.splitext(args.output)[0]
    fields = ["step", "bisections", "frame_ms", "depth_p99", "silhouette", "incomplete"]
    with open(base + ".csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        writer.writerows(rows)
    writer = csv.DictWriter(sys.stdout, fieldnames=fields)
    writer.writeheader()
    writer.writerows(rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for bisect in bisections:
        sel = [r for r in rows if r["bisections"] == bisect]
        t = [float(r["frame_ms"]) for r in sel]
        e = [max(float(r["depth_p99"]), 1e-7) for r in sel]
        ax.plot(t, e, marker="o", label="%d bisections" % bisect)
        for r, x, y in zip(sel, t, e):
            ax.annotate("%g" % r["step"], (x, y), fontsize=6, xytext=(3, 3),
                        textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("frame time (ms, median of 3, %dx%d)" % (args.size, args.size))
    ax.set_ylabel("depth error p99 (smallest radii)")
    ax.set_title("%s: %d atoms, labels = step scale" % (os.path.basename(args.input),
                                                        reader.GetOutput().GetNumberOfPoints()))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)
    print("sweep:        %d settings, %d atoms, %s" % (len(rows),
                                                       reader.GetOutput().GetNumberOfPoints(),
                                                       window.GetClassName()))
    print("plot:         %s (table %s.csv)" % (args.output, base))
    return 0


if __name__ == "__main__":
    sys.exit(main())
