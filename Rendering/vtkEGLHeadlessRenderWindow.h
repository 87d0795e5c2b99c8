// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkEGLHeadlessRenderWindow
 * @brief   OpenGL 4.5 core render window on EGL, with no X server and no surface.
 *
 * Debian's VTK 9.1 and 9.3 are built for X11 only: without a DISPLAY their
 * vtkXOpenGLRenderWindow aborts the process. This window opens an EGL display
 * instead and renders into VTK's own framebuffer objects, so tests, batch
 * renders and benchmarks run headless. (VTK 9.4 and later ship their own
 * vtkEGLRenderWindow, which vtkPointSurfacesRenderWindowFactory uses there
 * whenever an EGL display can be initialised; this window stays for the
 * case where none can, which it reports instead of crashing.)
 *
 * - on NVIDIA (or any vendor with EGL_EXT_platform_device), through an EGL
 *   device of a real GPU (`EGL_PLATFORM_DEVICE_EXT`);
 * - on CPUs, through Mesa's llvmpipe on `EGL_PLATFORM_SURFACELESS_MESA`;
 * - otherwise through the default EGL display.
 *
 * The context is created without a surface (EGL_KHR_surfaceless_context) and
 * VTK's framebuffers are never blitted to a window. It overrides
 * OpenGLInitContext() because Debian's GLEW, built for GLX, returns
 * GLEW_ERROR_NO_GLX_DISPLAY after it has already loaded every GL entry point
 * (from VTK 9.4 on, it loads GL with glad through eglGetProcAddress).
 *
 * When no EGL display or context can be had, Render() reports a clear
 * vtkErrorMacro once, draws nothing and returns: it never aborts.
 *
 * `POINTSURFACES_EGL_DEVICE=<n>` picks the n-th EGL device. Selection of this
 * window as VTK's default render window is done by
 * vtkPointSurfacesRenderWindowFactory.
 */
#ifndef vtkEGLHeadlessRenderWindow_h
#define vtkEGLHeadlessRenderWindow_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkOpenGLRenderWindow.h"

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class POINTSURFACESRENDERING_EXPORT vtkEGLHeadlessRenderWindow : public vtkOpenGLRenderWindow
{
public:
  static vtkEGLHeadlessRenderWindow* New();
  vtkTypeMacro(vtkEGLHeadlessRenderWindow, vtkOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Create the EGL display and context (once) and initialise VTK's GL state.
   * Failure leaves the window uninitialised and is reported by GetLastError().
   */
  void Initialize() override;
  void Finalize() override;
  ///@}

  ///@{
  /** vtkRenderWindow's interface, on the window's own EGL context. */
  void Start() override;
  void Render() override;
  void Frame() override;
  void MakeCurrent() override;
  void ReleaseCurrent() override;
  bool IsCurrent() override;
  int* GetScreenSize() VTK_SIZEHINT(2) override;
  void* GetGenericContext() override;
  void* GetGenericDisplayId() override;
  vtkTypeBool GetEventPending() override { return 0; }
  ///@}

  ///@{
  /**
   * There is no default framebuffer: these report VTK's own render
   * framebuffer when the default one is bound (vtkHardwareSelector checks
   * them before picking).
   */
  int GetColorBufferSizes(int* rgba) override;
  int GetDepthBufferSize() override;
  ///@}

  /** True when an EGL context exists and VTK's GL state is initialised. */
  bool IsInitialized() const { return this->Initialized; }

  /**
   * Why the last initialisation failed, or an empty string.
   */
  const char* GetLastError() const;

  /**
   * Which EGL platform the window runs on: "device", "surfaceless", "default",
   * or "none" before initialisation.
   */
  const char* GetPlatformName() const;

  /** The GL_RENDERER string of the context, or an empty string. */
  const char* GetRendererName() const;

protected:
  vtkEGLHeadlessRenderWindow();
  ~vtkEGLHeadlessRenderWindow() override;

  void CreateAWindow() override;
  void DestroyWindow() override;
  void OpenGLInitContext() override;
  int ReadPixels(const vtkRecti& rect, int front, int glFormat, int glType, void* data, int right)
    override;

private:
  vtkEGLHeadlessRenderWindow(const vtkEGLHeadlessRenderWindow&) = delete;
  void operator=(const vtkEGLHeadlessRenderWindow&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
