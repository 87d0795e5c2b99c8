// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psRoots.h
 * @brief Double-precision reference for the real roots of polynomials of degree 1 to 4.
 *
 * The splat ray caster solves F(t) = 0 along each ray in float on the GPU
 * (closed forms in Rendering/glsl/vtkSplatRoots.glsl). This is the reference
 * its results are checked against: the eigenvalues of the companion matrix
 * (Eigen), real ones kept, each polished by Newton steps in long double, and
 * the leading coefficient allowed to vanish (the degree then drops).
 */
#ifndef psRoots_h
#define psRoots_h

#include "PointSurfacesFiltersModule.h" // For export macro

namespace pointsurfaces
{
/**
 * Real roots of c[0] + c[1] t + ... + c[degree] t^degree, ascending, written
 * to `roots` (room for `degree` values); returns their count. A root of
 * multiplicity m is reported once per multiplicity found by the eigen solver
 * (near-double roots may come back as a close pair or, when their imaginary
 * parts do not vanish numerically, not at all).
 */
POINTSURFACESFILTERS_EXPORT int RealRoots(const double* c, int degree, double* roots);

/**
 * All roots, real and complex, of the same polynomial (companion-matrix
 * eigenvalues, unpolished): real parts in `re`, imaginary parts in `im`.
 */
POINTSURFACESFILTERS_EXPORT int ComplexRoots(const double* c, int degree, double* re, double* im);

/** p(t) in long double, by Horner. */
POINTSURFACESFILTERS_EXPORT long double EvaluatePolynomial(const double* c,
  int degree,
  long double t);
} // namespace pointsurfaces

#endif
