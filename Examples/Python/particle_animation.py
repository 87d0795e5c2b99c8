#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Render a particle time series as metaballs, headless, one PNG a frame.

    particle_animation.py [INPUT ...] [--out DIR] [--frames N] [--size N]
                          [--radius R] [--structure GRO] [--vdb]

INPUT is a time series, one file a step, in the order given (a shell glob
such as 'steps/*.vtp' sorts them): .vtp or .vtu (any point set; a "Radius"
point array is used when present), .vdb (OpenVDB point grids, through
vtkOpenVDBPointsReader; "pscale" is the radius) or .xyz (x y z per line);
or a trajectory in one file, every frame of which is a step: a LAMMPS dump
(.lammpstrj, .dump, vtkLAMMPSDumpReader; a "radius" column is the radius)
a GROMACS .gro (vtkGromacsGroReader; van der Waals radii of the elements)
or a GROMACS .xtc (vtkGromacsXtcReader; --structure names a .gro of the same
atoms, whose elements give the radii).
With no input, a built-in simulation runs instead: 20 000 particles falling
into a swirling vortex, coloured by speed.

Every frame, the positions change and vtkMetaballMapper rebuilds its
perspective grid and ray-casts the blobby surface (on the GPU, or natively
on the CPU under a software OpenGL such as llvmpipe); nothing else is
uploaded again. The camera stays fixed (set from the first frame), so
the frames can be joined into a video, for example with
`ffmpeg -i DIR/frame_%04d.png anim.mp4`. --vdb also writes each frame's
surface as an OpenVDB level set (DIR/frame_NNNN.vdb) for Houdini or Blender.
Prints the per-frame grid build and ray-cast times.
"""
import argparse
import os
import sys
import time

import numpy as np

import pointsurfaces
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkIOXML import vtkXMLGenericDataObjectReader
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkRenderer,
                                         vtkRenderWindow, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401


# Trajectories whose one file holds every step: their reader and radius array.
TRAJECTORIES = {".lammpstrj": "vtkLAMMPSDumpReader", ".dump": "vtkLAMMPSDumpReader",
                ".gro": "vtkGromacsGroReader", ".xtc": "vtkGromacsXtcReader"}


def trajectory_reader(path, structure=None):
    """The reader of a one-file trajectory; an .xtc takes its atoms' names from `structure`."""
    reader = getattr(pointsurfaces, TRAJECTORIES[os.path.splitext(path)[1].lower()])()
    reader.SetFileName(path)
    if structure and hasattr(reader, "SetStructureFileName"):
        reader.SetStructureFileName(structure)
    return reader


def expand_steps(inputs, structure=None):
    """(file, time or None, structure) for each time step: a trajectory gives one per frame."""
    steps = []
    for path in inputs:
        if os.path.splitext(path)[1].lower() in TRAJECTORIES:
            reader = trajectory_reader(path, structure)
            reader.UpdateInformation()
            times = reader.GetOutputInformation(0).Get(
                vtkStreamingDemandDrivenPipeline.TIME_STEPS()) or ()
            steps += [(path, t, structure) for t in times]
        else:
            steps.append((path, None, None))
    return steps


def read_step(path, time_value=None, structure=None):
    """Centres (n x 3) and radii (n, or None) of one time step."""
    ext = os.path.splitext(path)[1].lower()
    if ext == ".xyz":
        return np.loadtxt(path, ndmin=2)[:, :3], None
    if ext in TRAJECTORIES:
        reader = trajectory_reader(path, structure)
        reader.UpdateTimeStep(time_value)
        data = reader.GetOutput()
        if data.GetNumberOfPoints() == 0:
            raise RuntimeError("no atoms in %s at time %g" % (path, time_value))
        xyz = vtk_to_numpy(data.GetPoints().GetData()).astype(np.float64)
        radius = data.GetPointData().GetArray("radius")
        return xyz, vtk_to_numpy(radius).astype(np.float64) if radius is not None else None
    if ext == ".vdb":
        reader = pointsurfaces.vtkOpenVDBPointsReader()
        radius_name = "pscale"
    else:
        reader = vtkXMLGenericDataObjectReader()
        radius_name = "Radius"
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutput()
    if data is None or data.GetNumberOfPoints() == 0:
        raise RuntimeError("no points in " + path)
    xyz = vtk_to_numpy(data.GetPoints().GetData()).astype(np.float64)
    radius = data.GetPointData().GetArray(radius_name)
    return xyz, (vtk_to_numpy(radius).astype(np.float64).reshape(len(xyz), -1)[:, 0]
                 if radius is not None else None)


def spacing_radius(xyz):
    """A support radius for particles without one: about three neighbours inside each."""
    extent = np.ptp(xyz, axis=0).max()
    return 1.6 * extent * (3.0 / len(xyz)) ** (1.0 / 3.0) / 2.0


