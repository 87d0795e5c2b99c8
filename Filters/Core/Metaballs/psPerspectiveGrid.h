// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psPerspectiveGrid.h
 * @brief The perspective grid's geometry and voxel lists ([Bolla 2010] Algorithm 2), once.
 *
 * The view frustum cut into screen tiles times depth slabs, each voxel
 * listing the balls whose support reaches into it. Every builder places a
 * ball the same way, and this is that way:
 *
 * - a ball wholly outside one of the frustum's six planes is culled;
 * - the automatic slab range is the depth interval [d - r, d + r] of the
 *   balls in view, each clamped to the projection's near and far distances
 *   and to d >= 0, split into uniform slabs (the projection's first unit of
 *   depth when nothing is in view);
 * - a ball spans the slabs of its depth interval and the tiles its view-space
 *   box projects onto; a perspective ball that reaches the eye plane covers
 *   every tile.
 *
 * The double-precision reference (pointsurfaces::BuildPerspectiveGrid) and the
 * CPU ray caster (psMetaballCast) build with these functions;
 * vtkMetaballGridBuilder does the same in GLSL (vtkMetaballGridCS.glsl) and
 * takes its slab planes from here, and TestMetaballGridBuild checks its
 * lists against the reference's.
 *
 * Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based
 * Surfaces", M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
 */
#ifndef psPerspectiveGrid_h
#define psPerspectiveGrid_h

#include "PointSurfacesFiltersModule.h" // For export macro

#include <algorithm> // For std::max in the sort
#include <limits>    // For the default pair limit
#include <stdexcept> // For the pair limit's exception
#include <string>    // For its message
#include <vector>    // For the planes and lists

namespace pointsurfaces
{
/** The near and far view distances of an OpenGL projection matrix (row-major). */
POINTSURFACESFILTERS_EXPORT void ProjectionRange(const double viewToClip[16],
  bool parallel,
  double& nearDistance,
  double& farDistance);

/**
 * The six view-space planes of the frustum of `viewToClip`, 4 values each
 * (unit normal, offset), with the inside where n . x + d >= 0.
 */
POINTSURFACESFILTERS_EXPORT void FrustumPlanes(const double viewToClip[16], double planes[24]);

/**
 * Where the balls of one view go: frustum culling, the slab planes and each
 * ball's voxel range. Centres are in view space (the camera looks down -z).
 */
class POINTSURFACESFILTERS_EXPORT PerspectiveGridGeometry
{
public:
  /**
   * The grid of a `width` x `height` viewport in `tileSize` tiles and
   * `slabs` slabs (at least 1) for the row-major projection `viewToClip`.
   * The slab range starts empty: call SetSlabRange before Range.
   */
  PerspectiveGridGeometry(const double viewToClip[16],
    bool parallel,
    int width,
    int height,
    int tileSize,
    int slabs);

  /** Is the sphere (c, r) wholly outside one of the frustum's planes? */
  bool Outside(const double c[3], double r) const;

  /**
   * Widen [nearD, farD] by the depth interval of the sphere (c, r), which
   * is in the frustum, clamped to the projection's range and to d >= 0.
   * Start from nearD = the largest double, farD = 0.
   */
  void Extend(const double c[3], double r, double& nearD, double& farD) const;

  /**
   * Slabs from nearD to farD, uniform; when that interval is empty (no ball
   * in view), the projection's first unit of depth.
   */
  void SetSlabRange(double nearD, double farD);

  /** The slab that holds view distance d, clamped to the grid. */
  int SlabOf(double d) const;

  /**
   * The voxel range that the support of the in-frustum sphere (c, r)
   * reaches: tiles [r[0], r[1]] x [r[2], r[3]] and slabs [r[4], r[5]].
   * False when it lies beyond the slabs or off the viewport.
   */
  bool Range(const double c[3], double r, int range[6]) const;

