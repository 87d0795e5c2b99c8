// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkEGLHeadlessRenderWindow.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkEGLHeadlessRenderWindow);

namespace
{
const char* EGLErrorName(EGLint code)
{
  switch (code)
  {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default:
      return "EGL error";
  }
}

bool HasExtension(const char* list, const char* name)
{
  if (!list)
  {
    return false;
  }
  const size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + 1, name))
  {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
    {
      return true;
    }
  }
  return false;
}

// EGL displays are per-device singletons: several windows may share one, so
// eglTerminate only runs when the last window using it goes away.
std::mutex DisplayMutex;
std::map<EGLDisplay, int>& DisplayUsers()
{
  static std::map<EGLDisplay, int> users;
  return users;
}

void RetainDisplay(EGLDisplay dpy)
{
  std::lock_guard<std::mutex> lock(DisplayMutex);
  ++DisplayUsers()[dpy];
}

void ReleaseDisplay(EGLDisplay dpy)
{
  std::lock_guard<std::mutex> lock(DisplayMutex);
  auto it = DisplayUsers().find(dpy);
  if (it != DisplayUsers().end() && --it->second <= 0)
  {
    DisplayUsers().erase(it);
    eglTerminate(dpy);
  }
}
} // namespace

struct vtkEGLHeadlessRenderWindow::Internals
{
  EGLDisplay Display = EGL_NO_DISPLAY;
  EGLContext Context = EGL_NO_CONTEXT;
  EGLSurface Surface = EGL_NO_SURFACE; // only when EGL_KHR_surfaceless_context is missing
  std::string Platform = "none";
  std::string Error;
  std::string Renderer;
  bool CreationFailed = false;
  bool FailureReported = false;
  int ScreenSize[2] = { 0, 0 };

