// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballLevelOfDetail
 * @brief   Merges the balls that are small on screen, per frame, so that a cloud seen whole costs what its pixels cost.
 *
 * A ball whose support radius covers fewer than `pixels` pixels on screen
 * adds terms to every sample of every ray through its voxel but changes the
 * picture by less than a pixel. Each frame, on the GPU
 * (glsl/vtkMetaballLevelOfDetailCS.glsl), such balls are gathered into cells
 * of `pixels` x `pixels` pixels and the matching depth (cells about as deep
 * as they are wide at their distance), and the balls of one cell become one
 * ball: at their centroid (weighted by |q| R^3), with R^2 their mean R_i^2
 * plus three times their variance about the centroid (second moments add,
 * so the merged support spans theirs), the strength that keeps their
 * kernel mass (q R^3 = sum q_i R_i^3), and their weighted colour. Larger
 * balls, and a small ball alone in its cell, stay as they are. A merged
 * ball stands for balls within one cell, so on a closed surface the
 * silhouette moves within a cell of the exact one and the depth by a few
 * cells' depth (at most 3.2 in TestMetaballLevelOfDetail); a porous cloud,
 * whose rays pass through gaps, can change which gap a ray finds. It is
 * measured against the exact frame by TestMetaballLevelOfDetail and
 * bench_metaball_lod.py.
 *
 * The level is a ball buffer of 2n vec4 (the n balls, small ones with
 * radius 0, then the merged balls), which the grid and the ray caster read
 * instead of the balls; merged ball j has id n + j and its strength and
 * colour in GetMergedStrengths() and GetMergedColors(). Nothing is read back
 * (the merged count is read through a fence for the statistics). Private to
 * vtkMetaballMapper's GPU ray caster.
 */
#ifndef vtkMetaballLevelOfDetail_h
#define vtkMetaballLevelOfDetail_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkNew.h"                       // For the members
#include "vtkObject.h"

#include "psMetaballFrame.h" // For the balls and the view

class vtkComputeShaderProgram;
class vtkMetaballGPUCounters;
class vtkMetaballGridBuilder;
class vtkOpenGLRenderWindow;
class vtkShaderStorageBuffer;
class vtkWindow;

class POINTSURFACESRENDERING_EXPORT vtkMetaballLevelOfDetail : public vtkObject
{
public:
  static vtkMetaballLevelOfDetail* New();
  vtkTypeMacro(vtkMetaballLevelOfDetail, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Builds the level of `balls` for `view` with cells of `pixels` pixels,
   * scanning with `scanner`'s passes. With `wait`, the merged counts of this
   * build are read at once. The context of `renWin` must be current.
   */
  bool Build(vtkOpenGLRenderWindow* renWin,
    const pointsurfaces::MetaballBalls& balls,
    const pointsurfaces::MetaballView& view,
    double pixels,
    vtkMetaballGridBuilder* scanner,
    bool wait);

  ///@{
  /** The level of the last Build(): 2n balls, and the merged balls' strengths and colours. */
  vtkShaderStorageBuffer* GetLevelBalls();
  vtkShaderStorageBuffer* GetMergedStrengths();
  vtkShaderStorageBuffer* GetMergedColors();
  ///@}

  ///@{
  /**
   * Merged balls and the balls they stand for, of the latest build whose
   * counts have arrived (the last one with `wait`).
   */
  vtkGetMacro(NumberOfMergedBalls, vtkIdType);
  vtkGetMacro(NumberOfBallsMerged, vtkIdType);
  ///@}

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkMetaballLevelOfDetail();
  ~vtkMetaballLevelOfDetail() override;

  vtkIdType NumberOfMergedBalls = 0;
  vtkIdType NumberOfBallsMerged = 0;

private:
  struct Internals;
  Internals* Impl;

  vtkMetaballLevelOfDetail(const vtkMetaballLevelOfDetail&) = delete;
  void operator=(const vtkMetaballLevelOfDetail&) = delete;
};

#endif
