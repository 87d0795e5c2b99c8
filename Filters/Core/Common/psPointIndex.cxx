// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psPointIndex.h"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pointsurfaces
{
struct PointIndex::Tree
{
  pcl::KdTreeFLANN<pcl::PointXYZ> KdTree;
};

PointIndex::PointIndex(const double* xyz, long long n)
  : XYZ(xyz)
  , N(n)
  , Impl(new Tree)
{
  double lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 };
  for (long long i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = i ? std::min(lo[c], xyz[3 * i + c]) : xyz[c];
      hi[c] = i ? std::max(hi[c], xyz[3 * i + c]) : xyz[c];
    }
  }
  double diag = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    this->Centre[c] = 0.5 * (lo[c] + hi[c]);
    diag += (hi[c] - lo[c]) * (hi[c] - lo[c]);
  }
  diag = std::sqrt(diag);
  this->InvScale = diag > 0.0 ? 1.0 / diag : 1.0;
  if (n == 0)
  {
    return;
  }
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(static_cast<size_t>(n));
  for (long long i = 0; i < n; ++i)
  {
    auto& p = (*cloud)[static_cast<size_t>(i)];
    p.x = static_cast<float>((xyz[3 * i] - this->Centre[0]) * this->InvScale);
    p.y = static_cast<float>((xyz[3 * i + 1] - this->Centre[1]) * this->InvScale);
    p.z = static_cast<float>((xyz[3 * i + 2] - this->Centre[2]) * this->InvScale);
  }
  // Radius results are sorted here, in double, and only when asked for;
  // kNN results come sorted from FLANN's small-k result set either way.
  this->Impl->KdTree.setSortedResults(false);
  this->Impl->KdTree.setInputCloud(cloud);
}

PointIndex::~PointIndex() = default;

void PointIndex::Finish(const double q[3], std::vector<int>& ids, std::vector<double>& d2) const
{
  // Distances in double from the original coordinates, then re-sorted by
  // (distance, id): the float tree may order near-ties differently (and
  // leaves radius results unsorted). Most kNN answers are in order already
  // and are left as they are.
  d2.resize(ids.size());
  bool ordered = true;
  for (size_t j = 0; j < ids.size(); ++j)
  {
    const double* p = this->Point(ids[j]);
    const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    d2[j] = dx * dx + dy * dy + dz * dz;
    ordered = ordered && (j == 0 || d2[j - 1] <= d2[j]);
  }
  if (ordered)
  {
    return;
  }
  thread_local std::vector<std::pair<double, int>> pairs;
  pairs.resize(ids.size());
  for (size_t j = 0; j < ids.size(); ++j)
  {
    pairs[j] = std::make_pair(d2[j], ids[j]);
  }
  // Ties (common on grids) by id, as FLANN's own sort ordered them.
  std::sort(pairs.begin(), pairs.end());
  for (size_t j = 0; j < pairs.size(); ++j)
  {
    d2[j] = pairs[j].first;
    ids[j] = pairs[j].second;
  }
}

void PointIndex::Nearest(const double q[3],
  int k,
  std::vector<int>& ids,
  std::vector<double>& d2) const
{
  ids.clear();
  d2.clear();
  if (this->N == 0 || k <= 0)
  {
    return;
  }
  k = static_cast<int>(std::min<long long>(k, this->N));
  pcl::PointXYZ p;
  p.x = static_cast<float>((q[0] - this->Centre[0]) * this->InvScale);
  p.y = static_cast<float>((q[1] - this->Centre[1]) * this->InvScale);
  p.z = static_cast<float>((q[2] - this->Centre[2]) * this->InvScale);
  thread_local pcl::Indices found;
  thread_local std::vector<float> fd2;
  found.resize(k);
  fd2.resize(k);
  const int got = this->Impl->KdTree.nearestKSearch(p, static_cast<unsigned int>(k), found, fd2);
  ids.assign(found.begin(), found.begin() + std::max(got, 0));
  this->Finish(q, ids, d2);
}

void PointIndex::Within(const double q[3],
  double radius,
  std::vector<int>& ids,
  std::vector<double>& d2,
  bool sorted) const
{
  ids.clear();
  d2.clear();
  if (this->N == 0 || !(radius > 0.0))
  {
    return;
  }
  pcl::PointXYZ p;
  p.x = static_cast<float>((q[0] - this->Centre[0]) * this->InvScale);
  p.y = static_cast<float>((q[1] - this->Centre[1]) * this->InvScale);
  p.z = static_cast<float>((q[2] - this->Centre[2]) * this->InvScale);
  thread_local pcl::Indices found;
  thread_local std::vector<float> fd2;
  // A relative margin covers the float rounding of the scaled coordinates;
  // the exact test is done in double below.
  this->Impl->KdTree.radiusSearch(p, radius * this->InvScale * (1.0 + 1e-5) + 1e-6, found, fd2);
  const double r2 = radius * radius;
  if (!sorted)
  {
    // Exact radius test in double, no ordering.
    ids.clear();
    d2.clear();
    for (size_t j = 0; j < found.size(); ++j)
    {
      const double* x = this->Point(found[j]);
      const double dx = x[0] - q[0], dy = x[1] - q[1], dz = x[2] - q[2];
      const double e = dx * dx + dy * dy + dz * dz;
      if (e <= r2)
      {
        ids.push_back(found[j]);
        d2.push_back(e);
      }
    }
    return;
  }
  ids.assign(found.begin(), found.end());
  this->Finish(q, ids, d2);
  size_t keep = 0;
  while (keep < d2.size() && d2[keep] <= r2)
  {
    ++keep;
  }
  ids.resize(keep);
  d2.resize(keep);
}
} // namespace pointsurfaces

