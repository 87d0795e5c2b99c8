# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""What a change of colouring costs a render in ParaView: the Algebraic Splats
representation against ParaView's Point Gaussian one, in the same process.

    pvbatch bench_paraview_recolor.py PLUGIN SPLATS.vtp [--frames N] [--out DIR]
    pvbatch bench_paraview_recolor.py PLUGIN --smoke [--out DIR]

SPLATS.vtp is a splat set with two point scalar arrays A and B, as
`bench_splat_recolor.py --keep` writes them (splats_N.vtp in its --out).
--smoke fits the Bunny of Testing/Data in ParaView instead (the Algebraic
Splat Fitter; A and B its z and x) and renders 3 frames of each. Each representation shows
it coloured by A, with the camera turned away and the view's prop culling
off, so that a frame draws nothing and its time is what ParaView and the
mapper do before drawing. Then the median of --frames renders after each
event: nothing (plain), another colour array (ColorBy), another range of
A's colour map, another ambient colour (a display property). Output: one
CSV row per representation and event in DIR/paraview_recolor.csv, with the
time less the plain render (extra_ms) and its ratio to Point Gaussian's.
"""
import argparse
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_csv import TEST_DATA, write_rows  # noqa: E402
from paraview.simple import (Calculator, ColorBy, CreateRenderView, Delete,
                             GetColorTransferFunction, LoadPlugin, Render, ResetCamera, Show,
                             XMLPolyDataReader)


def measure(view, display, frames):
    view.GetRenderer().GetCullers().RemoveAllItems()
    ColorBy(display, ("POINTS", "A"))
    Render(view)
    ResetCamera(view)
    camera = view.GetActiveCamera()
    position, focal = camera.GetPosition(), camera.GetFocalPoint()
    camera.SetFocalPoint(*[2.0 * p - f for p, f in zip(position, focal)])  # nothing drawn
    Render(view)
    lut = GetColorTransferFunction("A")
    events = {
        "plain": lambda k: None,
        "array": lambda k: ColorBy(display, ("POINTS", "B" if k % 2 == 0 else "A")),
        "range": lambda k: lut.RescaleTransferFunction(0.0, 1.0 + 0.01 * k),
        "ambient colour": lambda k: setattr(display, "AmbientColor", [1.0, 0.01 * (k % 50), 0.0]),
    }
    times = {}
    for name, event in events.items():
        samples = []
        for k in range(frames):
            start = time.perf_counter()
            event(k)
            Render(view)
            samples.append(1000.0 * (time.perf_counter() - start))
        times[name] = statistics.median(samples)
    ColorBy(display, ("POINTS", "A"))
    return times


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("plugin")
    parser.add_argument("splats", nargs="?")
    parser.add_argument("--frames", type=int, default=7)
    parser.add_argument("--out", default="bench-results")
    parser.add_argument("--smoke", action="store_true")
    args = parser.parse_args()
    if not args.smoke and not args.splats:
        parser.error("give SPLATS.vtp, or --smoke")
    LoadPlugin(args.plugin, ns=globals())
    os.makedirs(args.out, exist_ok=True)
    if args.smoke:
        args.frames = 3
        scan = XMLPolyDataReader(FileName=[os.path.join(TEST_DATA, "bunny.vtp")])
        fitter = AlgebraicSplatFitter(Input=scan)  # noqa: F821 (from the plugin)
        height = Calculator(Input=fitter, ResultArrayName="A", Function="coordsZ")
        reader = Calculator(Input=height, ResultArrayName="B", Function="coordsX")
    else:
        reader = XMLPolyDataReader(FileName=[args.splats])
    reader.UpdatePipeline()
    splats = reader.GetDataInformation().GetNumberOfPoints()
    rows = []
    for representation in ("Algebraic Splats", "Point Gaussian"):
        view = CreateRenderView()
        view.ViewSize = [256, 256]
        view.OrientationAxesVisibility = 0
        display = Show(reader, view)
        display.SetRepresentationType(representation)
        for event, ms in measure(view, display, args.frames).items():
            rows.append(dict(splats=splats, representation=representation, event=event,
                             median_ms=round(ms, 2)))
        Delete(view)  # one GL context at a time: two left to exit made an X error
    plain = {r["representation"]: r["median_ms"] for r in rows if r["event"] == "plain"}
    for r in rows:
        r["extra_ms"] = round(max(0.0, r["median_ms"] - plain[r["representation"]]), 2)
    peer = {r["event"]: r["extra_ms"] for r in rows if r["representation"] == "Point Gaussian"}
    for r in rows:
        r["extra_ratio_to_point_gaussian"] = (round(r["extra_ms"] / peer[r["event"]], 3)
                                              if peer[r["event"]] > 0 else "")
    write_rows(os.path.join(args.out, "paraview_recolor.csv"), rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
