// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psMetaball.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pointsurfaces
{
namespace
{
// y = M x for a row-major 4x4 matrix and the point (x, w).
void Transform(const double m[16], const double x[3], double w, double y[4])
{
  for (int r = 0; r < 4; ++r)
  {
    y[r] = m[4 * r] * x[0] + m[4 * r + 1] * x[1] + m[4 * r + 2] * x[2] + m[4 * r + 3] * w;
  }
}

// The grid geometry of `view`, its slab range not yet set.
PerspectiveGridGeometry Geometry(const GridView& view)
{
  return PerspectiveGridGeometry(
    view.ViewToClip, view.Parallel, view.Width, view.Height, view.TileSize, view.Slabs);
}
} // namespace

//------------------------------------------------------------------------------
double KernelValue(MetaballKernel kernel, double x, double* derivative)
{
  double slope = 0.0, value = 0.0;
  if (x < 1.0)
  {
    value =
      VisitMetaballKernel<double>(kernel, [&](auto k) { return k.Value(std::max(x, 0.0), slope); });
  }
  if (derivative)
  {
    *derivative = slope;
  }
  return value;
}

//------------------------------------------------------------------------------
bool IsSPHKernel(MetaballKernel kernel)
{
  return KernelNormalization(kernel) > 0.0;
}

//------------------------------------------------------------------------------
double KernelNormalization(MetaballKernel kernel)
{
  return VisitMetaballKernel<double>(kernel, [](auto k) { return k.Normalization; });
}

//------------------------------------------------------------------------------
double SWIFTSupportFactor(MetaballKernel kernel)
{
  return VisitMetaballKernel<double>(kernel, [](auto k) { return k.SWIFTSupport; });
}

//------------------------------------------------------------------------------
double KernelSlopeBound(MetaballKernel kernel)
{
  return VisitMetaballKernel<double>(kernel, [](auto k) { return k.SlopeBound; });
}

//------------------------------------------------------------------------------
double LoneBallIsoRadius(MetaballKernel kernel, double threshold)
{
  if (!(threshold < KernelValue(kernel, 0.0)))
  {
    return 0.0;
  }
  double lo = 0.0, hi = 1.0; // in x = r^2 / R^2; the kernels decrease
  for (int i = 0; i < 100; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (KernelValue(kernel, mid) > threshold ? lo : hi) = mid;
  }
  return std::sqrt(0.5 * (lo + hi));
}

//------------------------------------------------------------------------------
bool ValidBall(const MetaballSet& set, long long i)
{
  const double* c = set.Centers + 3 * i;
  const double r = set.Radii[i];
  const double q = set.Strengths ? set.Strengths[i] : 1.0;
  return std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]) && std::isfinite(r) &&
    r > 0.0 && std::isfinite(q);
}

//------------------------------------------------------------------------------
void SupportBounds(const MetaballSet& set, double bounds[6])
{
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = std::numeric_limits<double>::infinity();
    bounds[2 * a + 1] = -std::numeric_limits<double>::infinity();
  }
  for (long long i = 0; i < set.Count; ++i)
  {
    if (!ValidBall(set, i))
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = std::min(bounds[2 * a], set.Centers[3 * i + a] - set.Radii[i]);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], set.Centers[3 * i + a] + set.Radii[i]);
    }
  }
}

//------------------------------------------------------------------------------
std::vector<long long> BallsReachingBox(const MetaballSet& set, const double bounds[6])
{
  std::vector<long long> ids;
  if (!(bounds[0] <= bounds[1] && bounds[2] <= bounds[3] && bounds[4] <= bounds[5]))
  {
    return ids;
  }
  for (long long i = 0; i < set.Count; ++i)
  {
    if (!ValidBall(set, i))
    {
      continue;
    }
    // Squared distance from the centre to the box, against R^2.
    double d2 = 0.0;
    for (int a = 0; a < 3; ++a)
    {
      const double c = set.Centers[3 * i + a];
      const double gap = std::max({ bounds[2 * a] - c, c - bounds[2 * a + 1], 0.0 });
      d2 += gap * gap;
    }
    if (d2 <= set.Radii[i] * set.Radii[i])
    {
      ids.push_back(i);
    }
  }
  return ids;
}

