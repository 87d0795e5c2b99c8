// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psSplatError.h"

#include "psLocalFit.h"
#include "psPointIndex.h"
#include "psPolynomial.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>

namespace pointsurfaces
{
namespace
{
// Signed first-order distance from p to the patch of splat j, and the squared
// in-plane distance to its origin.
double PatchDistance(const SplatArrays& s, long long j, const double p[3], double& inPlane2)
{
  LocalFrame frame;
  const double* n = s.Normal + 3 * j;
  const double* t = s.Tangent + 3 * j;
  for (int c = 0; c < 3; ++c)
  {
    frame.Origin[c] = s.Origin[3 * j + c];
    frame.Normal[c] = n[c];
    frame.Tangent[c] = t[c];
  }
  frame.Bitangent[0] = n[1] * t[2] - n[2] * t[1];
  frame.Bitangent[1] = n[2] * t[0] - n[0] * t[2];
  frame.Bitangent[2] = n[0] * t[1] - n[1] * t[0];
  frame.Scale = s.Scale[j];
  return PatchOffset(frame, s.Coefficients + MonomialCount(s.Degree) * j, s.Degree, p, inPlane2);
}
} // namespace

ErrorSummary EvaluateSplatError(const SplatArrays& splats,
  const double* points,
  long long n,
  std::vector<double>& delta,
  std::vector<double>& distance,
  std::vector<int>& covering)
{
  ErrorSummary summary;
  delta.assign(static_cast<size_t>(n), 0.0);
  distance.assign(static_cast<size_t>(n), 0.0);
  covering.assign(static_cast<size_t>(n), 0);
  if (splats.Count == 0 || n == 0)
  {
    return summary;
  }
  PointIndex origins(splats.Origin, splats.Count);
  const double maxRadius = *std::max_element(splats.Radius, splats.Radius + splats.Count);
  vtkSMPTools::For(0,
    n,
    [&](long long begin, long long end)
    {
      std::vector<int> ids;
      std::vector<double> d2;
      for (long long i = begin; i < end; ++i)
      {
        const double* p = points + 3 * i;
        origins.Within(p, maxRadius * 1.5, ids, d2);
        double sumW = 0.0, sumWE = 0.0, sumDelta = 0.0;
        int count = 0;
        for (size_t k = 0; k < ids.size(); ++k)
        {
          const long long j = ids[k];
          double inPlane2;
          const double e = PatchDistance(splats, j, p, inPlane2);
          if (inPlane2 > splats.Radius[j] * splats.Radius[j] || std::abs(e) > splats.Radius[j])
          {
            continue; // outside the disc, or another sheet of the surface
          }
          const double w = GaussianWeight(d2[k], splats.Scale[j] * splats.Scale[j]);
          sumW += w;
          sumWE += w * e;
          sumDelta += std::abs(e) * w;
          ++count;
        }
        if (count == 0 || !(sumW > 0.0))
        {
          origins.Nearest(p, 1, ids, d2);
          double inPlane2;
          distance[i] = ids.empty() ? 0.0 : std::abs(PatchDistance(splats, ids[0], p, inPlane2));
          delta[i] = distance[i];
          covering[i] = 0;
          continue;
        }
        distance[i] = std::abs(sumWE / sumW);
        delta[i] = sumDelta;
        covering[i] = count;
      }
    });
  double sum2 = 0.0;
  for (long long i = 0; i < n; ++i)
  {
    sum2 += distance[i] * distance[i];
    summary.Maximum = std::max(summary.Maximum, distance[i]);
    summary.Phi += delta[i];
    summary.Uncovered += covering[i] == 0 ? 1 : 0;
  }
  summary.RMS = std::sqrt(sum2 / static_cast<double>(n));
  return summary;
}
} // namespace pointsurfaces
