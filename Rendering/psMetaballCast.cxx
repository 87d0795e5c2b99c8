// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psMetaballCast.h"

#include "psMemory.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <new>

namespace pointsurfaces
{
namespace
{
using Clock = std::chrono::steady_clock;

// y = M (x, w) for a row-major 4x4 matrix.
void Apply(const double m[16], const double x[3], double w, double y[4])
{
  for (int r = 0; r < 4; ++r)
  {
    y[r] = m[4 * r] * x[0] + m[4 * r + 1] * x[1] + m[4 * r + 2] * x[2] + m[4 * r + 3] * w;
  }
}

// A float's bits as an unsigned integer in the float's order.
std::uint32_t SortKey(float v)
{
  std::uint32_t u;
  std::memcpy(&u, &v, sizeof(u));
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

bool Finite(float v)
{
  return std::isfinite(v);
}

// The balls in view space, and their grid ranges.
struct ViewBalls
{
  std::vector<float> X, Y, Z, R, Q; // view-space centre, radius, strength
  std::vector<unsigned int> Color;
  std::vector<int> Range; // 6 per ball: tiles x, tiles y, slabs; x0 > x1: not in the grid
};

// One stretch of a ray inside one ball's support.
struct Crossing
{
  float Enter, Exit;
  int Ball;     // index into the voxel's scratch
  float Peak;   // the most the ball adds to f on the ray: q K at its closest approach
  float Along;  // the ray parameter of the closest approach
  float Across; // the squared distance of the ray from the centre
};

// The balls whose supports hold the ray's current sample, as structure of
// arrays so that the sums over them run in SIMD lanes: a ray's samples
// spend most of their time in these sums where hundreds of SPH supports
// overlap. Entries [0, N) are live; the order is arbitrary.
struct ActiveSet
{
  std::vector<float> X, Y, Z, InvR2, Q, QOverR, R, Peak, Exit, Along, Across;
  std::vector<int> Ball;
  int N = 0;

  std::array<std::vector<float>*, 11> Columns()
  {
    return { &this->X,
      &this->Y,
      &this->Z,
      &this->InvR2,
      &this->Q,
      &this->QOverR,
      &this->R,
      &this->Peak,
      &this->Exit,
      &this->Along,
      &this->Across };
  }
  void Reserve(int count)
  {
    if (this->Ball.size() < static_cast<size_t>(count))
    {
      for (auto* v : this->Columns())
      {
        v->resize(count);
      }
      this->Ball.resize(count);
    }
  }
  void Remove(int k)
  {
    const int last = --this->N;
    for (auto* v : this->Columns())
    {
      (*v)[k] = (*v)[last];
    }
    this->Ball[k] = this->Ball[last];
  }
};

// Per thread: the voxel's balls as structure of arrays, a ray's crossings and
// its active balls, and the counters.
struct Scratch
{
  std::vector<float> X, Y, Z, R2, InvR2, R, Q, QOverR, Perp;
  std::vector<unsigned int> Color;
  std::vector<Crossing> Crossings, Unsorted; // the ray's crossings in the voxel, by Enter
  std::vector<std::uint64_t> Order;          // sort keys: Enter's bits, then the index
  ActiveSet Active;
  MetaballCastStatistics Stats;
};

// A block of BlockSize x BlockSize rays of a tile, consecutive in the
// tile's list of rays, and its four corner rays.
constexpr int BlockSize = 4;
// A crowded voxel's depth is cut into this many parts for the field bounds.
constexpr int BoundParts = 4;
// Voxels with at least this many balls get field bounds.
constexpr int BoundMinimumBalls = 32;
struct Block
{
  int Begin = 0, End = 0;
  int Corners[4] = { 0, 0, 0, 0 };
};

// A ray of the tile: its geometry and where its search stands.
struct Ray
{
  float Origin[3], Dir[3];
  float PerDistance; // d(view distance) / dt
  bool Searching = false, HaveA = false;
  float TA = 0.0f, FA = 0.0f;
};

template<class K>
class TileCaster
{
public:
  const MetaballCastInput& In;
  const MetaballCastSettings& S;
  const ViewBalls& Balls;
  const std::vector<size_t>& Offsets; // tile-major: (tile * slabs + slab)
  const std::vector<unsigned int>& Lists;
  const std::vector<double>& Planes;
  MetaballCastImages& Out;
  int TilesX;
  float Threshold;
  vtkSMPThreadLocal<Scratch>& Local;

  // f at t over the active balls, in SIMD lanes.
  float Field(const Scratch& s, const Ray& ray, float t, long long& terms) const
  {
    const float px = ray.Origin[0] + t * ray.Dir[0], py = ray.Origin[1] + t * ray.Dir[1],
                pz = ray.Origin[2] + t * ray.Dir[2];
    const ActiveSet& a = s.Active;
    const float *X = a.X.data(), *Y = a.Y.data(), *Z = a.Z.data(), *InvR2 = a.InvR2.data(),
                *Q = a.Q.data();
    const int n = a.N;
    float sum = 0.0f;
#pragma omp simd reduction(+ : sum)
    for (int k = 0; k < n; ++k)
    {
      const float dx = px - X[k], dy = py - Y[k], dz = pz - Z[k];
      const float x = (dx * dx + dy * dy + dz * dz) * InvR2[k];
      // Every lane computes the kernel (at x <= 1, where it is 0) and the
      // mask picks: branch-free, so that it vectorises.
      const float v = Q[k] * K::Value(std::min(x, 1.0f));
      sum += x < 1.0f ? v : 0.0f;
    }
    terms += n;
    return sum - this->Threshold;
  }

  // f at t with its gradient and colour, for shading a hit.
  float Field(const Scratch& s, const Ray& ray, float t, float grad[3], float color[4]) const
  {
    const float p[3] = {
      ray.Origin[0] + t * ray.Dir[0], ray.Origin[1] + t * ray.Dir[1], ray.Origin[2] + t * ray.Dir[2]
    };
    float f = -this->Threshold;
    const ActiveSet& a = s.Active;
    for (int k = 0; k < a.N; ++k)
    {
      const float d[3] = { p[0] - a.X[k], p[1] - a.Y[k], p[2] - a.Z[k] };
      const float x = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) * a.InvR2[k];
      if (!(x < 1.0f))
      {
        continue;
      }
      float slope;
      const float value = a.Q[k] * K::Value(x, slope);
      f += value;
      const float g = a.Q[k] * slope * 2.0f * a.InvR2[k];
      grad[0] += g * d[0];
      grad[1] += g * d[1];
      grad[2] += g * d[2];
      const float w = std::max(value, 0.0f);
      const unsigned int c = s.Color[a.Ball[k]];
      color[0] += w * static_cast<float>(c & 255u) / 255.0f;
      color[1] += w * static_cast<float>((c >> 8) & 255u) / 255.0f;
      color[2] += w * static_cast<float>((c >> 16) & 255u) / 255.0f;
      color[3] += w * static_cast<float>((c >> 24) & 255u) / 255.0f;
    }
    return f;
  }

  // An upper bound of f over [lo, hi] on the ray: the active balls and those
  // from `next` on that begin before hi, each at the point of [lo, hi]
  // nearest its centre, positive strengths only.
  float UpperBound(Scratch& s, int next, float lo, float hi) const
  {
    const ActiveSet& a = s.Active;
    const float *Along = a.Along.data(), *Across = a.Across.data(), *InvR2 = a.InvR2.data(),
                *Q = a.Q.data();
    const int n = a.N;
    float u = 0.0f;
#pragma omp simd reduction(+ : u)
    for (int k = 0; k < n; ++k)
    {
      const float along = std::min(std::max(Along[k], lo), hi) - Along[k];
      const float x = (Across[k] + along * along) * InvR2[k];
      const float v = Q[k] * K::Value(std::min(x, 1.0f));
      u += x < 1.0f && v > 0.0f ? v : 0.0f;
    }
    s.Stats.KernelTerms += n;
    const int count = static_cast<int>(s.Crossings.size());
    for (int i = next; i < count && s.Crossings[i].Enter < hi; ++i)
    {
      const Crossing& c = s.Crossings[i];
      const float q = s.Q[c.Ball];
      const float along = std::min(std::max(c.Along, lo), hi) - c.Along;
      const float x = (c.Across + along * along) * s.InvR2[c.Ball];
      ++s.Stats.KernelTerms;
      const float v = x < 1.0f ? q * K::Value(x) : 0.0f;
      u += v > 0.0f ? v : 0.0f; // positive terms only, as in the lanes above
    }
    return u - this->Threshold;
  }

  // Writes the hit at t of the ray through `pixel`.
  void Shade(Scratch& s, const Ray& ray, float t, int pixel) const
  {
    float grad[3] = { 0, 0, 0 }, color[4] = { 0, 0, 0, 0 };
    this->Field(s, ray, t, grad, color);
    s.Stats.KernelTerms += s.Active.N;
    float n[3] = { -grad[0], -grad[1], -grad[2] };
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k)
    {
      n[k] = len > 0.0f ? n[k] / len : -ray.Dir[k];
    }
    if (n[0] * ray.Dir[0] + n[1] * ray.Dir[1] + n[2] * ray.Dir[2] > 0.0f)
    {
      for (float& v : n)
      {
        v = -v; // seen from inside the surface: face the eye
      }
    }
    const double p[3] = {
      ray.Origin[0] + t * ray.Dir[0], ray.Origin[1] + t * ray.Dir[1], ray.Origin[2] + t * ray.Dir[2]
    };
    double clip[4];
    Apply(this->S.ViewToClip, p, 1.0, clip);
    const double depth = 0.5 * clip[2] / clip[3] + 0.5;
    float rgba[4] = { 1.0f, 1.0f, 1.0f, 1.0f };
    if (color[3] > 0.0f)
    {
      for (int k = 0; k < 3; ++k)
      {
        rgba[k] = std::min(std::max(color[k] / color[3], 0.0f), 1.0f);
      }
    }
    unsigned int packed = 0;
    for (int k = 0; k < 4; ++k)
    {
      packed |= static_cast<unsigned int>(std::lround(rgba[k] * 255.0f)) << (8 * k);
    }
    this->Out.Color[pixel] = packed;
    float* nd = &this->Out.NormalDistance[4 * static_cast<size_t>(pixel)];
    nd[0] = n[0];
    nd[1] = n[1];
    nd[2] = n[2];
    nd[3] = static_cast<float>(-p[2]);
    this->Out.Depth[pixel] = static_cast<float>(std::min(std::max(depth, 0.0), 1.0));
    ++s.Stats.Hits;
  }

