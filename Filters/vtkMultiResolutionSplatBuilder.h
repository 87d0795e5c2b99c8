// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMultiResolutionSplatBuilder
 * @brief   Algebraic splats with continuous level of detail: nested quality levels and an octree.
 *
 * The multi-resolution representation of sections 3.4 and 3.5 of
 * N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
 * M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]) as a filter of its own:
 * vtkAlgebraicSplatFitter with the Quality selection run over NumberOfLevels
 * nested levels, from CoarsestQualityFactor (s_0, default 4) down to
 * QualityFactor (s_k, default 1), 25 levels by default as in [Bolla 2010]
 * (25 to 50). Each splat is fitted once and tagged in SplatLOD
 * with the level where it first appears; the bucketed octree sorts the
 * splats by leaf and then by level, and stores per node the end of each
 * level's prefix (OctreeNodeLevelEnds), so that a mapper draws any level of
 * any node as a prefix of the node's range.
 *
 * Level 0 alone is exactly the single-level representation at s_0; levels
 * 0..L together hold every splat of the representation at s_L that is not
 * already claimed by a coarser splat.
 */
#ifndef vtkMultiResolutionSplatBuilder_h
#define vtkMultiResolutionSplatBuilder_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "vtkAlgebraicSplatFitter.h"

class POINTSURFACESFILTERS_EXPORT vtkMultiResolutionSplatBuilder : public vtkAlgebraicSplatFitter
{
public:
  static vtkMultiResolutionSplatBuilder* New();
  vtkTypeMacro(vtkMultiResolutionSplatBuilder, vtkAlgebraicSplatFitter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkMultiResolutionSplatBuilder();
  ~vtkMultiResolutionSplatBuilder() override = default;

private:
  vtkMultiResolutionSplatBuilder(const vtkMultiResolutionSplatBuilder&) = delete;
  void operator=(const vtkMultiResolutionSplatBuilder&) = delete;
};

#endif
