#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Splats against the sampling and the noise of one surface: the density and noise sweeps.

    bench_splat_density.py [MESH] [--points N ...] [--noise F ...] [--noise-unit U]
                           [--variants NAME ...] [--subdivide L] [--size PX] [--out DIR]
                           [--scan FILE] [--views AZ,EL ...] [--pictures DIR] [--smoke]

MESH (default: Testing/Data/bunny.vtp) is any triangle mesh pointsurfaces.scanio
reads. Each sample puts N points uniformly by area on its triangles
(surface_sampling.py; N 0: the mesh's own vertices) and moves each by
Gaussian noise of F times the mesh's bounding-box diagonal (noise along every
axis), or with --noise-unit spacing F times the noise-free sample's mean
spacing (the mean distance of a point to its 6 nearest, over 2 000 points),
the unit of issue 31's noise sweep (0, 0.1, 0.3 and 1 spacing). With
--scan FILE the points are that scan's instead (any file scanio reads, e.g.
a raw range scan of the mesh's object, in the mesh's frame), fitted as they
are and scored against MESH; --views picks the views (azimuth,elevation in
degrees, azimuth 0 to 360; default 0,15 120,-10 240,30), e.g. the scanner's side of a
one-sided scan. With --subdivide L the mesh is first Loop-subdivided L times, and
samples and reference share that smooth surface: sampled on the mesh's own
flat triangles, a dense sample resolves the facets (dihedral angles of
several degrees between flat faces that the reference shades smoothly),
and the fitter follows them. Each variant of the fitter (below) fits every sample; the splats are
drawn as bench_splat_quality.py draws them and scored against the mesh in
three views (masked SSIM, masked RMSE, coverage IoU, as there).

Variants (fitter settings on top of the defaults):

- default: the defaults (bound 0.5 local spacings, ToleranceUnit AUTOMATIC:
  NOISE with MaximumFeatureScale 16 on a noisy sample, SPACING on others);
- spacing: ToleranceUnit SPACING (the defaults before 2026-12-07, and the
  unit every variant below without noise or absolute had until then);