  // The ray's march through one voxel's balls (loaded into s) over [t0, t1].
  // True when it hit (and the pixel is written).
  // The supports the ray crosses within [t0, t1], sorted by where it
  // enters them, into s.Crossings (left empty when their peaks sum below T);
  // returns the sum of their peaks.
  float GatherCrossings(Scratch& s, const Ray& ray, int count, float t0, float t1) const
  {
    // The supports the ray crosses: the distance from the centre to the ray,
    // formed directly (no cancellation far from the eye).
    const float ox = ray.Origin[0], oy = ray.Origin[1], oz = ray.Origin[2];
    const float dx = ray.Dir[0], dy = ray.Dir[1], dz = ray.Dir[2];
    float* perp = s.Perp.data();
    const float* X = s.X.data();
    const float* Y = s.Y.data();
    const float* Z = s.Z.data();
    const float* R2 = s.R2.data();
    for (int j = 0; j < count; ++j)
    {
      const float cx = X[j] - ox, cy = Y[j] - oy, cz = Z[j] - oz;
      const float b = cx * dx + cy * dy + cz * dz;
      const float px = cx - b * dx, py = cy - b * dy, pz = cz - b * dz;
      perp[j] = R2[j] - (px * px + py * py + pz * pz);
    }
    int m = 0;
    float peaks = 0.0f;
    for (int j = 0; j < count; ++j)
    {
      if (perp[j] > 0.0f)
      {
        const float b = (X[j] - ox) * dx + (Y[j] - oy) * dy + (Z[j] - oz) * dz;
        const float h = std::sqrt(perp[j]);
        const float enter = std::max(b - h, t0), exit = std::min(b + h, t1);
        if (enter < exit)
        {
          float slope;
          const float closest = std::min(std::max(1.0f - perp[j] * s.InvR2[j], 0.0f), 1.0f);
          const float peak = std::max(s.Q[j], 0.0f) * K::Value(closest, slope);
          s.Unsorted[m] = { enter, exit, j, peak, b, s.R2[j] - perp[j] };
          s.Order[m] =
            (static_cast<std::uint64_t>(SortKey(enter)) << 32) | static_cast<unsigned>(m);
          ++m;
          peaks += peak;
        }
      }
    }
    s.Crossings.clear();
    if (m == 0 || peaks < this->Threshold)
    {
      return peaks; // no crossing here: left unsorted
    }
    // Sorted as integers, then gathered.
    std::sort(s.Order.begin(), s.Order.begin() + m);
    s.Crossings.resize(m);
    for (int i = 0; i < m; ++i)
    {
      s.Crossings[i] = s.Unsorted[s.Order[i] & 0xffffffffu];
    }
    return peaks;
  }

