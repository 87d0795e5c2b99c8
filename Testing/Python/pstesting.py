# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Shared helpers of the Python tests: data paths and image regression.

ctest passes POINTSURFACES_DATA_DIR (Testing/Data), POINTSURFACES_BASELINE_DIR
and POINTSURFACES_TEMP_DIR in the environment.
"""
import os
import sys

from vtkmodules.test import Testing as _vtktesting


def data_file(name):
    return os.path.join(os.environ["POINTSURFACES_DATA_DIR"], name)


def compare_image(render_window, name, threshold=0.15):
    """Compare the window with <baseline dir>/<name>.png (alternates <name>_1.png ...).

    Raises RuntimeError, with VTK's CDash measurements printed, on mismatch or
    when the baseline is missing; the test image is left in the temp dir.
    """
    temp = os.environ["POINTSURFACES_TEMP_DIR"]
    os.makedirs(temp, exist_ok=True)
    _vtktesting.VTK_TEMP_DIR = temp
    baseline = os.path.join(os.environ["POINTSURFACES_BASELINE_DIR"], name + ".png")
    render_window.Render()
    # Always keep the test image, so scripts/update-baseline.sh can pick it up.
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter
    grab = vtkWindowToImageFilter()
    grab.SetInput(render_window)
    grab.ReadFrontBufferOff()
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(os.path.join(temp, name + ".png"))
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    _vtktesting.compareImageWithSavedImage(grab, baseline, threshold)


def fail(message):
    print("FAILED: " + message)
    sys.exit(1)
