#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Benchmarks of the splat fitter. Each prints CSV and writes a plot.

    bench_splat_fit.py counts    [--out DIR] [scans...]   splat counts at s = 1, [Bolla 2010] Table 4.7
                                                          (unbounded fit; the error-bounded default beside it)
    bench_splat_fit.py million   [--out DIR] [--points N] 1M points (sampled on the Bunny's mesh) at s = 1
    bench_splat_fit.py tradeoff  [--out DIR]              error against time over degree, s, k, fit mode
    bench_splat_fit.py fittime   [--out DIR] [--runs N] [--label L] [--fitter-option NAME VALUE] [scans...]
                                                          the error-bounded fit's time against the
                                                          unbounded fit's in the same process, s = 2, 1, 0.5
    bench_splat_fit.py equalquality [--out DIR] [--runs N] [--label L] [--quality PEER.csv SCORES.csv...]
                                 [scans...]             time to the same picture: the unbounded fit at
                                                          its s = 1 and at its best masked SSIM, against
                                                          the cheapest default setting that scores as
                                                          well (scores from bench_splat_quality.py)
    bench_splat_fit.py levels    [--out DIR] [--runs N] [--label L] [scans...]
                                                          single levels at s = 1, 2, 4 and the
                                                          multi-resolution builder, against the
                                                          unbounded fit at s = 1
    add --smoke for a few-second run on a subset (what ctest runs): the committed Bunny
    add --data DIR to counts, fittime, equalquality and levels to read full-size scans

Scans (any file pointsurfaces.scanio reads: .ply .vtp .pcd .xyz .obj .off .om
.stl): those given; else, with --data DIR, the full-size scans in DIR (or a
folder one level below it): bunny.ply, igea.xyz and horse.ply for counts,
bunny.ply, horse.ply and lucy_50k.ply for fittime, equalquality and levels (a
scan not there is skipped, with one line on stderr); else the scans a clone
has: Testing/Data/bunny.vtp (the Stanford Bunny, 35 947 points) and
Testing/Data/bun000.vtp (one raw range scan of it, 40 256 points). million and
tradeoff always use the committed Bunny (million samples points on its
triangles). equalquality times only the scans whose models the quality
summaries hold (bunny, horse, lucy_50k). Times are wall-clock seconds of vtkAlgebraicSplatFitter.Update() on this machine,
with every core vtkSMPTools uses; compare them only within one run.

Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
"""
import argparse
import csv
import math
import os
import sys
import time

import numpy as np
import pointsurfaces
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from pointsurfaces.scanio import ScanReadError, read_scan

import bench_csv
from bench_csv import TEST_DATA, TOLERANCE_UNITS, find_input, skip, skip_unreadable
from surface_sampling import sample_surface

HERE = os.path.dirname(os.path.abspath(__file__))
BUNNY = os.path.join(TEST_DATA, "bunny.vtp")
COMMITTED = [BUNNY, os.path.join(TEST_DATA, "bun000.vtp")]  # the default scans
COUNT_SCANS = ("bunny.ply", "igea.xyz", "horse.ply")  # names in --data
TIMED_SCANS = ("bunny.ply", "horse.ply", "lucy_50k.ply")
THESIS = {"bunny": 1315, "igea": 4819, "horse": 2983}  # [Bolla 2010] Table 4.7, s = 1


def load(path, every=1):
    """The scan's points alone (float64), every `every`th; raises ScanReadError."""
    xyz = vtk_to_numpy(read_scan(path).GetPoints().GetData()).astype(np.float64)
    return points(xyz[::every])


def scan_paths(args, names):
    """The scans a benchmark reads: those given, else `names` in --data (each one
    missing skipped, with one line), else the committed ones."""
    if args.scans:
        return args.scans
    if args.data:
        return [p for p in (find_input(args.data, n, n) for n in names) if p]
    return list(COMMITTED)


def loaded(paths):
    """(path, points) of each scan that can be read; the others skipped, one line each."""
    for path in paths:
        try:
            yield path, load(path)
        except ScanReadError as e:
            skip_unreadable(path, e)


def points(xyz):
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(xyz, dtype=np.float64), deep=True))
    pd = vtkPolyData()
    pd.SetPoints(pts)
    return pd


