// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSurfacesRenderWindowFactory.h"

#include "vtkAutoInit.h"
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkRenderingOpenGLConfigure.h"
#include "vtkVersion.h"
#include "vtkVersionMacros.h"
#include "vtkXOpenGLRenderWindow.h"

// VTK 9.4 and later, built with EGL (Debian's 9.6 is), choose between X and
// EGL at run time themselves and select EGL devices
// (VTK_DEFAULT_EGL_DEVICE_INDEX): there, `auto` leaves vtkRenderWindow to VTK
// when X works, and otherwise (and in `egl` mode) the factory gives VTK's own
// vtkEGLRenderWindow. Older VTK (Debian's 9.1 and 9.3) is X only: there the
// factory supplies vtkEGLHeadlessRenderWindow.
#if (VTK_MAJOR_VERSION > 9 || (VTK_MAJOR_VERSION == 9 && VTK_MINOR_VERSION >= 4)) &&               \
  defined(VTK_OPENGL_HAS_EGL)
#define POINTSURFACES_VTK_EGL_WINDOW 1
#include "vtkEGLRenderWindow.h"
#else
#define POINTSURFACES_VTK_EGL_WINDOW 0
#endif

#include <EGL/egl.h>
#include <X11/Xlib.h>

#include <cstdlib>
#include <mutex>
#include <string>

// VTK's own OpenGL factory must be registered before ours is, so that the
// enable flags set below apply to its vtkRenderWindow override too.
VTK_MODULE_INIT(vtkRenderingOpenGL2);

vtkStandardNewMacro(vtkPointSurfacesRenderWindowFactory);

namespace
{
int CurrentMode = -1;
vtkPointSurfacesRenderWindowFactory* Installed = nullptr;

int X11ErrorIgnorer(Display*, XErrorEvent*)
{
  return 0;
}

bool ProbeXDisplay()
{
  const char* name = std::getenv("DISPLAY");
  if (!name || !*name)
  {
    return false;
  }
  // XOpenDisplay itself never aborts; it returns null when nothing answers.
  auto previous = XSetErrorHandler(X11ErrorIgnorer);
  Display* dpy = XOpenDisplay(name);
  XSetErrorHandler(previous);
  // The connection stays open for the life of the process: closing the last
  // client makes a default X server (Xvfb too) reset, and a window opened
  // during that reset is refused.
  return dpy != nullptr;
}

// Whether any EGL display can be initialised. VTK 9.6's vtkEGLRenderWindow
// crashes in Render() when none can; vtkEGLHeadlessRenderWindow reports it.
bool EGLUsable()
{
  static const bool usable = []
  {
    const EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    EGLint major = 0, minor = 0;
    // Left initialised: the window initialises the same display again.
    return display != EGL_NO_DISPLAY && eglInitialize(display, &major, &minor) == EGL_TRUE;
  }();
  return usable;
}

bool UseX11()
{
  switch (CurrentMode)
  {
    case vtkPointSurfacesRenderWindowFactory::EGL:
      return false;
    case vtkPointSurfacesRenderWindowFactory::X11:
      if (!vtkPointSurfacesRenderWindowFactory::IsXDisplayUsable())
      {
        static std::once_flag warned;
        std::call_once(warned,
          []
          {
            vtkGenericWarningMacro(<< "POINTSURFACES_RENDER_WINDOW=x11, but no X display can be "
                                      "opened (DISPLAY='"
                                   << (std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "")
                                   << "'): using the EGL window instead.");
          });
        return false;
      }
      return true;
    default:
      return vtkPointSurfacesRenderWindowFactory::IsXDisplayUsable();
  }
}

vtkObject* CreateRenderWindow()
{
  if (UseX11())
  {
    return vtkXOpenGLRenderWindow::New();
  }
#if POINTSURFACES_VTK_EGL_WINDOW
  if (EGLUsable())
  {
    vtkEGLRenderWindow* window = vtkEGLRenderWindow::New();
    if (const char* device = std::getenv("POINTSURFACES_EGL_DEVICE"))
    {
      window->SetDeviceIndex(std::atoi(device));
    }
    return window;
  }
#endif
  return vtkEGLHeadlessRenderWindow::New();
}

bool EnvironmentApplied = false;

void ApplyEnvironmentOnce()
{
  if (!EnvironmentApplied)
  {
    EnvironmentApplied = true;
    vtkPointSurfacesRenderWindowFactory::ConfigureFromEnvironment();
  }
}

// Applies the environment switch when the library is loaded (Python imports,
// programs that call into the library).
struct EnvironmentSwitch
{
  EnvironmentSwitch() { ApplyEnvironmentOnce(); }
} TheEnvironmentSwitch;
} // namespace

