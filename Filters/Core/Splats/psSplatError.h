// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psSplatError.h
 * @brief Approximation error of a splat set against points ([Bolla 2010] 3.3.3).
 *
 * Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
 * M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
 *
 * For a point p_i and each splat a_j whose disc covers it (in-plane distance
 * to o_j at most R_j), e_ij is the first-order orthogonal distance from p_i to
 * the patch g_j: (height - g(u, v)) h_j / sqrt(1 + |grad g|^2), in the
 * normalised frame of a_j. Then
 *
 * - delta_i = sum_j |e_ij| theta(||o_j - p_i||), theta(d) = exp(-d^2/h_j^2), and
 *   Phi = sum_i delta_i, as in [Bolla 2010];
 * - the distance to the blended surface is |sum_j w_ij e_ij / sum_j w_ij| with
 *   the same weights: what the two-pass blending renders.
 *
 * A point covered by no disc is measured against the patch of the nearest
 * splat, unbounded, and counted as uncovered (a hole).
 */
#ifndef psSplatError_h
#define psSplatError_h

#include "PointSurfacesFiltersModule.h" // For export macro

#include <vector> // For per-point results

namespace pointsurfaces
{
/** A splat set as plain arrays (xyz triples; Coefficients has MonomialCount(Degree) per splat). */
struct SplatArrays
{
  const double* Origin = nullptr;
  const double* Normal = nullptr;
  const double* Tangent = nullptr;
  const double* Scale = nullptr;
  const double* Radius = nullptr;
  const double* Coefficients = nullptr;
  int Degree = 2;
  long long Count = 0;
};

struct ErrorSummary
{
  double RMS = 0.0;     ///< root mean square distance to the blended surface
  double Maximum = 0.0; ///< largest distance (one-sided Hausdorff, points to splats)
  double Phi = 0.0;     ///< sum of delta_i
  long long Uncovered = 0;
};

/** Per-point delta_i and blended distance of `n` points; returns the summary. */
POINTSURFACESFILTERS_EXPORT ErrorSummary EvaluateSplatError(const SplatArrays& splats,
  const double* points,
  long long n,
  std::vector<double>& delta,
  std::vector<double>& distance,
  std::vector<int>& covering);
} // namespace pointsurfaces

#endif
