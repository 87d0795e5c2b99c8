// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psSplatFit.h
 * @brief One algebraic splat from a point and its neighbours ([Bolla 2010] 3.2).
 *
 * Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
 * M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
 *
 * FitSplat() is the per-splat kernel of vtkAlgebraicSplatFitter, as a plain
 * stateless function over the neighbour coordinates:
 *
 * 1. an unweighted plane through the neighbours gives the parametric domain;
 * 2. the feature size h is the mean distance, in that plane, from the point to
 *    its FeatureSizeNeighbors nearest neighbours ([Bolla 2010]: "the average
 *    distance of k nearest neighbors in the local parametric domain");
 * 3. Gaussian weights theta(d) = exp(-d^2 / (WeightScale h)^2);
 * 4. the weighted reference plane ([Bolla 2010] eq. 3.1); the origin is the
 *    point's projection onto it;
 * 5. g(u, v) fitted in the normalised frame ([Bolla 2010] eq. 3.2): by
 *    weighted least squares (Linear), with a robust loss through Ceres
 *    (Robust), or by iterating the MLS projection of the origin onto the
 *    surface (Projected).
 *
 * With MaximumDeviation > 0 (error-bounded splats, the default of the
 * fitter) steps 3 to 5 keep to the sheet of the surface that q lies on: the
 * fit starts from the plane through q itself, whose normal comes from q's
 * nearest neighbours, and is repeated with every neighbour's Gaussian
 * weight multiplied by exp(-(r / sigma)^2), r its distance to the current
 * patch and sigma the tolerance (iteratively reweighted least squares,
 * the residual term of robust implicit MLS, Oztireli et al. 2009). The other
 * side of a thin part and the other face of a sharp edge lie farther than
 * sigma from that plane and fall out of the fit, however close they are.
 * Sheets closer than the tolerance are, by definition, within it.
 */
#ifndef psSplatFit_h
#define psSplatFit_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "psLocalFit.h"

#include <vector> // For weights

namespace pointsurfaces
{
enum class FitMode
{
  Linear = 0,   ///< closed-form weighted least squares: fast, the default
  Robust = 1,   ///< Ceres with a Huber or Cauchy loss: scans with outliers
  Projected = 2 ///< origin moved onto the MLS surface by iteration: accuracy
};

enum class RobustLoss
{
  Huber = 0,
  Cauchy = 1
};

struct SplatFitParameters
{
  int Degree = 2;                 ///< 1 to 4
  int NumberOfNeighbors = 40;     ///< neighbours in the fit
  int FeatureSizeNeighbors = 100; ///< neighbours whose mean in-plane distance is h
  double WeightScale = 1.0;       ///< Gaussian width, in units of h
  FitMode Mode = FitMode::Linear;
  RobustLoss Loss = RobustLoss::Cauchy;
  double LossScale = 0.05;    ///< where the robust loss bends, in units of h
  int MaximumIterations = 10; ///< Projected: projection steps; Robust: solver iterations x 10
  double Tolerance = 1e-7;    ///< Projected: stop when |g(0,0)| < Tolerance (units of h)
  /**
   * Error bound, in units of the local point spacing (mean distance to the
   * SpacingNeighbors nearest distinct points): a splat covers only points
   * within it of its patch, and its fit keeps to q's sheet (see above).
   * 0 turns both off: the unbounded fit of [Bolla 2010].
   */
  double MaximumDeviation = 0.0;
  int ReweightingIterations = 4; ///< IRLS steps of the bounded fit
};

/** Neighbours whose mean distance is the local point spacing. */
constexpr int SpacingNeighbors = 6;

struct Splat
{
  LocalFrame Frame; ///< origin, axes, and Scale = h
  PolynomialFit Fit;
  int Iterations = 0;   ///< projection steps (Projected), solver iterations (Robust), else
                        ///< reweighting steps of the bounded fit (Linear)
  double Spacing = 0.0; ///< local point spacing around q (world units)
};

/**
 * Fit the splat of point `q` from its neighbours `nbrs` (xyz triples sorted by
 * distance to q; q itself may be among them). `orientation`, when given,
 * orients the normal. `weights`, when given, receives the Gaussian weight of
 * each of the first min(n, NumberOfNeighbors) neighbours, for carrying
 * attributes over. `domain`, when given, is steps 1 and 2 done already by
 * the caller with the same neighbours and orientation (the unweighted plane
 * of the first NumberOfNeighbors, with Scale = h): they are not repeated.
 * Never returns NaN: failures are in splat.Fit.Status.
 */
POINTSURFACESFILTERS_EXPORT Splat FitSplat(const double q[3],
  const double* nbrs,
  int n,
  const SplatFitParameters& params,
  const double* orientation = nullptr,
  std::vector<double>* weights = nullptr,
  const LocalFrame* domain = nullptr);

/**
 * Feature size: mean distance from q to the first `k` neighbours measured in
 * the plane of `frame` (only Normal is used); coincident points are skipped.
 * Returns 0 when there is no distinct neighbour.
 */
POINTSURFACESFILTERS_EXPORT double FeatureSize(const double q[3],
  const LocalFrame& frame,
  const double* nbrs,
  int n,
  int k);

/**
 * Local point spacing: mean distance from q to its first `k` distinct
 * neighbours (`nbrs` sorted by distance). 0 when there is none.
 */
POINTSURFACESFILTERS_EXPORT double LocalSpacing(const double q[3],
  const double* nbrs,
  int n,
  int k = SpacingNeighbors);

/**
 * The uncorrelated part of a neighbourhood's noise: the points' residuals
 * about their unweighted quadric in `frame` (first `k` points), each minus
 * that of its nearest neighbour in the plane; 1.4826 / sqrt(2) times the
 * median of their magnitudes. Relief that the quadric cannot follow varies
 * little from a point to its nearest neighbour and drops out (unlike in
 * NoiseScale, which counts it as noise on a sparse sample); a sensor's
 * noise does not. 0 when fewer than 10 points or the fit fails.
 */
POINTSURFACESFILTERS_EXPORT double UncorrelatedNoiseScale(const double* nbrs,
  int n,
  const LocalFrame& frame,
  int k);

/**
 * Robust noise scale of a neighbourhood: 1.4826 times the median distance of
 * its first `k` points to their unweighted quadric in `frame` (whose Scale,
 * h, normalises the fit), times sqrt(k / (k - 6)) for the quadric's six
 * coefficients: the standard deviation of Gaussian noise along the normal.
 * On a clean, dense sample it is the quadric's own error, small beside the
 * spacing; on a scan, the sensor's noise. 0 when fewer than 10 points or the
 * fit fails.
 */
POINTSURFACESFILTERS_EXPORT double NoiseScale(const double* nbrs,
  int n,
  const LocalFrame& frame,
  int k);

/**
 * The robust fit of Fit Mode Robust: starting from `initial`, minimise
 * sum w_i rho((g(u_i, v_i) - h_i)^2) with Ceres. Implemented in psRobustFit.cxx.
 */
POINTSURFACESFILTERS_EXPORT PolynomialFit FitPolynomialRobust(const double* points,
  const double* w,
  int n,
  const LocalFrame& frame,
  const PolynomialFit& initial,
  RobustLoss loss,
  double lossScale,
  int maxIterations,
  int* iterations = nullptr);
} // namespace pointsurfaces

#endif