# The fitter of [Bolla 2010] as PointSurfaces had it before the error bound:
# unbounded discs, quadratic patches, h calibrated on its Table 4.7. The
# peer of the default fitter in every benchmark here.
THESIS_FIT = {"MaximumDeviation": 0.0, "Degree": 2, "FeatureSizeNeighbors": 120}


def fit(pd, **settings):
    fitter = pointsurfaces.vtkAlgebraicSplatFitter()
    fitter.SetInputData(pd)
    for key, value in settings.items():
        getattr(fitter, "Set" + key)(value)
    start = time.perf_counter()
    fitter.Update()
    seconds = time.perf_counter() - start
    metric = pointsurfaces.vtkSplatErrorMetric()
    metric.SetInputData(pd)
    metric.SetSplatData(fitter.GetOutput())
    metric.Update()
    diagonal = pd.GetLength()
    return {"splats": fitter.GetOutput().GetNumberOfPoints(), "seconds": seconds,
            "rms_rel": metric.GetRMSDistance() / diagonal,
            "max_rel": metric.GetMaximumDistance() / diagonal,
            "uncovered": metric.GetNumberOfUncoveredPoints(),
            "unit": TOLERANCE_UNITS[fitter.GetResolvedToleranceUnit()]}


def write(rows, out, name):
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, name + ".csv")
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    writer = csv.DictWriter(sys.stdout, fieldnames=list(rows[0].keys()))
    writer.writeheader()
    writer.writerows(rows)
    return path


def plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as pyplot
    return pyplot


def counts(args):
    scans = [BUNNY] if args.smoke else scan_paths(args, COUNT_SCANS)
    rows = []
    for path, pd in loaded(scans):
        model = os.path.basename(path).split(".")[0].split("_")[0]
        # Table 4.7 is the unbounded fit (THESIS_FIT); the default,
        # error-bounded fit is listed beside it, and that fit with its bound
        # in spacings whatever the sample's noise (ToleranceUnit SPACING, the
        # default before ToleranceUnit AUTOMATIC).
        for order, name, bound, unit in ((0, "random", 0.0, {}), (2, "front", 0.0, {}),
                                         (0, "random, bounded", 0.5, {}),
                                         (0, "random, bounded", 0.5, {"ToleranceUnit": 0})):
            r = fit(pd, SelectionOrder=order, **(THESIS_FIT if bound == 0.0 else unit))
            rows.append({"model": model, "points": pd.GetNumberOfPoints(), "order": name,
                         "maximum_deviation": bound,
                         "tolerance_unit": (("automatic: " if not unit else "") + r["unit"]
                                            if bound > 0.0 else ""),
                         "splats": r["splats"],
                         "percent": round(100.0 * r["splats"] / pd.GetNumberOfPoints(), 2),
                         "thesis": THESIS.get(model, ""), "seconds": round(r["seconds"], 4),
                         "rms_rel": "%.3e" % r["rms_rel"], "max_rel": "%.3e" % r["max_rel"],
                         "uncovered": r["uncovered"]})
    if not rows:
        return skip("counts", "no scan to fit; nothing written")
    write(rows, args.out, "splat_counts")
    pyplot = plt()
    fig, ax = pyplot.subplots(figsize=(6, 4))
    models = sorted({r["model"] for r in rows}, key=[r["model"] for r in rows].index)
    x = np.arange(len(models))
    for i, order in enumerate(("random", "front")):
        ax.bar(x + 0.27 * (i - 1), [next(r["splats"] for r in rows if r["model"] == m and r["order"] == order)
                                    for m in models], 0.27, label="PointSurfaces, %s order" % order)
    ax.bar(x + 0.27, [THESIS.get(m, 0) for m in models], 0.27, label="thesis Table 4.7")
    ax.set_xticks(x)
    ax.set_xticklabels(models)
    ax.set_ylabel("splats at s = 1")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "splat_counts.png"), dpi=100)