  // The supports whose stretch begins by t, from s.Crossings[next] on, into
  // the active set.
  void Activate(Scratch& s, int& next, float t) const
  {
    const int n = static_cast<int>(s.Crossings.size());
    ActiveSet& active = s.Active;
    while (next < n && s.Crossings[next].Enter <= t)
    {
      const Crossing& c = s.Crossings[next++];
      const int j = c.Ball, k = active.N++;
      active.X[k] = s.X[j];
      active.Y[k] = s.Y[j];
      active.Z[k] = s.Z[j];
      active.InvR2[k] = s.InvR2[j];
      active.Q[k] = s.Q[j];
      active.QOverR[k] = s.QOverR[j];
      active.R[k] = s.R[j];
      active.Peak[k] = c.Peak;
      active.Exit[k] = c.Exit;
      active.Along[k] = c.Along;
      active.Across[k] = c.Across;
      active.Ball[k] = j;
    }
  }

  // The crossing in [ray.TA, t], where f changes sign: bisected over the
  // active balls (none left before TA, none enters after t).
  float Bisect(Scratch& s, const Ray& ray, float t) const
  {
    // The first sign change: bisect [TA, t] over the balls in reach there
    // (the active ones: none left before TA, none enters after t).
    float a = ray.TA, b = t, fa = ray.FA;
    for (int k = 0; k < this->S.Bisections; ++k)
    {
      const float m = 0.5f * (a + b);
      const float fm = this->Field(s, ray, m, s.Stats.KernelTerms);
      ++s.Stats.BisectionSamples;
      if ((fa < 0.0f) == (fm < 0.0f))
      {
        a = m;
        fa = fm;
      }
      else
      {
        b = m;
      }
    }
    return 0.5f * (a + b);
  }

  // The step bounds over the active balls: the sum of |q| / R (times the
  // kernel's slope bound, a Lipschitz constant of f), the sum of the peaks,
  // the smallest radius and the farthest exit.
  struct StepBounds
  {
    float Lipschitz = 0.0f, Smallest = std::numeric_limits<float>::max(), Reach = 0.0f,
          Bound = 0.0f;
  };

  // Drops the supports the ray has left by t; the step bounds over the rest.
  StepBounds DropAndBound(Scratch& s, float t) const
  {
    ActiveSet& active = s.Active;
    for (int k = 0; k < active.N;)
    {
      if (active.Exit[k] <= t)
      {
        active.Remove(k);
        continue;
      }
      ++k;
    }
    float lipschitz = 0.0f, smallest = std::numeric_limits<float>::max(), reach = t, bound = 0.0f;
    {
      const float *QOverR = active.QOverR.data(), *Peak = active.Peak.data(), *R = active.R.data(),
                  *Exit = active.Exit.data();
      const int m = active.N;
#pragma omp simd reduction(+ : lipschitz, bound) reduction(min : smallest) reduction(max : reach)
      for (int k = 0; k < m; ++k)
      {
        lipschitz += QOverR[k];
        bound += Peak[k];
        smallest = std::min(smallest, R[k]);
        reach = std::max(reach, Exit[k]);
      }
    }
    StepBounds bounds;
    bounds.Lipschitz = lipschitz;
    bounds.Smallest = smallest;
    bounds.Reach = reach;
    bounds.Bound = bound;
    return bounds;
  }

