# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""What the plugin's ParaView tests share: the view, the protein scene, image comparison.

Imported by TestPointSurfacesPlugin.py (pvbatch) and TestPointSurfacesClient.py
(pvpython client), after paraview.simple can be imported.
"""
import os
import shutil

from paraview.simple import ColorBy, CreateRenderView, PDBReader, Plane, RedistributeDataSet
from paraview.simple import Render, Show
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

SIZE = [320, 320]


class Checks:
    """Verdicts printed as ctest reads them: "ok:" or "FAILED:" lines.

    Only `rank` 0 decides: under --symmetric the other rank's data
    information holds only its own piece. Call it as check(ok, what); the
    failures are kept in `failures`.
    """

    def __init__(self, rank):
        self.rank = rank
        self.failures = []

    def __call__(self, ok, what):
        if self.rank != 0:
            return
        print(("ok:     " if ok else "FAILED: ") + what, flush=True)
        if not ok:
            self.failures.append(what)


def new_view():
    """A render view as the baselines were taken: 320 x 320, no axes, plain background."""
    view = CreateRenderView()
    view.ViewSize = SIZE
    view.OrientationAxesVisibility = 0
    view.Background = [0.32, 0.34, 0.43]
    view.UseColorPaletteForBackground = 0
    view.UseFXAA = 0  # screen-space anti-aliasing differs between serial and composited images
    return view


def show_protein(view, data, split):
    """A protein chain as Metaballs with element colours, through a plane; the camera set.

    With `split` the atoms go through RedistributeDataSet first. Returns the balls' display.
    """
    atoms = PDBReader(FileName=os.path.join(data, "hemoglobin_chainA.pdb"))
    balls = Show(RedistributeDataSet(Input=atoms) if split else atoms, view)
    balls.SetRepresentationType("Metaballs")
    balls.MetaballRadiusArray = "radius"
    balls.MetaballRadiusScale = 2.0
    ColorBy(balls, ("POINTS", "rgb_colors"))
    balls.MapScalars = 0
    b = atoms.GetDataInformation().GetBounds()
    centre = [0.5 * (b[2 * k] + b[2 * k + 1]) for k in range(3)]
    plane = Plane(Origin=[b[0] - 5, b[2] - 5, centre[2]], Point1=[b[1] + 5, b[2] - 5, centre[2]],
                  Point2=[b[0] - 5, b[3] + 5, centre[2]])
    plane_display = Show(plane, view)
    plane_display.DiffuseColor = [0.8, 0.8, 0.8]
    plane_display.Opacity = 1.0
    # The first render resets the camera to the (rank-dependent) bounds: set it after.
    Render(view)
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[0] + 50, centre[1] - 75, centre[2] + 75]
    view.CameraViewUp = [0, 0, 1]
    Render(view)
    return balls


def pixels(path):
    """An image file's dimensions and its RGB values as integers, one row per pixel."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    return image.GetDimensions(), vtk_to_numpy(image.GetPointData().GetScalars()).astype(int)[:, :3]


def differing_pixels(path, baseline):
    """The share of pixels with a channel more than 40/255 off the baseline.

    Returns (share, None), or (None, why) when the images cannot be compared.
    """
    if not os.path.exists(baseline):
        return None, "no baseline %s" % baseline
    (dims, a), (dims_b, b) = pixels(path), pixels(baseline)
    if dims != dims_b:
        return None, "image size %s, baseline %s" % (dims, dims_b)
    return (abs(a - b).max(axis=1) > 40).mean(), None


def compare_baseline(check, path, baselines, name, mpi, tolerance):
    """Rank 0's picture at `path` against BASELINES/NAME.png, through `check`.

    With POINTSURFACES_UPDATE_BASELINES=1 a serial run writes the baseline
    instead.
    """
    baseline = os.path.join(baselines, name + ".png")
    if os.environ.get("POINTSURFACES_UPDATE_BASELINES") and not mpi:
        shutil.copyfile(path, baseline)
        print("wrote baseline " + baseline)
        return
    differ, why = differing_pixels(path, baseline)
    if why:
        check(False, "%s: %s" % (name, why))
        return
    check(differ <= tolerance, "%s: %.3f %% of the pixels differ from the baseline (at most %.1f %%)"
          % (name, 100 * differ, 100 * tolerance))