def million(args):
    n = 20000 if args.smoke else args.points
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(BUNNY)
    reader.Update()
    mesh = reader.GetOutput()
    sample = sample_surface(mesh, n)
    pd = points(sample)
    rows = []
    # The error-bounded default in both orders, and the unbounded fit of
    # [Bolla 2010] as the peer in the same process.
    for order, name, bound in ((0, "random", None), (2, "front", None), (0, "random, unbounded", 0.0)):
        r = fit(pd, SelectionOrder=order) if bound is None else fit(
            pd, SelectionOrder=order, **THESIS_FIT)
        rows.append({"points": n, "order": name, "splats": r["splats"],
                     "seconds": round(r["seconds"], 3), "rms_rel": "%.3e" % r["rms_rel"],
                     "max_rel": "%.3e" % r["max_rel"]})
    write(rows, args.out, "million")


def timed_scans(args, qualities, smoke_qualities):
    """The scans (see scan_paths: Bunny, Horse, Lucy in --data), s values and runs of a
    timing benchmark; with --smoke, the committed Bunny, `smoke_qualities` and one run."""
    if args.smoke:
        return [BUNNY], smoke_qualities, 1
    return scan_paths(args, TIMED_SCANS), qualities, max(1, args.runs)


def time_fits(pd, settings, runs, warmup=False):
    """Fits `pd` with each setting (name, class name, {setter: value}), the settings
    interleaved `runs` times (after one untimed round with `warmup`); returns
    {name: (median seconds of Update(), last fitter)}."""
    seconds = {name: [] for name, _, _ in settings}
    last = {}
    for run in range(runs + (1 if warmup else 0)):
        for name, cls, pairs in settings:
            fitter = getattr(pointsurfaces, cls)()
            fitter.SetInputData(pd)
            for key, value in pairs.items():
                getattr(fitter, "Set" + key)(value)
            start = time.perf_counter()
            fitter.Update()
            if run > 0 or not warmup:
                seconds[name].append(time.perf_counter() - start)
            last[name] = fitter
    return {name: (float(np.median(seconds[name])), last[name]) for name, _, _ in settings}


def fittime(args):
    """Fit time of the default fitter against the unbounded fit (THESIS_FIT), both
    in this process, runs interleaved; the median of --runs each. Run it
    once per build (e.g. with LD_LIBRARY_PATH at another build's libraries)
    and --label each to compare builds."""
    scans, qualities, runs = timed_scans(args, (2.0, 1.0, 0.5), (1.0,))
    options = args.fitter_options
    rows = []
    for path, pd in loaded(scans):
        model = os.path.basename(path).split(".")[0]
        for s in qualities:
            # The thesis's unbounded fit and the default fitter (with --fitter-option).
            # (An option may set QualityFactor too: it comes last and wins.)
            settings = [("thesis", "vtkAlgebraicSplatFitter", dict(THESIS_FIT, QualityFactor=s)),
                        ("default", "vtkAlgebraicSplatFitter",
                         {"QualityFactor": s, **dict(options)})]
            timed = time_fits(pd, settings, runs)
            unbounded = timed["thesis"][0]
            for name, _, _ in settings:
                median, fitter = timed[name]
                rows.append({"label": args.label, "model": model, "points": pd.GetNumberOfPoints(),
                             "s": s, "maximum_deviation": fitter.GetMaximumDeviation(),
                             "splats": fitter.GetOutput().GetNumberOfPoints(), "runs": runs,
                             "seconds": round(median, 4),
                             "ratio_to_unbounded": round(median / unbounded, 3),
                             "fitter": " ".join([name] + ["%s=%s" % o for o in options
                                                          if name == "default"])})
    if not rows:
        return skip("fittime", "no scan to fit; nothing written")
    path = write(rows, args.out, "fit_time" + ("_" + args.label if args.label else ""))
    pyplot = plt()
    fig, ax = pyplot.subplots(figsize=(6, 4))
    for i, model in enumerate(sorted({r["model"] for r in rows})):
        sel = [r for r in rows if r["model"] == model and r["fitter"] != "thesis"]
        ax.plot([r["s"] for r in sel], [r["ratio_to_unbounded"] for r in sel], "o-", color="C%d" % i,
                label=model)
    ax.axhline(1.5, color="grey", ls="--", lw=1, label="1.5x")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("s")
    ax.set_ylabel("bounded fit time / unbounded fit time")
    ax.legend()
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.splitext(path)[0] + ".png", dpi=100)


