// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOctree.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pointsurfaces
{
namespace
{
struct Builder
{
  const double* XYZ;
  const double* Radius;
  const int* Level;
  int Bucket;
  int MaxDepth;
  Octree Tree;

  void Measure(OctreeNode& node) const
  {
    double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
    for (long long k = node.Begin; k < node.End; ++k)
    {
      const long long i = this->Tree.Order[k];
      for (int c = 0; c < 3; ++c)
      {
        lo[c] = std::min(lo[c], this->XYZ[3 * i + c] - this->Radius[i]);
        hi[c] = std::max(hi[c], this->XYZ[3 * i + c] + this->Radius[i]);
      }
    }
    double r = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      node.Bounds[2 * c] = lo[c];
      node.Bounds[2 * c + 1] = hi[c];
      node.Sphere[c] = 0.5 * (lo[c] + hi[c]);
    }
    for (long long k = node.Begin; k < node.End; ++k)
    {
      const long long i = this->Tree.Order[k];
      const double dx = this->XYZ[3 * i] - node.Sphere[0],
                   dy = this->XYZ[3 * i + 1] - node.Sphere[1],
                   dz = this->XYZ[3 * i + 2] - node.Sphere[2];
      r = std::max(r, std::sqrt(dx * dx + dy * dy + dz * dz) + this->Radius[i]);
    }
    node.Sphere[3] = r;
  }

  void Split(int nodeId)
  {
    OctreeNode node = this->Tree.Nodes[nodeId];
    const long long count = node.End - node.Begin;
    auto first = this->Tree.Order.begin() + node.Begin;
    auto last = this->Tree.Order.begin() + node.End;
    if (count <= this->Bucket || node.Depth >= this->MaxDepth)
    {
      std::stable_sort(
        first, last, [&](long long a, long long b) { return this->Level[a] < this->Level[b]; });
      return;
    }
    double mean[3] = { 0, 0, 0 };
    for (auto it = first; it != last; ++it)
    {
      for (int c = 0; c < 3; ++c)
      {
        mean[c] += this->XYZ[3 * *it + c];
      }
    }
    for (int c = 0; c < 3; ++c)
    {
      mean[c] /= static_cast<double>(count);
    }
    auto octant = [&](long long i)
    {
      return (this->XYZ[3 * i] > mean[0] ? 1 : 0) | (this->XYZ[3 * i + 1] > mean[1] ? 2 : 0) |
        (this->XYZ[3 * i + 2] > mean[2] ? 4 : 0);
    };
    std::stable_sort(first, last, [&](long long a, long long b) { return octant(a) < octant(b); });
    // Coincident origins cannot be separated: keep them in one leaf.
    if (octant(*first) == octant(*(last - 1)))
    {
      std::stable_sort(
        first, last, [&](long long a, long long b) { return this->Level[a] < this->Level[b]; });
      return;
    }
    std::vector<std::pair<long long, long long>> ranges;
    long long begin = node.Begin;
    for (long long k = node.Begin + 1; k <= node.End; ++k)
    {
      if (k == node.End || octant(this->Tree.Order[k]) != octant(this->Tree.Order[k - 1]))
      {
        ranges.emplace_back(begin, k);
        begin = k;
      }
    }
    const int firstChild = static_cast<int>(this->Tree.Nodes.size());
    this->Tree.Nodes[nodeId].FirstChild = firstChild;
    this->Tree.Nodes[nodeId].ChildCount = static_cast<int>(ranges.size());
    for (const auto& r : ranges)
    {
      OctreeNode child;
      child.Begin = r.first;
      child.End = r.second;
      child.Depth = node.Depth + 1;
      this->Measure(child);
      this->Tree.Nodes.push_back(child);
    }
    for (int c = 0; c < static_cast<int>(ranges.size()); ++c)
    {
      this->Split(firstChild + c);
    }
  }
};
} // namespace

Octree BuildOctree(const double* xyz,
  const double* radius,
  const int* level,
  long long n,
  int levels,
  int bucket,
  int maxDepth)
{
  Builder b{ xyz, radius, level, std::max(1, bucket), maxDepth, Octree() };
  b.Tree.Levels = std::max(1, levels);
  b.Tree.Order.resize(static_cast<size_t>(n));
  std::iota(b.Tree.Order.begin(), b.Tree.Order.end(), 0LL);
  OctreeNode root;
  root.End = n;
  if (n > 0)
  {
    b.Measure(root);
  }
  b.Tree.Nodes.push_back(root);
  if (n > 0)
  {
    b.Split(0);
  }
  // Level prefixes: for leaves the end of each level's run; for inner nodes
  // the end of the node (their points span several leaves).
  const int L = b.Tree.Levels;
  b.Tree.LevelEnds.assign(b.Tree.Nodes.size() * L, 0);
  for (size_t id = 0; id < b.Tree.Nodes.size(); ++id)
  {
    const OctreeNode& node = b.Tree.Nodes[id];
    long long k = node.Begin;
    for (int l = 0; l < L; ++l)
    {
      if (node.ChildCount == 0)
      {
        while (k < node.End && level[b.Tree.Order[k]] <= l)
        {
          ++k;
        }
        b.Tree.LevelEnds[id * L + l] = k;
      }
      else
      {
        b.Tree.LevelEnds[id * L + l] = node.End;
      }
    }
  }
  return b.Tree;
}
} // namespace pointsurfaces
