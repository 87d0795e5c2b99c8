// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psRoots.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace pointsurfaces
{
long double EvaluatePolynomial(const double* c, int degree, long double t)
{
  long double p = c[degree];
  for (int k = degree - 1; k >= 0; --k)
  {
    p = p * t + c[k];
  }
  return p;
}

namespace
{
long double Derivative(const double* c, int degree, long double t)
{
  long double p = static_cast<long double>(degree) * c[degree];
  for (int k = degree - 1; k >= 1; --k)
  {
    p = p * t + static_cast<long double>(k) * c[k];
  }
  return p;
}
} // namespace

int ComplexRoots(const double* c, int degree, double* re, double* im)
{
  while (degree > 0 && c[degree] == 0.0)
  {
    --degree;
  }
  if (degree <= 0)
  {
    return 0;
  }
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(degree, degree);
  for (int k = 0; k < degree; ++k)
  {
    companion(0, k) = -c[degree - 1 - k] / c[degree];
    if (k + 1 < degree)
    {
      companion(k + 1, k) = 1.0;
    }
  }
  Eigen::EigenSolver<Eigen::MatrixXd> solver(companion, false);
  for (int k = 0; k < degree; ++k)
  {
    re[k] = solver.eigenvalues()(k).real();
    im[k] = solver.eigenvalues()(k).imag();
  }
  return degree;
}

int RealRoots(const double* c, int degree, double* roots)
{
  // Drop vanishing leading coefficients: only exact zeros, the reference
  // keeps every huge root of a tiny leading term.
  while (degree > 0 && c[degree] == 0.0)
  {
    --degree;
  }
  double re[4], im[4];
  const int all = degree > 0 && degree <= 4 ? ComplexRoots(c, degree, re, im) : 0;
  int count = 0;
  for (int k = 0; k < all; ++k)
  {
    if (std::abs(im[k]) > 1e-7 * std::max(1.0, std::hypot(re[k], im[k])))
    {
      continue;
    }
    long double t = re[k];
    for (int it = 0; it < 8; ++it)
    {
      const long double d = Derivative(c, degree, t);
      if (d == 0.0L)
      {
        break;
      }
      const long double step = EvaluatePolynomial(c, degree, t) / d;
      if (!std::isfinite(static_cast<double>(step)))
      {
        break;
      }
      t -= step;
    }
    roots[count++] = static_cast<double>(t);
  }
  std::sort(roots, roots + count);
  return count;
}
} // namespace pointsurfaces