RESULTS = os.path.join(HERE, "results")
QUALITY = (os.path.join(RESULTS, "splat_quality_previous_summary.csv"),
           [os.path.join(RESULTS, "splat_quality_summary.csv"),
            os.path.join(RESULTS, "splat_quality_tolerance_summary.csv")])


def sweep_scores(path, model):
    """The settings of `model` scored in a bench_splat_quality.py summary: (degree, s,
    tolerance or None, masked SSIM, fit ms of that run, splats), once each per label."""
    scores = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            if r["model"] == model and r["method"] == "splats":
                tolerance = float(r["tolerance"]) if r["tolerance"] else None
                key = (int(r["degree"]), float(r["s"]), tolerance)
                scores[(r["fitter_label"],) + key] = key + (
                    float(r["masked_ssim"]), float(r["fit_ms"]), int(r["splats"]))
    return list(scores.values())


def equalquality(args):
    """Fit time at equal quality. The fit-time figure at the same s compares discs of
    different sizes: the default's h is half the thesis's, and its error bound stops
    discs where the surface leaves the patch, so it draws 4 to 9 times the splats and
    a better picture. Here the masked SSIM against the mesh (bench_splat_quality.py's
    summaries: --quality PEER SCORES..., the unbounded fit's sweep, then the default
    fitter's s and tolerance sweeps) sets two targets per scan: the unbounded fit's
    score at its default (quadratic, s = 1) and its best over its sweep (degree and
    s). For each, the default fitter's scored settings (degree, s, MaximumDeviation)
    that reach the score in the least fit time (the two fastest by their sweep's
    timing) are timed with the unbounded setting, interleaved in this process after
    one untimed round (median of --runs), and the faster is kept."""
    scans, _, runs = timed_scans(args, (), ())
    peer_csv, score_csvs = (args.quality[0], args.quality[1:]) if args.quality else QUALITY
    rows = []
    for path in scans:
        model = os.path.basename(path).split(".")[0]
        peer = sweep_scores(peer_csv, model)
        ours = [r for csv_path in score_csvs for r in sweep_scores(csv_path, model)]
        if not peer or not ours:
            skip(path, "no scores of %s in %s" % (model, " ".join([peer_csv] + score_csvs)))
            continue
        try:
            pd = load(path)
        except ScanReadError as e:
            skip_unreadable(path, e)
            continue
        targets = [("thesis default", next((r for r in peer if r[0] == 2 and r[1] == 1.0), None)),
                   ("thesis best", max(peer, key=lambda r: r[3]))]
        for target, score in targets:
            if score is None:
                print("equalquality: %s has no %s score (degree 2, s = 1) in %s"
                      % (model, target, peer_csv), file=sys.stderr)
                continue
            pdeg, ps, _, pssim, _, _ = score
            settings = [("thesis", "vtkAlgebraicSplatFitter",
                         dict(THESIS_FIT, Degree=pdeg, QualityFactor=ps))]
            candidates = sorted((r for r in ours if r[3] >= pssim), key=lambda r: r[4])[:2]
            for k, (degree, s, tolerance, _, _, _) in enumerate(candidates):
                chosen = {"Degree": degree, "QualityFactor": s}
                if tolerance is not None:
                    chosen["MaximumDeviation"] = tolerance
                settings.append(("default %d" % k, "vtkAlgebraicSplatFitter", chosen))
            timed = time_fits(pd, settings, runs, warmup=True)
            peer_seconds, peer_fitter = timed["thesis"]
            row = {"label": args.label, "model": model, "target": target, "runs": runs,
                   "thesis_degree": pdeg, "thesis_s": ps, "thesis_ssim": pssim,
                   "thesis_splats": peer_fitter.GetOutput().GetNumberOfPoints(),
                   "thesis_seconds": round(peer_seconds, 4),
                   "default_degree": "", "default_s": "", "default_tolerance": "",
                   "default_ssim": "", "default_splats": "", "default_seconds": "", "ratio": ""}
            if candidates:
                k = min(range(len(candidates)), key=lambda k: timed["default %d" % k][0])
                seconds, fitter = timed["default %d" % k]
                degree, s, _, ssim, _, splats = candidates[k]
                if fitter.GetOutput().GetNumberOfPoints() != splats:
                    print("equalquality: %s at degree %d, s = %g fits %d splats where its score "
                          "has %d: the scores are not this build's"
                          % (model, degree, s, fitter.GetOutput().GetNumberOfPoints(), splats),
                          file=sys.stderr)
                row.update({"default_degree": degree, "default_s": s,
                            "default_tolerance": fitter.GetMaximumDeviation(),
                            "default_ssim": ssim,
                            "default_splats": fitter.GetOutput().GetNumberOfPoints(),
                            "default_seconds": round(seconds, 4),
                            "ratio": round(seconds / peer_seconds, 3)})
            rows.append(row)
    if not rows:
        return skip("equalquality", "no scan with scores to compare; nothing written")
    path = write(rows, args.out, "fit_equal_quality" + ("_" + args.label if args.label else ""))
    pyplot = plt()
    fig, ax = pyplot.subplots(figsize=(6, 4))
    models = sorted({r["model"] for r in rows}, key=[r["model"] for r in rows].index)
    for i, target in enumerate(("thesis default", "thesis best")):
        ratio = {r["model"]: r["ratio"] for r in rows if r["target"] == target}
        # No bar where no setting reached the target.
        ax.bar([k + 0.4 * i - 0.2 for k in range(len(models))],
               [ratio.get(m) or float("nan") for m in models], 0.4, color="C%d" % i,
               label="at the SSIM of the unbounded fit's %s" % target.split()[1])
    ax.axhline(1.5, color="grey", ls="--", lw=1, label="1.5x")
    ax.set_xticks(range(len(models)))
    ax.set_xticklabels(models)
    ax.set_ylabel("default fit time / unbounded fit time")
    ax.legend(fontsize=8)
    ax.grid(True, axis="y", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.splitext(path)[0] + ".png", dpi=100)


