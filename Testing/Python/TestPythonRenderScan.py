# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Render the Bunny scan's points from Python through the window that
POINTSURFACES_RENDER_WINDOW selects, and compare with the shared baseline."""
import os

import pointsurfaces  # installs the render-window switch
from pstesting import compare_image, data_file, fail
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLPointGaussianMapper

reader = vtkXMLPolyDataReader()
reader.SetFileName(data_file("bunny.vtp"))
reader.Update()
if reader.GetOutput().GetNumberOfPoints() != 35947:
    fail("bunny.vtp should hold 35947 points")

mapper = vtkOpenGLPointGaussianMapper()
mapper.SetInputConnection(reader.GetOutputPort())
mapper.SetScaleFactor(0.0012)
mapper.EmissiveOff()
# Opaque, shaded discs (VTK's documented splat hook) instead of Gaussian blobs.
mapper.SetSplatShaderCode(
    "//VTK::Color::Impl\n"
    "float dist = dot(offsetVCVSOutput.xy, offsetVCVSOutput.xy);\n"
    "if (dist > 1.0) { discard; }\n"
    "float shade = sqrt(1.0 - dist);\n"
    "ambientColor *= shade;\n"
    "diffuseColor *= shade;\n")
actor = vtkActor()
actor.SetMapper(mapper)
actor.GetProperty().SetColor(0.85, 0.75, 0.6)

renderer = vtkRenderer()
renderer.AddActor(actor)
renderer.SetBackground(0.1, 0.1, 0.15)
window = vtkRenderWindow()
window.SetSize(300, 300)
window.SetMultiSamples(0)
window.AddRenderer(renderer)
renderer.ResetCamera()
renderer.GetActiveCamera().Zoom(1.4)

mode = os.environ.get("POINTSURFACES_RENDER_WINDOW")
expected = {"egl": pointsurfaces.egl_window_class(), "x11": "vtkXOpenGLRenderWindow"}.get(mode)
if expected and window.GetClassName() != expected:
    fail("POINTSURFACES_RENDER_WINDOW=%s gave a %s" % (mode, window.GetClassName()))
compare_image(window, "TestPythonRenderScan")
print("TestPythonRenderScan: passed")
