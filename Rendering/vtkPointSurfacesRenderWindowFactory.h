// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPointSurfacesRenderWindowFactory
 * @brief   Object-factory override that decides what vtkRenderWindow::New() returns.
 *
 * Debian's VTK 9.1 and 9.3 only know vtkXOpenGLRenderWindow, which aborts the
 * process when there is no X display. This factory overrides `vtkRenderWindow`
 * so that every VTK pipeline (C++, Python, the test drivers) gets a window that
 * works. "The EGL window" below is vtkEGLHeadlessRenderWindow on those VTK
 * versions, and VTK's own vtkEGLRenderWindow on VTK 9.4 and later built with
 * EGL (Debian's 9.6), which choose between X and EGL at run time themselves:
 * there `Auto` with a usable X display leaves vtkRenderWindow to VTK (whose
 * chain, without X, ends in an OSMesa window that crashes when libOSMesa is
 * missing; GetEGLWindowClassName() says which EGL window is used).
 *
 * | mode   | vtkRenderWindow::New() returns |
 * |--------|--------------------------------|
 * | `Auto` | VTK's X window when an X display can be opened, else the EGL window |
 * | `EGL`  | always the EGL window |
 * | `X11`  | VTK's X window; without a usable display, a warning and the EGL window |
 *
 * The one switch is the environment variable `POINTSURFACES_RENDER_WINDOW`,
 * read when the PointSurfaces::Rendering library is loaded: `auto` (default),
 * `egl`, `x11`, or `vtk` to leave VTK's own factory untouched. From code,
 * `vtkPointSurfacesRenderWindowFactory::InstallAsDefault()` (Python:
 * `pointsurfaces.use_egl()`) selects the EGL window, and SetMode() any mode.
 *
 * When neither EGL nor X works, the EGL window reports a clear error at the
 * first Render() and draws nothing, instead of aborting.
 */
#ifndef vtkPointSurfacesRenderWindowFactory_h
#define vtkPointSurfacesRenderWindowFactory_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkObjectFactory.h"

class POINTSURFACESRENDERING_EXPORT vtkPointSurfacesRenderWindowFactory : public vtkObjectFactory
{
public:
  static vtkPointSurfacesRenderWindowFactory* New();
  vtkTypeMacro(vtkPointSurfacesRenderWindowFactory, vtkObjectFactory);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** Which render window the factory hands out (POINTSURFACES_RENDER_WINDOW). */
  enum Modes
  {
    Auto = 0,
    EGL = 1,
    X11 = 2
  };

  /**
   * Register the factory (once), make its override the enabled one for
   * vtkRenderWindow, and set the mode. Returns false for an unknown mode.
   */
  static bool SetMode(int mode);

  /** The current mode, or -1 when the factory is not installed. */
  static int GetMode();

  /** SetMode(EGL): every new vtkRenderWindow is the EGL window (GetEGLWindowClassName()). */
  static bool InstallAsDefault() { return SetMode(EGL); }

  /** Unregister the factory and give vtkRenderWindow back to VTK's own overrides. */
  static void Uninstall();

  /**
   * Apply `POINTSURFACES_RENDER_WINDOW` (auto, egl, x11 or vtk); unknown
   * values give a warning and `auto`. Called when the library is loaded.
   */
  static void ConfigureFromEnvironment();

  /** True when $DISPLAY names an X server that accepts a connection (cached). */
  static bool IsXDisplayUsable();

  /** The class a vtkRenderWindow::New() would get in the current mode. */
  static const char* GetSelectedWindowClassName();

  /**
   * The headless window of this VTK: vtkEGLHeadlessRenderWindow (VTK 9.1 to
   * 9.3) or VTK's vtkEGLRenderWindow (9.4 and later, built with EGL, when an
   * EGL display can be initialised: VTK's window crashes in Render() when
   * none can, ours reports it and draws nothing).
   */
  static const char* GetEGLWindowClassName();

  const char* GetVTKSourceVersion() override;
  const char* GetDescription() override;

protected:
  vtkPointSurfacesRenderWindowFactory();
  ~vtkPointSurfacesRenderWindowFactory() override = default;

private:
  vtkPointSurfacesRenderWindowFactory(const vtkPointSurfacesRenderWindowFactory&) = delete;
  void operator=(const vtkPointSurfacesRenderWindowFactory&) = delete;
};

#endif