def levels(args):
    """Fit time of single levels at s = 1, 2 and 4 and of vtkMultiResolutionSplatBuilder
    (its default 25 levels from s = 4 to 1), the defaults otherwise; the median of --runs
    each, with the unbounded fit (THESIS_FIT) at s = 1 as the peer in this process."""
    scans, qualities, runs = timed_scans(args, (1.0, 2.0, 4.0), (2.0,))
    rows = []
    for path, pd in loaded(scans):
        model = os.path.basename(path).split(".")[0]
        settings = [("thesis, s = 1", "vtkAlgebraicSplatFitter", dict(THESIS_FIT, QualityFactor=1.0))]
        settings += [("s = %g" % s, "vtkAlgebraicSplatFitter", {"QualityFactor": s}) for s in qualities]
        settings += [("multi-resolution", "vtkMultiResolutionSplatBuilder", {})]
        timed = time_fits(pd, settings, runs)
        peer = timed["thesis, s = 1"][0]
        for name, _, _ in settings:
            median, fitter = timed[name]
            rows.append({"label": args.label, "model": model, "fit": name,
                         "splats": fitter.GetOutput().GetNumberOfPoints(),
                         "runs": runs, "seconds": round(median, 4),
                         "ratio_to_thesis_s1": round(median / peer, 3)})
    if not rows:
        return skip("levels", "no scan to fit; nothing written")
    path = write(rows, args.out, "fit_levels" + ("_" + args.label if args.label else ""))
    pyplot = plt()
    fig, ax = pyplot.subplots(figsize=(7, 4))
    names = [r["fit"] for r in rows if r["model"] == rows[0]["model"]]
    models = sorted({r["model"] for r in rows})
    width = 0.8 / len(models)
    for i, model in enumerate(models):
        ratio = {r["fit"]: r["ratio_to_thesis_s1"] for r in rows if r["model"] == model}
        ax.bar([k + i * width for k in range(len(names))], [ratio[n] for n in names], width,
               label=model, color="C%d" % i)
    ax.set_xticks([k + 0.4 - width / 2 for k in range(len(names))])
    ax.set_xticklabels(names, fontsize=8)
    ax.set_ylabel("fit time / unbounded fit at s = 1")
    ax.legend()
    ax.grid(True, axis="y", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.splitext(path)[0] + ".png", dpi=100)


