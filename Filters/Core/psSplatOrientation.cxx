// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psSplatOrientation.h"

#include "psPointIndex.h"
#include "psPolynomial.h"

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>
#include <utility>

namespace pointsurfaces
{
namespace
{
// How large the flux of a part's normals must be, as a share of its largest
// possible value, to decide which way is out.
constexpr double Decisive = 0.1;
// A part whose area-weighted normals sum to more than this share of its
// area is an open sheet, not a closed surface.
constexpr double OpenSheet = 0.3;
} // namespace

void FlipSplat(Splat& splat)
{
  LocalFrame& f = splat.Frame;
  for (int c = 0; c < 3; ++c)
  {
    f.Normal[c] = -f.Normal[c];
    f.Bitangent[c] = -f.Bitangent[c];
  }
  // (u, v, w) -> (u, -v, -w): the monomial u^(d-j) v^j changes sign with j,
  // and the whole of g with w.
  int k = 0;
  for (int d = 0; d <= MaximumDegree; ++d)
  {
    for (int j = 0; j <= d; ++j, ++k)
    {
      splat.Fit.Coefficients[k] *= (j % 2 == 0) ? -1.0 : 1.0;
    }
  }
}

long long OrientSplats(const std::vector<Splat*>& splats, int k, long long* parts)
{
  const long long n = static_cast<long long>(splats.size());
  if (parts)
  {
    *parts = 0;
  }
  if (n == 0)
  {
    return 0;
  }
  std::vector<double> xyz(3 * n);
  for (long long i = 0; i < n; ++i)
  {
    std::copy(splats[i]->Frame.Origin, splats[i]->Frame.Origin + 3, &xyz[3 * i]);
  }
  // The k-nearest-neighbour graph, made symmetric.
  const int kk = static_cast<int>(std::min<long long>(std::max(k, 1) + 1, n));
  std::vector<int> neighbours(static_cast<size_t>(n) * kk, -1);
  {
    PointIndex index(xyz.data(), n);
    vtkSMPTools::For(0,
      n,
      [&](long long begin, long long end)
      {
        std::vector<int> ids;
        std::vector<double> d2;
        for (long long i = begin; i < end; ++i)
        {
          index.Nearest(&xyz[3 * i], kk, ids, d2);
          std::copy(ids.begin(), ids.end(), &neighbours[static_cast<size_t>(i) * kk]);
        }
      });
  }
  std::vector<std::vector<int>> adjacency(n);
  for (long long i = 0; i < n; ++i)
  {
    for (int m = 0; m < kk; ++m)
    {
      const int j = neighbours[static_cast<size_t>(i) * kk + m];
      if (j >= 0 && j != i)
      {
        adjacency[i].push_back(j);
        adjacency[j].push_back(static_cast<int>(i));
      }
    }
  }
  // The cost of an edge: how far the normals turn (Hoppe's 1 - |n_i.n_j|),
  // plus how steeply the edge leaves each splat's plane (|e.n| for the unit
  // edge e). Along the surface an edge lies nearly in both planes; between
  // the two faces of a thin part it runs along their normals, which are
  // antiparallel and so turn by nothing: by angle alone such an edge was as
  // cheap as any, and the propagation crossed through the part and turned
  // one face inward (a third of Lucy's splats).
  auto cost = [&](long long i, long long j)
  {
    const double* a = splats[i]->Frame.Normal;
    const double* b = splats[j]->Frame.Normal;
    const double turn = 1.0 - std::abs(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
    const double e[3] = {
      xyz[3 * j] - xyz[3 * i], xyz[3 * j + 1] - xyz[3 * i + 1], xyz[3 * j + 2] - xyz[3 * i + 2]
    };
    const double length = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    if (!(length > 0.0))
    {
      return turn;
    }
    return turn +
      (std::abs(e[0] * a[0] + e[1] * a[1] + e[2] * a[2]) +
        std::abs(e[0] * b[0] + e[1] * b[1] + e[2] * b[2])) /
      length;
  };

  // Seeds in order of decreasing height; Prim's algorithm over each part.
  std::vector<long long> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(),
    order.end(),
    [&](long long a, long long b) { return xyz[3 * a + 2] > xyz[3 * b + 2]; });
  std::vector<char> done(n, 0);
  std::vector<char> turned(n, 0);
  auto flip = [&](long long i)
  {
    FlipSplat(*splats[i]);
    turned[i] = !turned[i];
  };
  std::vector<long long> part;
  using Edge = std::pair<double, std::pair<long long, long long>>; // cost, (from, to)
  std::priority_queue<Edge, std::vector<Edge>, std::greater<Edge>> queue;
  for (const long long seed : order)
  {
    if (done[seed])
    {
      continue;
    }
    if (parts)
    {
      ++*parts;
    }
    if (splats[seed]->Frame.Normal[2] < 0.0)
    {
      flip(seed);
    }
    done[seed] = 1;
    part.assign(1, seed);
    for (const int j : adjacency[seed])
    {
      queue.push({ cost(seed, j), { seed, j } });
    }
    while (!queue.empty())
    {
      const auto [from, to] = queue.top().second;
      queue.pop();
      if (done[to])
      {
        continue;
      }
      done[to] = 1;
      part.push_back(to);
      const double* a = splats[from]->Frame.Normal;
      const double* b = splats[to]->Frame.Normal;
      if (a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < 0.0)
      {
        flip(to);
      }
      for (const int j : adjacency[to])
      {
        if (!done[j])
        {
          queue.push({ cost(to, j), { to, j } });
        }
      }
    }
    // Which way is out, on a closed part: there the integral of (x - c).n
    // over the area is three times the enclosed volume, positive for
    // outward normals whatever c and the shape. Summed over the part's
    // splats (weighted by h squared, their share of the area) it decides,
    // unless it is too close to zero to. The seed's rule alone (the highest
    // normal points up) turned all of Lucy inward at some settings: her
    // highest splat, on a wing's tip, lies on its underside. An open sheet
    // (a range scan, whose patch may be concave towards the scanner) keeps
    // the seed's rule: a part is taken for closed when its normals nearly
    // cancel (the area-weighted sum of a closed surface's normals is zero),
    // under OpenSheet of their total.
    double centre[3] = { 0.0, 0.0, 0.0 }, weight = 0.0;
    for (const long long i : part)
    {
      const double w = splats[i]->Frame.Scale * splats[i]->Frame.Scale;
      for (int c = 0; c < 3; ++c)
      {
        centre[c] += w * xyz[3 * i + c];
      }
      weight += w;
    }
    if (!(weight > 0.0) || part.size() < 4)
    {
      continue;
    }
    for (double& c : centre)
    {
      c /= weight;
    }
    double flux = 0.0, magnitude = 0.0, area[3] = { 0.0, 0.0, 0.0 };
    for (const long long i : part)
    {
      const double w = splats[i]->Frame.Scale * splats[i]->Frame.Scale;
      const double* m = splats[i]->Frame.Normal;
      double along = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        along += (xyz[3 * i + c] - centre[c]) * m[c];
        area[c] += w * m[c];
      }
      flux += w * along;
      magnitude += w * std::abs(along);
    }
    const double open =
      std::sqrt(area[0] * area[0] + area[1] * area[1] + area[2] * area[2]) / weight;
    if (open < OpenSheet && flux < -Decisive * magnitude)
    {
      for (const long long i : part)
      {
        flip(i);
      }
    }
  }
  long long flipped = 0;
  for (const char t : turned)
  {
    flipped += t;
  }
  return flipped;
}
} // namespace pointsurfaces