  bool MarchVoxel(Scratch& s, Ray& ray, int count, float t0, float t1, bool nearSlab, int pixel)
    const
  {
    ++s.Stats.VoxelVisits;
    s.Stats.SupportTests += count;
    this->GatherCrossings(s, ray, count, t0, t1);
    // f <= sum of the peaks - T on the whole stretch: below T, no crossing
    // here (and the ray arrives outside: whatever made f >= 0 before this
    // voxel reaches into it and would count among the peaks).
    if (s.Crossings.empty())
    {
      ++s.Stats.EmptyVoxelVisits;
      this->Outside(ray, t1);
      return false;
    }
    const int n = static_cast<int>(s.Crossings.size());
    ActiveSet& active = s.Active;
    active.Reserve(n);
    active.N = 0;
    int next = 0;
    float t = s.Crossings[0].Enter;
    while (true)
    {
      this->Activate(s, next, t);
      const float f = this->Field(s, ray, t, s.Stats.KernelTerms);
      ++s.Stats.Samples;
      if (ray.HaveA && (ray.FA < 0.0f) != (f < 0.0f))
      {
        // The first sign change: bisected there.
        this->Shade(s, ray, this->Bisect(s, ray, t), pixel);
        ray.Searching = false;
        return true;
      }
      if (!ray.HaveA && nearSlab && t <= t0 && f >= 0.0f)
      {
        ++s.Stats.StartingInside;
      }
      ray.TA = t;
      ray.FA = f;
      ray.HaveA = true;
      if (t >= t1)
      {
        return false;
      }
      const StepBounds bounds = this->DropAndBound(s, t);
      const float lipschitz = bounds.Lipschitz, smallest = bounds.Smallest, reach = bounds.Reach,
                  bound = bounds.Bound;
      float tNext;
      if (active.N == 0 || bound < this->Threshold)
      {
        // f <= sum of the active peaks - T < 0 until another support begins.
        if (next >= n)
        {
          // No support begins ahead in this voxel: f < 0 to its end.
          ray.TA = t1;
          ray.FA = -this->Threshold;
          return false;
        }
        tNext = s.Crossings[next].Enter; // f < 0 across the gap
      }
      else
      {
        const float base = static_cast<float>(this->S.StepScale) * smallest;
        const float step = std::max(base, std::abs(f) / (lipschitz * K::SlopeBound));
        float limit = std::min(reach, t1);
        if (next < n)
        {
          limit = std::min(limit, s.Crossings[next].Enter);
        }
        tNext = std::min(t + step, limit);
        // Outside the surface, a longer step where an upper bound of f over
        // it stays below 0 (past supports that begin on the way, which it
        // counts): tried to the voxel's end, then over a quarter and a
        // sixteenth of that.
        for (float span = t1 - t; f < 0.0f && span > 2.0f * (tNext - t); span *= 0.25f)
        {
          if (this->UpperBound(s, next, t, t + span) < 0.0f)
          {
            tNext = t + span;
            break;
          }
        }
      }
      tNext = std::min(tNext, t1);
      // Float may not move: take the next representable value.
      t = tNext > t ? tNext : std::nextafter(t, std::numeric_limits<float>::max());
    }
  }

  // Whether f can reach 0 in the view-space box [lo, hi] (the balls of the
  // voxel loaded in s): the sum over the balls of their positive strength
  // times the kernel at the box's point nearest the centre, an upper bound
  // of f + T anywhere in the box, against T.
  bool Live(Scratch& s, int count, const float lo[3], const float hi[3]) const
  {
    // A margin for float sums taken in another order than Field's.
    const float target = this->Threshold * std::max(1.0f - 1e-6f * static_cast<float>(count), 0.9f);
    // In chunks of SIMD sums, stopping at the first chunk that reaches it.
    constexpr int Chunk = 32;
    const float *X = s.X.data(), *Y = s.Y.data(), *Z = s.Z.data(), *InvR2 = s.InvR2.data(),
                *Q = s.Q.data();
    const float lx = lo[0], ly = lo[1], lz = lo[2], hx = hi[0], hy = hi[1], hz = hi[2];
    float sum = 0.0f;
    for (int begin = 0; begin < count; begin += Chunk)
    {
      const int end = std::min(begin + Chunk, count);
      float part = 0.0f;
#pragma omp simd reduction(+ : part)
      for (int j = begin; j < end; ++j)
      {
        const float dx = std::max(std::max(lx - X[j], X[j] - hx), 0.0f);
        const float dy = std::max(std::max(ly - Y[j], Y[j] - hy), 0.0f);
        const float dz = std::max(std::max(lz - Z[j], Z[j] - hz), 0.0f);
        const float x = (dx * dx + dy * dy + dz * dz) * InvR2[j];
        const float v = Q[j] * K::Value(std::min(x, 1.0f));
        part += x < 1.0f && v > 0.0f ? v : 0.0f;
      }
      sum += part;
      if (sum >= target)
      {
        s.Stats.KernelTerms += end;
        return true;
      }
    }
    s.Stats.KernelTerms += count;
    return sum >= target; // T <= 0: live even where nothing adds
  }

