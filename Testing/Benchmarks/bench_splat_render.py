#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Frame time and image error of vtkAlgebraicSplatMapper against linear-splat peers.

One scan (default: the Bunny, Testing/Data/bunny.vtp, whose triangles give the
ground truth) is drawn in the same process and window by:

- the original triangle mesh, smooth-shaded and 4 x 4 supersampled: the
  reference image; and the same mesh without supersampling;
- algebraic splats of degree 1 to 4 at several qualities s, blended (two
  passes) and opaque, each with and without back-face culling (the fitter
  orients the splats' normals); the cubic ones at s = 1 also with adaptive
  anti-aliasing 2 x 2 and 3 x 3, and with full-screen 2 x 2 supersampling
  (the window drawn at twice the size, then averaged);
- vtkPointGaussianMapper (sphere-shaded sprites) and vtkOpenGLSphereMapper
  over all the original points, at several radii (multiples of the mean
  point spacing).

For each it records the median frame time (render plus a one-pixel read-back,
which waits for the GPU), the RMSE of the RGB image against the reference, the
primitive count and the bytes per primitive in GPU vertex buffers, and its
frame time as a ratio to the best (lowest-error) vtkPointGaussianMapper run at
the same size. CSV goes to stdout and <out>/splat_render.csv; the plot
<out>/splat_render_<size>.png draws error against frame time.

At equal error: for each peer's lowest-error run, the fastest splat run (no
supersampling) whose error is no larger, with its frame time as a ratio to
the peer's and its share of the primitives (<out>/splat_render_equal_error.csv,
also printed as # lines).

--points N draws N points sampled uniformly (by area, seeded) on the mesh's
triangles instead of its vertices: a dense scan, the case the figures of
[Bolla 2010] are for, where the peers draw every point and the splats stay
few.

The timings depend on the GL implementation: on llvmpipe every fragment is
computed on the CPU, so cost follows the shaded fragments, not the primitive
count. Use --size to add sizes (1080p: --size 1920x1080).

Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
"""
import argparse
import csv
import os
import sys
import time

import numpy as np

import pointsurfaces  # noqa: F401  (registers the EGL window factory)
from bench_csv import scatter_time_vs_rmse, write_rows
from bench_scene import OffscreenScene, material as shared_material
from pointsurfaces import vtkAlgebraicSplatFitter, vtkAlgebraicSplatMapper
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData, vtkStaticPointLocator
from vtkmodules.vtkCommonCore import vtkIdList
from vtkmodules.vtkFiltersCore import vtkPolyDataNormals
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper
from vtkmodules.vtkRenderingCore import vtkPointGaussianMapper
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLSphereMapper

from surface_sampling import sample_surface

# VTK's own sphere-like sprite for vtkPointGaussianMapper (its examples' shading).
SPHERE_SPRITE = """//VTK::Color::Impl
  float dist = dot(offsetVCVSOutput.xy, offsetVCVSOutput.xy);
  if (dist > 1.0) { discard; } else {
    float scale = (1.0 - dist);
    ambientColor *= scale;
    diffuseColor *= scale;
  }
