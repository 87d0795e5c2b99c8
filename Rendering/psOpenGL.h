// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * The one place where the VTK version decides how GL is reached.
 *
 * VTK up to 9.3 loads GL entry points with GLEW (`vtk_glew.h`, VTK::glew);
 * VTK 9.4 and later with glad (`vtk_glad.h`, VTK::glad). Every source of the
 * project that calls GL includes this header instead of either, and asks for
 * a GL version with HasOpenGLVersion(), which reads the current context and
 * so works with both loaders. The CMake side (which target to link) is chosen
 * once in the top-level CMakeLists.txt (POINTSURFACES_VTK_GL_TARGETS).
 */
#ifndef psOpenGL_h
#define psOpenGL_h

#include "vtkVersionMacros.h"

#if VTK_MAJOR_VERSION > 9 || (VTK_MAJOR_VERSION == 9 && VTK_MINOR_VERSION >= 4)
#define POINTSURFACES_VTK_GLAD 1
#include "vtk_glad.h"
#else
#define POINTSURFACES_VTK_GLAD 0
#include "vtk_glew.h"
#endif

namespace pointsurfaces
{
/**
 * True when the current context is OpenGL major.minor or newer. Needs a
 * current context whose entry points are loaded; false otherwise.
 */
inline bool HasOpenGLVersion(int major, int minor)
{
  GLint have[2] = { 0, 0 };
  glGetIntegerv(GL_MAJOR_VERSION, &have[0]);
  glGetIntegerv(GL_MINOR_VERSION, &have[1]);
  // Drain a GL_INVALID_ENUM from a context older than 3.0, which lacks both.
  while (glGetError() != GL_NO_ERROR)
  {
  }
  return have[0] > major || (have[0] == major && have[1] >= minor);
}
} // namespace pointsurfaces

#endif
