// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psSplatSelection.h
 * @brief Quality-based decimation ([Bolla 2010] 3.3.1) and the candidate orders it visits.
 *
 * Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
 * M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
 *
 * A chosen point claims the points its splat covers; claimed points are
 * never chosen. In [Bolla 2010] that is every point within s·h_i of it in
 * its parametric domain (in-plane distance <= s·h_i, and height <= s·h_i so
 * that the other side of a thin part is not claimed: CoverByDistance());
 * error-bounded splats cover only the points within their tolerance
 * (psSplatBound.h). The
 * visiting order decides how many points end up chosen: RandomOrder() is
 * that of [Bolla 2010], LatticeOrder() visits first the points nearest to
 * the centres of a grid slightly coarser than the splat spacing, which
 * leaves fewer gaps for later splats to fill.
 *
 * The state vector makes levels nest ([Bolla 2010] 3.4): points chosen at a
 * coarser s stay chosen at a finer one, and only the remaining points are
 * visited.
 */
#ifndef psSplatSelection_h
#define psSplatSelection_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "psLocalFit.h"
#include "psPointIndex.h"

#include <functional> // For the frame callback
#include <vector>     // For orders and states

namespace pointsurfaces
{
enum class PointState : signed char
{
  Free = 0,
  Chosen = 1,
  Claimed = 2,
  Unusable = 3, ///< no frame could be computed: degenerate neighbourhood
  Reserved = 4  ///< another chunk's point (streaming fit): never chosen or claimed here
};

/**
 * Choose point i: compute what its splat needs and report its frame (origin
 * unused, Normal and Scale = h, for front growth); false when degenerate.
 */
using FrameFunction = std::function<bool(long long, LocalFrame&)>;

/**
 * The points that chosen point i covers at quality s, as indices into the
 * index (any order, duplicates allowed). Called only for chosen points.
 */
using CoverFunction = std::function<void(long long, double, std::vector<int>&)>;

/** 0..n-1 shuffled with std::mt19937(seed): deterministic on every platform. */
POINTSURFACESFILTERS_EXPORT std::vector<long long> RandomOrder(long long n, unsigned int seed);

/**
 * Points nearest to the centres of a cubic grid of cell size `cell` first
 * (cells in z, y, x order), then the others in RandomOrder(seed).
 */
POINTSURFACESFILTERS_EXPORT std::vector<long long> LatticeOrder(const double* xyz,
  long long n,
  double cell,
  unsigned int seed);

/**
 * Choose points in `order` with quality factor s. Each chosen point claims
 * the points that `cover` reports for it, and claimed points are never
 * chosen. With `front`, each choice is followed by growing a front: the
 * free points around it are chosen next, those whose in-plane distance is
 * nearest to sqrt(3) s h first (the spacing of a hexagonal covering), and
 * `order` only seeds new fronts. `state` (size n) is read and updated.
 * Points already Chosen (`alreadyChosen`, from coarser levels) first claim
 * what they cover at this s. Returns the newly chosen point ids, in the
 * order they were chosen.
 *
 * With `slabWidth` > 0 the work runs in parallel: the points are cut into
 * slabs of at least that width along the longest axis, the even slabs are
 * decimated concurrently, then the odd ones, each in `order`. The result is
 * deterministic and independent of the number of threads; next to slab
 * borders a few more splats may be chosen than in one sequential pass.
 * `frameOf` and `cover` must then be safe to call from several threads
 * for different points, and a point's cover must not reach beyond the
 * neighbouring slabs.
 */
POINTSURFACESFILTERS_EXPORT std::vector<long long> SelectByQuality(const PointIndex& index,
  double s,
  const std::vector<long long>& order,
  const FrameFunction& frameOf,
  const CoverFunction& cover,
  std::vector<PointState>& state,
  const std::vector<long long>& alreadyChosen = {},
  bool front = false,
  double slabWidth = 0.0);

/**
 * The cover of [Bolla 2010] 3.3.1: the points within s·h of `centre` in the
 * plane of `frame` whose height above it is at most s·h.
 */
POINTSURFACESFILTERS_EXPORT void CoverByDistance(const PointIndex& index,
  const double centre[3],
  const LocalFrame& frame,
  double s,
  std::vector<int>& ids);
} // namespace pointsurfaces

#endif
