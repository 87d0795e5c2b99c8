// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psPolynomial.h"

#include <algorithm>
#include <cmath>

namespace pointsurfaces
{
int DegreeFromMonomialCount(int count)
{
  for (int d = 1; d <= MaximumDegree; ++d)
  {
    if (MonomialCount(d) == count)
    {
      return d;
    }
  }
  return -1;
}

double EvaluateWithGradient(const double* c, int degree, double u, double v, double& du, double& dv)
{
  double upow[MaximumDegree + 1];
  double vpow[MaximumDegree + 1];
  Powers(u, v, degree, upow, vpow);
  double g = 0.0;
  du = dv = 0.0;
  int i = 0;
  for (int total = 0; total <= degree; ++total)
  {
    for (int pu = total; pu >= 0; --pu, ++i)
    {
      const int pv = total - pu;
      g += c[i] * upow[pu] * vpow[pv];
      if (pu > 0)
      {
        du += c[i] * pu * upow[pu - 1] * vpow[pv];
      }
      if (pv > 0)
      {
        dv += c[i] * pv * upow[pu] * vpow[pv - 1];
      }
    }
  }
  return g;
}
bool HeightRange(const double* c, int degree, double rho, double& lo, double& hi)
{
  double k[15] = {};
  std::copy(c, c + MonomialCount(std::max(1, std::min(degree, MaximumDegree))), k);
  const double r2 = rho * rho;
  const double linear = std::hypot(k[1], k[2]) * rho;
  const double mean = 0.5 * (k[3] + k[5]);
  const double spread = std::hypot(0.5 * (k[3] - k[5]), 0.5 * k[4]);
  const double higher =
    (std::abs(k[6]) + std::abs(k[7]) + std::abs(k[8]) + std::abs(k[9])) * r2 * rho +
    (std::abs(k[10]) + std::abs(k[11]) + std::abs(k[12]) + std::abs(k[13]) + std::abs(k[14])) * r2 *
      r2;
  hi = std::min(k[0] + linear + std::max(mean + spread, 0.0) * r2 + higher, rho);
  lo = std::max(k[0] - linear + std::min(mean - spread, 0.0) * r2 - higher, -rho);
  return lo <= hi;
}
} // namespace pointsurfaces
