// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psSplatBound.h
 * @brief Error-bounded discs: how far a fitted splat may reach, and which points it covers.
 *
 * A splat of [Bolla 2010] ("High Quality Rendering of Large Point-based
 * Surfaces", M.S. thesis, N. K. R. Bolla, IIIT Hyderabad, 2010) is its
 * polynomial over a disc of radius R = s h. Where the surface bends away
 * from the patch inside that disc (thin parts, sharp edges, fine relief) or
 * ends inside it (open borders), the patch sticks out past the data as a
 * flake, and more splats do not help: each still reaches as far. BoundSplat
 * shrinks each disc to where its patch stays within a tolerance of the
 * points, and stops it at the data's borders:
 *
 * - every candidate point p gets its in-plane distance rho and its
 *   deviation e = |height - g(u, v)| h from the patch (world units);
 *   points with e <= tolerance are *on* the patch;
 * - a point off the patch that lies within `Adjacency` spacings of a point
 *   on it belongs to the same sheet of the surface, which bends away
 *   there: the disc must stop short of it (R < rho; only past
 *   `CentreReach` spacings, so that a disc covers its own point). Points off the patch
 *   and away from it are another sheet (the other side of a thin part) and
 *   do not bound the disc;
 * - with point normals (the input's, or PCA normals of each point's own
 *   few neighbours), a point within the tolerance whose normal turns away
 *   from the patch's normal there by more than `NormalAngle` lies on a
 *   wall that meets the patch's sheet at a crease or a fold: it is not
 *   covered, and it stops the disc as a bend does. Within the tolerance
 *   alone, the rows of a fold's other wall next to its crease pass for the
 *   patch, and a disc reaching over them shows the patch's face where the
 *   fold is dark;
 * - the points on the patch within max(R, 3 spacings) are projected on 16
 *   directions of the plane, each point on the directions within
 *   `BorderAngle` of its own: where their reach in a direction (the support
 *   function) falls short of the disc by more than the band in which
 *   randomly spread points of the local density would put `BorderPoints`
 *   points (at least `BorderSlack` spacings, at most half the disc's
 *   radius), the data ends on that side
 *   (an open border, or the rim of a thin part), and the disc reaches at
 *   most `BorderMargin` spacings past it;
 * - last, the patch's rim is sampled in the same 16 directions, and the disc
 *   shrinks until every sample lies within `MaximumReach` sampling
 *   distances (one over the square root of the density) along the plane,
 *   and twice the tolerance across it, of a point on or near the patch: a
 *   patch fitted on one side of a border can turn steeply just past it.
 *
 * The splat covers exactly the points on its patch within the final R, so
 * its measured maximum deviation over what it covers is within the
 * tolerance by construction.
 */
#ifndef psSplatBound_h
#define psSplatBound_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "psSplatFit.h"

#include <vector> // For covered points

namespace pointsurfaces
{
struct BoundParameters
{
  double Tolerance = 0.0;    ///< largest deviation of a covered point (world units)
  double Spacing = 0.0;      ///< local point spacing (world units)
  double Adjacency = 1.5;    ///< same-sheet distance, in spacings
  double BorderSlack = 1.0;  ///< least shortfall of the data that is a border, in spacings
  double BorderPoints = 7.0; ///< points expected in the band that would make a border
  double BorderMargin = 0.5; ///< how far a disc may reach past the data, in spacings
  double BorderAngle = 45.0; ///< a point supports the directions within this angle of its own,
                             ///< in degrees (180: every direction it projects onto positively)
  double MaximumReach =
    2.5;                    ///< how far the disc's rim may lie from the data, in sampling distances
  double CentreReach = 0.5; ///< off-patch points nearer the centre (in spacings) stop no disc
  double NormalAngle = 60.0; ///< largest angle between a covered point's normal and the patch's,
                             ///< in degrees (with normals; 90 or more: no test)
  bool MeasureOnly = false;  ///< only measure: keep the radius, cover every point in the disc
};

struct SplatBound
{
  double Radius = 0.0;       ///< bounded disc radius (world units)
  double MaxDeviation = 0.0; ///< largest deviation over the covered points (world units)
  bool Border = false;       ///< the disc was stopped at a border of the data
  bool BentAway = false;     ///< the disc was stopped where the surface leaves the patch
};

/**
 * Bound the disc of `splat` (fitted) whose nominal radius is `radius`.
 * `points` are the `n` candidate points (xyz triples), which must include
 * every point within sqrt(2) max(radius, 3 spacings) of the splat's origin.
 * On return `covered` (when given) holds the indices into `points` of the
 * points the splat covers and `rho` their in-plane distances, infinite for
 * a covered point that lies farther off the patch than the final radius
 * (a tolerance above it): within the tolerance, but off the disc as a
 * renderer or vtkSplatErrorMetric sees it, so that no claim counts on it.
 * `normals`,
 * when given, are the points' normals (n triples, either sign, any length;
 * a zero normal is unknown and passes).
 */
POINTSURFACESFILTERS_EXPORT SplatBound BoundSplat(const Splat& splat,
  double radius,
  const double* points,
  int n,
  const BoundParameters& params,
  std::vector<int>* covered = nullptr,
  std::vector<double>* rho = nullptr,
  const double* normals = nullptr);

/** The largest radius BoundSplat looks at for a nominal `radius`: its candidates must reach it. */
POINTSURFACESFILTERS_EXPORT double BoundSearchRadius(double radius, double spacing);
} // namespace pointsurfaces

#endif
