#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Image quality of algebraic splats against the mesh of the same scan, as a user sees it.

    bench_splat_quality.py [--models PATH ...] [--data DIR] [--out DIR] [--quick] ...

The scans, each with faces: --models (any mesh with triangles that
pointsurfaces.scanio reads: .ply .vtp .obj .off .om .stl); else, with --data
DIR, the full-size bunny.ply, horse.ply and lucy_50k.ply in DIR (or a folder
one level below it; one not there, or unreadable, is skipped with one line on
stderr); else the Stanford Bunny a clone has, Testing/Data/bunny.vtp (35 947
points, 69 451 triangles). A model of --models that cannot be read, or has no
triangles, ends the run with exit status 1.

For each scan and each of several views (cameras around the model, at
azimuths and elevations about its up axis):

- the ground truth is the triangle mesh itself, drawn by vtkPolyDataMapper
  with smooth normals (vtkPolyDataNormals, no splitting) on a white
  background. The camera is set once per view from the mesh's bounds
  (ResetCamera on the mesh alone, then Azimuth and Elevation) and its
  clipping range from the mesh's bounds (padded by 10 % of their diagonal);
  the same camera is reused for everything drawn in that view, so the
  splats' own bounds never move it.
- the splats are fitted by vtkAlgebraicSplatFitter from the mesh's vertices
  alone (no normals, no faces, no arrays: as from a scanner) and drawn by
  vtkAlgebraicSplatMapper with its defaults (two-pass blending on, no
  anti-aliasing, no LOD), with the same headlight and material (light grey,
  ambient 0.1, diffuse 0.9, no specular; scalar colouring off).

Metrics per view, over the pixels that either image covers (the mask: pixels
not exactly the background colour in the mesh image or in the splat image):

- masked_rmse: RMSE of the RGB images (0..1) over the masked pixels;
- masked_ssim: mean over the masked pixels of the full SSIM map of
  skimage.metrics.structural_similarity on the grey images (luminance
  0.299 R + 0.587 G + 0.114 B; Wang et al.'s settings: 11 x 11 Gaussian
  window, sigma 1.5, population covariance, data range 1);
- coverage_iou: |mesh pixels AND splat pixels| / |mesh pixels OR splat pixels|.

Per setting, and without any camera: stray_splats, the share of splats whose
patch strays from the mesh by more than the mesh's mean edge length (its
point spacing) anywhere on its disc (sampled at the centre and on two rings,
half the radius and the rim, 16 directions each; vtkImplicitPolyDataDistance),
and stray_max, the largest such distance in edge lengths. A flake that no
view happens to show is counted here. Open borders count: a disc may reach
half a spacing past the data there, so that distance is the mesh's border
edge, in the plane. inward_splats: the share of splats whose SplatNormal
disagrees with the mesh's outward normal (vtkPolyDataNormals with
AutoOrientNormals) at the nearest vertex, among those whose normals are
within 60 degrees of that axis either way: orientation errors, which the
two-sided shading hides and back-face culling turns into holes.

Also per row: the splat count, the fit time (fit_ms: the wall-clock time of
one vtkAlgebraicSplatFitter.Update(), or the median of --fit-runs runs, with
every core vtkSMPTools uses) and the frame time (frame_ms: the median of
--frames renders, each followed by a one-pixel depth read-back, which waits
for the GPU; the first render of an actor, which compiles shaders and uploads
buffers, is not timed). fit_cpu_ms and frame_cpu_ms are the CPU time of this
process over the same runs: on llvmpipe, whose threads draw in this process,
they move less than the wall times when other work shares the cores.

Sweep: QualityFactor s (--s) times degree (--degrees), the "s" sweep. When
the fitter has the MaximumDeviation tolerance (in local point spacings; found
with hasattr), the s sweep runs at its default value, and --tolerances (and
the default) are swept at the few s of --tolerance-s: the "tol@s=..." sweeps.
Without it the tolerance column is empty. A setting in both sweeps is fitted
and drawn once.

Rows with method "mesh" are the mesh scored against itself through the same
path (score_mesh): masked RMSE 0, SSIM 1, IoU 1 is the self-check, and their
frame_ms and splats (its triangle count) put the mesh's own cost beside the
splats'. score_mesh() is where a reconstruction peer plugs in: any vtkPolyData
with triangles (CGAL's reconstruction at the splats' primitive budget, an
OpenMesh decimation) is scored against the same reference images in the same
views; --peer-mesh MODEL PATH does it for a mesh written to a file.

