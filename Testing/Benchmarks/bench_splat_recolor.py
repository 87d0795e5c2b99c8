#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""What a change of colouring costs a render: vtkAlgebraicSplatMapper against
vtkPointGaussianMapper over the same splat centres, in the same window.

A mesh (default: the Bunny, Testing/Data/bunny.vtp) is sampled uniformly by
area at each --points N and fitted at the fitter's defaults; the splats get
two scalar arrays. Each mapper colours them by the first array through a
lookup table, and the camera looks away from them with the renderer's prop
culling off, so that a frame draws nothing and its time is what the mapper
does before drawing. Then, for each event, the median of --frames frames,
each after that event:

- frame: nothing changes;
- array: the other colour array (SelectColorArray);
- range: another scalar range;
- lut: another lookup table hue range;
- property: another actor colour (the superclass watches the property);
- input: the splats' poly data Modified(): everything built again.

vtkAlgebraicSplatMapper uploads the colours alone for array, range, lut and
property (GetGeometryBuildTime() stays put: the geometry_rebuilt column);
vtkPointGaussianMapper, like VTK's other OpenGL mappers, builds all of its
buffers again. A change's cost is the median frame after it less the median
plain frame of the same mapper (extra_ms): vtkPointGaussianMapper draws every
point even when none is in view, the splat mapper's octree culls them all.
Output in --out: splat_recolor.csv (points, splats, mapper, event, median
wall and process-CPU ms, geometry_rebuilt, extra_ms and its ratio to
vtkPointGaussianMapper's for the same event) and splat_recolor.png (extra_ms
against the splats, per event). Timings are wall-clock on whatever this runs
on: compare them only within one run.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_csv import TEST_DATA, write_rows  # noqa: E402
from bench_scene import OffscreenScene  # noqa: E402
from surface_sampling import sample_surface  # noqa: E402

import pointsurfaces  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402
from vtkmodules.vtkCommonCore import vtkLookupTable, vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkPolyData  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkActor  # noqa: E402
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLPointGaussianMapper  # noqa: E402

EVENTS = ["frame", "array", "range", "lut", "property", "input"]


def read_mesh(path):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetOutput().GetNumberOfPoints() == 0:
        raise SystemExit("%s: no points read" % path)
    return reader.GetOutput()


def fitted_splats(mesh, n):
    """The fitter's splats (defaults) of n points sampled on the mesh, with the
    scalar arrays A (height) and B (a random value)."""
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(sample_surface(mesh, n)), deep=1))
    cloud = vtkPolyData()
    cloud.SetPoints(points)
    fitter = pointsurfaces.vtkAlgebraicSplatFitter()
    fitter.SetInputData(cloud)
    fitter.Update()
    splats = vtkPolyData()
    splats.ShallowCopy(fitter.GetOutput())
    m = splats.GetNumberOfPoints()
    height = numpy_to_vtk(np.linspace(0.0, 1.0, m), deep=1)
    height.SetName("A")
    other = numpy_to_vtk(np.random.default_rng(1).random(m), deep=1)
    other.SetName("B")
    splats.GetPointData().AddArray(height)
    splats.GetPointData().AddArray(other)
    return splats


def make_mapper(kind, splats):
    if kind == "algebraic splats":
        mapper = pointsurfaces.vtkAlgebraicSplatMapper()
    else:
        mapper = vtkOpenGLPointGaussianMapper()
        mapper.SetScaleArray("SplatRadius")
        mapper.SetScaleFactor(1.0)
        mapper.SetEmissive(0)
    mapper.SetInputData(splats)
    mapper.ScalarVisibilityOn()
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("A")
    mapper.SetScalarRange(0.0, 1.0)
    lut = vtkLookupTable()
    lut.Build()
    mapper.SetLookupTable(lut)
    return mapper