"""


def parse_size(text):
    if "x" in text:
        w, h = text.split("x")
        return int(w), int(h)
    return int(text), int(text)


class Scene(OffscreenScene):
    """The shared scene with one camera, fitted to the mesh; the size is set per image."""

    def __init__(self, mesh):
        super().__init__()
        b = mesh.GetBounds()
        centre = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
        diag = ((b[1] - b[0]) ** 2 + (b[3] - b[2]) ** 2 + (b[5] - b[4]) ** 2) ** 0.5
        cam = self.renderer.GetActiveCamera()
        cam.SetFocalPoint(*centre)
        cam.SetPosition(centre[0] + 0.3 * diag, centre[1] + 0.15 * diag, centre[2] + 1.6 * diag)
        cam.SetViewUp(0, 1, 0)
        cam.SetViewAngle(30)
        cam.SetClippingRange(0.5 * diag, 3.0 * diag)

    def image(self, size):
        self.resize(size)
        return self.pixels()

    def frame_ms(self, size, frames):
        self.resize(size)
        self.window.Render()  # warm-up: buffers, shaders
        return self.timed_frames(frames)[0]


def supersampled(scene, size, factor):
    big = scene.image((size[0] * factor, size[1] * factor))
    return big.reshape(size[1], factor, size[0], factor, 3).mean(axis=(1, 3))


def write_png(path, image):
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkIOImage import vtkPNGWriter
    h, w, _ = image.shape
    data = vtkImageData()
    data.SetDimensions(w, h, 1)
    data.GetPointData().SetScalars(
        numpy_to_vtk((255.0 * image).round().astype(np.uint8).reshape(-1, 3), deep=True))
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(data)
    writer.Write()


def rmse(a, b):
    return float(np.sqrt(np.mean((a - b) ** 2)))


def material(actor):
    return shared_material(actor, (0.9, 0.85, 0.8), ambient=0.15, diffuse=0.85)


def mean_spacing(points, samples=2000):
    locator = vtkStaticPointLocator()
    data = vtkPolyData()
    data.SetPoints(points)
    locator.SetDataSet(data)
    locator.BuildLocator()
    ids = vtkIdList()
    n = points.GetNumberOfPoints()
    step = max(1, n // samples)
    total, count = 0.0, 0
    for i in range(0, n, step):
        p = points.GetPoint(i)
        locator.FindClosestNPoints(2, p, ids)
        q = points.GetPoint(ids.GetId(1))
        total += sum((p[k] - q[k]) ** 2 for k in range(3)) ** 0.5
        count += 1
    return total / count


def equal_error(rows):
    """Per size and peer: its lowest-error run against the fastest splat run at no more error."""
    result = []
    for label in sorted({r["size"] for r in rows}):
        splats = [r for r in rows if r["size"] == label and r["method"] == "algebraic"
                  and r["aa"] == 1]
        for peer in ("point-gaussian", "sphere"):
            runs = [r for r in rows if r["size"] == label and r["method"] == peer]
            if not runs:
                continue
            best = min(runs, key=lambda r: float(r["rmse"]))
            reach = [r for r in splats if float(r["rmse"]) <= float(best["rmse"])]
            fastest = min(reach, key=lambda r: float(r["frame_ms"])) if reach else None
            e = dict(size=label, peer=peer, peer_setting=best["s"], peer_rmse=best["rmse"],
                     peer_ms=best["frame_ms"], splat="", splat_rmse="", splat_ms="",
                     time_ratio="", primitive_ratio="")
            if fastest:
                e.update(splat="degree %s, s = %s, %s%s" % (
                    fastest["degree"], fastest["s"],
                    "blended" if fastest["blend"] == 1 else "opaque",
                    ", back faces culled" if fastest["cull"] == 1 else ""),
                    splat_rmse=fastest["rmse"], splat_ms=fastest["frame_ms"],
                    time_ratio="%.3f" % (float(fastest["frame_ms"]) / float(best["frame_ms"])),
                    primitive_ratio="%.2f%%" % (100.0 * fastest["primitives"] / best["primitives"]))
            result.append(e)
    return result


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("mesh", nargs="?", default=os.path.join(here, "..", "Data", "bunny.vtp"),
                        help="a .vtp mesh with triangles (default: Testing/Data/bunny.vtp)")
    parser.add_argument("--out", default="bench-results", help="folder for the CSVs and plots")
    parser.add_argument("--size", action="append", help="e.g. 512 or 1920x1080 (repeatable)")
    parser.add_argument("--frames", type=int, default=7)
    parser.add_argument("--smoke", action="store_true", help="tiny sizes and few runs (CI)")
    parser.add_argument("--images", action="store_true", help="also write each run's image")
    parser.add_argument("--points", type=int, default=0,
                        help="sample this many points on the mesh instead of its vertices")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    sizes = [parse_size(s) for s in (args.size or (["96"] if args.smoke else ["512", "1024"]))]
    frames = 1 if args.smoke else args.frames

    reader = vtkXMLPolyDataReader()
    reader.SetFileName(args.mesh)
    reader.Update()
    mesh = reader.GetOutput()
    if mesh.GetNumberOfPolys() == 0:
        print("bench_splat_render.py: %s has no triangles for the reference image" % args.mesh)
        return 1
    points = vtkPolyData()
    if args.points > 0:
        sampled = vtkPoints()
        sampled.SetData(numpy_to_vtk(sample_surface(mesh, args.points), deep=True))
        points.SetPoints(sampled)
    else:
        points.SetPoints(mesh.GetPoints())
    n_points = points.GetNumberOfPoints()
    verts = vtkCellArray()  # vtkOpenGLSphereMapper draws vertex cells
    verts.SetData(numpy_to_vtkIdTypeArray(np.arange(n_points + 1, dtype=np.int64), deep=True),
                  numpy_to_vtkIdTypeArray(np.arange(n_points, dtype=np.int64), deep=True))
    points.SetVerts(verts)
    spacing = mean_spacing(points.GetPoints())
    scene = Scene(mesh)

    normals = vtkPolyDataNormals()
    normals.SetInputData(mesh)
    normals.SplittingOff()
    mesh_mapper = vtkPolyDataMapper()
    mesh_mapper.SetInputConnection(normals.GetOutputPort())
    mesh_actor = material(vtkActor())
    mesh_actor.SetMapper(mesh_mapper)

    # Splat sets, fitted once each.
    degrees = [3] if args.smoke else [1, 2, 3, 4]
    qualities = [1.0] if args.smoke else [1.0, 2.0, 4.0]
    splat_sets = {}
    for degree in degrees:
        for s in qualities:
            fitter = vtkAlgebraicSplatFitter()
            fitter.SetInputData(points)
            fitter.SetDegree(degree)
            fitter.SetQualityFactor(s)
            t0 = time.perf_counter()
            fitter.Update()
            out = vtkPolyData()
            out.ShallowCopy(fitter.GetOutput())
            splat_sets[(degree, s)] = (out, time.perf_counter() - t0)

    rows = []
    for size in sizes:
        scene.show(mesh_actor)
        reference = supersampled(scene, size, 4)
        label = "%dx%d" % size

        def record(method, actor, prims, bytes_per, degree="", s="", aa="", image=None, ms=None,
                   blend="", cull=""):
            scene.show(actor)
            if image is None:
                image = scene.image(size)
            if ms is None:
                ms = scene.frame_ms(size, frames)
            if args.images:
                name = "%s_%s_d%s_s%s_aa%s.png" % (label, method, degree, s, aa)
                write_png(os.path.join(args.out, name), image)
            rows.append(
                dict(size=label, method=method, degree=degree, s=s, aa=aa, blend=blend, cull=cull,
                     primitives=prims,
                     primitive_fraction="%.4f" % (prims / n_points), frame_ms="%.2f" % ms,
                     rmse="%.5f" % rmse(image, reference), gpu_bytes_per_primitive=bytes_per))

        record("mesh", mesh_actor, mesh.GetNumberOfPolys(), 3 * 24)

        for (degree, s), (splats, _) in splat_sets.items():
            aas = [1, 2, 3] if degree == 3 and s == qualities[0] else [1]
            for aa in aas:
                for blend in ((1, 0) if aa == 1 else (1,)):
                    for cull in ((0, 1) if aa == 1 else (0,)):
                        mapper = vtkAlgebraicSplatMapper()
                        mapper.SetInputData(splats)
                        mapper.SetAntiAliasing(aa)
                        mapper.SetBlending(blend)
                        actor = material(vtkActor())
                        actor.SetMapper(mapper)
                        actor.GetProperty().SetBackfaceCulling(cull)
                        scene.show(actor)
                        scene.image(size)
                        record("algebraic", actor, splats.GetNumberOfPoints(),
                               mapper.GetGPUBytesPerSplat(), degree, s, aa, blend=blend, cull=cull)
            if degree == 3 and s == qualities[0]:
                # Full-screen 2 x 2 supersampling of the same splats.
                mapper = vtkAlgebraicSplatMapper()
                mapper.SetInputData(splats)
                actor = material(vtkActor())
                actor.SetMapper(mapper)
                scene.show(actor)
                image = supersampled(scene, size, 2)
                ms = scene.frame_ms((2 * size[0], 2 * size[1]), frames)
                record("algebraic-fsaa2", actor, splats.GetNumberOfPoints(),
                       mapper.GetGPUBytesPerSplat(), degree, s, "fsaa2", image=image, ms=ms,
                       blend=1)

        # Radii in mean point spacings: below 1 the peers leave holes.
        factors = [1.5] if args.smoke else [1.5, 3.0, 5.0]
        for factor in factors:
            gaussian = vtkPointGaussianMapper()
            gaussian.SetInputData(points)
            gaussian.SetScaleFactor(factor * spacing)
            gaussian.SetSplatShaderCode(SPHERE_SPRITE)
            gaussian.EmissiveOff()
            actor = material(vtkActor())
            actor.SetMapper(gaussian)
            record("point-gaussian", actor, n_points, 12 + 4, s="r=%.2fh" % factor)
            sphere = vtkOpenGLSphereMapper()
            sphere.SetInputData(points)
            sphere.SetRadius(factor * spacing)
            actor = material(vtkActor())
            actor.SetMapper(sphere)
            record("sphere", actor, n_points, 12 + 4, s="r=%.2fh" % factor)

    # Ratios against the lowest-error vtkPointGaussianMapper run per size.
    for label in sorted({r["size"] for r in rows}):
        peers = [r for r in rows if r["size"] == label and r["method"] == "point-gaussian"]
        best = min(peers, key=lambda r: float(r["rmse"]))
        for r in rows:
            if r["size"] == label:
                r["time_vs_gaussian"] = "%.3f" % (float(r["frame_ms"]) / float(best["frame_ms"]))

    fields = ["size", "method", "degree", "s", "aa", "blend", "cull", "primitives",
              "primitive_fraction",
              "frame_ms", "time_vs_gaussian", "rmse", "gpu_bytes_per_primitive"]
    path = os.path.join(args.out, "splat_render.csv")
    write_rows(path, rows, fields)
    equal = equal_error(rows)
    with open(os.path.join(args.out, "splat_render_equal_error.csv"), "w", newline="") as f:
        eq_writer = csv.DictWriter(f, fieldnames=list(equal[0].keys()) if equal else ["size"])
        eq_writer.writeheader()
        eq_writer.writerows(equal)
    for e in equal:
        print("# equal error, %s, against %s %s (RMSE %s, %s ms): %s" % (
            e["size"], e["peer"], e["peer_setting"], e["peer_rmse"], e["peer_ms"],
            "no splat run reaches it" if not e["splat"] else
            "%s (RMSE %s) in %s ms: %sx the time with %s of the primitives" % (
                e["splat"], e["splat_rmse"], e["splat_ms"], e["time_ratio"],
                e["primitive_ratio"])))
    for (degree, s), (splats, seconds) in splat_sets.items():
        print("# fit degree %d s=%g: %d splats (%.1f%% of %d points) in %.2f s" % (
            degree, s, splats.GetNumberOfPoints(), 100.0 * splats.GetNumberOfPoints() / n_points,
            n_points, seconds))

    def note(r):
        if not r["method"].startswith("algebraic"):
            return None
        return "d%s s%s aa%s%s%s" % (r["degree"], r["s"], r["aa"],
                                     "" if r["blend"] == 1 else " opaque",
                                     " culled" if r["cull"] == 1 else "")

    for label in sorted({r["size"] for r in rows}):
        scatter_time_vs_rmse(
            [r for r in rows if r["size"] == label],
            (("algebraic", "o"), ("algebraic-fsaa2", "s"), ("point-gaussian", "^"),
             ("sphere", "v"), ("mesh", "*")),
            os.path.join(args.out, "splat_render_%s.png" % label),
            "%s, %s" % (os.path.basename(args.mesh), label), "RMSE vs 4x4-supersampled mesh",
            note=note, size=(7, 4.5))
    return 0


if __name__ == "__main__":
    sys.exit(main())