- scaleN: MaximumFeatureScale N (adaptive feature size), e.g. scale4;
- noise: ToleranceUnit NOISE (the bound at least 3 noise scales);
- absolute: ToleranceUnit ABSOLUTE (the bound in world units);
- tolX: MaximumDeviation X (in the tolerance's unit);
- featureX: FeatureNoiseFactor X (0: the first fit at the k-nearest h);
- Name=X: any setting of vtkAlgebraicSplatFitter, e.g. MaximumNormalAngle=10;
- words joined by '+' combine, e.g. noise+scale16.
The default list: default, scale4, scale8, noise, noise+scale4.

Density independence is what the issue asks of the fitter: above the
sampling that resolves the surface, the splat count should stop growing with
N, at the same picture. Output in --out: splat_density.csv (one row per
sample and variant: points, noise and its unit, variant, splats, splats per
point, the unit the bound was measured in (ToleranceUnit AUTOMATIC
resolved), the points no splat covers (vtkSplatErrorMetric), fit seconds, the
fit's peak memory, masked SSIM, RMSE, IoU) and splat_density.png (splats,
fit time, peak memory and SSIM against the points, one line per variant and
noise; against the noise, one line per variant, when there is one N). Each fit runs in a process of its
own that reads the sample from a temporary file, fits and exits; its peak
memory (peak_gb, GiB) is that process's peak resident set (VmHWM): the
interpreter and VTK (about 0.1 GiB), the points read and the fit. Timings are wall-clock
on whatever this runs on: compare them only within one run. With --pictures DIR
each fit's views are also written there as MODEL_POINTS_NOISE_VARIANT_viewK.png
(mesh | splats | difference, as bench_splat_quality.py writes them).
"""
import argparse
import json
import os
import shutil
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_splat_quality as quality  # noqa: E402
from bench_csv import (TEST_DATA, TOLERANCE_UNITS, peak_resident_gib, run_json_child,  # noqa: E402
                       write_rows)
from surface_sampling import sample_surface  # noqa: E402

import pointsurfaces  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkPolyData  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter  # noqa: E402

VARIANTS = ["default", "scale4", "scale8", "noise", "noise+scale4"]


def settings_of(variant):
    """The fitter settings a variant names: words joined by '+', each one of
    default, spacing (ToleranceUnit SPACING), noise (ToleranceUnit NOISE),
    absolute (ToleranceUnit ABSOLUTE),
    scaleN (MaximumFeatureScale N), tolX (MaximumDeviation X), featureX
    (FeatureNoiseFactor X) or Name=X (any setting, e.g. NormalAngle=15)."""
    settings = {}
    for word in variant.split("+"):
        if word == "default":
            continue
        if word == "spacing":
            settings["ToleranceUnit"] = 0
        elif word == "noise":
            settings["ToleranceUnit"] = 1
        elif word == "absolute":
            settings["ToleranceUnit"] = 2
        elif word.startswith("scale") and word[5:].isdigit():
            settings["MaximumFeatureScale"] = int(word[5:])
        elif word.startswith("tol"):
            settings["MaximumDeviation"] = float(word[3:])
        elif word.startswith("feature"):
            settings["FeatureNoiseFactor"] = float(word[7:])
        elif "=" in word:
            name, value = word.split("=", 1)
            settings[name] = int(value) if value.lstrip("-").isdigit() else float(value)
        else:
            raise ValueError("unknown variant word %r in %r" % (word, variant))
    return settings
VIEWS = [(0, 15), (120, -10), (240, 30)]


def mean_spacing(xyz, probes=2000):
    """The mean distance of a point to its 6 nearest others, over `probes` points."""
    from vtkmodules.vtkCommonCore import vtkIdList
    from vtkmodules.vtkCommonDataModel import vtkStaticPointLocator
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz), deep=1))
    data = vtkPolyData()
    data.SetPoints(points)
    locator = vtkStaticPointLocator()
    locator.SetDataSet(data)
    locator.BuildLocator()
    ids = vtkIdList()
    total, count = 0.0, 0
    for i in np.random.default_rng(3).choice(len(xyz), size=min(probes, len(xyz)), replace=False):
        locator.FindClosestNPoints(7, xyz[i], ids)
        near = [ids.GetId(j) for j in range(ids.GetNumberOfIds()) if ids.GetId(j) != i][:6]
        total += float(np.linalg.norm(xyz[near] - xyz[i], axis=1).sum())
        count += len(near)
    return total / max(count, 1)


def sample(mesh, n, noise, diagonal, unit="diagonal"):
    """A vtkPolyData of n points on the mesh (its vertices for n = 0), with noise of
    `noise` times the diagonal or the noise-free sample's mean spacing (`unit`)."""
    if n == 0:
        xyz = vtk_to_numpy(mesh.GetPoints().GetData()).astype(np.float64)
    else:
        xyz = sample_surface(mesh, n)
    if noise > 0:
        length = mean_spacing(xyz) if unit == "spacing" else diagonal
        xyz = xyz + np.random.default_rng(2).normal(0.0, noise * length, xyz.shape)
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz), deep=1))
    cloud = vtkPolyData()
    cloud.SetPoints(points)
    return cloud


def subdivide(mesh, levels):
    """The mesh Loop-subdivided `levels` times (triangles only)."""
    from vtkmodules.vtkFiltersCore import vtkTriangleFilter
    from vtkmodules.vtkFiltersModeling import vtkLoopSubdivisionFilter
    triangles = vtkTriangleFilter()
    triangles.SetInputData(mesh)
    loop = vtkLoopSubdivisionFilter()
    loop.SetInputConnection(triangles.GetOutputPort())
    loop.SetNumberOfSubdivisions(levels)
    loop.Update()
    out = vtkPolyData()
    out.ShallowCopy(loop.GetOutput())
    return out


def fit(cloud, settings):
    fitter = pointsurfaces.vtkAlgebraicSplatFitter()
    fitter.SetInputData(cloud)
    for name, value in settings.items():
        getattr(fitter, "Set" + name)(value)
    start = time.perf_counter()
    fitter.Update()
    seconds = time.perf_counter() - start
    splats = vtkPolyData()
    splats.ShallowCopy(fitter.GetOutput())
    return splats, seconds


def write_vtp(data, path):
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(data)
    writer.SetDataModeToAppended()
    writer.EncodeAppendedDataOff()
    if not writer.Write():
        raise RuntimeError("cannot write " + path)


