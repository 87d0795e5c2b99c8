// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballGPURayCaster
 * @brief   vtkMetaballMapper's primary rays in compute shaders.
 *
 * The perspective grid by vtkMetaballGridBuilder, then
 * vtkMetaballRayCastCS.glsl: one work group per screen tile walks the
 * tile's voxels front to back with the voxel's balls in shared memory and
 * writes the images. The march's counters go to the frame's counter buffer;
 * the cast's GPU time is read a frame late (no stall). Private to
 * vtkMetaballMapper.
 */
#ifndef vtkMetaballGPURayCaster_h
#define vtkMetaballGPURayCaster_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkMetaballRayCaster.h"
#include "vtkNew.h"               // For the members
#include "vtkOpenGLRenderTimer.h" // For the GPU time

#include <string> // For the defines

class vtkComputeShaderProgram;
class vtkMetaballGridBuilder;
class vtkMetaballLevelOfDetail;

class POINTSURFACESRENDERING_EXPORT vtkMetaballGPURayCaster : public vtkMetaballRayCaster
{
public:
  static vtkMetaballGPURayCaster* New();
  vtkTypeMacro(vtkMetaballGPURayCaster, vtkMetaballRayCaster);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  bool Cast(vtkOpenGLRenderWindow* renWin,
    const pointsurfaces::MetaballCastRequest& request,
    pointsurfaces::MetaballBalls& balls,
    pointsurfaces::MetaballImages& images,
    vtkShaderStorageBuffer* counters,
    pointsurfaces::MetaballCastStatistics& stats) override;
  bool CountsOnHost() const override { return false; }
  ///@{
  /** The grid's read-backs and overflows (vtkMetaballGridBuilder's counts). */
  vtkIdType GetNumberOfReadBacks();
  vtkIdType GetNumberOfOverflows();
  ///@}
  void ReleaseGraphicsResources(vtkWindow* win) override;

protected:
  vtkMetaballGPURayCaster();
  ~vtkMetaballGPURayCaster() override;

private:
  /** The ray casting program for the request's defines, compiled; null on failure. */
  vtkComputeShaderProgram* Program(vtkOpenGLRenderWindow* renWin,
    const pointsurfaces::MetaballCastRequest& request);

  vtkNew<vtkMetaballGridBuilder> Grid;
  vtkNew<vtkMetaballLevelOfDetail> Level;
  vtkNew<vtkComputeShaderProgram> RayCast;
  std::string Defines;
  vtkOpenGLRenderTimer Timer;

  vtkMetaballGPURayCaster(const vtkMetaballGPURayCaster&) = delete;
  void operator=(const vtkMetaballGPURayCaster&) = delete;
};

#endif