Output (in --out): splat_quality.csv (also on stdout), one row per view;
splat_quality_summary.csv, the mean over views (also printed as # lines);
splat_quality_ssim_vs_splats.png and splat_quality_ssim_vs_frame.png (mean
masked SSIM over the views, one panel per model, one line per fitter label and
degree; --compare PREVIOUS.csv adds the curves of an earlier run, for example
of another fitter, told apart by --label); splat_quality_rmse_iou.png (masked
RMSE and coverage IoU against splat count); and <model>_mesh_vs_splats.png,
the mesh beside the splats in the first view at the fitter's default degree
and s = 1, cut to the model. --images writes, for every setting and view, the
mesh, the splats and their difference (grey: 4 x the RGB difference; red:
pixels only the mesh covers, holes; blue: pixels only the splats cover,
spill past the silhouette).

Frame times come from whatever GL this runs on (llvmpipe on the CPU: cost
follows shaded fragments); compare them only within one machine, and with the
load averages printed at the start and end of the run (other work on the
cores inflates both times; the image metrics do not depend on it).

--quick is the smoke test ctest runs: the first model only (by default
Testing/Data/bunny.vtp, which a clean clone has), one view, 128 x 128,
degree 3, s = 2 and 1 (and MaximumDeviation 0.2 at s = 1 when the fitter has
it), one frame. It fails when the mesh does not score 1 against itself.

Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
"""
import argparse
import csv
import os
import statistics
import sys
import time

import numpy as np

import pointsurfaces
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkPolyDataNormals
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper

from pointsurfaces.scanio import ScanReadError, read_scan

import bench_csv
from bench_csv import TEST_DATA, find_input, skip, skip_unreadable
from bench_scene import OffscreenScene, material as shared_material

try:
    from skimage.metrics import structural_similarity
except ImportError:
    sys.exit("bench_splat_quality.py: needs scikit-image (Debian: python3-skimage; "
             "scripts/install-deps.sh installs it)")

HERE = os.path.dirname(os.path.abspath(__file__))
MODELS = ["bunny.ply", "horse.ply", "lucy_50k.ply"]  # the full-size models' names in --data
BUNNY = os.path.join(TEST_DATA, "bunny.vtp")  # the default model
# Up axis per model (file stem prefix); the Bunny's is y. Lucy and the horse stand on z.
UP_AXIS = {"horse": "z", "lucy": "z"}
# (azimuth, elevation) in degrees about the up axis, from the front view.
VIEWS = [(0, 15), (60, 30), (120, -10), (180, 15), (240, 30), (300, -10)]
BACKGROUND = (1.0, 1.0, 1.0)
COLOUR = (0.8, 0.8, 0.8)
FIELDS = ["fitter_label", "method", "model", "view", "azimuth", "elevation", "degree", "s",
          "tolerance", "sweep", "splats", "points", "fit_ms", "fit_cpu_ms", "frame_ms",
          "frame_cpu_ms", "masked_rmse", "masked_ssim", "coverage_iou", "covered_reference",
          "covered_test", "stray_splats", "stray_max", "inward_splats"]


def parse_size(text):
    if "x" in text:
        w, h = text.split("x")
        return int(w), int(h)
    return int(text), int(text)


def load_mesh(path):
    """Points and triangles only: arrays (the horse's RGB, PLY confidence) are dropped.
    Raises ScanReadError."""
    raw = read_scan(path)
    mesh = vtkPolyData()
    mesh.SetPoints(raw.GetPoints())
    mesh.SetPolys(raw.GetPolys())
    return mesh


def scan_of(mesh):
    """The mesh's vertices alone, as a scanner would give them."""
    points = vtkPolyData()
    points.SetPoints(mesh.GetPoints())
    return points


def material(actor):
    return shared_material(actor, COLOUR, ambient=0.1, diffuse=0.9)


def mesh_actor(mesh):
    normals = vtkPolyDataNormals()
    normals.SetInputData(mesh)
    normals.SplittingOff()
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(normals.GetOutputPort())
    mapper.ScalarVisibilityOff()
    actor = material(vtkActor())
    actor.SetMapper(mapper)
    return actor


def splat_actor(splats):
    mapper = pointsurfaces.vtkAlgebraicSplatMapper()
    mapper.SetInputData(splats)
    mapper.ScalarVisibilityOff()
    actor = material(vtkActor())
    actor.SetMapper(mapper)
    return actor


class Scene(OffscreenScene):
    """The shared scene; the camera is set per view."""

    def __init__(self, size):
        super().__init__(size, BACKGROUND)

    def cameras(self, mesh, up_axis, views):
        """One camera state per view, set from the mesh alone and kept for everything after."""
        up = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}[up_axis]
        front = {"x": (0, 0, 1), "y": (0, 0, 1), "z": (0, 1, 0)}[up_axis]
        b = mesh.GetBounds()
        pad = 0.1 * ((b[1] - b[0]) ** 2 + (b[3] - b[2]) ** 2 + (b[5] - b[4]) ** 2) ** 0.5
        padded = [b[0] - pad, b[1] + pad, b[2] - pad, b[3] + pad, b[4] - pad, b[5] + pad]
        self.show(mesh_actor(mesh))
        states = []
        for azimuth, elevation in views:
            cam = self.renderer.GetActiveCamera()
            cam.SetFocalPoint(0, 0, 0)
            cam.SetPosition(*front)
            cam.SetViewUp(*up)
            cam.SetViewAngle(30)
            self.renderer.ResetCamera()  # from the mesh's bounds: it is the only actor
            cam.Azimuth(azimuth)
            cam.Elevation(elevation)
            cam.OrthogonalizeViewUp()
            self.renderer.ResetCameraClippingRange(padded)
            states.append(dict(position=cam.GetPosition(), focal=cam.GetFocalPoint(),
                               up=cam.GetViewUp(), angle=cam.GetViewAngle(),
                               clip=cam.GetClippingRange()))
        return states

    def use(self, state):
        cam = self.renderer.GetActiveCamera()
        cam.SetPosition(*state["position"])
        cam.SetFocalPoint(*state["focal"])
        cam.SetViewUp(*state["up"])
        cam.SetViewAngle(state["angle"])
        cam.SetClippingRange(*state["clip"])

    def image(self, state):
        """RGB image (rows bottom-up, 0..1) of the current actor from one camera state."""
        self.use(state)
        image = self.pixels()
        assert self.renderer.GetActiveCamera().GetClippingRange() == state["clip"], \
            "the renderer moved the camera's clipping range"
        return image

    def frame_ms(self, state, frames):
        """Median wall-clock and process-CPU milliseconds of a frame."""
        self.use(state)
        return self.timed_frames(frames)


def covered(image):
    return np.any(image != np.asarray(BACKGROUND), axis=2)


def grey(image):
    return image @ np.array([0.299, 0.587, 0.114])


def score_images(reference, test):
    """Masked RMSE, masked SSIM and coverage IoU of test against reference (see the docstring)."""
    ref_mask, test_mask = covered(reference), covered(test)
    mask = ref_mask | test_mask
    union = int(mask.sum())
    if union == 0:
        return dict(masked_rmse=0.0, masked_ssim=1.0, coverage_iou=1.0,
                    covered_reference=0, covered_test=0)
    rmse = float(np.sqrt(np.mean((reference[mask] - test[mask]) ** 2)))
    _, ssim_map = structural_similarity(grey(reference), grey(test), data_range=1.0,
                                        gaussian_weights=True, sigma=1.5,
                                        use_sample_covariance=False, full=True)
    return dict(masked_rmse=rmse, masked_ssim=float(ssim_map[mask].mean()),
                coverage_iou=float((ref_mask & test_mask).sum()) / union,
                covered_reference=int(ref_mask.sum()), covered_test=int(test_mask.sum()))


def score_actor(scene, model, actor, frames, images_out=None, tag=""):
    """Per view: the actor's image scored against the model's references, and its frame time."""
    scene.show(actor)
    rows = []
    for view, (state, reference) in enumerate(zip(model["cameras"], model["references"])):
        image = scene.image(state)  # also the warm-up render of this view
        if view == 0:
            model["last_image"] = image
        row = score_images(reference, image)
        wall, cpu = scene.frame_ms(state, frames) if frames > 0 else ("", "")
        row.update(view=view, azimuth=model["views"][view][0],
                   elevation=model["views"][view][1], frame_ms=wall, frame_cpu_ms=cpu)
        rows.append(row)
        if images_out:
            write_diagnostic(os.path.join(images_out, "%s_%s_view%d.png" % (
                model["name"], tag, view)), reference, image)
    return rows


def score_mesh(scene, model, mesh, frames, images_out=None, tag="mesh"):
    """Score any triangle mesh against the model's reference in its views.

    The entry point for a reconstruction peer: pass the mesh a reconstruction
    (CGAL, Poisson, a decimation) made from the same scan, at a triangle
    budget comparable to the splat count, and compare its rows with the
    splats'. Scoring the reference mesh itself is the self-check (RMSE 0,
    SSIM 1, IoU 1)."""
    return score_actor(scene, model, mesh_actor(mesh), frames, images_out, tag)


def mean_edge_length(mesh):
    """Mean edge length of the mesh's triangles: its point spacing."""
    points = vtk_to_numpy(mesh.GetPoints().GetData()).astype(np.float64)
    polys = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    edges = np.concatenate([points[polys[:, 0]] - points[polys[:, 1]],
                            points[polys[:, 1]] - points[polys[:, 2]],
                            points[polys[:, 2]] - points[polys[:, 0]]])
    return float(np.linalg.norm(edges, axis=1).mean())


def disc_samples(splats, rings=(0.5, 1.0), directions=16):
    """World points on each splat's patch: its origin and `directions` points on each
    ring (a fraction of the disc radius); an array (splats, samples, 3)."""
    def array(name):
        return vtk_to_numpy(splats.GetPointData().GetArray(name)).astype(np.float64)
    origin = vtk_to_numpy(splats.GetPoints().GetData()).astype(np.float64)
    normal, tangent = array("SplatNormal"), array("SplatTangent")
    bitangent = np.cross(normal, tangent)
    h, radius, c = array("SplatFeatureSize"), array("SplatRadius"), array("SplatCoefficients")
    if c.ndim == 1:
        c = c[:, None]
    angles = np.linspace(0.0, 2.0 * np.pi, directions, endpoint=False)
    fraction = np.concatenate([[0.0]] + [np.full(directions, f) for f in rings])
    angle = np.concatenate([[0.0]] + [angles for _ in rings])
    rho = radius[:, None] * fraction[None, :] / h[:, None]
    u, v = rho * np.cos(angle)[None, :], rho * np.sin(angle)[None, :]
    # The monomials in the data model's order: by total degree, then descending power of u.
    monomials = [u ** (d - j) * v ** j for d in range(5) for j in range(d + 1)]
    g = sum(c[:, k][:, None] * monomials[k] for k in range(c.shape[1]))
    return origin[:, None, :] + h[:, None, None] * (
        u[..., None] * tangent[:, None, :] + v[..., None] * bitangent[:, None, :] +
        g[..., None] * normal[:, None, :])


def stray_splats(mesh, splats, spacing=None):
    """(share of splats whose disc strays more than a mesh edge length from the mesh,
    largest stray in edge lengths), over disc_samples."""
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    from vtkmodules.vtkFiltersCore import vtkImplicitPolyDataDistance
    if splats.GetNumberOfPoints() == 0:
        return 0.0, 0.0
    spacing = spacing or mean_edge_length(mesh)
    samples = disc_samples(splats)
    distance = vtkImplicitPolyDataDistance()
    distance.SetInput(mesh)
    values = vtkDoubleArray()
    distance.FunctionValue(numpy_to_vtk(samples.reshape(-1, 3).copy(), deep=True), values)
    worst = np.abs(vtk_to_numpy(values)).reshape(samples.shape[:2]).max(axis=1) / spacing
    return float((worst > 1.0).mean()), float(worst.max())


def outward_normals(mesh):
    """The mesh's vertices and their outward normals (vtkPolyDataNormals, AutoOrientNormals)."""
    normals = vtkPolyDataNormals()
    normals.SetInputData(mesh)
    normals.SplittingOff()
    normals.ConsistencyOn()
    normals.AutoOrientNormalsOn()
    normals.Update()
    out = normals.GetOutput()
    return (vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64),
            vtk_to_numpy(out.GetPointData().GetNormals()).astype(np.float64))