class Vortex:
    """Particles falling into a swirling vortex, re-seeded at the top."""

    def __init__(self, n, seed=3):
        self.rng = np.random.default_rng(seed)
        self.xyz = self.seed(n)
        self.xyz[:, 2] = self.rng.uniform(-1.0, 1.0, n)

    def seed(self, n):
        r = np.sqrt(self.rng.uniform(0.04, 1.0, n))
        a = self.rng.uniform(0.0, 2.0 * np.pi, n)
        return np.column_stack([r * np.cos(a), r * np.sin(a), np.full(n, 1.0)])

    def step(self, dt=0.04):
        x, y, z = self.xyz.T
        r2 = x * x + y * y + 0.05
        # Swirl around z, pull inward, fall.
        velocity = np.column_stack([-y / r2 - 0.3 * x, x / r2 - 0.3 * y, -1.2 * np.ones_like(z)])
        self.xyz += dt * velocity
        out = self.xyz[:, 2] < -1.0
        self.xyz[out] = self.seed(int(out.sum()))
        return np.linalg.norm(velocity, axis=1)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("inputs", nargs="*", help="one file a time step (default: a simulation)")
    parser.add_argument("--out", default="frames")
    parser.add_argument("--frames", type=int, default=60, help="simulated frames (no input)")
    parser.add_argument("--particles", type=int, default=20000, help="simulated particles")
    parser.add_argument("--size", type=int, default=640)
    parser.add_argument("--radius", type=float, default=0.0,
                        help="support radius where the data has none (default: from spacing)")
    parser.add_argument("--structure", help="a .gro of an .xtc's atoms (names, radii)")
    parser.add_argument("--vdb", action="store_true", help="also write OpenVDB level sets")
    args = parser.parse_args()
    for path in args.inputs + ([args.structure] if args.structure else []):
        if not os.path.exists(path):
            print("particle_animation.py: no such file: " + path)
            return 1
    if not os.environ.get("DISPLAY"):
        pointsurfaces.use_egl()
    os.makedirs(args.out, exist_ok=True)

    vortex = None if args.inputs else Vortex(args.particles)
    inputs = expand_steps(args.inputs, args.structure)
    steps = len(inputs) if args.inputs else args.frames

    poly = vtkPolyData()
    points = vtkPoints()
    points.SetDataTypeToDouble()
    poly.SetPoints(points)
    mapper = pointsurfaces.vtkMetaballMapper()
    mapper.SetInputData(poly)
    mapper.GetField().SetRadiusArrayName("Radius")  # every step gets one (below)
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetSpecular(0.3)
    actor.GetProperty().SetSpecularPower(30)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0.08, 0.09, 0.12)
    window = vtkRenderWindow()
    window.SetSize(args.size, args.size)
    window.SetMultiSamples(0)
    window.AddRenderer(renderer)
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ReadFrontBufferOff()
    png = vtkPNGWriter()
    png.SetInputConnection(grab.GetOutputPort())
    level_set = pointsurfaces.vtkMetaballLevelSetWriter() if args.vdb else None
    if level_set:
        level_set.GetField().SetRadiusArrayName("Radius")

    builds, rays, frames = [], [], []
    for k in range(steps):
        if vortex:
            speed = vortex.step()
            xyz, radii = vortex.xyz, None
        else:
            xyz, radii = read_step(*inputs[k])
            speed = None
        if radii is None:
            if args.radius <= 0.0:
                args.radius = spacing_radius(xyz)
            radii = np.full(len(xyz), args.radius)
        # New arrays every step: the mapper sees the change and uploads once.
        points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz), deep=True))
        radius_array = numpy_to_vtk(radii, deep=True)
        radius_array.SetName("Radius")
        poly.GetPointData().AddArray(radius_array)
        if speed is not None:
            colours = numpy_to_vtk(speed, deep=True)
            colours.SetName("Speed")
            poly.GetPointData().SetScalars(colours)
            lut = vtkColorTransferFunction()
            lo, hi = np.percentile(speed, [5, 95])
            lut.AddRGBPoint(float(lo), 0.2, 0.35, 0.8)
            lut.AddRGBPoint(float(0.5 * (lo + hi)), 0.9, 0.9, 0.85)
            lut.AddRGBPoint(float(hi), 1.0, 0.45, 0.15)
            mapper.SetLookupTable(lut)
            mapper.UseLookupTableScalarRangeOn()
        poly.Modified()
        if k == 0:
            # From the side, a little above: the vortex axis is z.
            camera = renderer.GetActiveCamera()
            camera.SetFocalPoint(0.0, 0.0, 0.0)
            camera.SetPosition(0.0, -4.0, 1.2)
            camera.SetViewUp(0.0, 0.0, 1.0)
            renderer.ResetCamera()
            renderer.ResetCameraClippingRange()
        t0 = time.perf_counter()
        window.Render()
        window.GetZbufferDataAtPoint(0, 0)
        frames.append(1000.0 * (time.perf_counter() - t0))
        builds.append(mapper.GetGridBuildTime())
        rays.append(mapper.GetRayCastTime())
        name = os.path.join(args.out, "frame_%04d" % k)
        grab.Modified()
        png.SetFileName(name + ".png")
        png.Write()
        if level_set:
            level_set.SetInputData(poly)
            level_set.SetFileName(name + ".vdb")
            level_set.Write()

    print("frames:       %d of %d particles, %dx%d, in %s" % (steps, len(xyz), args.size,
                                                              args.size, args.out))
    print("window:       %s, %s ray caster" % (
        window.GetClassName(), "CPU" if mapper.GetRayCasterInUse() == mapper.CPU else "GPU"))
    print("per frame:    median %.1f ms (grid build %.2f ms, ray cast %.1f ms); first %.1f ms"
          % (float(np.median(frames[1:] or frames)), float(np.median(builds)),
             float(np.median(rays)), frames[0]))
    print("uploads:      %d (one a changed frame)" % mapper.GetNumberOfUploads())
    if level_set:
        print("level sets:   %d .vdb files, voxel %.4g" % (steps, level_set.GetUsedVoxelSize()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
