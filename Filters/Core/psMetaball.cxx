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

// Is the sphere (view space) entirely outside one of the frustum's planes?
bool OutsideFrustum(const double p[16], const double c[3], double radius)
{
  double planes[24];
  FrustumPlanes(p, planes);
  for (int k = 0; k < 6; ++k)
  {
    const double* e = planes + 4 * k;
    if (e[0] * c[0] + e[1] * c[1] + e[2] * c[2] + e[3] < -radius)
    {
      return true;
    }
  }
  return false;
}

// The slab holding view distance d: planes[k] <= d < planes[k + 1], clamped.
int SlabOf(const std::vector<double>& planes, double d)
{
  const int slabs = static_cast<int>(planes.size()) - 1;
  const auto it = std::upper_bound(planes.begin(), planes.end(), d);
  const int k = static_cast<int>(it - planes.begin()) - 1;
  return std::min(std::max(k, 0), slabs - 1);
}
} // namespace

//------------------------------------------------------------------------------
void ProjectionRange(const double p[16], bool parallel, double& nearD, double& farD)
{
  const double a = p[10], b = p[11];
  if (parallel)
  {
    // z_clip = a z + b with a = -2 / (f - n), b = -(f + n) / (f - n)
    nearD = (b + 1.0) / a;
    farD = (b - 1.0) / a;
  }
  else
  {
    nearD = b / (a - 1.0);
    farD = b / (a + 1.0);
  }
  if (!std::isfinite(nearD) || !std::isfinite(farD))
  {
    nearD = 0.0;
    farD = std::numeric_limits<double>::max();
  }
  if (nearD > farD)
  {
    std::swap(nearD, farD);
  }
}

//------------------------------------------------------------------------------
void FrustumPlanes(const double p[16], double planes[24])
{
  int k = 0;
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int sign = -1; sign <= 1; sign += 2, ++k)
    {
      // Inside: row3 + sign * row_axis >= 0.
      double* e = planes + 4 * k;
      for (int c = 0; c < 4; ++c)
      {
        e[c] = p[12 + c] + sign * p[4 * axis + c];
      }
      const double norm = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
      for (int c = 0; c < 4; ++c)
      {
        e[c] = norm > 0.0 ? e[c] / norm : (c == 3 ? 1.0 : 0.0);
      }
    }
  }
}

