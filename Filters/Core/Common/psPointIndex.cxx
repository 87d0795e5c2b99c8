// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psPointIndex.h"

#include "vtkSMPTools.h"

#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>

namespace pointsurfaces
{
namespace
{
// nanoflann's view of the caller's coordinates, which it reads in place.
struct Cloud
{
  const double* XYZ;
  size_t N;
  size_t kdtree_get_point_count() const { return this->N; }
  double kdtree_get_pt(size_t i, size_t c) const { return this->XYZ[3 * i + c]; }
  template<class Box>
  bool kdtree_get_bbox(Box&) const
  {
    return false;
  }
};

using Metric = nanoflann::L2_Simple_Adaptor<double, Cloud, double, std::uint32_t>;
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<Metric, Cloud, 3, std::uint32_t>;

// The search options: exact, results left in the order found (the result
// sets below order them). nanoflann 1.5 renamed SearchParams.
#if NANOFLANN_VERSION < 0x150
const nanoflann::SearchParams Unsorted(32, 0.0f, false);
#else
const nanoflann::SearchParameters Unsorted(0.0f, false);
#endif

// The tree offers a point to a result set when its distance is below
// worstDist(); each set makes its own exact test, so its bound sits one
// ulp above the distances it takes.
double Above(double d2)
{
  return std::nextafter(d2, std::numeric_limits<double>::infinity());
}

// The k nearest points as a max-heap of (squared distance, id): the kept
// set is the k smallest pairs whatever the order of the visit, so ties at
// the k-th distance go to the lower ids. The first k points are taken as
// they come and heaped once; each closer one then replaces the top.
struct NearestSet
{
  using DistanceType = double;
  using IndexType = std::uint32_t;
  size_t K;
  std::vector<std::pair<double, int>>& Heap;
  double Worst = std::numeric_limits<double>::infinity();
  void init() {}
  size_t size() const { return this->Heap.size(); }
  bool empty() const { return this->Heap.empty(); }
  bool full() const { return this->Heap.size() == this->K; }
  void sort() {}
  double worstDist() const { return this->Worst; }
  bool addPoint(double d2, std::uint32_t id)
  {
    const std::pair<double, int> p(d2, static_cast<int>(id));
    auto& h = this->Heap;
    if (h.size() < this->K)
    {
      h.push_back(p);
      if (h.size() == this->K)
      {
        std::make_heap(h.begin(), h.end());
        this->Worst = Above(h.front().first);
      }
      return true;
    }
    if (!(p < h.front()))
    {
      return true;
    }
    // Sift the new pair down from the top.
    const size_t n = h.size();
    size_t i = 0;
    for (;;)
    {
      size_t c = 2 * i + 1;
      if (c >= n)
      {
        break;
      }
      if (c + 1 < n && h[c] < h[c + 1])
      {
        ++c;
      }
      if (!(p < h[c]))
      {
        break;
      }
      h[i] = h[c];
      i = c;
    }
    h[i] = p;
    this->Worst = Above(h.front().first);
    return true;
  }
};

// Every point within a squared radius, straight into the caller's vectors.
struct WithinSet
{
  using DistanceType = double;
  using IndexType = std::uint32_t;
  double R2;
  double Bound;
  std::vector<int>& Ids;
  std::vector<double>& D2;
  void init() {}
  size_t size() const { return this->Ids.size(); }
  bool empty() const { return this->Ids.empty(); }
  bool full() const { return true; }
  void sort() {}
  double worstDist() const { return this->Bound; }
  bool addPoint(double d2, std::uint32_t id)
  {
    if (d2 <= this->R2)
    {
      this->Ids.push_back(static_cast<int>(id));
      this->D2.push_back(d2);
    }
    return true;
  }
};

// `pairs` sorted by (squared distance, id), ties (common on grids) by id,
// into `ids` and `d2`.
void SortInto(std::vector<std::pair<double, int>>& pairs,
  std::vector<int>& ids,
  std::vector<double>& d2)
{
  std::sort(pairs.begin(), pairs.end());
  ids.resize(pairs.size());
  d2.resize(pairs.size());
  for (size_t j = 0; j < pairs.size(); ++j)
  {
    d2[j] = pairs[j].first;
    ids[j] = pairs[j].second;
  }
}
} // namespace

struct PointIndex::Tree
{
  Cloud Points;
  std::unique_ptr<KdTree> Index;
};

PointIndex::PointIndex(const double* xyz, long long n)
  : XYZ(xyz)
  , N(n)
  , Impl(new Tree)
{
  this->Impl->Points = Cloud{ xyz, static_cast<size_t>(std::max(0LL, n)) };
  if (n <= 0)
  {
    return;
  }
  // Leaves of 16 points; nanoflann 1.5 and later build on every core.
#if NANOFLANN_VERSION < 0x150
  const nanoflann::KDTreeSingleIndexAdaptorParams params(16);
#else
  const nanoflann::KDTreeSingleIndexAdaptorParams params(16,
    nanoflann::KDTreeSingleIndexAdaptorFlags::None,
    static_cast<unsigned int>(std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads())));
#endif
  this->Impl->Index = std::make_unique<KdTree>(3, this->Impl->Points, params);
}

PointIndex::~PointIndex() = default;

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
  thread_local std::vector<std::pair<double, int>> heap;
  heap.clear();
  heap.reserve(static_cast<size_t>(k));
  NearestSet found{ static_cast<size_t>(k), heap };
  this->Impl->Index->findNeighbors(found, q, Unsorted);
  SortInto(heap, ids, d2);
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
  const double r2 = radius * radius;
  WithinSet found{ r2, Above(r2), ids, d2 };
  this->Impl->Index->findNeighbors(found, q, Unsorted);
  if (!sorted)
  {
    return;
  }
  thread_local std::vector<std::pair<double, int>> pairs;
  pairs.resize(ids.size());
  for (size_t j = 0; j < ids.size(); ++j)
  {
    pairs[j] = std::make_pair(d2[j], ids[j]);
  }
  SortInto(pairs, ids, d2);
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
