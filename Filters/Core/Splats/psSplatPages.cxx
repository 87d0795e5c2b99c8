// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psSplatPages.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace pointsurfaces
{
PageSelection SelectPages(const LODOctree& lod,
  double bytesPerSplat,
  double budgetBytes,
  const LODView* view)
{
  PageSelection out;
  const Octree& tree = lod.Tree;
  const int L = std::max(1, tree.Levels);
  if (tree.Nodes.empty())
  {
    return out;
  }
  // The levels each page asks for (0: none), and its distance to the eye.
  struct Want
  {
    int Node;
    int Levels;
    double Distance;
  };
  std::vector<Want> wants;
  if (view)
  {
    std::unordered_map<long long, int> leafAt;
    for (size_t id = 0; id < tree.Nodes.size(); ++id)
    {
      if (tree.Nodes[id].ChildCount == 0 && tree.Nodes[id].End > tree.Nodes[id].Begin)
      {
        leafAt[tree.Nodes[id].Begin] = static_cast<int>(id);
      }
    }
    for (const DrawRange& r : SelectDrawRanges(lod, *view))
    {
      const auto it = leafAt.find(r.Begin);
      if (it == leafAt.end())
      {
        continue;
      }
      const OctreeNode& node = tree.Nodes[it->second];
      const double dx = node.Sphere[0] - view->Eye[0], dy = node.Sphere[1] - view->Eye[1],
                   dz = node.Sphere[2] - view->Eye[2];
      wants.push_back(Want{ it->second,
        r.Level + 1,
        view->Parallel ? 0.0 : std::sqrt(dx * dx + dy * dy + dz * dz) - lod.Reach[it->second] });
    }
    std::stable_sort(wants.begin(),
      wants.end(),
      [](const Want& a, const Want& b) { return a.Distance < b.Distance; });
  }
  else
  {
    for (size_t id = 0; id < tree.Nodes.size(); ++id)
    {
      if (tree.Nodes[id].ChildCount == 0 && tree.Nodes[id].End > tree.Nodes[id].Begin)
      {
        wants.push_back(Want{ static_cast<int>(id), L, 0.0 });
      }
    }
  }
  auto levelEnd = [&](int id, int l)
  { return l < 0 ? tree.Nodes[id].Begin : tree.LevelEnds[static_cast<size_t>(id) * L + l]; };
  double smallest = std::numeric_limits<double>::infinity();
  for (const Want& w : wants)
  {
    out.Wanted +=
      bytesPerSplat * static_cast<double>(levelEnd(w.Node, w.Levels - 1) - levelEnd(w.Node, -1));
    const long long first = levelEnd(w.Node, 0) - levelEnd(w.Node, -1);
    if (first > 0)
    {
      smallest = std::min(smallest, bytesPerSplat * static_cast<double>(first));
    }
  }
  out.SmallestPage = std::isfinite(smallest) ? smallest : 0.0;
  // Level by level, nearest pages first.
  std::vector<int> loaded(wants.size(), 0);
  std::vector<char> stopped(wants.size(), 0);
  for (int l = 0; l < L; ++l)
  {
    for (size_t k = 0; k < wants.size(); ++k)
    {
      const Want& w = wants[k];
      if (stopped[k] || w.Levels <= l)
      {
        continue;
      }
      const double cost =
        bytesPerSplat * static_cast<double>(levelEnd(w.Node, l) - levelEnd(w.Node, l - 1));
      if (budgetBytes > 0.0 && out.Bytes + cost > budgetBytes)
      {
        stopped[k] = 1;
        continue;
      }
      out.Bytes += cost;
      loaded[k] = l + 1;
    }
  }
  for (size_t k = 0; k < wants.size(); ++k)
  {
    if (loaded[k] > 0)
    {
      PageRange r;
      r.Node = wants[k].Node;
      r.Begin = levelEnd(r.Node, -1);
      r.End = levelEnd(r.Node, loaded[k] - 1);
      r.Levels = loaded[k];
      if (r.End > r.Begin)
      {
        out.Splats += r.End - r.Begin;
        out.Ranges.push_back(r);
      }
    }
  }
  std::sort(out.Ranges.begin(),
    out.Ranges.end(),
    [](const PageRange& a, const PageRange& b) { return a.Begin < b.Begin; });
  return out;
}

PageSelection PieceOfSelection(const PageSelection& selection,
  int piece,
  int pieces,
  double bytesPerSplat)
{
  if (pieces < 2)
  {
    return selection;
  }
  PageSelection out;
  out.Wanted = selection.Wanted;
  out.SmallestPage = selection.SmallestPage;
  if (piece < 0 || piece >= pieces)
  {
    return out;
  }
  long long total = 0;
  for (const PageRange& r : selection.Ranges)
  {
    total += r.End - r.Begin;
  }
  // The share [first, last) of the chosen splats counted in the file's order.
  const long long first = total / pieces * piece + std::min<long long>(piece, total % pieces);
  const long long last = first + total / pieces + (piece < total % pieces ? 1 : 0);
  long long at = 0; // chosen splats before the current range
  for (const PageRange& r : selection.Ranges)
  {
    const long long n = r.End - r.Begin;
    const long long lo = std::max(first, at), hi = std::min(last, at + n);
    if (hi > lo)
    {
      PageRange cut = r; // a cut range keeps its page's Levels
      cut.Begin = r.Begin + (lo - at);
      cut.End = r.Begin + (hi - at);
      out.Ranges.push_back(cut);
      out.Splats += hi - lo;
    }
    at += n;
  }
  out.Bytes = static_cast<double>(out.Splats) * bytesPerSplat;
  return out;
}
} // namespace pointsurfaces