def measure(scene, kind, splats, frames):
    """One row per event for `kind` drawing `splats`."""
    mapper = make_mapper(kind, splats)
    actor = vtkActor()
    actor.SetMapper(mapper)
    scene.show(actor)
    scene.renderer.GetCullers().RemoveAllItems()
    scene.renderer.ResetCamera()
    camera = scene.renderer.GetActiveCamera()
    position, focal = np.array(camera.GetPosition()), np.array(camera.GetFocalPoint())
    camera.SetFocalPoint(*(2.0 * position - focal))  # look away: nothing is drawn
    scene.renderer.ResetCameraClippingRange()
    scene.window.Render()
    state = {"k": 0}

    def step(event):
        k = state["k"] = state["k"] + 1
        if event == "array":
            mapper.SelectColorArray("B" if k % 2 else "A")
        elif event == "range":
            mapper.SetScalarRange(0.0, 1.0 + 0.01 * k)
        elif event == "lut":
            mapper.GetLookupTable().SetHueRange(0.0, 0.5 + 0.01 * (k % 40))
            mapper.GetLookupTable().Build()
        elif event == "property":
            actor.GetProperty().SetColor(1.0, 0.5 + 0.01 * (k % 40), 0.2)
        elif event == "input":
            splats.Modified()

    rows = []
    for event in EVENTS:
        before = mapper.GetGeometryBuildTime() if hasattr(mapper, "GetGeometryBuildTime") else None
        wall, cpu = scene.timed_frames(frames, lambda: step(event))
        rebuilt = "" if before is None else int(mapper.GetGeometryBuildTime() != before)
        rows.append(dict(mapper=kind, event=event, median_ms=round(wall, 3), cpu_ms=round(cpu, 3),
                         geometry_rebuilt=rebuilt))
    scene.renderer.RemoveAllViewProps()
    return rows


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    events = [e for e in EVENTS if e != "frame"]
    fig, axes = plt.subplots(1, len(events), figsize=(3.2 * len(events), 3.4), sharey=True)
    for axis, event in zip(axes, events):
        for kind, style in (("algebraic splats", "o-"), ("vtkPointGaussianMapper", "s--")):
            mine = [r for r in rows if r["mapper"] == kind and r["event"] == event]
            axis.plot([r["splats"] for r in mine], [max(r["extra_ms"], 1e-2) for r in mine], style,
                      label=kind)
        axis.set_xscale("log")
        axis.set_yscale("log")
        axis.set_title(event)
        axis.set_xlabel("splats")
        axis.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("cost of the change, ms (median frame\nafter it less a plain frame)")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mesh", nargs="?", default=os.path.join(TEST_DATA, "bunny.vtp"))
    parser.add_argument("--points", type=float, nargs="+", default=[2e5, 1e6, 4e6])
    parser.add_argument("--frames", type=int, default=7)
    parser.add_argument("--out", default="bench-results")
    parser.add_argument("--smoke", action="store_true", help="20 000 points, 3 frames")
    parser.add_argument("--keep", action="store_true",
                        help="write each splat set (arrays A and B) to splats_N.vtp in --out, "
                             "for bench_paraview_recolor.py")
    args = parser.parse_args()
    if args.smoke:
        args.points, args.frames = [2e4], 3
    os.makedirs(args.out, exist_ok=True)
    mesh = read_mesh(args.mesh)
    scene = OffscreenScene(size=(256, 256))
    rows = []
    for n in args.points:
        splats = fitted_splats(mesh, int(n))
        if args.keep:
            writer = vtkXMLPolyDataWriter()
            writer.SetFileName(os.path.join(args.out, "splats_%d.vtp" % int(n)))
            writer.SetInputData(splats)
            writer.Write()
        found = []
        for kind in ("algebraic splats", "vtkPointGaussianMapper"):
            found += measure(scene, kind, splats, args.frames)
        # The change's own cost: the frame after it, less a frame without it.
        plain = {r["mapper"]: r["median_ms"] for r in found if r["event"] == "frame"}
        for r in found:
            r["extra_ms"] = round(max(0.0, r["median_ms"] - plain[r["mapper"]]), 3)
        peer = {r["event"]: r["extra_ms"] for r in found if r["mapper"] == "vtkPointGaussianMapper"}
        for r in found:
            ratio = r["extra_ms"] / peer[r["event"]] if peer[r["event"]] > 0 else None
            rows.append(dict(model=os.path.splitext(os.path.basename(args.mesh))[0], points=int(n),
                             splats=splats.GetNumberOfPoints(), **r,
                             extra_ratio_to_gaussian="" if ratio is None else round(ratio, 3)))
    write_rows(os.path.join(args.out, "splat_recolor.csv"), rows)
    plot(rows, os.path.join(args.out, "splat_recolor.png"))
    bad = [r for r in rows if r["mapper"] == "algebraic splats" and
           r["event"] in ("array", "range", "lut", "property") and r["geometry_rebuilt"]]
    if bad:
        print("the geometry was built again for: %s" % ", ".join(r["event"] for r in bad), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
