// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psLocalFit.h
 * @brief Weighted least-squares reference planes and polynomial fits ([Bolla 2010] eqs. 3.1, 3.2).
 *
 * Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
 * M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
 *
 * The per-splat kernel of the MLS fitter, as plain functions with no VTK and
 * no state, so they can run in vtkSMPTools loops and be tested directly.
 * Everything is accumulated in double, relative to a caller-given centre, and
 * the polynomial is fitted in the normalised frame (u/h, v/h, n/h): results do
 * not depend on where the model sits (offsets near 1e7) or on its scale.
 * Degenerate neighbourhoods are reported, never turned into NaN.
 */
#ifndef psLocalFit_h
#define psLocalFit_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "psPolynomial.h"

#include <cmath> // For std::exp

namespace pointsurfaces
{
/** An orthonormal frame: origin o, normal n, tangents t and b = n x t, and the feature size h. */
struct LocalFrame
{
  double Origin[3] = { 0, 0, 0 };
  double Normal[3] = { 0, 0, 1 };
  double Tangent[3] = { 1, 0, 0 };
  double Bitangent[3] = { 0, 1, 0 };
  double Scale = 1.0;
};

enum class FitStatus
{
  Ok = 0,
  ReducedDegree, ///< the fit succeeded at a lower degree than asked
  TooFewPoints,  ///< fewer weighted points than unknowns, even at degree 1
  Degenerate,    ///< coincident or collinear points: no plane or no fit
  NonFinite      ///< NaN or Inf in the input
};

/** A short English description of a status, for warnings. */
POINTSURFACESFILTERS_EXPORT const char* FitStatusName(FitStatus status);

/**
 * Weighted plane through `n` points (xyz triples) with weights `w` (may be
 * null: all 1). The origin is the weighted centroid, the normal the
 * eigenvector of the smallest eigenvalue of the weighted covariance, the
 * tangent that of the largest. Signs are made deterministic: the normal
 * agrees with `orientation` when it is given, and the tangent's largest
 * component is positive. frame.Scale is left untouched.
 */
POINTSURFACESFILTERS_EXPORT FitStatus FitReferencePlane(const double* points,
  const double* w,
  int n,
  LocalFrame& frame,
  const double* orientation = nullptr);

/** Result of a local polynomial fit. */
struct PolynomialFit
{
  int Degree = 0;
  double Coefficients[MonomialCount(MaximumDegree)] = {};
  FitStatus Status = FitStatus::Degenerate;
  double WeightedRMS = 0.0; ///< weighted RMS residual, in units of frame.Scale
};

/**
 * Fit g(u, v) of `degree` (1..4) to the points by weighted least squares in
 * the normalised frame: u = (p - o)·t / h, v = (p - o)·b / h,
 * height = (p - o)·n / h, minimising sum w_i (g(u_i, v_i) - height_i)^2.
 * A rank-deficient system falls back to the highest degree that is well
 * posed (status ReducedDegree); coefficients are always finite.
 * `residuals`, when given (n values), receives each point's distance to the
 * patch along the normal, |height_i - g(u_i, v_i)| h (world units), where
 * the fit succeeds.
 */
POINTSURFACESFILTERS_EXPORT PolynomialFit FitPolynomial(const double* points,
  const double* w,
  int n,
  const LocalFrame& frame,
  int degree,
  double* residuals = nullptr);

/**
 * Coordinates of p in the normalised frame: u = (p - o)·t / h,
 * v = (p - o)·b / h, height = (p - o)·n / h.
 */
inline void ToLocal(const LocalFrame& f, const double p[3], double uvh[3])
{
  const double d[3] = { p[0] - f.Origin[0], p[1] - f.Origin[1], p[2] - f.Origin[2] };
  const double inv = 1.0 / f.Scale;
  uvh[0] = (d[0] * f.Tangent[0] + d[1] * f.Tangent[1] + d[2] * f.Tangent[2]) * inv;
  uvh[1] = (d[0] * f.Bitangent[0] + d[1] * f.Bitangent[1] + d[2] * f.Bitangent[2]) * inv;
  uvh[2] = (d[0] * f.Normal[0] + d[1] * f.Normal[1] + d[2] * f.Normal[2]) * inv;
}

/**
 * p against the patch of degree `degree` (coefficients `c`) over frame `f`:
 * the signed distance of p off the patch along the patch's normal, to first
 * order, (height - g(u, v)) h / sqrt(1 + |grad g|^2), in world units.
 * `inPlane2` receives p's squared distance from the origin in the frame's
 * plane, (u^2 + v^2) h^2, and `height` (when given) p's signed deviation
 * along the frame's normal, (height - g(u, v)) h. These put p on a splat's
 * disc or off it for vtkSplatErrorMetric and the renderers (|offset| and
 * the in-plane distance within the radius).
 */
POINTSURFACESFILTERS_EXPORT double PatchOffset(const LocalFrame& f,
  const double* c,
  int degree,
  const double p[3],
  double& inPlane2,
  double* height = nullptr);

/** The Gaussian weight exp(-d^2 / h^2) of [Bolla 2010]. */
inline double GaussianWeight(double distanceSquared, double hSquared)
{
  return hSquared > 0.0 ? std::exp(-distanceSquared / hSquared) : 0.0;
}
} // namespace pointsurfaces

#endif
