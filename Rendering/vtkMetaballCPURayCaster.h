// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballCPURayCaster
 * @brief   vtkMetaballMapper's primary rays on the CPU, uploaded as images.
 *
 * pointsurfaces::CastMetaballs (vtkSMPTools over screen tiles, the march in
 * SIMD lanes) on the host copies of the balls, then the three images into
 * the textures the shading, shadow and selection passes read. The choice on
 * software OpenGL (Mesa llvmpipe), where the compute shaders run on the
 * CPU anyway and much slower. Its count of rays starting inside goes into
 * the frame's counter buffer, like the shaders' counts. Private to
 * vtkMetaballMapper.
 */
#ifndef vtkMetaballCPURayCaster_h
#define vtkMetaballCPURayCaster_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkMetaballRayCaster.h"

class POINTSURFACESRENDERING_EXPORT vtkMetaballCPURayCaster : public vtkMetaballRayCaster
{
public:
  static vtkMetaballCPURayCaster* New();
  vtkTypeMacro(vtkMetaballCPURayCaster, vtkMetaballRayCaster);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  bool Cast(vtkOpenGLRenderWindow* renWin,
    const pointsurfaces::MetaballCastRequest& request,
    pointsurfaces::MetaballBalls& balls,
    pointsurfaces::MetaballImages& images,
    vtkShaderStorageBuffer* counters,
    pointsurfaces::MetaballCastStatistics& stats) override;
  bool CountsOnHost() const override { return true; }

protected:
  vtkMetaballCPURayCaster();
  ~vtkMetaballCPURayCaster() override;

private:
  pointsurfaces::MetaballCastImages Images; // the last cast's, reused frame after frame

  vtkMetaballCPURayCaster(const vtkMetaballCPURayCaster&) = delete;
  void operator=(const vtkMetaballCPURayCaster&) = delete;
};

#endif