namespace
{
// Calls f(i, x - centre_i, |x - centre_i|^2, R_i^2) for each valid ball of
// `set` (those of `ids` when given), in order.
template<typename F>
void ForEachValidBall(const MetaballSet& set,
  const double x[3],
  const unsigned* ids,
  long long idCount,
  F&& f)
{
  const long long n = ids ? idCount : set.Count;
  for (long long k = 0; k < n; ++k)
  {
    const long long i = ids ? static_cast<long long>(ids[k]) : k;
    if (!ValidBall(set, i))
    {
      continue;
    }
    const double* c = set.Centers + 3 * i;
    const double d[3] = { x[0] - c[0], x[1] - c[1], x[2] - c[2] };
    f(i, d, d[0] * d[0] + d[1] * d[1] + d[2] * d[2], set.Radii[i] * set.Radii[i]);
  }
}
} // namespace

//------------------------------------------------------------------------------
double FieldValue(const MetaballSet& set,
  const double x[3],
  double gradient[3],
  const unsigned* ids,
  long long idCount)
{
  double sum = 0.0;
  double g[3] = { 0.0, 0.0, 0.0 };
  ForEachValidBall(set,
    x,
    ids,
    idCount,
    [&](long long i, const double d[3], double r2, double R2)
    {
      if (r2 >= R2)
      {
        return;
      }
      const double q = set.Strengths ? set.Strengths[i] : 1.0;
      double slope = 0.0;
      sum += q * KernelValue(set.Kernel, r2 / R2, gradient ? &slope : nullptr);
      if (gradient)
      {
        const double s = q * slope * 2.0 / R2;
        g[0] += s * d[0];
        g[1] += s * d[1];
        g[2] += s * d[2];
      }
    });
  if (gradient)
  {
    gradient[0] = g[0];
    gradient[1] = g[1];
    gradient[2] = g[2];
  }
  return sum - set.Threshold;
}

//------------------------------------------------------------------------------
long long DominantBall(const MetaballSet& set,
  const double x[3],
  const unsigned* ids,
  long long idCount)
{
  long long best = -1;
  double bestTerm = 0.0, bestRatio = std::numeric_limits<double>::infinity();
  ForEachValidBall(set,
    x,
    ids,
    idCount,
    [&](long long i, const double*, double r2, double R2)
    {
      const double ratio = r2 / R2;
      const double q = set.Strengths ? set.Strengths[i] : 1.0;
      const double term = ratio < 1.0 ? std::max(q * KernelValue(set.Kernel, ratio), 0.0) : 0.0;
      if (best < 0 || term > bestTerm || (term == bestTerm && ratio < bestRatio))
      {
        best = i;
        bestTerm = term;
        bestRatio = ratio;
      }
    });
  return best;
}

//------------------------------------------------------------------------------
bool BallVoxels(const GridView& view,
  const std::vector<double>& slabPlanes,
  const double centre[3],
  double radius,
  int range[6])
{
  if (slabPlanes.size() < 2)
  {
    return false;
  }
  GridView slabs = view;
  slabs.Slabs = static_cast<int>(slabPlanes.size()) - 1;
  PerspectiveGridGeometry geometry = Geometry(slabs);
  geometry.SetSlabRange(slabPlanes.front(), slabPlanes.back());
  double cv[4];
  Transform(view.WorldToView, centre, 1.0, cv);
  return !geometry.Outside(cv, radius) && geometry.Range(cv, radius, range);
}

namespace
{
// The slab range of `view` set on `geometry`: fixed, or that of the valid
// balls in the frustum.
void SetSlabs(const MetaballSet& set, const GridView& view, PerspectiveGridGeometry& geometry)
{
  double nearD = view.SlabNear, farD = view.SlabFar;
  if (!(farD > nearD))
  {
    nearD = std::numeric_limits<double>::max();
    farD = 0.0;
    for (long long i = 0; i < set.Count; ++i)
    {
      double cv[4];
      Transform(view.WorldToView, set.Centers + 3 * i, 1.0, cv);
      if (ValidBall(set, i) && !geometry.Outside(cv, set.Radii[i]))
      {
        geometry.Extend(cv, set.Radii[i], nearD, farD);
      }
    }
  }
  geometry.SetSlabRange(nearD, farD);
}
} // namespace

//------------------------------------------------------------------------------
std::vector<double> SlabPlanes(const MetaballSet& set, const GridView& view)
{
  PerspectiveGridGeometry geometry = Geometry(view);
  SetSlabs(set, view, geometry);
  return geometry.GetSlabPlanes();
}

