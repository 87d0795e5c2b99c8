// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psSplatLOD.h
 * @brief View-dependent selection over the splat octree: frustum culling and continuous LOD.
 *
 * Given the octree of psOctree (nodes, levels, level ends), the quality
 * factor s of each level and the splats' radii, SelectDrawRanges walks the
 * tree for one view: nodes whose bounding sphere lies outside the view
 * frustum are skipped, and each visible leaf draws the prefix of its
 * level-sorted splats down to the first level whose splats are at most
 * PixelError pixels across on screen (all levels when PixelError is 0);
 * a node of a partly loaded set (Octree::PresentLevels) draws no finer
 * level than it holds, with that level's s.
 * The result is a list of contiguous index ranges, each with its level's s,
 * ready for one draw call each. A model matrix moves the spheres and scales
 * them and the splats by its largest axis scale. Plain functions: no GL, no
 * VTK.
 */
#ifndef psSplatLOD_h
#define psSplatLOD_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "psOctree.h"

#include <vector> // For ranges

namespace pointsurfaces
{
/** An octree ready for view selection: the tree and what each node needs to pick a level. */
struct LODOctree
{
  Octree Tree;
  std::vector<double> LevelQuality; ///< s of each level, Tree.Levels values
  /// Per node: the mean of R / s over its splats (R at level l is about s_l times it).
  std::vector<double> MeanScale;
  /// Per node: the radius of a sphere around Tree.Nodes[i].Sphere's centre that holds the
  /// patches: the discs' sphere grown by (sqrt(2) - 1) times the largest R, since a patch
  /// may rise up to R above its disc.
  std::vector<double> Reach;
};

/**
 * The LOD octree of `tree`, with `levelQuality` (s per level) and the splats'
 * disc radii `radius` and levels `level`, indexed in the tree's (sorted) order.
 */
POINTSURFACESFILTERS_EXPORT LODOctree MakeLODOctree(Octree tree,
  std::vector<double> levelQuality,
  const double* radius,
  const int* level);

/** One view. Planes are in world coordinates, 4 values each, inside where n . x + d >= 0. */
struct LODView
{
  double Planes[24] = {};
  double Eye[3] = { 0, 0, 0 };
  /// Model to world, row-major, column vectors; ignored when ModelIsIdentity.
  double ModelToWorld[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  bool ModelIsIdentity = true;
  bool Parallel = false;
  double ParallelScale = 1.0;  ///< half the view's height in world units (parallel)
  double TanHalfAngle = 0.577; ///< tan of half the vertical view angle (perspective)
  int ViewportHeight = 1;      ///< pixels
  bool Cull = true;            ///< skip nodes outside the frustum
  double PixelError = 0.0;     ///< 0: every level
};

/** Splats [Begin, End) of the sorted set, drawn with the s of `Level`: levels 0 .. Level of leaf `Node`. */
struct DrawRange
{
  long long Begin = 0;
  long long End = 0;
  int Level = 0;
  double Quality = 1.0;
  int Node = -1;
};

/**
 * The ranges to draw for `view`, in the order of a depth-first walk that
 * visits a node's children last to first. Empty ranges are left out.
 */
POINTSURFACESFILTERS_EXPORT std::vector<DrawRange> SelectDrawRanges(const LODOctree& tree,
  const LODView& view);
} // namespace pointsurfaces

#endif
