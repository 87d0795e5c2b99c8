#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Fit a point scan with algebraic splats, render it headless to a PNG, and
report what it cost.

    render_scan.py [input.{ply,vtp,pcd,xyz,obj,off,om,stl}] [output.png]
                   [--size N] [--degree D] [--quality S] [--points]

The scan is read by pointsurfaces.scanio.read_scan: PLY with any elements
(MeshLab's range maps, with a camera before the vertices, included), ASCII
or binary, by pointsurfaces.vtkPLYScanReader; VTP by VTK; PCD by PCL; OBJ, OFF, OM
and STL by OpenMesh; XYZ as x y z per line. A file that cannot be read (a
missing, truncated or damaged file, an unknown extension) ends the script
with one line on stderr naming the file, and exit status 1.

The splats are fitted with vtkAlgebraicSplatFitter (degree D, quality s),
measured against the scan with vtkSplatErrorMetric and ray cast with
vtkAlgebraicSplatMapper. --points draws the raw points as shaded discs with
VTK's vtkPointGaussianMapper instead, the linear-splat baseline. Rendering
goes through PointSurfaces' EGL window when there is no X display.
"""
import argparse
import math
import os
import sys
import time

import pointsurfaces
from pointsurfaces.scanio import ScanReadError, read_scan
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkRenderer, vtkRenderWindow,
                                         vtkWindowToImageFilter)
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLPointGaussianMapper

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_INPUT = os.path.join(HERE, "..", "..", "Testing", "Data", "bunny.vtp")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input", nargs="?", default=DEFAULT_INPUT,
                        help="the scan (default: Testing/Data/bunny.vtp, the Stanford Bunny)")
    parser.add_argument("output", nargs="?", default="scan.png",
                        help="the PNG (default: scan.png)")
    parser.add_argument("--size", type=int, default=800)
    parser.add_argument("--degree", type=int, default=3)
    parser.add_argument("--quality", type=float, default=1.0)
    parser.add_argument("--points", action="store_true", help="draw the raw points instead")
    parser.add_argument("--aa", type=int, default=2, choices=(1, 2, 3),
                        help="adaptive anti-aliasing: n x n rays at silhouette pixels")
    parser.add_argument("--no-blend", action="store_true", help="opaque splats, one pass")
    args = parser.parse_args()

    t0 = time.perf_counter()
    try:
        poly = read_scan(args.input)
    except ScanReadError as e:
        sys.exit("render_scan.py: %s" % e)
    load_s = time.perf_counter() - t0
    n = poly.GetNumberOfPoints()

    report = []
    if args.points:
        spacing = poly.GetLength() / math.sqrt(n)
        mapper = vtkOpenGLPointGaussianMapper()
        mapper.SetInputData(poly)
        mapper.SetScaleFactor(1.4 * spacing)
        mapper.EmissiveOff()
        mapper.SetScalarVisibility(poly.GetPointData().GetScalars() is not None)
        mapper.SetSplatShaderCode(
            "//VTK::Color::Impl\n"
            "float dist = dot(offsetVCVSOutput.xy, offsetVCVSOutput.xy);\n"
            "if (dist > 1.0) { discard; }\n"
            "float shade = sqrt(1.0 - dist);\n"
            "ambientColor *= shade;\n"
            "diffuseColor *= shade;\n")
    else:
        fitter = pointsurfaces.vtkAlgebraicSplatFitter()
        fitter.SetInputData(poly)
        fitter.SetDegree(args.degree)
        fitter.SetQualityFactor(args.quality)
        t0 = time.perf_counter()
        fitter.Update()
        fit_ms = 1000 * (time.perf_counter() - t0)
        metric = pointsurfaces.vtkSplatErrorMetric()
        metric.SetInputData(poly)
        metric.SetSplatConnection(fitter.GetOutputPort())
        metric.Update()
        diagonal = poly.GetLength()
        splats = fitter.GetOutput().GetNumberOfPoints()
        report = [
            "splats:       %d (degree %d, s = %g, %.1f %% of the points)"
            % (splats, args.degree, args.quality, 100.0 * splats / n),
            "fit:          %.1f ms" % fit_ms,
            "error:        RMS %.2e, max %.2e of the bounding-box diagonal, %d points uncovered"
            % (metric.GetRMSDistance() / diagonal, metric.GetMaximumDistance() / diagonal,
               metric.GetNumberOfUncoveredPoints()),
        ]
        mapper = pointsurfaces.vtkAlgebraicSplatMapper()
        mapper.SetInputConnection(fitter.GetOutputPort())
        mapper.SetScalarVisibility(poly.GetPointData().GetScalars() is not None)
        mapper.SetAntiAliasing(args.aa)
        mapper.SetBlending(not args.no_blend)
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(0.85, 0.75, 0.6)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0.1, 0.1, 0.15)
    window = vtkRenderWindow()
    window.SetSize(args.size, args.size)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Zoom(1.3)

    t0 = time.perf_counter()
    window.Render()
    first_ms = 1000 * (time.perf_counter() - t0)
    frames = 10
    t0 = time.perf_counter()
    for _ in range(frames):
        renderer.GetActiveCamera().Azimuth(0.5)
        window.Render()
    frame_ms = 1000 * (time.perf_counter() - t0) / frames

    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    writer = vtkPNGWriter()
    writer.SetInputConnection(grab.GetOutputPort())
    writer.SetFileName(args.output)
    writer.Write()
    print("input:        %s" % os.path.relpath(args.input))
    print("points:       %d" % n)
    for line in report:
        print(line)
    print("window:       %s" % window.GetClassName())
    print("load:         %.1f ms" % (1000 * load_s))
    print("first frame:  %.1f ms (context, shaders, upload)" % first_ms)
    print("frame:        %.1f ms at %dx%d" % (frame_ms, args.size, args.size))
    print("image:        %s" % args.output)


if __name__ == "__main__":
    main()