  int GetTilesX() const { return this->TilesX; }
  int GetTilesY() const { return this->TilesY; }
  int GetSlabs() const { return this->Slabs; }
  double GetSlabNear() const { return this->SlabNear; }
  double GetSlabFar() const { return this->SlabFar; }
  /** Slabs + 1 view distances, ascending; the last is the slab range's far end. */
  const std::vector<double>& GetSlabPlanes() const { return this->Planes; }
  /** The frustum's six view-space planes (FrustumPlanes). */
  const double* GetFrustumPlanes() const { return this->Frustum; }
  double GetProjectionNear() const { return this->ProjectionNear; }
  /** The projection's far distance, at most 1e30 (an infinite far plane). */
  double GetProjectionFar() const { return this->ProjectionFar; }

private:
  double ViewToClip[16];
  double Frustum[24];
  double Corners[8][4]; // per box corner: the sum over the axes of +-1 times ViewToClip's columns
  bool Parallel;
  int Width, Height, TileSize, TilesX, TilesY, Slabs;
  double ProjectionNear = 0.0, ProjectionFar = 0.0;
  double SlabNear = 0.0, SlabFar = 0.0;
  std::vector<double> Planes;
};

/** The order of the voxels in the lists. */
enum class VoxelOrder
{
  SlabMajor, ///< voxel = (slab * tilesY + ty) * tilesX + tx (the GPU's and the reference's)
  TileMajor ///< voxel = (ty * tilesX + tx) * slabs + slab (a tile's slabs together: the CPU caster's)
};

/**
 * The voxel lists by a counting sort of the (voxel, ball) pairs, in ball
 * order, so each voxel's list ascends: `offsets` gets voxels + 1 entries,
 * voxel v's balls being lists[offsets[v], offsets[v + 1]). `range(i)` gives
 * ball i's int[6] voxel range, or null when it is in no voxel. Returns the
 * largest list. Throws std::length_error, before the lists are allocated,
 * when there are more pairs than `maximumPairs`.
 */
template<typename Offset, typename RangeOf>
long long SortIntoVoxels(long long count,
  int tilesX,
  int tilesY,
  int slabs,
  VoxelOrder order,
  RangeOf&& range,
  std::vector<Offset>& offsets,
  std::vector<unsigned int>& lists,
  size_t maximumPairs = std::numeric_limits<size_t>::max())
{
  const size_t voxels = static_cast<size_t>(tilesX) * tilesY * slabs;
  auto forEachVoxel = [&](const int* r, auto&& visit)
  {
    for (int z = r[4]; z <= r[5]; ++z)
    {
      for (int y = r[2]; y <= r[3]; ++y)
      {
        for (int x = r[0]; x <= r[1]; ++x)
        {
          const size_t tile = static_cast<size_t>(y) * tilesX + x;
          visit(order == VoxelOrder::SlabMajor ? static_cast<size_t>(z) * tilesX * tilesY + tile
                                               : tile * slabs + z);
        }
      }
    }
  };
  offsets.assign(voxels + 1, 0);
  for (long long i = 0; i < count; ++i)
  {
    if (const int* r = range(i))
    {
      forEachVoxel(r, [&](size_t v) { ++offsets[v + 1]; });
    }
  }
  long long most = 0;
  for (size_t v = 0; v < voxels; ++v)
  {
    most = std::max(most, static_cast<long long>(offsets[v + 1]));
    offsets[v + 1] += offsets[v];
  }
  if (static_cast<size_t>(offsets[voxels]) > maximumPairs)
  {
    throw std::length_error("the grid has " + std::to_string(offsets[voxels]) +
      " (voxel, ball) pairs, more than the " + std::to_string(maximumPairs) +
      " that the memory limit leaves room for");
  }
  lists.resize(offsets[voxels]);
  std::vector<Offset> cursor(offsets.begin(), offsets.end() - 1);
  for (long long i = 0; i < count; ++i)
  {
    if (const int* r = range(i))
    {
      forEachVoxel(r, [&](size_t v) { lists[cursor[v]++] = static_cast<unsigned int>(i); });
    }
  }
  return most;
}
} // namespace pointsurfaces

#endif