  // The view-space box around the segments of the block's rays between view
  // depths da and db: at a given depth a ray's point is affine in its
  // pixel, so the four corner rays' points bound the others'.
  static void BlockBox(const std::vector<Ray>& rays,
    const Block& b,
    float da,
    float db,
    float lo[3],
    float hi[3])
  {
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::numeric_limits<float>::max();
      hi[k] = -std::numeric_limits<float>::max();
    }
    for (int c : b.Corners)
    {
      const Ray& ray = rays[c];
      for (float d : { da, db })
      {
        const float t = d / ray.PerDistance;
        for (int k = 0; k < 3; ++k)
        {
          const float v = ray.Origin[k] + t * ray.Dir[k];
          lo[k] = std::min(lo[k], v);
          hi[k] = std::max(hi[k], v);
        }
      }
    }
    // Float rounding must not cut a ball's reach off.
    for (int k = 0; k < 3; ++k)
    {
      const float slack = 1e-5f * (std::abs(lo[k]) + std::abs(hi[k]));
      lo[k] -= slack;
      hi[k] += slack;
    }
  }

  // The ray's last sample is at t, outside the surface (f = -T there).
  void Outside(Ray& ray, float t) const
  {
    ray.TA = t;
    ray.FA = -this->Threshold;
    ray.HaveA = true;
  }

  // A ray's visit of a voxel where f < 0 throughout: nothing to sample.
  void PassEmpty(Scratch& s, Ray& ray, float t1) const
  {
    ++s.Stats.VoxelVisits;
    ++s.Stats.EmptyVoxelVisits;
    this->Outside(ray, t1);
  }

  // The rays of `blocks` [begin, end) (a group of up to 2 x 2 blocks)
  // through a voxel of `count` balls (loaded in s) between view depths d0
  // and d1. In a crowded voxel the depth is cut in BoundParts and the field
  // bounded in each part's box, first around the whole group, then, in the
  // parts where that bound reaches T, around each block: a block's rays
  // march only from its first part where the bound reaches T to the end of
  // its last, and skip the voxel when there is none. SPH gas is the case: a
  // ray crosses hundreds of supports, mostly where the density is far
  // below T.
  void MarchGroup(Scratch& s,
    std::vector<Ray>& rays,
    const std::vector<int>& pixels,
    const std::vector<Block>& blocks,
    size_t begin,
    size_t end,
    int count,
    float d0,
    float d1,
    bool nearSlab) const
  {
    bool searching = false;
    for (int r = blocks[begin].Begin; r < blocks[end - 1].End && !searching; ++r)
    {
      searching = rays[r].Searching;
    }
    if (!searching)
    {
      return; // every ray of the group has hit: no bounds to take
    }
    bool bounded = count >= BoundMinimumBalls;
    for (size_t k = begin; k < end && bounded; ++k)
    {
      for (int c : blocks[k].Corners)
      {
        bounded = bounded && rays[c].PerDistance > 0.0f;
      }
    }
    auto depth = [d0, d1](int part)
    { return part >= BoundParts ? d1 : d0 + (d1 - d0) * part / BoundParts; };
    bool groupLive[BoundParts] = {};
    if (bounded)
    {
      bool any = false;
      for (int part = 0; part < BoundParts; ++part)
      {
        float lo[3], hi[3];
        for (size_t k = begin; k < end; ++k)
        {
          float blo[3], bhi[3];
          BlockBox(rays, blocks[k], depth(part), depth(part + 1), blo, bhi);
          for (int c = 0; c < 3; ++c)
          {
            lo[c] = k == begin ? blo[c] : std::min(lo[c], blo[c]);
            hi[c] = k == begin ? bhi[c] : std::max(hi[c], bhi[c]);
          }
        }
        groupLive[part] = this->Live(s, count, lo, hi);
        any = any || groupLive[part];
      }
      if (!any)
      {
        for (int r = blocks[begin].Begin; r < blocks[end - 1].End; ++r)
        {
          if (rays[r].Searching)
          {
            this->PassEmpty(s, rays[r], d1 / rays[r].PerDistance);
          }
        }
        return;
      }
    }
    for (size_t k = begin; k < end; ++k)
    {
      const Block& b = blocks[k];
      bool searching = false;
      for (int r = b.Begin; r < b.End; ++r)
      {
        searching = searching || rays[r].Searching;
      }
      if (!searching)
      {
        continue;
      }
      int first = 0, last = BoundParts - 1;
      if (bounded)
      {
        first = -1;
        for (int part = 0; part < BoundParts; ++part)
        {
          float lo[3], hi[3];
          BlockBox(rays, b, depth(part), depth(part + 1), lo, hi);
          if (groupLive[part] && this->Live(s, count, lo, hi))
          {
            first = first < 0 ? part : first;
            last = part;
          }
        }
      }
      const float from = depth(first), to = depth(last + 1);
      for (int r = b.Begin; r < b.End; ++r)
      {
        Ray& ray = rays[r];
        if (!ray.Searching)
        {
          continue;
        }
        if (first < 0)
        {
          this->PassEmpty(s, ray, d1 / ray.PerDistance);
          continue;
        }
        if (first > 0)
        {
          // f < 0 before `from`: the ray arrives there outside.
          this->Outside(ray, from / ray.PerDistance);
        }
        if (!this->MarchVoxel(s,
              ray,
              count,
              from / ray.PerDistance,
              to / ray.PerDistance,
              nearSlab && first == 0,
              pixels[r]) &&
          last + 1 < BoundParts)
        {
          this->Outside(ray, d1 / ray.PerDistance); // and f < 0 after `to`
        }
      }
    }
  }