//------------------------------------------------------------------------------
double KernelValue(MetaballKernel kernel, double x, double* derivative)
{
  double slope = 0.0, value = 0.0;
  if (x < 1.0)
  {
    value = VisitMetaballKernel<double>(
      kernel, [&](auto k) { return k.Value(std::max(x, 0.0), slope); });
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
  double cv[4];
  Transform(view.WorldToView, centre, 1.0, cv);
  if (slabPlanes.size() < 2 || OutsideFrustum(view.ViewToClip, cv, radius))
  {
    return false;
  }
  const double d = -cv[2];
  if (d + radius < slabPlanes.front() || d - radius > slabPlanes.back())
  {
    return false;
  }
  range[4] = SlabOf(slabPlanes, d - radius);
  range[5] = SlabOf(slabPlanes, d + radius);

  const int tilesX = (view.Width + view.TileSize - 1) / view.TileSize;
  const int tilesY = (view.Height + view.TileSize - 1) / view.TileSize;
  double lo[2] = { std::numeric_limits<double>::max(), std::numeric_limits<double>::max() };
  double hi[2] = { -lo[0], -lo[1] };
  // A perspective ball reaching the eye plane projects over the whole screen.
  bool everywhere = !view.Parallel && d - radius <= 0.0;
  for (int k = 0; k < 8 && !everywhere; ++k)
  {
    const double corner[3] = { cv[0] + ((k & 1) ? radius : -radius),
      cv[1] + ((k & 2) ? radius : -radius),
      cv[2] + ((k & 4) ? radius : -radius) };
    double clip[4];
    Transform(view.ViewToClip, corner, 1.0, clip);
    if (!(clip[3] > 0.0))
    {
      everywhere = true;
      break;
    }
    const double px = (0.5 * clip[0] / clip[3] + 0.5) * view.Width;
    const double py = (0.5 * clip[1] / clip[3] + 0.5) * view.Height;
    lo[0] = std::min(lo[0], px);
    lo[1] = std::min(lo[1], py);
    hi[0] = std::max(hi[0], px);
    hi[1] = std::max(hi[1], py);
  }
  if (everywhere)
  {
    range[0] = 0;
    range[1] = tilesX - 1;
    range[2] = 0;
    range[3] = tilesY - 1;
    return true;
  }
  if (hi[0] < 0.0 || hi[1] < 0.0 || lo[0] >= view.Width || lo[1] >= view.Height)
  {
    return false;
  }
  range[0] = std::max(0, static_cast<int>(std::floor(lo[0] / view.TileSize)));
  range[1] = std::min(tilesX - 1, static_cast<int>(std::floor(hi[0] / view.TileSize)));
  range[2] = std::max(0, static_cast<int>(std::floor(lo[1] / view.TileSize)));
  range[3] = std::min(tilesY - 1, static_cast<int>(std::floor(hi[1] / view.TileSize)));
  return true;
}

//------------------------------------------------------------------------------
std::vector<double> SlabPlanes(const MetaballSet& set, const GridView& view)
{
  const int slabs = std::max(1, view.Slabs);
  double nearD = view.SlabNear, farD = view.SlabFar;
  if (!(farD > nearD))
  {
    double pNear, pFar;
    ProjectionRange(view.ViewToClip, view.Parallel, pNear, pFar);
    nearD = std::numeric_limits<double>::max();
    farD = -nearD;
    for (long long i = 0; i < set.Count; ++i)
    {
      if (!ValidBall(set, i))
      {
        continue;
      }
      double cv[4];
      Transform(view.WorldToView, set.Centers + 3 * i, 1.0, cv);
      const double r = set.Radii[i];
      if (OutsideFrustum(view.ViewToClip, cv, r))
      {
        continue;
      }
      nearD = std::min(nearD, -cv[2] - r);
      farD = std::max(farD, -cv[2] + r);
    }
    nearD = std::max(nearD, pNear);
    farD = std::min(farD, pFar);
    if (!(farD > nearD))
    {
      nearD = pNear;
      farD = std::min(pFar, pNear + 1.0);
    }
  }
  std::vector<double> planes(slabs + 1);
  for (int k = 0; k <= slabs; ++k)
  {
    planes[k] = nearD + (farD - nearD) * k / slabs;
  }
  planes.back() = farD;
  return planes;
}

//------------------------------------------------------------------------------
PerspectiveGrid BuildPerspectiveGrid(const MetaballSet& set, const GridView& view)
{
  PerspectiveGrid grid;
  if (view.Width <= 0 || view.Height <= 0 || view.TileSize <= 0)
  {
    return grid;
  }
  grid.TilesX = (view.Width + view.TileSize - 1) / view.TileSize;
  grid.TilesY = (view.Height + view.TileSize - 1) / view.TileSize;
  grid.Slabs = std::max(1, view.Slabs);
  grid.SlabPlanes = SlabPlanes(set, view);
  const long long voxels = static_cast<long long>(grid.TilesX) * grid.TilesY * grid.Slabs;

  // Count: voxels per ball.
  std::vector<long long> counts(set.Count, 0);
  std::vector<int> ranges(6 * set.Count, 0);
  for (long long i = 0; i < set.Count; ++i)
  {
    if (!ValidBall(set, i))
    {
      ++grid.Invalid;
      continue;
    }
    int* r = &ranges[6 * i];
    if (!BallVoxels(view, grid.SlabPlanes, set.Centers + 3 * i, set.Radii[i], r))
    {
      ++grid.Culled;
      continue;
    }
    counts[i] = static_cast<long long>(r[1] - r[0] + 1) * (r[3] - r[2] + 1) * (r[5] - r[4] + 1);
  }
  // Exclusive scan: each ball's first pair.
  std::vector<long long> first(set.Count + 1, 0);
  for (long long i = 0; i < set.Count; ++i)
  {
    first[i + 1] = first[i] + counts[i];
  }
  grid.Pairs = first[set.Count];
  // Scatter (voxel, ball), in ball order.
  std::vector<unsigned> pairVoxel(grid.Pairs), pairBall(grid.Pairs);
  for (long long i = 0; i < set.Count; ++i)
  {
    if (!counts[i])
    {
      continue;
    }
    const int* r = &ranges[6 * i];
    long long k = first[i];
    for (int z = r[4]; z <= r[5]; ++z)
    {
      for (int y = r[2]; y <= r[3]; ++y)
      {
        for (int x = r[0]; x <= r[1]; ++x)
        {
          pairVoxel[k] =
            static_cast<unsigned>((static_cast<long long>(z) * grid.TilesY + y) * grid.TilesX + x);
          pairBall[k] = static_cast<unsigned>(i);
          ++k;
        }
      }
    }
  }
  // Counting sort by voxel, stable: ball ids ascend within a voxel.
  grid.Offsets.assign(voxels + 1, 0);
  for (long long k = 0; k < grid.Pairs; ++k)
  {
    ++grid.Offsets[pairVoxel[k] + 1];
  }
  for (long long v = 0; v < voxels; ++v)
  {
    grid.MaxPerVoxel = std::max(grid.MaxPerVoxel, grid.Offsets[v + 1]);
    grid.Offsets[v + 1] += grid.Offsets[v];
  }
  grid.Balls.resize(grid.Pairs);
  std::vector<unsigned> next(grid.Offsets.begin(), grid.Offsets.end() - 1);
  for (long long k = 0; k < grid.Pairs; ++k)
  {
    grid.Balls[next[pairVoxel[k]]++] = pairBall[k];
  }
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