def inward_splats(outward, splats):
    """Share of the splats whose normal points against the mesh's outward normal at the
    nearest vertex (`outward`: outward_normals(mesh)), of those within 60 degrees of it."""
    from scipy.spatial import cKDTree
    if splats.GetNumberOfPoints() == 0:
        return 0.0
    points, normals = outward
    origin = vtk_to_numpy(splats.GetPoints().GetData()).astype(np.float64)
    normal = vtk_to_numpy(splats.GetPointData().GetArray("SplatNormal")).astype(np.float64)
    cosine = (normal * normals[cKDTree(points).query(origin)[1]]).sum(axis=1)
    sure = np.abs(cosine) > 0.5
    return float((cosine[sure] < 0.0).sum()) / max(1, int(sure.sum()))


def fit_splats(points, degree, s, tolerance, runs, options=()):
    """Splats of one setting, and the fit's wall-clock and process-CPU ms (medians of runs).

    options: (name, value) pairs for the fitter's other setters (Set<name>),
    as --fitter-option gives them."""
    times, cpu = [], []
    for _ in range(max(1, runs)):
        fitter = pointsurfaces.vtkAlgebraicSplatFitter()
        fitter.SetInputData(points)
        fitter.SetDegree(degree)
        fitter.SetQualityFactor(s)
        if tolerance is not None:
            fitter.SetMaximumDeviation(tolerance)
        for name, value in options:
            getattr(fitter, "Set" + name)(value)
        t0, c0 = time.perf_counter(), time.process_time()
        fitter.Update()
        times.append(1000.0 * (time.perf_counter() - t0))
        cpu.append(1000.0 * (time.process_time() - c0))
    splats = vtkPolyData()
    splats.ShallowCopy(fitter.GetOutput())
    return splats, statistics.median(times), statistics.median(cpu)


