// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psPointIndex.h
 * @brief k-nearest-neighbour and radius queries on double-precision points, through nanoflann's kd-tree.
 *
 * The tree reads the caller's coordinates in place (they must outlive the
 * index) and measures in double, so a scan placed at 1e7 keeps its full
 * precision; besides the coordinates it holds about 11 bytes a point, a
 * 4-byte index map and the nodes of 16-point leaves (PCL's KdTreeFLANN,
 * used before, kept float copies of the points three times over and two
 * index maps, some 60 bytes a point). Results are exact and deterministic:
 * sorted by (squared distance, id), and ties at the k-th distance go to the
 * lower ids. Queries are const and may run from several threads at once.
 * Ids are ints: an index holds fewer than 2^31 points.
 */
#ifndef psPointIndex_h
#define psPointIndex_h

#include "PointSurfacesFiltersModule.h" // For export macro

#include <memory> // For std::unique_ptr
#include <vector> // For results

namespace pointsurfaces
{
class POINTSURFACESFILTERS_EXPORT PointIndex
{
public:
  /** Index `n` points given as xyz triples. Points must be finite. */
  PointIndex(const double* xyz, long long n);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  long long Size() const { return this->N; }
  const double* Point(long long i) const { return this->XYZ + 3 * i; }

  /**
   * The k nearest points to q (q itself included when it is an indexed
   * point), sorted by distance; fewer when the index holds fewer.
   */
  void Nearest(const double q[3], int k, std::vector<int>& ids, std::vector<double>& d2) const;

  /** All points within `radius` of q, sorted by distance unless `sorted` is false. */
  void Within(const double q[3],
    double radius,
    std::vector<int>& ids,
    std::vector<double>& d2,
    bool sorted = true) const;

private:
  const double* XYZ;
  long long N;
  struct Tree;
  std::unique_ptr<Tree> Impl;
};
/**
 * Coincident and near-coincident points: a point within `tolerance` of an
 * earlier point in the same cell of a grid 100 times that size is merged
 * into it (exact duplicates always are; closer points straddle a cell
 * border with a chance of 3 % of their distance over the tolerance). Returns the ids of the points kept, in
 * increasing order. A scan exported with one vertex per face corner (OBJ
 * with normals or texture coordinates) repeats each point several times;
 * fitted as they are, the repeats count as neighbours and shrink the
 * feature size, and the splats multiply.
 */
POINTSURFACESFILTERS_EXPORT std::vector<long long> UniquePoints(const double* xyz,
  long long n,
  double tolerance);

/**
 * The ids 0..n-1 of `n` finite points in Morton (Z) order over their
 * bounding cube at 2^21 cells a side, ties by id. Points near in space are
 * then mostly near in memory: neighbour searches and the work on their
 * results touch fewer cache lines (a 10M-point fit of randomly ordered
 * samples took 1.17 times as long). The order depends on the coordinates
 * only, not on the input's order, except among points of one cell.
 */
POINTSURFACESFILTERS_EXPORT std::vector<long long> SpatialOrder(const double* xyz, long long n);
} // namespace pointsurfaces

#endif
