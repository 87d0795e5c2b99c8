#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Render a PDB molecule as a blobby metaball surface, headless, to a PNG.

    molecule_metaballs.py [input.pdb] [output.png] [--size N] [--shadows]

input.pdb is any PDB file (default: Testing/Data/hemoglobin_chainA.pdb, chain
A of hemoglobin 3GQP, 1 079 atoms, which a clone has); output.png defaults to
molecule.png in the current folder.

Atoms are read by VTK's vtkPDBReader; each becomes a metaball whose support
radius is twice its van der Waals radius (RadiusScale 2: with Wyvill's kernel
and T = 0.5 a lone atom shows at its van der Waals radius), coloured by
element through the reader's rgb_colors array. Prints the atom count and the
mapper's per-frame grid build, ray cast and shadow times.
"""
import argparse
import os
import sys
import time

import pointsurfaces
from vtkmodules.vtkIOChemistry import vtkPDBReader
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLight, vtkRenderer, vtkRenderWindow,
                                         vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

HERE = os.path.dirname(os.path.abspath(__file__))
# Chain A of hemoglobin (PDB 3GQP, 1 079 atoms), which a clone has.
DEFAULT_INPUT = os.path.join(HERE, "..", "..", "Testing", "Data", "hemoglobin_chainA.pdb")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input", nargs="?", default=DEFAULT_INPUT,
                        help="any PDB file (default: Testing/Data/hemoglobin_chainA.pdb)")
    parser.add_argument("output", nargs="?", default="molecule.png",
                        help="the PNG (default: molecule.png)")
    parser.add_argument("--size", type=int, default=800)
    parser.add_argument("--shadows", action="store_true")
    args = parser.parse_args()
    if not os.path.exists(args.input):
        print("molecule_metaballs.py: no such file: " + args.input)
        return 1
    pointsurfaces.use_egl() if not os.environ.get("DISPLAY") else None

    reader = vtkPDBReader()
    reader.SetFileName(args.input)
    reader.Update()
    atoms = reader.GetOutput().GetNumberOfPoints()

    mapper = pointsurfaces.vtkMetaballMapper()
    mapper.SetInputConnection(reader.GetOutputPort())
    mapper.GetField().SetRadiusArrayName("radius")
    mapper.GetField().SetRadiusScale(2.0)
    mapper.SetColorModeToDirectScalars()
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("rgb_colors")
    mapper.SetShadows(args.shadows)
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetAmbient(0.25)
    actor.GetProperty().SetDiffuse(0.8)
    actor.GetProperty().SetSpecular(0.3)
    actor.GetProperty().SetSpecularPower(20)

    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0.1, 0.1, 0.15)
    if args.shadows:
        # A light above and to the side casts the shadows; a dim headlight
        # keeps the shadowed side readable.
        head = vtkLight()
        head.SetLightTypeToHeadlight()
        head.SetIntensity(0.35)
        renderer.AddLight(head)
        light = vtkLight()
        light.SetLightTypeToSceneLight()
        light.SetPositional(False)
        light.SetPosition(1.0, 1.5, 1.0)
        light.SetFocalPoint(0.0, 0.0, 0.0)
        renderer.AddLight(light)
    window = vtkRenderWindow()
    window.SetSize(args.size, args.size)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Zoom(1.4)
    t0 = time.perf_counter()
    window.Render()
    first_ms = 1000.0 * (time.perf_counter() - t0)
    t0 = time.perf_counter()
    window.Render()
    window.GetZbufferDataAtPoint(0, 0)
    frame_ms = 1000.0 * (time.perf_counter() - t0)
    # One more frame that waits for its statistics (GPU times are a frame late).
    mapper.CollectStatisticsOn()
    window.Render()

    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    writer = vtkPNGWriter()
    writer.SetFileName(args.output)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print("atoms:        %d" % atoms)
    print("window:       %s" % window.GetClassName())
    print("first frame:  %.1f ms (context, shaders, upload)" % first_ms)
    print("frame:        %.1f ms at %dx%d: grid %.1f ms, rays %.1f ms, shadows %.1f ms"
          % (frame_ms, args.size, args.size, mapper.GetGridBuildTime(), mapper.GetRayCastTime(),
             mapper.GetShadowTime()))
    print("grid:         %d (voxel, ball) pairs, at most %d balls per voxel"
          % (mapper.GetNumberOfPairs(), mapper.GetMaximumBallsPerVoxel()))
    print("image:        %s" % args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