// The module implements VTK::RenderingCore: vtk_module_autoinit() in a
// consumer calls this before main(), so C++ programs that only link the
// module (and never name one of its symbols) get the switch as well.
POINTSURFACESRENDERING_EXPORT void PointSurfacesRendering_AutoInit_Construct()
{
  ApplyEnvironmentOnce();
}

POINTSURFACESRENDERING_EXPORT void PointSurfacesRendering_AutoInit_Destruct() {}

//------------------------------------------------------------------------------
vtkPointSurfacesRenderWindowFactory::vtkPointSurfacesRenderWindowFactory()
{
  this->RegisterOverride("vtkRenderWindow",
    "vtkEGLHeadlessRenderWindow",
    "PointSurfaces render window (EGL when no X display)",
    1,
    CreateRenderWindow);
}

//------------------------------------------------------------------------------
bool vtkPointSurfacesRenderWindowFactory::SetMode(int mode)
{
  if (mode != Auto && mode != EGL && mode != X11)
  {
    vtkGenericWarningMacro(<< "Unknown render window mode " << mode);
    return false;
  }
#if POINTSURFACES_VTK_EGL_WINDOW
  if (mode == Auto && IsXDisplayUsable())
  {
    // VTK's own factory gives its X window (and ParaView 6.1's client crashes
    // deleting an X window made outside it). Without X, VTK would go on from
    // EGL to OSMesa and crash in Render() when libOSMesa is missing, so the
    // override stays, with VTK's EGL window.
    Uninstall();
    CurrentMode = Auto;
    return true;
  }
#endif
  if (!Installed)
  {
    // The registry owns the factory; VTK frees it with the other factories at exit.
    Installed = vtkPointSurfacesRenderWindowFactory::New();
    vtkObjectFactory::RegisterFactory(Installed);
    Installed->Delete();
  }
  // Factories are asked in registration order: turn every other
  // vtkRenderWindow override off so that ours answers wherever it sits.
  vtkObjectFactory::SetAllEnableFlags(0, "vtkRenderWindow");
  vtkObjectFactory::SetAllEnableFlags(1, "vtkRenderWindow", "vtkEGLHeadlessRenderWindow");
  CurrentMode = mode;
  return true;
}

//------------------------------------------------------------------------------
int vtkPointSurfacesRenderWindowFactory::GetMode()
{
  return CurrentMode;
}

//------------------------------------------------------------------------------
void vtkPointSurfacesRenderWindowFactory::Uninstall()
{
  if (!Installed)
  {
    return;
  }
  vtkObjectFactory::UnRegisterFactory(Installed);
  Installed = nullptr;
  CurrentMode = -1;
  vtkObjectFactory::SetAllEnableFlags(1, "vtkRenderWindow");
}

//------------------------------------------------------------------------------
void vtkPointSurfacesRenderWindowFactory::ConfigureFromEnvironment()
{
  const char* value = std::getenv("POINTSURFACES_RENDER_WINDOW");
  const std::string mode = value ? value : "";
  if (mode == "vtk")
  {
    Uninstall();
  }
  else if (mode == "egl")
  {
    SetMode(EGL);
  }
  else if (mode == "x11" || mode == "x")
  {
    SetMode(X11);
  }
  else
  {
    if (!mode.empty() && mode != "auto")
    {
      vtkGenericWarningMacro(<< "POINTSURFACES_RENDER_WINDOW='" << mode
                             << "' is not one of auto, egl, x11, vtk: using auto.");
    }
    SetMode(Auto);
  }
}

//------------------------------------------------------------------------------
bool vtkPointSurfacesRenderWindowFactory::IsXDisplayUsable()
{
  static const bool usable = ProbeXDisplay();
  return usable;
}

//------------------------------------------------------------------------------
const char* vtkPointSurfacesRenderWindowFactory::GetSelectedWindowClassName()
{
  if (CurrentMode < 0)
  {
    return "vtkXOpenGLRenderWindow"; // VTK's own choice, with a display
  }
  return UseX11() ? "vtkXOpenGLRenderWindow" : GetEGLWindowClassName();
}

//------------------------------------------------------------------------------
const char* vtkPointSurfacesRenderWindowFactory::GetEGLWindowClassName()
{
  return POINTSURFACES_VTK_EGL_WINDOW && EGLUsable() ? "vtkEGLRenderWindow"
                                                     : "vtkEGLHeadlessRenderWindow";
}

//------------------------------------------------------------------------------
const char* vtkPointSurfacesRenderWindowFactory::GetVTKSourceVersion()
{
  return VTK_SOURCE_VERSION;
}

//------------------------------------------------------------------------------
const char* vtkPointSurfacesRenderWindowFactory::GetDescription()
{
  return "PointSurfaces headless render window factory";
}

//------------------------------------------------------------------------------
void vtkPointSurfacesRenderWindowFactory::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << CurrentMode << "\n";
}