def settings(args, tol0):
    """(degree, s, tolerance or None, sweep) to run: the s sweep at the fitter's default
    tolerance (tol0, None without the knob), then the tolerance sweep at a few s."""
    runs = []
    for degree in args.degrees:
        for s in args.s:
            runs.append((degree, s, tol0, "s"))
        if tol0 is not None:
            tol_s = args.s if args.tolerance_s == ["all"] else [float(v) for v in args.tolerance_s]
            for s in tol_s:
                # The default tolerance too: its point, fitted in the s sweep, joins the curve.
                for tol in sorted(set(args.tolerances) | {tol0}):
                    runs.append((degree, s, tol, "tol@s=%g" % s))
    return runs


def to_png_array(image):
    """0..1 RGB rows bottom-up (VTK's order) to uint8 rows bottom-up."""
    return (255.0 * np.clip(image, 0, 1)).round().astype(np.uint8)


def write_png(path, image):
    h, w, _ = image.shape
    data = vtkImageData()
    data.SetDimensions(w, h, 1)
    data.GetPointData().SetScalars(numpy_to_vtk(to_png_array(image).reshape(-1, 3), deep=True))
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(data)
    writer.Write()


def side_by_side(*images, gap=8):
    h = images[0].shape[0]
    spacer = np.ones((h, gap, 3))
    parts = []
    for i, image in enumerate(images):
        if i:
            parts.append(spacer)
        parts.append(image)
    return np.concatenate(parts, axis=1)


