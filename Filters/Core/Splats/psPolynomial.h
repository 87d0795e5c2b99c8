// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psPolynomial.h
 * @brief Bivariate polynomials g(u,v) of degree 1 to 4 in the monomial order of the splat data model.
 *
 * Plain functions, no VTK: the fitter builds its least-squares systems from
 * Monomials(), the error metrics and the CPU reference ray caster evaluate
 * Evaluate() and Gradient(). Monomials are ordered by total degree, then by
 * descending power of u (see vtkSplatDataModel and the README's Data model section):
 * 1, u, v, u², uv, v², u³, u²v, uv², v³, u⁴, u³v, u²v², uv³, v⁴.
 */
#ifndef psPolynomial_h
#define psPolynomial_h

#include "PointSurfacesFiltersModule.h" // For export macro

namespace pointsurfaces
{
constexpr int MaximumDegree = 4;

/** Number of monomials of total degree <= degree: 3, 6, 10, 15 for degrees 1 to 4. */
constexpr int MonomialCount(int degree)
{
  return (degree + 1) * (degree + 2) / 2;
}

/** The degree whose monomial count is `count`, or -1 when no degree 1..4 has it. */
POINTSURFACESFILTERS_EXPORT int DegreeFromMonomialCount(int count);

/** u^0 .. u^degree and v^0 .. v^degree. */
inline void Powers(double u, double v, int degree, double* upow, double* vpow)
{
  upow[0] = vpow[0] = 1.0;
  for (int k = 1; k <= degree; ++k)
  {
    upow[k] = upow[k - 1] * u;
    vpow[k] = vpow[k - 1] * v;
  }
}

/**
 * Write the MonomialCount(degree) monomials at (u, v) to `out`. Inline: the
 * fitter and the disc bounds call it for every neighbour of every splat.
 */
inline void Monomials(double u, double v, int degree, double* out)
{
  double upow[MaximumDegree + 1];
  double vpow[MaximumDegree + 1];
  Powers(u, v, degree, upow, vpow);
  int i = 0;
  for (int total = 0; total <= degree; ++total)
  {
    for (int pu = total; pu >= 0; --pu)
    {
      out[i++] = upow[pu] * vpow[total - pu];
    }
  }
}

/** g(u, v) for coefficients `c` in monomial order. */
inline double Evaluate(const double* c, int degree, double u, double v)
{
  double m[MonomialCount(MaximumDegree)];
  Monomials(u, v, degree, m);
  double sum = 0.0;
  for (int i = 0; i < MonomialCount(degree); ++i)
  {
    sum += c[i] * m[i];
  }
  return sum;
}

/** g(u, v) and its partial derivatives. */
POINTSURFACESFILTERS_EXPORT double EvaluateWithGradient(const double* c,
  int degree,
  double u,
  double v,
  double& du,
  double& dv);

/**
 * A range [lo, hi] that holds g over the disc u^2 + v^2 <= rho^2: the
 * constant, the linear part's reach |grad| rho, the quadratic form's
 * eigenvalues times rho^2, and sum |c_k| rho^k for the cubic and quartic
 * terms, clamped to the splat's cylinder |height| <= rho. The splat
 * mapper's geometry shader bounds each splat with the same range.
 * Returns false when the patch leaves the cylinder over the whole disc.
 */
POINTSURFACESFILTERS_EXPORT bool HeightRange(const double* c,
  int degree,
  double rho,
  double& lo,
  double& hi);
} // namespace pointsurfaces

#endif
