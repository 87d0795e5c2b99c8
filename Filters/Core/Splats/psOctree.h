// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psOctree.h
 * @brief Bucketed octree over splats for culling and continuous LOD ([Bolla 2010] 3.4-3.5).
 *
 * Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based
 * Surfaces", M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
 *
 * Cells are split at the mean of their splat origins (as in [Bolla 2010]) until
 * a cell holds at most `bucket` splats. Nodes are numbered depth first and
 * the splats are reordered so that every node covers a contiguous range; in
 * a leaf they are sorted by level, coarsest first, so that drawing a prefix
 * of a leaf draws its first levels. Bounds and bounding spheres include the
 * disc radius of every splat.
 */
#ifndef psOctree_h
#define psOctree_h

#include "PointSurfacesFiltersModule.h" // For export macro

#include <vector> // For nodes

namespace pointsurfaces
{
struct OctreeNode
{
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 }; ///< xmin xmax ymin ymax zmin zmax, discs included
  double Sphere[4] = { 0, 0, 0, 0 };       ///< centre and radius, discs included
  int FirstChild = -1;                     ///< children are contiguous nodes
  int ChildCount = 0;
  int Depth = 0;
  long long Begin = 0; ///< range of reordered splats
  long long End = 0;
};

struct Octree
{
  std::vector<OctreeNode> Nodes; ///< node 0 is the root
  std::vector<long long> Order;  ///< output position -> input splat index
  int Levels = 1;
  std::vector<long long> LevelEnds; ///< per node, Levels values: end of each level's prefix
  /// Per node, or empty (every level present; any other size is ignored): how many levels,
  /// coarsest first, a node's splats hold (a splat file's pages loaded in part).
  std::vector<int> PresentLevels;
};

/**
 * Build the octree of `n` splats with origins `xyz`, disc radii `radius` and
 * levels `level` (0 = coarsest, < levels).
 */
POINTSURFACESFILTERS_EXPORT Octree BuildOctree(const double* xyz,
  const double* radius,
  const int* level,
  long long n,
  int levels,
  int bucket = 64,
  int maxDepth = 21);
} // namespace pointsurfaces

#endif