def cropped(*images, margin=8):
    """The images cut to the box around what any of them covers (the same box for all)."""
    mask = np.any([covered(image) for image in images], axis=0)
    if not mask.any():
        return images
    rows, cols = np.where(mask)
    y0, y1 = max(rows.min() - margin, 0), rows.max() + margin + 1
    x0, x1 = max(cols.min() - margin, 0), cols.max() + margin + 1
    return [image[y0:y1, x0:x1] for image in images]


def write_diagnostic(path, reference, image, flakes=None):
    """mesh | test | |difference| x 4 (grey) with the mask's disagreement in red / blue, and
    `flakes` (a mask, when given: the test in front of the mesh) in orange."""
    diff = np.clip(4.0 * np.abs(reference - image).mean(axis=2), 0, 1)
    panel = np.repeat((1.0 - diff)[:, :, None], 3, axis=2)
    ref_mask, test_mask = covered(reference), covered(image)
    panel[ref_mask & ~test_mask] = (1.0, 0.0, 0.0)  # mesh only: a hole in the test
    panel[test_mask & ~ref_mask] = (0.0, 0.3, 1.0)  # test only: spill past the silhouette
    if flakes is not None:
        panel[flakes] = (1.0, 0.55, 0.0)  # the test stands in front of the mesh
    write_png(path, side_by_side(*cropped(reference, image, panel)))


SUMMARY_FIELDS = ["fitter_label", "method", "model", "degree", "s", "tolerance", "sweep",
                  "views", "splats", "fit_ms", "fit_cpu_ms", "frame_ms", "frame_cpu_ms",
                  "masked_rmse", "masked_ssim", "coverage_iou", "stray_splats", "stray_max",
                  "inward_splats"]


def summarise(rows):
    """Mean over views per (label, method, model, degree, s, tolerance, sweep)."""
    groups = {}
    for r in rows:
        key = tuple(str(r[f]) for f in ("fitter_label", "method", "model", "degree", "s",
                                         "tolerance", "sweep"))
        groups.setdefault(key, []).append(r)
    out = []
    for key, rs in groups.items():
        def mean(field):
            values = [float(r[field]) for r in rs if r[field] != ""]
            return statistics.fmean(values) if values else None
        ms, cpu = mean("frame_ms"), mean("frame_cpu_ms") if "frame_cpu_ms" in rs[0] else None
        out.append(dict(zip(("fitter_label", "method", "model", "degree", "s", "tolerance",
                             "sweep"), key),
                        views=len(rs), splats=int(rs[0]["splats"]), fit_ms=rs[0]["fit_ms"],
                        fit_cpu_ms=rs[0].get("fit_cpu_ms", ""),
                        frame_ms="" if ms is None else "%.2f" % ms,
                        frame_cpu_ms="" if cpu is None else "%.2f" % cpu,
                        masked_rmse="%.5f" % mean("masked_rmse"),
                        masked_ssim="%.5f" % mean("masked_ssim"),
                        coverage_iou="%.5f" % mean("coverage_iou"),
                        stray_splats=rs[0].get("stray_splats", ""),
                        stray_max=rs[0].get("stray_max", ""),
                        inward_splats=rs[0].get("inward_splats", "")))
    return out


