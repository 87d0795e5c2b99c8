# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""`import pointsurfaces` with Debian's python3: the wrapped classes, the
render-window switch, and the headless window's state."""
import os

import pointsurfaces
from pstesting import fail
from vtkmodules.vtkRenderingCore import vtkRenderWindow

for name in ("vtkEGLHeadlessRenderWindow", "vtkPointSurfacesRenderWindowFactory",
             "vtkComputeShaderProgram", "vtkShaderStorageBuffer", "vtkAlgebraicSplatFitter",
             "vtkSplatErrorMetric", "vtkAtomRadii", "vtkMultiResolutionSplatBuilder",
             "vtkAlgebraicSplatMapper"):
    if not hasattr(pointsurfaces, name):
        fail("pointsurfaces has no " + name)

# The optional libraries' modules: each built one's classes are here, and
# OPTIONAL_MODULES says which were built (all of them in the test build,
# whose packages install-deps.sh installs).
optional = {"FiltersOpenVDB": "vtkOpenVDBParticleMesher", "IOOpenVDB": "vtkOpenVDBPointsReader",
            "IOOpenMesh": "vtkOpenMeshReader", "IOPCL": "vtkPCDReader",
            "IOHDF5": "vtkGadgetHDF5Reader", "IOLAS": "vtkLASReader",
            "RenderingHDF5": "vtkStreamingSplatMapper"}


def release():
    with open("/etc/os-release") as f:
        return dict(line.rstrip("\n").split("=", 1) for line in f if "=" in line).get(
            "VERSION_CODENAME", "").strip('"')


# Debian 12 packages no LAS library: IOLAS is built from Debian 13 on.
expected = {m: m != "IOLAS" or release() != "bookworm" for m in optional}
if sorted(pointsurfaces.OPTIONAL_MODULES) != sorted(optional):
    fail("OPTIONAL_MODULES lists %s" % sorted(pointsurfaces.OPTIONAL_MODULES))
for module, cls in optional.items():
    if pointsurfaces.OPTIONAL_MODULES.get(module) != hasattr(pointsurfaces, cls):
        fail("%s: OPTIONAL_MODULES says %s, the class %s is %s" % (
            module, pointsurfaces.OPTIONAL_MODULES.get(module), cls,
            "there" if hasattr(pointsurfaces, cls) else "missing"))
    if pointsurfaces.OPTIONAL_MODULES.get(module) != expected[module]:
        fail("the test build %s PointSurfaces::%s" % (
            "lacks" if expected[module] else "has", module))

# vtkEGLHeadlessRenderWindow up to VTK 9.3, VTK's vtkEGLRenderWindow from 9.4.
egl_class = pointsurfaces.egl_window_class()
if egl_class not in ("vtkEGLHeadlessRenderWindow", "vtkEGLRenderWindow"):
    fail("egl_window_class() names " + egl_class)
if not pointsurfaces.use_egl():
    fail("use_egl() returned False")
window = vtkRenderWindow()
if window.GetClassName() != egl_class:
    fail("after use_egl(), vtkRenderWindow() is a " + window.GetClassName())
if pointsurfaces.render_window_class() != egl_class:
    fail("render_window_class() disagrees with use_egl()")

try:
    pointsurfaces.set_render_window_mode("wayland")
    fail("an unknown mode was accepted")
except ValueError:
    pass

# 'vtk' hands window creation back to VTK itself.
pointsurfaces.set_render_window_mode("vtk")
if vtkRenderWindow().GetClassName() == "vtkEGLHeadlessRenderWindow":
    fail("mode 'vtk' still creates our EGL window")
pointsurfaces.set_render_window_mode("auto")
expected = "vtkXOpenGLRenderWindow" if os.environ.get("DISPLAY") else egl_class
if not os.environ.get("DISPLAY") and vtkRenderWindow().GetClassName() != expected:
    fail("auto without DISPLAY should give the EGL window")

egl = pointsurfaces.vtkEGLHeadlessRenderWindow()
if egl.IsInitialized() or egl.GetPlatformName() != "none":
    fail("a new EGL window must not hold a context before its first render")
print("TestPythonPackage: passed")
