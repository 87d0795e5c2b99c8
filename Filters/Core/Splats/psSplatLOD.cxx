// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psSplatLOD.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace pointsurfaces
{
//------------------------------------------------------------------------------
LODOctree MakeLODOctree(Octree tree,
  std::vector<double> levelQuality,
  const double* radius,
  const int* level)
{
  LODOctree out;
  out.Tree = std::move(tree);
  out.LevelQuality = std::move(levelQuality);
  const size_t count = out.Tree.Nodes.size();
  out.MeanScale.assign(count, 0.0);
  out.Reach.assign(count, 0.0);
  for (size_t i = 0; i < count; ++i)
  {
    const OctreeNode& node = out.Tree.Nodes[i];
    double sum = 0.0, largest = 0.0;
    for (long long k = node.Begin; k < node.End; ++k)
    {
      sum += radius[k] / out.LevelQuality[level[k]];
      largest = std::max(largest, radius[k]);
    }
    out.Reach[i] = node.Sphere[3] + (std::sqrt(2.0) - 1.0) * largest;
    out.MeanScale[i] = node.End > node.Begin ? sum / (node.End - node.Begin) : 0.0;
  }
  return out;
}

//------------------------------------------------------------------------------
std::vector<DrawRange> SelectDrawRanges(const LODOctree& lod, const LODView& view)
{
  std::vector<DrawRange> ranges;
  const Octree& tree = lod.Tree;
  if (tree.Nodes.empty())
  {
    return ranges;
  }
  const double* m = view.ModelToWorld;
  double scale = 1.0; // the largest axis scale of the model matrix
  if (!view.ModelIsIdentity)
  {
    scale = 0.0;
    for (int a = 0; a < 3; ++a)
    {
      scale =
        std::max(scale, std::sqrt(m[0 + a] * m[0 + a] + m[4 + a] * m[4 + a] + m[8 + a] * m[8 + a]));
    }
  }
  // Pixels per world unit at distance d.
  auto pixelsPerUnit = [&](double d)
  {
    return view.Parallel ? view.ViewportHeight / (2.0 * view.ParallelScale)
                         : view.ViewportHeight / (2.0 * std::max(d, 1e-30) * view.TanHalfAngle);
  };
  std::vector<int> stack{ 0 };
  while (!stack.empty())
  {
    const int id = stack.back();
    stack.pop_back();
    const OctreeNode& node = tree.Nodes[id];
    double c[3] = { node.Sphere[0], node.Sphere[1], node.Sphere[2] };
    double r = lod.Reach[id];
    if (!view.ModelIsIdentity)
    {
      double w[3];
      for (int row = 0; row < 3; ++row)
      {
        w[row] = m[4 * row] * c[0] + m[4 * row + 1] * c[1] + m[4 * row + 2] * c[2] + m[4 * row + 3];
      }
      std::copy(w, w + 3, c);
      r *= scale;
    }
    bool outside = false;
    for (int p = 0; view.Cull && p < 6 && !outside; ++p)
    {
      const double* e = view.Planes + 4 * p;
      outside = e[0] * c[0] + e[1] * c[1] + e[2] * c[2] + e[3] < -r;
    }
    if (outside)
    {
      continue;
    }
    if (node.ChildCount > 0)
    {
      for (int k = 0; k < node.ChildCount; ++k)
      {
        stack.push_back(node.FirstChild + k);
      }
      continue;
    }
    // Continuous LOD: levels down to the first whose splats are small enough.
    int level = tree.Levels - 1;
    if (view.PixelError > 0.0)
    {
      const double dx = c[0] - view.Eye[0], dy = c[1] - view.Eye[1], dz = c[2] - view.Eye[2];
      const double d = std::max(std::sqrt(dx * dx + dy * dy + dz * dz) - r, 1e-30);
      const double ppu = pixelsPerUnit(d);
      for (int l = 0; l < tree.Levels; ++l)
      {
        // The splats' size in world units: R = s_l times the mean scale,
        // times the model's scale.
        if (2.0 * lod.LevelQuality[l] * lod.MeanScale[id] * scale * ppu <= view.PixelError)
        {
          level = l;
          break;
        }
      }
    }
    // A partly loaded node draws its finest level present, with that level's s
    // (a coarser splat drawn with a finer level's s would shrink and leave holes).
    if (tree.PresentLevels.size() == tree.Nodes.size())
    {
      level = std::min(level, tree.PresentLevels[id] - 1);
      if (level < 0)
      {
        continue;
      }
    }
    const long long end = tree.LevelEnds[static_cast<size_t>(id) * tree.Levels + level];
    if (end > node.Begin)
    {
      DrawRange range;
      range.Begin = node.Begin;
      range.End = end;
      range.Level = level;
      range.Quality = lod.LevelQuality[level];
      range.Node = id;
      ranges.push_back(range);
    }
  }
  return ranges;
}
} // namespace pointsurfaces
