// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psSampleNoise.h"

#include "psLocalFit.h"
#include "psPointIndex.h"
#include "psSplatFit.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace pointsurfaces
{
namespace
{
constexpr int Narrow = 16;
constexpr int Wide = 64;
// Growth of a probe whose narrow residual is exactly 0 while its wide one
// is not (relief on a flat, clean sample): clean.
constexpr double CleanGrowth = 1e3;

// The robust residual scale of the first `k` of `coords` about their own
// PCA plane's quadric; -1 when they have no plane or no width.
double ResidualAt(const std::vector<double>& coords, const std::vector<double>& d2, int k)
{
  LocalFrame frame;
  if (FitReferencePlane(coords.data(), nullptr, k, frame) != FitStatus::Ok)
  {
    return -1.0;
  }
  frame.Scale = std::sqrt(d2[static_cast<size_t>(k - 1)]);
  if (!(frame.Scale > 0.0))
  {
    return -1.0;
  }
  return NoiseScale(coords.data(), k, frame, k);
}

double Median(std::vector<double>& v)
{
  if (v.empty())
  {
    return 0.0;
  }
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}
} // namespace

SampleNoise MeasureSampleNoise(const double* xyz, long long n, const PointIndex& index, int probes)
{
  SampleNoise result;
  if (n < Wide || probes < 1)
  {
    return result;
  }
  const long long count = std::min<long long>(probes, n);
  // Per probe: its growth and its noise over its spacing; NaN when it gave none.
  std::vector<double> growth(static_cast<size_t>(count), std::nan(""));
  std::vector<double> noise(static_cast<size_t>(count), std::nan(""));
  vtkSMPTools::For(0,
    count,
    [&](long long begin, long long end)
    {
      std::vector<int> ids;
      std::vector<double> d2, coords;
      for (long long j = begin; j < end; ++j)
      {
        // Evenly through the points' order (a scan's lines or a spatial
        // order spread them over the surface); the middle of each stretch.
        const long long i = (2 * j + 1) * n / (2 * count);
        const double* q = xyz + 3 * i;
        index.Nearest(q, Wide, ids, d2);
        if (static_cast<int>(ids.size()) < Wide)
        {
          continue;
        }
        coords.resize(3 * ids.size());
        for (size_t k = 0; k < ids.size(); ++k)
        {
          std::copy(xyz + 3 * static_cast<long long>(ids[k]),
            xyz + 3 * static_cast<long long>(ids[k]) + 3,
            &coords[3 * k]);
        }
        const double spacing = LocalSpacing(q, coords.data(), Wide);
        const double narrow = ResidualAt(coords, d2, Narrow);
        const double wide = ResidualAt(coords, d2, Wide);
        if (!(spacing > 0.0) || narrow < 0.0 || wide < 0.0)
        {
          continue;
        }
        noise[static_cast<size_t>(j)] = narrow / spacing;
        growth[static_cast<size_t>(j)] =
          narrow > 0.0 ? std::min(CleanGrowth, wide / narrow) : (wide > 0.0 ? CleanGrowth : 1.0);
      }
    });
  std::vector<double> g, s;
  for (long long j = 0; j < count; ++j)
  {
    if (!std::isnan(growth[static_cast<size_t>(j)]))
    {
      g.push_back(growth[static_cast<size_t>(j)]);
      s.push_back(noise[static_cast<size_t>(j)]);
    }
  }
  result.Probes = static_cast<int>(g.size());
  if (result.Probes == 0)
  {
    return result;
  }
  result.Growth = Median(g);
  result.NoiseOverSpacing = Median(s);
  result.Noisy = result.Growth < NoisyGrowth && result.NoiseOverSpacing >= MinimumNoise;
  return result;
}
} // namespace pointsurfaces