  // The ray through the centre of pixel (x, y), in view space, as the GPU
  // pass casts it.
  Ray PixelRay(int x, int y) const
  {
    Ray ray;
    const double ndc[2] = { (x + 0.5) / this->S.Width * 2.0 - 1.0,
      (y + 0.5) / this->S.Height * 2.0 - 1.0 };
    double nearPoint[4], farPoint[4];
    const double nearClip[3] = { ndc[0], ndc[1], -1.0 }, farClip[3] = { ndc[0], ndc[1], 1.0 };
    Apply(this->S.ClipToView, nearClip, 1.0, nearPoint);
    Apply(this->S.ClipToView, farClip, 1.0, farPoint);
    double dir[3], norm = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      nearPoint[k] /= nearPoint[3];
      farPoint[k] /= farPoint[3];
      dir[k] = farPoint[k] - nearPoint[k];
      norm += dir[k] * dir[k];
    }
    norm = std::sqrt(norm);
    for (int k = 0; k < 3; ++k)
    {
      ray.Dir[k] = static_cast<float>(dir[k] / norm);
    }
    ray.Origin[0] = this->S.Parallel ? static_cast<float>(nearPoint[0]) : 0.0f;
    ray.Origin[1] = this->S.Parallel ? static_cast<float>(nearPoint[1]) : 0.0f;
    ray.Origin[2] = 0.0f;
    ray.PerDistance = -ray.Dir[2];
    ray.Searching = ray.PerDistance > 0.0f;
    return ray;
  }

  // One screen tile: its rays, block by block, walk its voxels front to back.
  void CastTile(int tile) const
  {
    Scratch& s = this->Local.Local();
    const int tx = tile % this->TilesX, ty = tile / this->TilesX;
    const int ts = this->S.TileSize;
    const int x0 = tx * ts, y0 = ty * ts;
    const int x1 = std::min(x0 + ts, this->S.Width), y1 = std::min(y0 + ts, this->S.Height);
    std::vector<Ray> rays;
    rays.reserve(static_cast<size_t>(ts) * ts);
    std::vector<int> pixels;
    std::vector<Block> blocks;
    std::vector<size_t> groups; // the first block of each group of 2 x 2 blocks, and the end
    // Rays block by block, blocks group by group: each block's rays, and
    // each group's blocks, are consecutive.
    for (int gy = y0; gy < y1; gy += 2 * BlockSize)
    {
      for (int gx = x0; gx < x1; gx += 2 * BlockSize)
      {
        groups.push_back(blocks.size());
        for (int by = gy; by < std::min(gy + 2 * BlockSize, y1); by += BlockSize)
        {
          for (int bx = gx; bx < std::min(gx + 2 * BlockSize, x1); bx += BlockSize)
          {
            Block block;
            block.Begin = static_cast<int>(rays.size());
            const int bx1 = std::min(bx + BlockSize, x1), by1 = std::min(by + BlockSize, y1);
            for (int y = by; y < by1; ++y)
            {
              for (int x = bx; x < bx1; ++x)
              {
                rays.push_back(this->PixelRay(x, y));
                pixels.push_back(y * this->S.Width + x);
              }
            }
            block.End = static_cast<int>(rays.size());
            const int w = bx1 - bx;
            block.Corners[0] = block.Begin;
            block.Corners[1] = block.Begin + w - 1;
            block.Corners[2] = block.End - w;
            block.Corners[3] = block.End - 1;
            blocks.push_back(block);
          }
        }
      }
    }
    groups.push_back(blocks.size());
    s.Stats.Rays += static_cast<long long>(rays.size());
    const int slabs = this->S.Slabs;
    // Empty voxels touch no ray: a run of them only moves each searching
    // ray's last sample (outside) to the run's end, which is done once,
    // before the next voxel with balls. Sparse sets are mostly such runs.
    auto countSearching = [&rays]()
    {
      long long n = 0;
      for (const Ray& ray : rays)
      {
        n += ray.Searching ? 1 : 0;
      }
      return n;
    };
    long long searching = countSearching();
    bool emptyRun = false; // empty voxels passed since the last one with balls
    float emptyEnd = 0.0f;
    for (int slab = 0; slab < slabs && searching > 0; ++slab)
    {
      const size_t voxel = static_cast<size_t>(tile) * slabs + slab;
      const size_t first = this->Offsets[voxel];
      const int count = static_cast<int>(this->Offsets[voxel + 1] - first);
      const float d0 = static_cast<float>(this->Planes[slab]);
      const float d1 = static_cast<float>(this->Planes[slab + 1]);
      if (count == 0)
      {
        emptyRun = true;
        emptyEnd = d1;
        s.Stats.VoxelVisits += searching; // no ray stops in it
        s.Stats.EmptyVoxelVisits += searching;
        continue;
      }
      if (emptyRun)
      {
        for (Ray& ray : rays)
        {
          if (ray.Searching)
          {
            this->Outside(ray, emptyEnd / ray.PerDistance);
          }
        }
        emptyRun = false;
      }
      this->Load(s, first, count);
      for (size_t g = 0; g + 1 < groups.size(); ++g)
      {
        this->MarchGroup(
          s, rays, pixels, blocks, groups[g], groups[g + 1], count, d0, d1, slab == 0);
      }
      searching = countSearching();
    }
  }

  // The voxel's balls into the thread's structure of arrays.
  void Load(Scratch& s, size_t first, int count) const
  {
    if (s.X.size() < static_cast<size_t>(count))
    {
      for (auto* v : { &s.X, &s.Y, &s.Z, &s.R2, &s.InvR2, &s.R, &s.Q, &s.QOverR, &s.Perp })
      {
        v->resize(count);
      }
      s.Color.resize(count);
      s.Unsorted.resize(count);
      s.Order.resize(count);
    }
    for (int j = 0; j < count; ++j)
    {
      const unsigned int id = this->Lists[first + j];
      const float r = this->Balls.R[id];
      s.X[j] = this->Balls.X[id];
      s.Y[j] = this->Balls.Y[id];
      s.Z[j] = this->Balls.Z[id];
      s.R[j] = r;
      s.R2[j] = r * r;
      s.InvR2[j] = 1.0f / (r * r);
      s.Q[j] = this->Balls.Q[id];
      s.QOverR[j] = std::abs(this->Balls.Q[id]) / r;
      s.Color[j] = this->Balls.Color[id];
    }
  }
};