//------------------------------------------------------------------------------
PerspectiveGrid BuildPerspectiveGrid(const MetaballSet& set, const GridView& view)
{
  PerspectiveGrid grid;
  if (view.Width <= 0 || view.Height <= 0 || view.TileSize <= 0)
  {
    return grid;
  }
  PerspectiveGridGeometry geometry = Geometry(view);
  SetSlabs(set, view, geometry);
  grid.TilesX = geometry.GetTilesX();
  grid.TilesY = geometry.GetTilesY();
  grid.Slabs = geometry.GetSlabs();
  grid.SlabPlanes = geometry.GetSlabPlanes();

  // Each ball's voxel range, then the lists by voxel.
  std::vector<int> ranges(6 * set.Count, 0);
  std::vector<unsigned char> placed(set.Count, 0);
  for (long long i = 0; i < set.Count; ++i)
  {
    double cv[4];
    Transform(view.WorldToView, set.Centers + 3 * i, 1.0, cv);
    if (!ValidBall(set, i))
    {
      ++grid.Invalid;
    }
    else if (geometry.Outside(cv, set.Radii[i]) ||
      !geometry.Range(cv, set.Radii[i], &ranges[6 * i]))
    {
      ++grid.Culled;
    }
    else
    {
      placed[i] = 1;
    }
  }
  grid.MaxPerVoxel = static_cast<unsigned>(SortIntoVoxels(
    set.Count,
    grid.TilesX,
    grid.TilesY,
    grid.Slabs,
    VoxelOrder::SlabMajor,
    [&](long long i) { return placed[i] ? &ranges[6 * i] : nullptr; },
    grid.Offsets,
    grid.Balls));
  grid.Pairs = static_cast<long long>(grid.Balls.size());
  return grid;
}

//------------------------------------------------------------------------------
RayHit CastRay(const MetaballSet& set,
  const double origin[3],
  const double direction[3],
  double tMin,
  double tMax,
  double step,
  int bisections)
{
  RayHit hit;
  if (!(step > 0.0) || !(tMax > tMin))
  {
    return hit;
  }
  const double dd =
    direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2];
  if (!(dd > 0.0))
  {
    return hit;
  }
  // Only the balls whose support the segment passes through.
  std::vector<unsigned> ids;
  for (long long i = 0; i < set.Count; ++i)
  {
    if (!ValidBall(set, i))
    {
      continue;
    }
    const double* c = set.Centers + 3 * i;
    const double oc[3] = { c[0] - origin[0], c[1] - origin[1], c[2] - origin[2] };
    const double t = std::min(
      std::max((oc[0] * direction[0] + oc[1] * direction[1] + oc[2] * direction[2]) / dd, tMin),
      tMax);
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      const double e = origin[k] + t * direction[k] - c[k];
      d2 += e * e;
    }
    if (d2 < set.Radii[i] * set.Radii[i])
    {
      ids.push_back(static_cast<unsigned>(i));
    }
  }
  if (ids.empty())
  {
    return hit;
  }
  auto field = [&](double t)
  {
    const double x[3] = {
      origin[0] + t * direction[0], origin[1] + t * direction[1], origin[2] + t * direction[2]
    };
    return FieldValue(set, x, nullptr, ids.data(), static_cast<long long>(ids.size()));
  };
  double t0 = tMin, f0 = field(t0);
  while (t0 < tMax)
  {
    const double t1 = std::min(t0 + step, tMax);
    const double f1 = field(t1);
    if ((f0 < 0.0) != (f1 < 0.0))
    {
      double a = t0, b = t1, fa = f0;
      for (int k = 0; k < bisections; ++k)
      {
        const double m = 0.5 * (a + b);
        const double fm = field(m);
        if ((fa < 0.0) == (fm < 0.0))
        {
          a = m;
          fa = fm;
        }
        else
        {
          b = m;
        }
      }
      hit.Hit = true;
      hit.T = 0.5 * (a + b);
      double g[3];
      for (int k = 0; k < 3; ++k)
      {
        hit.Point[k] = origin[k] + hit.T * direction[k];
      }
      FieldValue(set, hit.Point, g, ids.data(), static_cast<long long>(ids.size()));
      const double norm = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      for (int k = 0; k < 3; ++k)
      {
        hit.Normal[k] = norm > 0.0 ? -g[k] / norm : 0.0;
      }
      return hit;
    }
    t0 = t1;
    f0 = f1;
  }
  return hit;
}
} // namespace pointsurfaces