namespace pointsurfaces
{
namespace
{
// The low 21 bits of v, two zero bits after each.
unsigned long long Spread(unsigned long long v)
{
  v &= 0x1fffffULL;
  v = (v | (v << 32)) & 0x1f00000000ffffULL;
  v = (v | (v << 16)) & 0x1f0000ff0000ffULL;
  v = (v | (v << 8)) & 0x100f00f00f00f00fULL;
  v = (v | (v << 4)) & 0x10c30c30c30c30c3ULL;
  v = (v | (v << 2)) & 0x1249249249249249ULL;
  return v;
}
} // namespace

std::vector<long long> SpatialOrder(const double* xyz, long long n)
{
  std::vector<long long> order(static_cast<size_t>(std::max(0LL, n)));
  std::iota(order.begin(), order.end(), 0LL);
  if (n < 2)
  {
    return order;
  }
  double lo[3] = { xyz[0], xyz[1], xyz[2] }, hi[3] = { xyz[0], xyz[1], xyz[2] };
  for (long long i = 1; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], xyz[3 * i + c]);
      hi[c] = std::max(hi[c], xyz[3 * i + c]);
    }
  }
  const double side = std::max({ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2] });
  const double cells = 2097151.0; // 2^21 - 1
  const double scale = side > 0.0 ? cells / side : 0.0;
  std::vector<std::pair<unsigned long long, long long>> keys(static_cast<size_t>(n));
  vtkSMPTools::For(0,
    n,
    [&](long long begin, long long end)
    {
      for (long long i = begin; i < end; ++i)
      {
        unsigned long long code = 0;
        for (int c = 0; c < 3; ++c)
        {
          const double g = std::min(cells, std::max(0.0, (xyz[3 * i + c] - lo[c]) * scale));
          code |= Spread(static_cast<unsigned long long>(g)) << c;
        }
        keys[i] = std::make_pair(code, i);
      }
    });
  vtkSMPTools::Sort(keys.begin(), keys.end());
  for (long long i = 0; i < n; ++i)
  {
    order[i] = keys[i].second;
  }
  return order;
}

std::vector<long long> UniquePoints(const double* xyz, long long n, double tolerance)
{
  std::vector<long long> kept;
  if (n <= 0)
  {
    return kept;
  }
  double lo[3] = { xyz[0], xyz[1], xyz[2] };
  for (long long i = 1; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], xyz[3 * i + c]);
    }
  }
  // Points are sorted into cells 100 times the tolerance (exact coordinates
  // without a tolerance); within a cell, a point within the tolerance of an
  // earlier kept point is merged into it. Two points closer than the
  // tolerance fall into different cells with a chance of 3 in 100 of their
  // distance over the tolerance.
  const double cell = 100.0 * tolerance;
  struct Key
  {
    double K[3];
    long long Id;
  };
  std::vector<Key> keys(static_cast<size_t>(n));
  for (long long i = 0; i < n; ++i)
  {
    keys[i].Id = i;
    for (int c = 0; c < 3; ++c)
    {
      const double d = xyz[3 * i + c] - lo[c];
      keys[i].K[c] = tolerance > 0.0 ? std::floor(d / cell) : d;
    }
  }
  auto sameCell = [](const Key& a, const Key& b)
  { return a.K[0] == b.K[0] && a.K[1] == b.K[1] && a.K[2] == b.K[2]; };
  vtkSMPTools::Sort(keys.begin(),
    keys.end(),
    [](const Key& a, const Key& b)
    {
      for (int c = 0; c < 3; ++c)
      {
        if (a.K[c] != b.K[c])
        {
          return a.K[c] < b.K[c];
        }
      }
      return a.Id < b.Id;
    });
  const double tol2 = tolerance * tolerance;
  size_t first = 0; // first kept of the current cell, in `kept`
  for (size_t j = 0; j < keys.size(); ++j)
  {
    if (j == 0 || !sameCell(keys[j], keys[j - 1]))
    {
      first = kept.size();
      kept.push_back(keys[j].Id);
      continue;
    }
    const double* p = xyz + 3 * keys[j].Id;
    bool merged = tolerance <= 0.0; // same exact coordinates
    for (size_t k = first; k < kept.size() && !merged; ++k)
    {
      const double* q = xyz + 3 * kept[k];
      merged = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
          (p[2] - q[2]) * (p[2] - q[2]) <=
        tol2;
    }
    if (!merged)
    {
      kept.push_back(keys[j].Id);
    }
  }
  std::sort(kept.begin(), kept.end());
  return kept;
}
} // namespace pointsurfaces
