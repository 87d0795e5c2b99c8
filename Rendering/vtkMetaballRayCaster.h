// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballRayCaster
 * @brief   Casts the primary rays of vtkMetaballMapper: the grid and the march.
 *
 * [Bolla 2010] Algorithms 2 and 3: a perspective grid over the view, then
 * coherent ray casting per screen tile into the colour, normal and depth
 * images that the mapper's shadow, shading and selection passes read. Two
 * implementations share this interface: vtkMetaballGPURayCaster (compute
 * shaders) and vtkMetaballCPURayCaster (pointsurfaces::CastMetaballs,
 * uploaded), and the mapper picks one per frame (its RayCaster setting).
 * Private to vtkMetaballMapper.
 */
#ifndef vtkMetaballRayCaster_h
#define vtkMetaballRayCaster_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkObject.h"

#include "psMetaballCast.h"  // For the statistics
#include "psMetaballFrame.h" // For the frame's data

class vtkOpenGLRenderWindow;
class vtkShaderStorageBuffer;
class vtkWindow;

class POINTSURFACESRENDERING_EXPORT vtkMetaballRayCaster : public vtkObject
{
public:
  vtkTypeMacro(vtkMetaballRayCaster, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Casts `balls` from request.View into `images` (sized to the view).
   * `counters` is the frame's counter buffer (vtkMetaballGPUCounters), which
   * the shaders add into. `stats` gets what was counted on the host: the
   * grid's pairs, fullest voxel and culled balls, the rays, the build and
   * cast times (0: not known yet), and, for a caster that CountsOnHost, the
   * march's counters too. False when nothing was cast: with an error
   * reported, or with the reason in stats.Error for the mapper to report.
   */
  virtual bool Cast(vtkOpenGLRenderWindow* renWin,
    const pointsurfaces::MetaballCastRequest& request,
    pointsurfaces::MetaballBalls& balls,
    pointsurfaces::MetaballImages& images,
    vtkShaderStorageBuffer* counters,
    pointsurfaces::MetaballCastStatistics& stats) = 0;

  /**
   * Does `stats` hold the march's counters (samples, visits, kernel terms,
   * hits)? Else they come with the GPU counters, a frame or more later.
   */
  virtual bool CountsOnHost() const = 0;

  virtual void ReleaseGraphicsResources(vtkWindow*) {}

protected:
  vtkMetaballRayCaster() = default;
  ~vtkMetaballRayCaster() override = default;

private:
  vtkMetaballRayCaster(const vtkMetaballRayCaster&) = delete;
  void operator=(const vtkMetaballRayCaster&) = delete;
};

#endif