def read_vtp(path):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    out = vtkPolyData()
    out.ShallowCopy(reader.GetOutput())
    return out


def fit_in_child(cloud_path, variant, folder):
    """Fits in a child process that reads the sample and exits: its splats,
    fit seconds and peak resident memory (GiB: the interpreter, VTK, the
    points read and the fit)."""
    splat_path = os.path.join(folder, "splats.vtp")
    command = [sys.executable, os.path.abspath(__file__), "--child", cloud_path, splat_path,
               "--variants", variant]
    result = run_json_child(command, "the fit of %s (%s)" % (cloud_path, variant))
    return read_vtp(splat_path), result["fit_s"], result["peak_gib"]


def resolved_unit(splats):
    """The unit the fit's bound was measured in (ToleranceUnit AUTOMATIC resolved)."""
    unit = splats.GetFieldData().GetArray("SplatToleranceUnit")
    return TOLERANCE_UNITS[int(unit.GetTuple1(0))] if unit else ""


def child(cloud_path, splat_path, variant):
    splats, seconds = fit(read_vtp(cloud_path), settings_of(variant))
    write_vtp(splats, splat_path)
    print(json.dumps(dict(fit_s=seconds, peak_gib=peak_resident_gib())))
    return 0


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, middle, memory, right) = plt.subplots(1, 4, figsize=(18, 4))
    # Against the noise when every row has one N, else against N.
    by_noise = len({int(r["points"]) for r in rows}) == 1 and len({float(r["noise"]) for r in rows}) > 1
    along = "noise" if by_noise else "points"

    def key_of(r):
        return (r["variant"], None if by_noise else float(r["noise"]), int(r.get("subdivisions", 0)),
                r.get("noise_unit", "diagonal"))
    for key in sorted({key_of(r) for r in rows}, key=str):
        mine = sorted((r for r in rows if key_of(r) == key), key=lambda r: float(r[along]))
        xs = [float(r[along]) for r in mine]
        label = key[0] + ("" if by_noise else ", noise %g %s" % (key[1], key[3])) + \
            (", %d subdivisions" % key[2] if key[2] else "")
        left.plot(xs, [int(r["splats"]) for r in mine], marker="o", label=label)
        middle.plot(xs, [float(r["fit_s"]) for r in mine], marker="o", label=label)
        if all(r.get("peak_gb") not in (None, "") for r in mine):
            memory.plot(xs, [float(r["peak_gb"]) for r in mine], marker="o", label=label)
        right.plot(xs, [float(r["masked_ssim"]) for r in mine], marker="o", label=label)
    for axis, title in ((left, "splats"), (middle, "fit time, s"),
                        (memory, "peak memory of the fit's process, GiB"),
                        (right, "masked SSIM against the mesh")):
        if by_noise:
            axis.set_xscale("symlog", linthresh=0.1)
            axis.set_xlabel("noise, %s" % rows[0].get("noise_unit", "diagonal") + "s")
        else:
            axis.set_xscale("log")
            axis.set_xlabel("points")
        axis.set_title(title)
    left.set_yscale("log")
    middle.set_yscale("log")
    right.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mesh", nargs="?", default=os.path.join(TEST_DATA, "bunny.vtp"))
    parser.add_argument("--points", type=float, nargs="+", default=[2e5, 1e6])
    parser.add_argument("--noise", type=float, nargs="+", default=[1e-4])
    parser.add_argument("--noise-unit", choices=("diagonal", "spacing"), default="diagonal",
                        help="--noise in bounding-box diagonals or in the sample's mean spacings")
    parser.add_argument("--variants", nargs="+", default=VARIANTS)
    parser.add_argument("--size", type=int, default=300, help="image side, pixels")
    parser.add_argument("--up", choices=("x", "y", "z"), help="up axis (default: z for Lucy and the horse)")
    parser.add_argument("--subdivide", type=int, default=0, metavar="L",
                        help="Loop-subdivide the mesh L times first: samples and reference then "
                             "share a smooth surface instead of the mesh's flat facets")
    parser.add_argument("--out", default="bench-results")
    parser.add_argument("--pictures", metavar="DIR",
                        help="also write each fit's views (mesh | splats | difference) into DIR")
    parser.add_argument("--scan", metavar="FILE",
                        help="fit this scan's points (in MESH's frame) instead of samples of MESH")
    parser.add_argument("--views", nargs="+", metavar="AZ,EL",
                        help="views as azimuth,elevation degrees, azimuth 0 to 360 (default %s)"
                             % " ".join("%d,%d" % v for v in VIEWS))
    parser.add_argument("--smoke", action="store_true", help="20 000 points, two variants, 96 pixels")
    parser.add_argument("--child", nargs=2, metavar=("CLOUD", "SPLATS"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        return child(args.child[0], args.child[1], args.variants[0])
    for variant in args.variants:
        try:
            settings_of(variant)
        except ValueError as error:
            parser.error(str(error))
    if args.smoke:
        args.points, args.noise, args.variants, args.size = [2e4], [1e-4], ["default", "scale4"], 96
    os.makedirs(args.out, exist_ok=True)
    mesh = quality.load_mesh(args.mesh)
    if args.subdivide > 0:
        mesh = subdivide(mesh, args.subdivide)
    b = mesh.GetBounds()
    diagonal = ((b[1] - b[0]) ** 2 + (b[3] - b[2]) ** 2 + (b[5] - b[4]) ** 2) ** 0.5
    stem = os.path.basename(args.mesh).split(".")[0]
    up = args.up or quality.UP_AXIS.get(stem.split("_")[0], "y")
    scene = quality.Scene((args.size, args.size))
    views = [tuple(float(x) for x in v.split(",")) for v in args.views] if args.views else VIEWS
    cameras = scene.cameras(mesh, up, views)
    model = dict(name=stem, cameras=cameras, views=views,
                 references=[scene.image(c) for c in cameras])
    if args.pictures:
        os.makedirs(args.pictures, exist_ok=True)
    rows = []
    folder = tempfile.mkdtemp(prefix="bench_splat_density_")
    try:
        if args.scan:
            from pointsurfaces.scanio import read_scan
            cloud = vtkPolyData()
            cloud.SetPoints(read_scan(args.scan).GetPoints())
            stem = os.path.basename(args.scan).split(".")[0]
            args.noise_unit = "scan"
            rows += sweep_sample(args, stem, model, scene, folder, cloud, 0.0)
        else:
            for noise in args.noise:
                for n in [int(p) for p in args.points]:
                    rows += sweep_sample(args, stem, model, scene, folder,
                                         sample(mesh, n, noise, diagonal, args.noise_unit), noise)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    write_rows(os.path.join(args.out, "splat_density.csv"), rows)
    plot(rows, os.path.join(args.out, "splat_density.png"))
    return 0


def uncovered(cloud, splats):
    """The points of `cloud` that no splat covers."""
    metric = pointsurfaces.vtkSplatErrorMetric()
    metric.SetInputData(cloud)
    metric.SetSplatData(splats)
    metric.Update()
    return int(metric.GetNumberOfUncoveredPoints())


def sweep_sample(args, stem, model, scene, folder, cloud, noise):
    """Every variant's fit of one sample, each in a process of its own."""
    rows = []
    cloud_path = os.path.join(folder, "cloud.vtp")
    write_vtp(cloud, cloud_path)
    for variant in args.variants:
        splats, seconds, peak = fit_in_child(cloud_path, variant, folder)
        scores = quality.score_actor(
            scene, model, quality.splat_actor(splats), 0, images_out=args.pictures,
            tag="%d_%g_%s" % (cloud.GetNumberOfPoints(), noise, variant.replace("=", "")))
        rows.append(dict(
            model=stem, subdivisions=args.subdivide, points=cloud.GetNumberOfPoints(), noise=noise,
            noise_unit=args.noise_unit, variant=variant, splats=splats.GetNumberOfPoints(),
            splats_per_point=round(splats.GetNumberOfPoints() / cloud.GetNumberOfPoints(), 4),
            unit=resolved_unit(splats),
            uncovered=uncovered(cloud, splats),
            fit_s=round(seconds, 3), peak_gb=round(peak, 3),
            masked_ssim=round(float(np.mean([s["masked_ssim"] for s in scores])), 4),
            masked_rmse=round(float(np.mean([s["masked_rmse"] for s in scores])), 4),
            coverage_iou=round(float(np.mean([s["coverage_iou"] for s in scores])), 4)))
        print("# %s" % rows[-1], flush=True)
    return rows


if __name__ == "__main__":
    sys.exit(main())
