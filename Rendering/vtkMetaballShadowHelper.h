// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballShadowHelper
 * @brief   Shadows of vtkMetaballMapper from secondary rays ([Bolla 2010] 5.3).
 *
 * For each of the first four lights that are on, a perspective grid is built
 * from the light's point of view (vtkMetaballGridBuilder with the light as
 * camera, parallel for a directional light, framing the balls' bounds), and
 * vtkMetaballShadowCS.glsl walks, for every pixel the primary rays hit, the
 * one tile of that grid its ray to the light crosses. The result is an
 * image of how much each light is blocked, which the mapper's shading pass
 * reads. In the manner of vtkOpenGLPointGaussianMapperHelper: the mapper
 * owns it and calls it in its Render. Private to vtkMetaballMapper.
 */
#ifndef vtkMetaballShadowHelper_h
#define vtkMetaballShadowHelper_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkNew.h"                       // For the members
#include "vtkObject.h"
#include "vtkOpenGLRenderTimer.h" // For the GPU time

#include "psMetaballFrame.h" // For the frame's data

#include <string> // For the defines

class vtkComputeShaderProgram;
class vtkMatrix4x4;
class vtkMetaballGridBuilder;
class vtkRenderer;
class vtkShaderStorageBuffer;
class vtkTextureObject;
class vtkWindow;

class POINTSURFACESRENDERING_EXPORT vtkMetaballShadowHelper : public vtkObject
{
public:
  static vtkMetaballShadowHelper* New();
  vtkTypeMacro(vtkMetaballShadowHelper, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The shadow image of the cast `view` (its images' depths) for the
   * renderer's lights. `model`: the float balls to world; `bounds`: the
   * balls' world bounds, which the light cameras frame. Returns the number
   * of lights shadowed (0 on failure, with an error reported).
   */
  int Cast(vtkRenderer* ren,
    const pointsurfaces::MetaballCastRequest& request,
    const pointsurfaces::MetaballBalls& balls,
    const pointsurfaces::MetaballImages& images,
    vtkMatrix4x4* model,
    const double bounds[6],
    vtkShaderStorageBuffer* counters);

  /** The last Cast's image: per pixel, how much each of four lights is blocked. */
  vtkTextureObject* GetShadowImage();

  /** The GPU time of the last shadow pass whose query completed, in seconds (0: none yet). */
  double GetElapsedSeconds();

  ///@{
  /** The light grids' read-backs and overflows (vtkMetaballGridBuilder's counts). */
  vtkIdType GetNumberOfReadBacks();
  vtkIdType GetNumberOfOverflows();
  ///@}

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkMetaballShadowHelper();
  ~vtkMetaballShadowHelper() override;

private:
  /** The shadow program for the kernel, compiled; null on failure. */
  vtkComputeShaderProgram* Program(vtkOpenGLRenderWindow* renWin, pointsurfaces::MetaballKernel k);

  vtkNew<vtkMetaballGridBuilder> LightGrid;
  vtkNew<vtkComputeShaderProgram> Shadow;
  std::string Defines;
  vtkNew<vtkTextureObject> ShadowImage;
  vtkOpenGLRenderTimer Timer;

  vtkMetaballShadowHelper(const vtkMetaballShadowHelper&) = delete;
  void operator=(const vtkMetaballShadowHelper&) = delete;
};

#endif