def plot(summary, compare, out):
    """Mean masked SSIM against splat count and frame time; RMSE and IoU against splat count."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = [dict(r, source="") for r in summary]
    ours = {r["fitter_label"] for r in summary}
    rows += [dict(r, source=" (compare)" if r["fitter_label"] in ours else "") for r in compare]
    models = list(dict.fromkeys(r["model"] for r in rows if r["method"] == "splats"))
    if not models:
        return []
    curves = {}
    for r in rows:
        if r["method"] == "splats":
            key = (r["fitter_label"] + r["source"], r["model"], int(r["degree"]), r["sweep"])
            curves.setdefault(key, []).append(r)
    colours = {d: "C%d" % i for i, d in enumerate(sorted({k[2] for k in curves}))}
    labels = sorted({k[0] for k in curves})
    sweeps = sorted({k[3] for k in curves}, key=lambda v: (v != "s", v))
    styles = ["-", "--", ":", "-."]
    markers = ["o", "^", "s", "v", "D", "x"]

    def draw(metric, xfield, axes, ylabel):
        for col, model in enumerate(models):
            ax = axes[col]
            for (label, m, degree, sweep), rs in sorted(curves.items()):
                pts = sorted((float(r[xfield]), float(r[metric]), r["s"], r["tolerance"])
                             for r in rs if m == model and r[xfield] != "")
                if not pts:
                    continue
                ax.plot([p[0] for p in pts], [p[1] for p in pts],
                        styles[labels.index(label) % len(styles)],
                        marker=markers[sweeps.index(sweep) % len(markers)],
                        color=colours[degree], markersize=4,
                        label="%s, degree %d%s" % (label, degree,
                                                   "" if sweep == "s" else ", " + sweep))
                if label in ours:  # this run's settings, not the compared run's
                    for x, y, s, tol in pts:
                        ax.annotate(("s=%g" % float(s)) if sweep == "s" else "t=%s" % tol,
                                    (x, y), fontsize=6, textcoords="offset points",
                                    xytext=(3, -8))
            # Meshes scored by score_mesh (reconstruction peers): one point each.
            for r in rows:
                if r["method"] == "peer-mesh" and r["model"] == model and r[xfield] != "":
                    ax.plot([float(r[xfield])], [float(r[metric])], "k*", markersize=8,
                            label="%s%s (mesh)" % (r["fitter_label"], r["source"]))
            # The mesh's own cost: its triangle count, its frame time.
            mesh = [r for r in rows if r["method"] == "mesh" and r["model"] == model
                    and r["source"] == "" and r[xfield] != ""]
            if mesh:
                ax.axvline(float(mesh[0][xfield]), color="grey", linestyle=":", linewidth=1,
                           label="mesh: %s" % ("triangles" if xfield == "splats"
                                               else "its frame time"))
            ax.set_xscale("log")
            ax.set_title(model)
            ax.set_xlabel("splats" if xfield == "splats" else "frame time (ms, median)")
            ax.grid(True, alpha=0.3, which="both")
            if col == 0:
                ax.set_ylabel(ylabel)
            ax.legend(fontsize=6)

    written = []
    for xfield, name in (("splats", "splat_quality_ssim_vs_splats.png"),
                         ("frame_ms", "splat_quality_ssim_vs_frame.png")):
        fig, axes = plt.subplots(1, len(models), figsize=(5 * len(models), 4.5), squeeze=False)
        draw("masked_ssim", xfield, axes[0], "masked SSIM against the mesh (mean over views)")
        fig.tight_layout()
        fig.savefig(os.path.join(out, name), dpi=100)
        plt.close(fig)
        written.append(name)
    fig, axes = plt.subplots(2, len(models), figsize=(5 * len(models), 8.5), squeeze=False)
    draw("masked_rmse", "splats", axes[0], "masked RMSE, RGB (mean over views)")
    draw("coverage_iou", "splats", axes[1], "coverage IoU (mean over views)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "splat_quality_rmse_iou.png"), dpi=100)
    plt.close(fig)
    written.append("splat_quality_rmse_iou.png")
    return written


def write_csv(path, fields, rows):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)


def picture_setting(args, default_degree, tol0):
    """The setting of the mesh-beside-splats picture: default degree, the s nearest 1."""
    degree = default_degree if default_degree in args.degrees else args.degrees[0]
    s = min(args.s, key=lambda v: abs(v - 1.0))
    return (degree, s, tol0, "s")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--models", nargs="+", metavar="PATH",
                        help="meshes with triangles (default: see --data)")
    parser.add_argument("--data", metavar="DIR",
                        help="folder of the full-size models %s (default: the committed "
                             "Testing/Data/bunny.vtp)" % ", ".join(MODELS))
    parser.add_argument("--out", default="bench-results", help="folder for the CSVs and plots")
    parser.add_argument("--label", default="current",
                        help="names the fitter in the CSV and plots (e.g. previous, new)")
    parser.add_argument("--compare", metavar="CSV",
                        help="splat_quality.csv of an earlier run, drawn beside this one")
    parser.add_argument("--size", default="512", help="window size: 512 or WxH")
    parser.add_argument("--views", type=int, default=len(VIEWS),
                        help="number of views, the first N of %s" % (VIEWS,))
    parser.add_argument("--up", choices=["auto", "x", "y", "z"], default="auto",
                        help="the models' up axis (auto: z for horse and lucy, else y)")
    parser.add_argument("--s", type=float, nargs="+", default=[2, 1.5, 1, 0.75, 0.5, 0.35, 0.25],
                        help="QualityFactor values")
    parser.add_argument("--degrees", type=int, nargs="+", default=[2, 3],
                        help="splat degrees (1 to 4)")
    parser.add_argument("--tolerances", type=float, nargs="+", default=[0.05, 0.1, 0.2, 0.4],
                        help="MaximumDeviation values, when the fitter has it (0: no bound)")
    parser.add_argument("--tolerance-s", nargs="+", default=["1", "0.5"],
                        help="the s at which the tolerances are swept ('all': every s)")
    parser.add_argument("--frames", type=int, default=5, help="renders per frame-time median")
    parser.add_argument("--fit-runs", type=int, default=1, help="fits per fit-time median")
    parser.add_argument("--peer-mesh", nargs=2, action="append", default=[],
                        metavar=("MODEL", "PATH"),
                        help="also score this mesh (e.g. a reconstruction) for MODEL")
    parser.add_argument("--fitter-option", nargs=2, action="append", default=[],
                        metavar=("NAME", "VALUE"), type=str,
                        help="also call the fitter's SetNAME(VALUE) (a number) for every "
                             "setting, e.g. WeightScale 0.5; tell runs apart with --label")
    parser.add_argument("--images", action="store_true",
                        help="write every view's mesh | splats | difference picture")
    parser.add_argument("--quick", action="store_true",
                        help="smoke test: first model, one view, 128 px, degree 3, s = 2 and 1")
    parser.add_argument("--require-module-under", metavar="DIR",
                        help="fail unless the pointsurfaces module is loaded from under DIR")
    args = parser.parse_args()

    fitter_options = bench_csv.fitter_options(parser, args.fitter_option,
                                              pointsurfaces.vtkAlgebraicSplatFitter)
    module = os.path.realpath(pointsurfaces.__file__)
    print("# pointsurfaces module: %s" % module, file=sys.stderr)
    if args.require_module_under:
        root = os.path.realpath(args.require_module_under)
        if not module.startswith(root + os.sep):
            print("bench_splat_quality.py: pointsurfaces is %s, not under %s" % (module, root),
                  file=sys.stderr)
            return 2
        # The shared libraries too: a build tree's RUNPATH may point at another tree.
        libs = set()
        if os.path.exists("/proc/self/maps"):
            with open("/proc/self/maps") as maps:
                libs = {line.split()[-1] for line in maps if "libPointSurfaces" in line}
        stray = sorted(lib for lib in libs if not os.path.realpath(lib).startswith(root + os.sep))
        for lib in sorted(libs):
            print("# loaded: %s" % lib, file=sys.stderr)
        if stray:
            print("bench_splat_quality.py: libraries not under %s: %s (set LD_LIBRARY_PATH)"
                  % (root, ", ".join(stray)), file=sys.stderr)
            return 2
    if not os.environ.get("POINTSURFACES_RENDER_WINDOW"):
        pointsurfaces.use_egl()

    if args.models:
        paths = args.models
    elif args.data:
        paths = [p for p in (find_input(args.data, m, m) for m in MODELS) if p]
    else:
        paths = [BUNNY]
    views = VIEWS[:max(1, args.views)]
    size = parse_size(args.size)
    frames = args.frames
    if args.quick:
        paths, views, size, frames = paths[:1], VIEWS[:1], (128, 128), 1
        args.degrees, args.s, args.tolerances, args.tolerance_s = [3], [2.0, 1.0], [0.2], ["1"]
    # A model named by --models (or the committed Bunny) that cannot be used is an
    # error; one from --data is skipped.
    from_data = args.data and not args.models
    meshes = []
    for p in paths:
        try:
            mesh = load_mesh(p)
        except ScanReadError as e:
            if not from_data:
                print("bench_splat_quality.py: %s" % e, file=sys.stderr)
                return 1
            skip_unreadable(p, e)
            continue
        if mesh.GetNumberOfPolys() == 0:
            if not from_data:
                print("bench_splat_quality.py: %s has no triangles for the reference" % p,
                      file=sys.stderr)
                return 1
            skip(p, "no triangles for the reference")
            continue
        meshes.append((p, mesh))
    if not meshes:
        skip("the run", "no model to score; nothing written")
        return 0
    os.makedirs(args.out, exist_ok=True)
    images_out = args.out if args.images else None

    probe = pointsurfaces.vtkAlgebraicSplatFitter()
    tol0 = probe.GetMaximumDeviation() if hasattr(probe, "SetMaximumDeviation") else None
    runs = settings(args, tol0)
    picture = picture_setting(args, probe.GetDegree(), tol0)
    print("# fitter %s: tolerance knob MaximumDeviation %s; %d fits per model, %d view(s), "
          "%dx%d" % (args.label, "absent" if tol0 is None else "present (default %g)" % tol0,
                     len({r[:3] for r in runs}), len(views), size[0], size[1]), file=sys.stderr)

    print("# load average at start: %.2f %.2f %.2f" % os.getloadavg(), file=sys.stderr)
    scene = Scene(size)
    rows = []
    start = time.perf_counter()
    for path, mesh in meshes:
        name = os.path.splitext(os.path.basename(path))[0]
        up = args.up if args.up != "auto" else next(
            (a for k, a in UP_AXIS.items() if name.startswith(k)), "y")
        model = dict(name=name, views=views, cameras=scene.cameras(mesh, up, views),
                     spacing=mean_edge_length(mesh), outward=outward_normals(mesh))
        scene.show(mesh_actor(mesh))
        model["references"] = [scene.image(state) for state in model["cameras"]]
        points = scan_of(mesh)
        common = dict(model=name, points=points.GetNumberOfPoints(), sweep="", degree="", s="",
                      tolerance="")

        # The mesh against itself, through the path a reconstruction peer takes.
        for r in score_mesh(scene, model, mesh, frames):
            rows.append(dict(r, **common, fitter_label="mesh", method="mesh",
                             splats=mesh.GetNumberOfPolys(), fit_ms="", fit_cpu_ms=""))
        for model_name, peer_path in args.peer_mesh:
            if model_name == name:
                peer = load_mesh(peer_path)
                peer_label = os.path.splitext(os.path.basename(peer_path))[0]
                for r in score_mesh(scene, model, peer, frames, images_out, "peer-" + peer_label):
                    rows.append(dict(r, **common, fitter_label=peer_label, method="peer-mesh",
                                     splats=peer.GetNumberOfPolys(), fit_ms="",
                                     fit_cpu_ms=""))

        done = {}
        for degree, s, tol, sweep in runs:
            setting = dict(common, fitter_label=args.label, method="splats", degree=degree, s=s,
                           tolerance="" if tol is None else tol, sweep=sweep)
            if (degree, s, tol) in done:  # the same fit in the other sweep: reuse it
                rows += [dict(r, sweep=sweep) for r in done[(degree, s, tol)]]
                continue
            splats, fit_ms, fit_cpu_ms = fit_splats(points, degree, s, tol, args.fit_runs,
                                                    fitter_options)
            tag = "%s_d%d_s%g%s" % (args.label, degree, s, "" if tol is None else "_t%g" % tol)
            stray, stray_max = stray_splats(mesh, splats, model["spacing"])
            inward = inward_splats(model["outward"], splats)
            view_rows = [dict(r, **setting, splats=splats.GetNumberOfPoints(),
                              fit_ms="%.1f" % fit_ms, fit_cpu_ms="%.1f" % fit_cpu_ms,
                              stray_splats="%.5f" % stray, stray_max="%.2f" % stray_max,
                              inward_splats="%.5f" % inward)
                         for r in score_actor(scene, model, splat_actor(splats), frames,
                                              images_out, tag)]
            done[(degree, s, tol)] = view_rows
            rows += view_rows
            if (degree, s, tol, sweep) == picture:
                write_png(os.path.join(args.out, "%s_mesh_vs_splats.png" % name),
                          side_by_side(*cropped(model["references"][0], model["last_image"])))
            print("# %s %s d%d s=%g%s: %d splats, fit %.0f ms, SSIM %.4f, RMSE %.4f, IoU %.4f, "
                  "stray %.2f %%, inward %.2f %%, %s ms/frame (%.0f s so far)" % (
                      args.label, name, degree, s, "" if tol is None else " tol=%g" % tol,
                      splats.GetNumberOfPoints(), fit_ms,
                      statistics.fmean(r["masked_ssim"] for r in view_rows),
                      statistics.fmean(r["masked_rmse"] for r in view_rows),
                      statistics.fmean(r["coverage_iou"] for r in view_rows), 100.0 * stray,
                      100.0 * inward,
                      "%.1f" % statistics.median(r["frame_ms"] for r in view_rows)
                      if frames > 0 else "-", time.perf_counter() - start), file=sys.stderr)

    print("# load average at end: %.2f %.2f %.2f (%.0f s)" % (
        os.getloadavg() + (time.perf_counter() - start,)), file=sys.stderr)
    for r in rows:
        for f in ("masked_rmse", "masked_ssim", "coverage_iou"):
            r[f] = "%.5f" % r[f]
        for f in ("frame_ms", "frame_cpu_ms"):
            if r[f] != "":
                r[f] = "%.2f" % r[f]
    path = os.path.join(args.out, "splat_quality.csv")
    write_csv(path, FIELDS, rows)
    writer = csv.DictWriter(sys.stdout, fieldnames=FIELDS, extrasaction="ignore")
    writer.writeheader()
    writer.writerows(rows)

    summary = summarise(rows)
    write_csv(os.path.join(args.out, "splat_quality_summary.csv"), SUMMARY_FIELDS, summary)
    print("# mean over %d view(s): %s" % (len(views), " ".join(SUMMARY_FIELDS)))
    for r in summary:
        print("# " + " ".join(str(r[f]) for f in SUMMARY_FIELDS))
    status = 0
    for r in summary:
        if r["method"] == "mesh" and (float(r["masked_ssim"]) < 0.99999 or
                                      float(r["coverage_iou"]) < 0.99999):
            print("bench_splat_quality.py: the mesh of %s does not match itself" % r["model"],
                  file=sys.stderr)
            status = 1

    compare = summarise(read_csv(args.compare)) if args.compare else []
    for name in plot(summary, compare, args.out):
        print("# wrote " + os.path.join(args.out, name))
    print("# wrote " + path)
    return status


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


if __name__ == "__main__":
    sys.exit(main())
