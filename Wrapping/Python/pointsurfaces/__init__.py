# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""PointSurfaces: algebraic splats and metaballs for VTK.

Import it with Debian's ``/usr/bin/python3`` next to ``vtkmodules``::

    import pointsurfaces
    pointsurfaces.use_egl()          # optional: render headless through EGL

Every class of the PointSurfaces modules is available here, for example
``pointsurfaces.vtkEGLHeadlessRenderWindow``; those of a third-party library
(OpenVDB, OpenMesh, PCL, HDF5) where its module was built
(``pointsurfaces.OPTIONAL_MODULES``). ``pointsurfaces.scanio``
reads scans (.ply .vtp .pcd .xyz .obj .off .om .stl) into a vtkPolyData,
with one clear error for a bad file: ``scanio.read_scan(path)``.

Which window ``vtkRenderWindow()`` returns is decided by the environment
variable ``POINTSURFACES_RENDER_WINDOW`` (``auto``, ``egl``, ``x11`` or
``vtk``), read at import; ``use_egl()`` and ``set_render_window_mode()``
change it from code.
"""

# VTK's own OpenGL factory first, so that ours takes precedence over it.
from vtkmodules import vtkRenderingOpenGL2 as _vtkRenderingOpenGL2  # noqa: F401

from .PointSurfacesFilters import *  # noqa: F401,F403
from .PointSurfacesFiltersParallel import *  # noqa: F401,F403
from .PointSurfacesIO import *  # noqa: F401,F403
from .PointSurfacesRendering import *  # noqa: F401,F403
from .PointSurfacesRendering import vtkPointSurfacesRenderWindowFactory as _Factory

# The modules of third-party libraries are built when the library is found
# (OpenVDB, OpenMesh, PCL's io, VTK's HDF5, LASzip): the classes of those that were
# built are here too; OPTIONAL_MODULES says which ones.
OPTIONAL_MODULES = {}
for _name in ("FiltersOpenVDB", "IOOpenVDB", "IOOpenMesh", "IOPCL", "IOHDF5", "IOLAS",
              "RenderingHDF5"):
    try:
        _module = __import__("pointsurfaces.PointSurfaces" + _name, fromlist=["*"])
    except ImportError:
        OPTIONAL_MODULES[_name] = False
        continue
    OPTIONAL_MODULES[_name] = True
    globals().update({k: v for k, v in vars(_module).items() if k.startswith("vtk")})
del _name

__version__ = "0.1.0"

_MODES = {"auto": _Factory.Auto, "egl": _Factory.EGL, "x11": _Factory.X11}


def use_egl():
    """Make every new vtkRenderWindow headless, through EGL (egl_window_class())."""
    return bool(_Factory.InstallAsDefault())


def egl_window_class():
    """The headless window of this VTK: vtkEGLHeadlessRenderWindow (VTK 9.1 to
    9.3) or VTK's own vtkEGLRenderWindow (9.4 and later, built with EGL)."""
    return _Factory.GetEGLWindowClassName()


def set_render_window_mode(mode):
    """Select 'auto', 'egl' or 'x11' windows, or 'vtk' for VTK's own factory."""
    if mode == "vtk":
        _Factory.Uninstall()
        return True
    if mode not in _MODES:
        raise ValueError("mode must be one of auto, egl, x11, vtk, not %r" % (mode,))
    return bool(_Factory.SetMode(_MODES[mode]))


def render_window_class():
    """The class name that vtkRenderWindow() returns in the current mode."""
    return _Factory.GetSelectedWindowClassName()