  // Initialise dpy and create a core context on it; on failure terminate it
  // and append the reason to Error.
  bool TryDisplay(EGLDisplay dpy, const char* platform)
  {
    std::ostringstream why;
    if (dpy == EGL_NO_DISPLAY)
    {
      this->Error += std::string(platform) + ": no display; ";
      return false;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(dpy, &major, &minor))
    {
      this->Error +=
        std::string(platform) + ": eglInitialize failed (" + EGLErrorName(eglGetError()) + "); ";
      return false;
    }
    RetainDisplay(dpy);
    if (!eglBindAPI(EGL_OPENGL_API))
    {
      this->Error += std::string(platform) + ": no desktop OpenGL API; ";
      ReleaseDisplay(dpy);
      return false;
    }
    const EGLint configAttribs[] = { EGL_SURFACE_TYPE,
      0,
      EGL_RENDERABLE_TYPE,
      EGL_OPENGL_BIT,
      EGL_RED_SIZE,
      8,
      EGL_GREEN_SIZE,
      8,
      EGL_BLUE_SIZE,
      8,
      EGL_NONE };
    EGLConfig config = nullptr;
    EGLint numConfigs = 0;
    if (!eglChooseConfig(dpy, configAttribs, &config, 1, &numConfigs) || numConfigs < 1)
    {
      this->Error += std::string(platform) + ": no OpenGL config; ";
      ReleaseDisplay(dpy);
      return false;
    }
    // Ask for 4.5 core (compute shaders, SSBOs), then settle for what VTK needs.
    const EGLint versions[][2] = { { 4, 5 }, { 4, 3 }, { 3, 2 } };
    for (const auto& v : versions)
    {
      const EGLint ctxAttribs[] = { EGL_CONTEXT_MAJOR_VERSION,
        v[0],
        EGL_CONTEXT_MINOR_VERSION,
        v[1],
        EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
        EGL_NONE };
      this->Context = eglCreateContext(dpy, config, EGL_NO_CONTEXT, ctxAttribs);
      if (this->Context != EGL_NO_CONTEXT)
      {
        break;
      }
    }
    if (this->Context == EGL_NO_CONTEXT)
    {
      this->Error +=
        std::string(platform) + ": eglCreateContext failed (" + EGLErrorName(eglGetError()) + "); ";
      ReleaseDisplay(dpy);
      return false;
    }
    if (!HasExtension(eglQueryString(dpy, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
    {
      const EGLint pbufferAttribs[] = { EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE };
      this->Surface = eglCreatePbufferSurface(dpy, config, pbufferAttribs);
    }
    if (!eglMakeCurrent(dpy, this->Surface, this->Surface, this->Context))
    {
      this->Error +=
        std::string(platform) + ": eglMakeCurrent failed (" + EGLErrorName(eglGetError()) + "); ";
      this->DestroyContext(dpy);
      ReleaseDisplay(dpy);
      return false;
    }
    this->Display = dpy;
    this->Platform = platform;
    this->Error.clear();
    return true;
  }

  void DestroyContext(EGLDisplay dpy)
  {
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (this->Surface != EGL_NO_SURFACE)
    {
      eglDestroySurface(dpy, this->Surface);
      this->Surface = EGL_NO_SURFACE;
    }
    eglDestroyContext(dpy, this->Context);
    this->Context = EGL_NO_CONTEXT;
  }

  // Devices of real GPUs first, then Mesa's surfaceless platform, then the
  // default display. POINTSURFACES_EGL_DEVICE=<n> restricts the search to one device.
  bool Create()
  {
    this->Error.clear();
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
    auto queryDevices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
    const char* deviceEnv = std::getenv("POINTSURFACES_EGL_DEVICE");
    const int requested = (deviceEnv && *deviceEnv) ? std::atoi(deviceEnv) : -1;

    if (getPlatformDisplay && queryDevices &&
      HasExtension(clientExtensions, "EGL_EXT_platform_device"))
    {
      EGLint count = 0;
      if (queryDevices(0, nullptr, &count) && count > 0)
      {
        std::vector<EGLDeviceEXT> devices(count);
        queryDevices(count, devices.data(), &count);
        for (EGLint i = 0; i < count; ++i)
        {
          if (requested >= 0 && i != requested)
          {
            continue;
          }
          const char* deviceExtensions =
            queryDeviceString ? queryDeviceString(devices[i], EGL_EXTENSIONS) : nullptr;
          if (requested < 0 && HasExtension(deviceExtensions, "EGL_MESA_device_software"))
          {
            continue; // a CPU rasteriser: the surfaceless platform below serves it better
          }
          if (this->TryDisplay(
                getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), "device"))
          {
            return true;
          }
        }
      }
      if (requested >= 0)
      {
        this->Error += "POINTSURFACES_EGL_DEVICE=" + std::to_string(requested) +
          " is not a usable EGL device (" + std::to_string(count) + " found); ";
        return false;
      }
    }
    if (getPlatformDisplay && HasExtension(clientExtensions, "EGL_MESA_platform_surfaceless") &&
      this->TryDisplay(
        getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
        "surfaceless"))
    {
      return true;
    }
    return this->TryDisplay(eglGetDisplay(EGL_DEFAULT_DISPLAY), "default");
  }
};

//------------------------------------------------------------------------------
vtkEGLHeadlessRenderWindow::vtkEGLHeadlessRenderWindow()
  : Internal(new Internals)
{
  // Nothing is ever shown: render into VTK's framebuffers and read back from them.
  this->ShowWindow = false;
  this->UseOffScreenBuffers = true;
  this->FrameBlitMode = NoBlit;
  this->SetWindowName("PointSurfaces EGL");
}

//------------------------------------------------------------------------------
vtkEGLHeadlessRenderWindow::~vtkEGLHeadlessRenderWindow()
{
  this->Finalize();
  vtkRenderer* ren;
  vtkCollectionSimpleIterator rit;
  this->Renderers->InitTraversal(rit);
  while ((ren = this->Renderers->GetNextRenderer(rit)))
  {
    ren->SetRenderWindow(nullptr);
  }
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::CreateAWindow()
{
  if (this->Internal->Context != EGL_NO_CONTEXT || this->Internal->CreationFailed)
  {
    return;
  }
  if (!this->Internal->Create())
  {
    this->Internal->CreationFailed = true;
    std::string why = this->Internal->Error;
    this->Internal->Error = "no EGL display or OpenGL context could be created (" + why +
      "). Neither EGL nor an X display is usable: install Mesa's EGL driver "
      "(libegl-mesa0) or an NVIDIA driver, or set DISPLAY to a running X server";
    return;
  }
  this->OwnContext = 1;
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::DestroyWindow()
{
  Internals& in = *this->Internal;
  if (in.Context == EGL_NO_CONTEXT)
  {
    return;
  }
  if (this->Initialized)
  {
    this->MakeCurrent();
    this->ReleaseGraphicsResources(this);
  }
  in.DestroyContext(in.Display);
  ReleaseDisplay(in.Display);
  in.Display = EGL_NO_DISPLAY;
  in.Platform = "none";
  this->Initialized = false;
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::Initialize()
{
  if (this->Initialized)
  {
    return;
  }
  this->CreateAWindow();
  if (this->Internal->Context == EGL_NO_CONTEXT)
  {
    return;
  }
  this->MakeCurrent();
  this->OpenGLInit();
  if (this->Initialized)
  {
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    this->Internal->Renderer = renderer ? renderer : "";
  }
  else
  {
    this->Internal->CreationFailed = true;
    this->DestroyWindow();
  }
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::Finalize()
{
  this->DestroyWindow();
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::OpenGLInitContext()
{
  this->ContextCreationTime.Modified();
  if (this->Initialized)
  {
    return;
  }
#if POINTSURFACES_VTK_GLAD
  // VTK 9.4 and later load GL with glad: through EGL's own resolver here.
  if (gladLoadGL(reinterpret_cast<GLADloadfunc>(eglGetProcAddress)) == 0)
  {
    this->Internal->Error = "glad could not load OpenGL through eglGetProcAddress";
    return;
  }
  if (!GLAD_GL_VERSION_3_2)
  {
    this->Internal->Error = "the EGL context does not provide OpenGL 3.2 or later";
    return;
  }
#else
  // Debian's GLEW is built for GLX: glewInit() loads every GL entry point,
  // then fails its GLX part with GLEW_ERROR_NO_GLX_DISPLAY. That is harmless here.
  const GLenum result = glewInit();
  if (result != GLEW_OK && result != GLEW_ERROR_NO_GLX_DISPLAY)
  {
    this->Internal->Error = std::string("GLEW could not load OpenGL: ") +
      reinterpret_cast<const char*>(glewGetErrorString(result));
    return;
  }
  if (!GLEW_VERSION_3_2)
  {
    this->Internal->Error = "the EGL context does not provide OpenGL 3.2 or later";
    return;
  }
  this->GlewInitValid = true;
#endif
  this->Initialized = true;
  GLfloat range[2] = { 1.0f, 1.0f };
  glGetFloatv(GL_ALIASED_LINE_WIDTH_RANGE, range);
  this->MaximumHardwareLineWidth = glGetError() == GL_NO_ERROR ? range[1] : 1.0f;
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::Start()
{
  if (!this->Initialized)
  {
    this->Initialize();
  }
  if (this->Initialized)
  {
    this->Superclass::Start();
  }
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::Render()
{
  if (!this->Initialized)
  {
    this->Initialize();
  }
  if (!this->Initialized)
  {
    if (!this->Internal->FailureReported)
    {
      this->Internal->FailureReported = true;
      vtkErrorMacro(<< "Cannot render: " << this->Internal->Error);
    }
    return;
  }
  this->Superclass::Render();
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::Frame()
{
  if (!this->Initialized)
  {
    return;
  }
  this->FrameBlitMode = NoBlit; // there is no window to blit to
  this->Superclass::Frame();
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::MakeCurrent()
{
  Internals& in = *this->Internal;
  if (in.Context != EGL_NO_CONTEXT && eglGetCurrentContext() != in.Context)
  {
    eglMakeCurrent(in.Display, in.Surface, in.Surface, in.Context);
  }
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::ReleaseCurrent()
{
  Internals& in = *this->Internal;
  if (in.Context != EGL_NO_CONTEXT && eglGetCurrentContext() == in.Context)
  {
    eglMakeCurrent(in.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
}

//------------------------------------------------------------------------------
bool vtkEGLHeadlessRenderWindow::IsCurrent()
{
  return this->Internal->Context != EGL_NO_CONTEXT &&
    eglGetCurrentContext() == this->Internal->Context;
}

//------------------------------------------------------------------------------
int* vtkEGLHeadlessRenderWindow::GetScreenSize()
{
  // A headless window has no screen: report the largest framebuffer we allow.
  GLint maxSize = 16384;
  if (this->Initialized)
  {
    this->MakeCurrent();
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
  }
  this->Internal->ScreenSize[0] = maxSize;
  this->Internal->ScreenSize[1] = maxSize;
  return this->Internal->ScreenSize;
}

//------------------------------------------------------------------------------
void* vtkEGLHeadlessRenderWindow::GetGenericContext()
{
  return this->Internal->Context;
}

//------------------------------------------------------------------------------
void* vtkEGLHeadlessRenderWindow::GetGenericDisplayId()
{
  return this->Internal->Display;
}

//------------------------------------------------------------------------------
int vtkEGLHeadlessRenderWindow::ReadPixels(const vtkRecti& rect,
  int front,
  int glFormat,
  int glType,
  void* data,
  int right)
{
  if (!this->Initialized)
  {
    // Never hand back uninitialised memory after a failed render.
    const size_t components = glFormat == GL_RGBA ? 4 : (glFormat == GL_RGB ? 3 : 1);
    const size_t bytes = glType == GL_FLOAT ? sizeof(float) : 1;
    std::memset(data,
      0,
      static_cast<size_t>(rect.GetWidth()) * static_cast<size_t>(rect.GetHeight()) * components *
        bytes);
    return VTK_ERROR;
  }
  return this->Superclass::ReadPixels(rect, front, glFormat, glType, data, right);
}

//------------------------------------------------------------------------------
namespace
{
// Run `query` with VTK's render framebuffer as the draw framebuffer when the
// (surfaceless, empty) default framebuffer is bound.
template<typename Query>
int OnRenderFramebuffer(vtkOpenGLRenderWindow* win, vtkOpenGLFramebufferObject* fbo, Query query)
{
  GLint bound = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
  if (bound != 0 || !fbo || fbo->GetFBOIndex() == 0)
  {
    return query();
  }
  win->GetState()->PushDrawFramebufferBinding();
  fbo->Bind(GL_DRAW_FRAMEBUFFER);
  fbo->ActivateDrawBuffer(0);
  const int result = query();
  win->GetState()->PopDrawFramebufferBinding();
  return result;
}
} // namespace

int vtkEGLHeadlessRenderWindow::GetColorBufferSizes(int* rgba)
{
  if (!this->Initialized)
  {
    return this->Superclass::GetColorBufferSizes(rgba);
  }
  this->MakeCurrent();
  return OnRenderFramebuffer(
    this, this->RenderFramebuffer, [&] { return this->Superclass::GetColorBufferSizes(rgba); });
}

int vtkEGLHeadlessRenderWindow::GetDepthBufferSize()
{
  if (!this->Initialized)
  {
    return this->Superclass::GetDepthBufferSize();
  }
  this->MakeCurrent();
  return OnRenderFramebuffer(
    this, this->RenderFramebuffer, [&] { return this->Superclass::GetDepthBufferSize(); });
}

//------------------------------------------------------------------------------
const char* vtkEGLHeadlessRenderWindow::GetLastError() const
{
  return this->Internal->Error.c_str();
}

//------------------------------------------------------------------------------
const char* vtkEGLHeadlessRenderWindow::GetPlatformName() const
{
  return this->Internal->Platform.c_str();
}

//------------------------------------------------------------------------------
const char* vtkEGLHeadlessRenderWindow::GetRendererName() const
{
  return this->Internal->Renderer.c_str();
}

//------------------------------------------------------------------------------
void vtkEGLHeadlessRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Platform: " << this->Internal->Platform << "\n";
  os << indent << "Renderer: " << this->Internal->Renderer << "\n";
  os << indent << "LastError: " << this->Internal->Error << "\n";
}
