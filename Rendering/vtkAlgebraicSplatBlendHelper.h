// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkAlgebraicSplatBlendHelper
 * @brief   Two-pass blending of vtkAlgebraicSplatMapper: float targets, depth copies, compositing.
 *
 * The mapper's blended frame, as vtkOpenGLPointGaussianMapperHelper is its
 * mapper's drawing: a visibility pass writes each pixel's nearest hit pushed
 * back along the ray into a depth target that starts as a copy of the
 * scene's depth; a blending pass accumulates the weighted colours of every
 * hit in front of it in a float target, with the early depth test dropping
 * what lies behind and the shader comparing its hit with a copy of that
 * depth; a full-screen pass normalises the colour and composites it into
 * the scene's framebuffer with the nearest hit's true depth.
 *
 * The mapper supplies the passes' programs and the draw calls (Passes); the
 * helper owns the targets, sized to the viewport and to the scene's depth
 * format, and the GL state between the passes. Messages go to the owner.
 * Private to PointSurfaces::Rendering.
 */
#ifndef vtkAlgebraicSplatBlendHelper_h
#define vtkAlgebraicSplatBlendHelper_h

#include "vtkObject.h"

#include <functional> // For the passes
#include <memory>     // For the targets

class vtkOpenGLRenderWindow;
class vtkOpenGLState;
class vtkShaderProgram;
class vtkWindow;

class vtkAlgebraicSplatBlendHelper : public vtkObject
{
public:
  static vtkAlgebraicSplatBlendHelper* New();
  vtkTypeMacro(vtkAlgebraicSplatBlendHelper, vtkObject);

  /** What the mapper draws in each pass. */
  struct Passes
  {
    /** Make the visibility pass's program current; nullptr when it failed. */
    std::function<vtkShaderProgram*()> UseVisibility;
    /** Make the blending pass's program current; nullptr when it failed. */
    std::function<vtkShaderProgram*()> UseBlending;
    /** Draw the splats with the current program. */
    std::function<void()> Draw;
  };

  /** The blend's settings (the mapper's properties of the same names). */
  struct Settings
  {
    bool Blending = true;          ///< two-pass blending of overlapping splats
    double BlendDepthOffset = 0.5; ///< hits this far behind the nearest blend, in units of h
    double BlendSharpness = 3.0;   ///< k of the weight exp(-k r^2 / R^2)
    int AntiAliasing = 1;          ///< n x n rays at silhouette pixels (1: off)
  };

  /**
   * Draw one blended frame into the framebuffer bound for drawing, over its
   * viewport. Warnings and errors are reported by `owner`.
   */
  void Render(vtkOpenGLRenderWindow* renWin,
    const Settings& settings,
    const Passes& passes,
    vtkObject* owner);

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkAlgebraicSplatBlendHelper();
  ~vtkAlgebraicSplatBlendHelper() override;

private:
  struct Targets;
  std::unique_ptr<Targets> T;

  /**
   * The visibility and blending passes into the targets, the scene's
   * depth copied first; the GL state as it was afterwards. False when a
   * pass's program failed.
   */
  bool Accumulate(vtkOpenGLRenderWindow* renWin,
    const int viewport[4],
    const Settings& settings,
    const Passes& passes,
    vtkObject* owner);
  /** New targets for the viewport's size and the scene's depth format. */
  void AllocateTargets(vtkOpenGLRenderWindow* renWin, int width, int height, int depthFormat);
  /** The scene's depth into the targets' (cleared, with a warning, when it cannot be). */
  void CopySceneDepth(vtkOpenGLState* ostate,
    const int viewport[4],
    bool multisampled,
    int depthFormat,
    vtkObject* owner);
  /** The blending pass: every hit in front of the visible depth, weighted. */
  bool Blend(vtkOpenGLState* ostate,
    int width,
    int height,
    int depthFormat,
    const Settings& settings,
    const Passes& passes);
  /** Normalises the sums and composites them with the true depth. */
  void Composite(vtkOpenGLRenderWindow* renWin, vtkObject* owner);

  vtkAlgebraicSplatBlendHelper(const vtkAlgebraicSplatBlendHelper&) = delete;
  void operator=(const vtkAlgebraicSplatBlendHelper&) = delete;
};

#endif