// The perspective grid in tile-major order: Offsets[(tile * slabs + slab)].
void BuildGrid(const MetaballCastInput& in,
  const MetaballCastSettings& S,
  int tilesX,
  int tilesY,
  size_t maximumPairs,
  ViewBalls& balls,
  std::vector<double>& planes,
  std::vector<size_t>& offsets,
  std::vector<unsigned int>& lists,
  MetaballCastStatistics& stats)
{
  const long long n = in.Count;
  balls.X.assign(n, 0.0f);
  balls.Y.assign(n, 0.0f);
  balls.Z.assign(n, 0.0f);
  balls.R.assign(n, 0.0f);
  balls.Q.assign(n, 1.0f);
  balls.Color.assign(n, 0xffffffffu);
  balls.Range.assign(6 * n, 0);
  PerspectiveGridGeometry geometry(
    S.ViewToClip, S.Parallel, S.Width, S.Height, S.TileSize, S.Slabs);
  struct Extent
  {
    double Near = std::numeric_limits<double>::max();
    double Far = 0.0;
    long long Invalid = 0, Culled = 0;
  };
  vtkSMPThreadLocal<Extent> extents;
  std::vector<unsigned char> visible(n, 0);
  // View space, frustum culling and the depth range of what is visible.
  vtkSMPTools::For(0,
    n,
    [&](long long begin, long long end)
    {
      Extent& e = extents.Local();
      for (long long i = begin; i < end; ++i)
      {
        const float* b = in.Balls + 4 * i;
        const float q = in.Strengths ? in.Strengths[i] : 1.0f;
        if (!Finite(b[0]) || !Finite(b[1]) || !Finite(b[2]) || !Finite(b[3]) || !(b[3] > 0.0f) ||
          !Finite(q))
        {
          ++e.Invalid;
          continue;
        }
        const double x[3] = { b[0], b[1], b[2] };
        double c[4];
        Apply(S.WorldToView, x, 1.0, c);
        if (geometry.Outside(c, b[3]))
        {
          ++e.Culled;
          continue;
        }
        balls.X[i] = static_cast<float>(c[0]);
        balls.Y[i] = static_cast<float>(c[1]);
        balls.Z[i] = static_cast<float>(c[2]);
        balls.R[i] = b[3];
        balls.Q[i] = q;
        balls.Color[i] = in.Colors ? in.Colors[i] : 0xffffffffu;
        visible[i] = 1;
        geometry.Extend(c, b[3], e.Near, e.Far);
      }
    });
  double slabNear = std::numeric_limits<double>::max(), slabFar = 0.0;
  for (const Extent& e : extents)
  {
    slabNear = std::min(slabNear, e.Near);
    slabFar = std::max(slabFar, e.Far);
    stats.Invalid += e.Invalid;
    stats.Culled += e.Culled;
  }
  geometry.SetSlabRange(slabNear, slabFar);
  planes = geometry.GetSlabPlanes();
  stats.SlabNear = geometry.GetSlabNear();
  stats.SlabFar = geometry.GetSlabFar();
  // Each visible ball's voxel range, from its (float) view-space centre.
  std::atomic<long long> culled(0);
  vtkSMPTools::For(0,
    n,
    [&](long long begin, long long end)
    {
      long long out = 0;
      for (long long i = begin; i < end; ++i)
      {
        int* range = &balls.Range[6 * i];
        range[0] = 1; // empty until placed
        range[1] = 0;
        const double c[3] = { balls.X[i], balls.Y[i], balls.Z[i] };
        if (visible[i] && !geometry.Range(c, balls.R[i], range))
        {
          range[0] = 1;
          range[1] = 0;
          ++out;
        }
      }
      culled += out;
    });
  stats.Culled += culled;
  // The lists, tile-major: a tile's slabs lie together.
  stats.MaxPerVoxel = SortIntoVoxels(
    n,
    tilesX,
    tilesY,
    S.Slabs,
    VoxelOrder::TileMajor,
    [&](long long i)
    { return balls.Range[6 * i] <= balls.Range[6 * i + 1] ? &balls.Range[6 * i] : nullptr; },
    offsets,
    lists,
    maximumPairs);
  stats.Pairs = static_cast<long long>(lists.size());
}