def tradeoff(args):
    pd = load(BUNNY, every=4 if args.smoke else 1)
    degrees = (1, 2) if args.smoke else (1, 2, 3, 4)
    qualities = (1.0,) if args.smoke else (0.5, 1.0, 2.0)
    neighbours = (40,) if args.smoke else (20, 40, 80)
    modes = ((0, "linear"), (2, "projected")) if args.smoke else (
        (0, "linear"), (1, "robust"), (2, "projected"))
    rows = []
    for degree in degrees:
        for s in qualities:
            for k in neighbours:
                for mode, name in modes:
                    r = fit(pd, Degree=degree, QualityFactor=s, NumberOfNeighbors=k, FitMode=mode)
                    rows.append({"degree": degree, "s": s, "k": k, "mode": name,
                                 "splats": r["splats"], "seconds": round(r["seconds"], 4),
                                 "rms_rel": "%.3e" % r["rms_rel"], "max_rel": "%.3e" % r["max_rel"]})
    write(rows, args.out, "tradeoff")
    pyplot = plt()
    fig, ax = pyplot.subplots(figsize=(7, 4.5))
    markers = {"linear": "o", "robust": "s", "projected": "^"}
    for degree in degrees:
        for name in markers:
            sel = [r for r in rows if r["degree"] == degree and r["mode"] == name]
            if sel:
                ax.scatter([r["seconds"] for r in sel], [float(r["rms_rel"]) for r in sel],
                           marker=markers[name], color="C%d" % degree,
                           label="degree %d, %s" % (degree, name))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("fit time [s] (Bunny, this machine)")
    ax.set_ylabel("RMS distance / bounding-box diagonal")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "tradeoff.png"), dpi=100)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("bench", choices=("counts", "million", "tradeoff", "fittime", "equalquality",
                                              "levels"))
    parser.add_argument("scans", nargs="*",
                        help="counts, fittime, equalquality, levels: scans to fit "
                             "(default: see --data)")
    parser.add_argument("--data", metavar="DIR",
                        help="folder of the full-size scans (counts: %s; fittime, equalquality, "
                             "levels: %s); default: Testing/Data/bunny.vtp and bun000.vtp"
                             % (", ".join(COUNT_SCANS), ", ".join(TIMED_SCANS)))
    parser.add_argument("--out", default="bench-results", help="folder for the CSV and plot")
    parser.add_argument("--points", type=int, default=1000000)
    parser.add_argument("--runs", type=int, default=3, help="fittime, equalquality, levels: runs per setting")
    parser.add_argument("--label", default="", help="fittime, equalquality, levels: names the run in the CSV")
    parser.add_argument("--fitter-option", nargs=2, action="append", default=[],
                        metavar=("NAME", "VALUE"),
                        help="fittime: also call SetNAME(VALUE) (a number) on the default fitter, "
                             "e.g. MaximumDeviation 0 FeatureSizeNeighbors 24 for the unbounded fit "
                             "at today's h; tell runs apart with --label")
    parser.add_argument("--quality", nargs="+", metavar="CSV",
                        help="equalquality: bench_splat_quality.py summaries, the unbounded fit's "
                             "sweep first, then the default fitter's (default: the committed "
                             "ones in results/)")
    parser.add_argument("--smoke", action="store_true",
                        help="a few seconds on the committed Bunny (what ctest runs)")
    args = parser.parse_args()
    if args.quality and len(args.quality) < 2:
        parser.error("--quality: the unbounded fit's summary and at least one of the default's")
    args.fitter_options = bench_csv.fitter_options(parser, args.fitter_option,
                                                   pointsurfaces.vtkAlgebraicSplatFitter)
    {"counts": counts, "million": million, "tradeoff": tradeoff, "fittime": fittime,
     "equalquality": equalquality, "levels": levels}[args.bench](args)


if __name__ == "__main__":
    main()
