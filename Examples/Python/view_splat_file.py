#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Draw a multi-resolution splat file within a GPU memory budget, its pages
loaded by a thread while the view moves.

    view_splat_file.py [file.psplat] [--budget MB] [--pixel-error PX] [--size N]
                       [--orbit N] [--png out.png]

The file is one that vtkStreamingSplatFitter or vtkSplatFileWriter wrote
(docs/guide/large-clouds.md); without one, the Bunny (Testing/Data/bunny.vtp)
is fitted with three levels and written as bunny.psplat first.
vtkStreamingSplatMapper draws it: each render asks for the pages and levels
the view needs within --budget MB of GPU buffers and draws what is in memory;
a thread reads the rest, coarsest levels first.

With --png, or without a display, the camera orbits --orbit steps (one render
a step, never waiting for the disk), then waits for the last view's pages and
writes the picture. Otherwise a window opens: a timer renders again while
pages load, so the picture sharpens as you turn it. A file that cannot be
read ends the script with the mapper's one-line error and exit status 1.
"""
import argparse
import os
import sys
import time

import pointsurfaces
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkRenderer, vtkRenderWindow,
                                         vtkRenderWindowInteractor, vtkWindowToImageFilter)

HERE = os.path.dirname(os.path.abspath(__file__))
BUNNY = os.path.join(HERE, "..", "..", "Testing", "Data", "bunny.vtp")


def make_bunny_file(path):
    from pointsurfaces.scanio import read_scan
    fitter = pointsurfaces.vtkAlgebraicSplatFitter()
    fitter.SetInputData(read_scan(BUNNY))
    fitter.SetNumberOfLevels(3)
    writer = pointsurfaces.vtkSplatFileWriter()
    writer.SetInputConnection(fitter.GetOutputPort())
    writer.SetFileName(path)
    writer.SetPageSize(1024)
    writer.Write()


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("file", nargs="?", help="a .psplat file (default: the Bunny, made here)")
    parser.add_argument("--budget", type=float, default=256.0, help="MB of GPU buffers")
    parser.add_argument("--pixel-error", type=float, default=1.0,
                        help="levels down to splats this many pixels across (0: all)")
    parser.add_argument("--size", type=int, default=800)
    parser.add_argument("--orbit", type=int, default=12, help="steps of the orbit (--png)")
    parser.add_argument("--png", help="orbit, then write the last view here")
    args = parser.parse_args()
    if not getattr(pointsurfaces, "vtkStreamingSplatMapper", None):
        sys.exit("view_splat_file.py: this build has no PointSurfaces::RenderingHDF5")

    path = args.file
    if not path:
        path = "bunny.psplat"
        make_bunny_file(path)
    headless = args.png or not os.environ.get("DISPLAY")
    if headless:
        pointsurfaces.use_egl()

    mapper = pointsurfaces.vtkStreamingSplatMapper()
    mapper.SetFileName(path)
    mapper.SetMemoryBudget(args.budget)
    mapper.SetLODPixelError(args.pixel_error)
    errors = []

    @calldata_type(VTK_STRING)
    def on_error(caller, event, message):
        errors.append(message.strip().splitlines()[-1])
    mapper.AddObserver(vtkCommand.ErrorEvent, on_error)
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(0.9, 0.85, 0.75)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0.1, 0.1, 0.15)
    window = vtkRenderWindow()
    window.AddRenderer(renderer)
    window.SetSize(args.size, args.size)
    renderer.ResetCamera()  # the file's bounds, before any page is loaded

    start = time.perf_counter()
    window.Render()
    if errors or mapper.GetNumberOfSplats() == 0:
        sys.exit("view_splat_file.py: %s" % (errors[0] if errors else path + ": nothing to draw"))
    first = None
    if not headless:
        # The mapper renders again by itself while pages load
        # (RenderWhileLoading): no timer of our own.
        interactor = vtkRenderWindowInteractor()
        interactor.SetRenderWindow(window)
        interactor.Initialize()
        interactor.Start()
        return 0

    camera = renderer.GetActiveCamera()
    frames = []
    for _ in range(args.orbit):
        camera.Azimuth(360.0 / max(1, args.orbit))
        renderer.ResetCameraClippingRange()
        t = time.perf_counter()
        window.Render()
        frames.append(time.perf_counter() - t)
        if first is None and mapper.GetNumberOfResidentSplats() > 0:
            first = time.perf_counter() - start
    while mapper.GetLoading():
        mapper.WaitForPages(1.0)
        window.Render()
    if first is None:
        first = time.perf_counter() - start
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    writer = vtkPNGWriter()
    writer.SetInputConnection(grab.GetOutputPort())
    writer.SetFileName(args.png or "view_splat_file.png")
    writer.Write()
    print("splats:       %d in %s (%.1f MB)" % (mapper.GetNumberOfSplats(), path,
                                                 os.path.getsize(path) / 1e6))
    print("resident:     %d (%.1f MB of GPU buffers, budget %g MB)" % (
        mapper.GetNumberOfResidentSplats(),
        mapper.GetNumberOfResidentSplats() * mapper.GetBytesPerSplat() / 1e6, args.budget))
    print("first:        %.2f s to the first picture with splats" % first)
    if frames:
        print("orbit:        %d frames, median %.0f ms, longest %.0f ms (not waiting for the disk)"
              % (len(frames), 1000 * sorted(frames)[len(frames) // 2], 1000 * max(frames)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