template<class K>
void CastTiles(const MetaballCastInput& in,
  const MetaballCastSettings& S,
  const ViewBalls& balls,
  const std::vector<size_t>& offsets,
  const std::vector<unsigned int>& lists,
  const std::vector<double>& planes,
  int tilesX,
  int tilesY,
  MetaballCastImages& out,
  MetaballCastStatistics& stats)
{
  vtkSMPThreadLocal<Scratch> local;
  const TileCaster<K> caster{
    in, S, balls, offsets, lists, planes, out, tilesX, static_cast<float>(in.Threshold), local
  };
  vtkSMPTools::For(0,
    tilesX * tilesY,
    1,
    [&](int begin, int end)
    {
      for (int tile = begin; tile < end; ++tile)
      {
        caster.CastTile(tile);
      }
    });
  for (const Scratch& s : local)
  {
    stats.Rays += s.Stats.Rays;
    stats.Hits += s.Stats.Hits;
    stats.StartingInside += s.Stats.StartingInside;
    stats.VoxelVisits += s.Stats.VoxelVisits;
    stats.EmptyVoxelVisits += s.Stats.EmptyVoxelVisits;
    stats.SupportTests += s.Stats.SupportTests;
    stats.Samples += s.Stats.Samples;
    stats.BisectionSamples += s.Stats.BisectionSamples;
    stats.KernelTerms += s.Stats.KernelTerms;
  }
}

} // namespace

//------------------------------------------------------------------------------
double MetaballCastBallBytes(long long balls)
{
  // View-space x, y, z, R, q and colour (24), the voxel range (24), the
  // visibility flag (1), with a margin for the vectors' slack.
  return 64.0 * static_cast<double>(std::max(balls, 0LL));
}

//------------------------------------------------------------------------------
void CastMetaballs(const MetaballCastInput& input,
  const MetaballCastSettings& settings,
  MetaballCastImages& images,
  MetaballCastStatistics* statistics)
{
  MetaballCastStatistics stats;
  const int width = std::max(settings.Width, 0), height = std::max(settings.Height, 0);
  const size_t pixels = static_cast<size_t>(width) * height;
  images.Width = width;
  images.Height = height;
  // Every pixel a miss: the start of a cast, and all a failed one leaves.
  auto clear = [&]()
  {
    images.Color.assign(pixels, 0u);
    images.NormalDistance.assign(4 * pixels, 0.0f);
    images.Depth.assign(pixels, 1.0f);
  };
  clear();
  if (input.Count > static_cast<long long>(std::numeric_limits<unsigned int>::max()))
  {
    stats.Error = "more than 2^32 - 1 balls: ball ids are 32-bit, as on the GPU";
  }
  if (pixels == 0 || settings.TileSize <= 0 || settings.Slabs <= 0 || input.Count <= 0 ||
    !stats.Error.empty() || !input.Balls)
  {
    if (statistics)
    {
      *statistics = stats;
    }
    return;
  }
  // The memory the cast may take: its copy of the balls first, what is left
  // for the grid's pairs (4 bytes each, and as much again while sorting).
  const double limit = MemoryLimitBytes(settings.MemoryLimit);
  const double ballBytes = MetaballCastBallBytes(input.Count);
  if (limit > 0.0 && ballBytes > limit)
  {
    stats.Error = std::to_string(input.Count) + " balls need about " + FormatBytes(ballBytes) +
      " of ray-caster memory, more than " +
      (settings.MemoryLimit > 0.0 ? "its memory limit" : "the free physical memory") + " (" +
      FormatBytes(limit) +
      "): draw fewer balls (a subset, or the GPU ray caster), or raise MemoryLimit";
    if (statistics)
    {
      *statistics = stats;
    }
    return;
  }
  const size_t maximumPairs = limit > 0.0
    ? static_cast<size_t>(std::min((limit - ballBytes) / 8.0, 1e18))
    : std::numeric_limits<size_t>::max();
  const auto start = Clock::now();
  const int tilesX = (width + settings.TileSize - 1) / settings.TileSize;
  const int tilesY = (height + settings.TileSize - 1) / settings.TileSize;
  ViewBalls balls;
  std::vector<double> planes;
  std::vector<size_t> offsets;
  std::vector<unsigned int> lists;
  auto built = start;
  try
  {
    BuildGrid(input, settings, tilesX, tilesY, maximumPairs, balls, planes, offsets, lists, stats);
    built = Clock::now();
    // One instance of the march per kernel, so that the kernel inlines.
    auto cast = [&](auto kernel)
    {
      CastTiles<decltype(kernel)>(
        input, settings, balls, offsets, lists, planes, tilesX, tilesY, images, stats);
    };
    VisitMetaballKernel<float>(input.Kernel, cast);
  }
  catch (const std::length_error& e)
  {
    // More (voxel, ball) pairs than the memory limit leaves room for.
    stats.Error = std::string(e.what()) +
      ": use fewer slabs or larger tiles, draw fewer balls, or raise MemoryLimit";
    clear();
  }
  catch (const std::bad_alloc&)
  {
    // The grid's (voxel, ball) pairs or the scratch do not fit: no image.
    stats.Error = "not enough memory for the grid's (voxel, ball) pairs: use fewer slabs or "
                  "larger tiles";
    clear();
  }
  const auto done = Clock::now();
  stats.GridSeconds = std::chrono::duration<double>(built - start).count();
  stats.CastSeconds = std::chrono::duration<double>(done - built).count();
  if (statistics)
  {
    *statistics = stats;
  }
}
} // namespace pointsurfaces
