// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psSplatBound.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace pointsurfaces
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
// The directions of the plane in which the border and the rim are tested.
constexpr int Directions = 16;

// In-plane position (world units), in-plane distance and deviation of each
// candidate within reach (the patch is evaluated only there). Candidates
// farther than BoundSearchRadius from the origin are left out, so that
// the result does not depend on how many more the caller passed.
struct Candidate
{
  double U, V, Rho, E;
  int Index;
  bool Turned; // within the tolerance, but its normal turns away from the patch's
};

// One BoundSplat call: the candidates on and off the patch, the points near
// it binned by in-plane distance, and the phases that cut the disc (where
// the surface bends away, where the data ends, where the patch leaves the
// data). Its scratch is per thread and kept between calls: BoundSplat calls
// back into nothing and starts no parallel work, so no thread re-enters it
// while it is in use.
class DiscBound
{
public:
  DiscBound(const Splat& splat,
    double radius,
    const double* points,
    int n,
    const BoundParameters& params,
    const double* normals)
    : S(splat)
    , F(splat.Frame)
    , H(splat.Frame.Scale)
    , Radius(radius)
    , Points(points)
    , N(n)
    , P(params)
    , Normals(normals)
    , Spacing(params.Spacing > 0.0 ? params.Spacing : splat.Frame.Scale)
    , Tol(params.Tolerance)
    , Reach(std::max(radius, 3.0 * this->Spacing)) // the border test looks this far
  {
  }

  // The candidates within reach, on the patch (within the tolerance, not
  // turned) or off it.
  void Gather();
  // The points on or near the patch, binned by in-plane distance.
  void BinNearPoints();
  // The radius at which the surface bends away, from r; sets BentAway.
  double BendRadius(double r, SplatBound& bound) const;
  // The radius at which the data ends, from r; sets Border.
  double BorderRadius(double r, SplatBound& bound) const;
  // r, shrunk until the patch's rim stays by the data; sets Border.
  double RimRadius(double r, SplatBound& bound) const;
  // The bound of the disc of radius r: it covers the points on the patch within it.
  SplatBound Finish(double r,
    SplatBound& bound,
    std::vector<int>* covered,
    std::vector<double>* rho) const;

private:
  using NearIterator = std::vector<const double*>::const_iterator;
  // The bin of in-plane distance `value`.
  int BinOf(double value) const
  {
    const double x = value / this->BinWidth;
    return x > 0.0 ? (x < this->Bins - 1 ? static_cast<int>(x) : this->Bins - 1) : 0;
  }
  // The near points whose rho may lie in [lo, hi] (a superset: whole bins).
  std::pair<NearIterator, NearIterator> NearBand(double lo, double hi) const
  {
    const std::vector<const double*>& near = NearScratch();
    const std::vector<int>& binStart = BinStartScratch();
    return std::make_pair(near.begin() + binStart[this->BinOf(lo) > 0 ? this->BinOf(lo) - 1 : 0],
      near.begin() + binStart[std::min(this->Bins, this->BinOf(hi) + 2)]);
  }
  bool IsNear(const Candidate& c) const { return c.E <= 2.0 * this->Tol && !c.Turned; }

  static std::vector<Candidate>& OnScratch()
  {
    thread_local std::vector<Candidate> on;
    return on;
  }
  static std::vector<Candidate>& OffScratch()
  {
    thread_local std::vector<Candidate> off;
    return off;
  }
  static std::vector<const double*>& NearScratch()
  {
    thread_local std::vector<const double*> near;
    return near;
  }
  static std::vector<int>& BinStartScratch()
  {
    thread_local std::vector<int> binStart;
    return binStart;
  }

  const Splat& S;
  const LocalFrame& F;
  const double H;
  const double Radius;
  const double* Points;
  const int N;
  const BoundParameters& P;
  const double* Normals;
  const double Spacing, Tol, Reach;
  double Adjacency = 0.0, BinWidth = 1.0;
  int Bins = 1;
};

//------------------------------------------------------------------------------
void DiscBound::Gather()
{
  const LocalFrame& f = this->F;
  const Splat& splat = this->S;
  const BoundParameters& params = this->P;
  const double h = this->H, tol = this->Tol, reach = this->Reach, radius = this->Radius;
  const double* points = this->Points;
  const double* normals = this->Normals;
  const int n = this->N;
  // |cos| of the largest angle between a covered point's normal and the patch's.
  const double agreement =
    normals && params.NormalAngle < 90.0 ? std::cos(params.NormalAngle * Pi / 180.0) : -1.0;
  std::vector<Candidate>& on = OnScratch();
  std::vector<Candidate>& off = OffScratch();
  on.clear();
  off.clear();
  const double search2 = 2.0 * reach * reach;
  for (int j = 0; j < n; ++j)
  {
    const double* p = points + 3 * j;
    const double d[3] = { p[0] - f.Origin[0], p[1] - f.Origin[1], p[2] - f.Origin[2] };
    if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > search2)
    {
      continue;
    }
    double uvh[3];
    ToLocal(f, p, uvh);
    const double rhoJ = std::sqrt(uvh[0] * uvh[0] + uvh[1] * uvh[1]) * h;
    if (rhoJ > reach)
    {
      continue;
    }
    Candidate c{ uvh[0] * h,
      uvh[1] * h,
      rhoJ,
      std::abs(uvh[2] - Evaluate(splat.Fit.Coefficients, splat.Fit.Degree, uvh[0], uvh[1])) * h,
      j,
      false };
    if (agreement > 0.0 && c.E <= tol && !params.MeasureOnly)
    {
      // The patch's normal at (u, v) is (-g_u, -g_v, 1) in the frame.
      double du = 0.0, dv = 0.0;
      EvaluateWithGradient(splat.Fit.Coefficients, splat.Fit.Degree, uvh[0], uvh[1], du, dv);
      const double* m = normals + 3 * j;
      const double mt = m[0] * f.Tangent[0] + m[1] * f.Tangent[1] + m[2] * f.Tangent[2];
      const double mb = m[0] * f.Bitangent[0] + m[1] * f.Bitangent[1] + m[2] * f.Bitangent[2];
      const double mn = m[0] * f.Normal[0] + m[1] * f.Normal[1] + m[2] * f.Normal[2];
      const double length2 = (mt * mt + mb * mb + mn * mn) * (1.0 + du * du + dv * dv);
      const double dot = mn - du * mt - dv * mb;
      c.Turned = length2 > 0.0 && dot * dot < agreement * agreement * length2;
    }
    if (params.MeasureOnly)
    {
      // The unbounded disc of [Bolla 2010] covers its cylinder of height R.
      if (c.Rho <= radius && std::abs(uvh[2]) * h <= radius)
      {
        on.push_back(c);
      }
      continue;
    }
    (c.E <= tol && !c.Turned ? on : off).push_back(c);
  }
}

//------------------------------------------------------------------------------
void DiscBound::BinNearPoints()
{
  // The points on or near the patch (within twice the tolerance), binned by
  // in-plane distance (a counting sort into bins an adjacency wide): two
  // points closer than d in space differ by at most d in rho, so each
  // nearness test below looks only at the bins of a band of rho.
  this->Adjacency = std::abs(this->P.Adjacency * this->Spacing);
  // NaN gives way to the first.
  this->BinWidth = std::max(1e-3 * this->Reach, this->Adjacency);
  this->Bins = static_cast<int>(this->Reach / this->BinWidth) + 1;
  const int bins = this->Bins;
  const double* points = this->Points;
  const std::vector<Candidate>& on = OnScratch();
  const std::vector<Candidate>& off = OffScratch();
  std::vector<const double*>& near = NearScratch();
  std::vector<int>& binStart = BinStartScratch();
  binStart.assign(static_cast<size_t>(bins) + 1, 0);
  for (const Candidate& c : on)
  {
    ++binStart[this->BinOf(c.Rho) + 1];
  }
  for (const Candidate& c : off)
  {
    binStart[this->BinOf(c.Rho) + 1] += this->IsNear(c) ? 1 : 0;
  }
  for (int b = 0; b < bins; ++b)
  {
    binStart[b + 1] += binStart[b];
  }
  near.resize(static_cast<size_t>(binStart[bins]));
  {
    thread_local std::vector<int> fill;
    fill.assign(binStart.begin(), binStart.end() - 1);
    for (const Candidate& c : on)
    {
      near[fill[this->BinOf(c.Rho)]++] = points + 3 * c.Index;
    }
    for (const Candidate& c : off)
    {
      if (this->IsNear(c))
      {
        near[fill[this->BinOf(c.Rho)]++] = points + 3 * c.Index;
      }
    }
  }
}

//------------------------------------------------------------------------------
double DiscBound::BendRadius(double r, SplatBound& bound) const
{
  // Where the surface bends away: the nearest point off the patch that
  // continues the points on or near it. A point barely off (under twice
  // the tolerance) is noise as often as it is a bend: it is not covered,
  // but does not stop the disc; nor does a point within CentreReach
  // spacings of the centre (so that the disc always covers its own
  // centre). A point on a wall that turns away from the patch (Turned)
  // stops it however near the patch it lies. A splat whose point sits on
  // the lip of a deep fold is stopped half a spacing out: with a whole
  // spacing, its disc hung over the fold's opening as a light half-disc.
  thread_local std::vector<const Candidate*> stoppers;
  stoppers.clear();
  for (const Candidate& c : OffScratch())
  {
    if (c.Rho < r && (c.E > 2.0 * this->Tol || c.Turned) &&
      c.Rho >= this->P.CentreReach * this->Spacing)
    {
      stoppers.push_back(&c);
    }
  }
  std::sort(stoppers.begin(),
    stoppers.end(),
    [](const Candidate* a, const Candidate* b) { return a->Rho < b->Rho; });
  const double adjacent2 = this->Adjacency * this->Adjacency;
  for (const Candidate* c : stoppers)
  {
    const double* p = this->Points + 3 * c->Index;
    const auto range = this->NearBand(c->Rho - this->Adjacency, c->Rho + this->Adjacency);
    for (auto it = range.first; it != range.second; ++it)
    {
      const double* q = *it;
      const double d2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
        (p[2] - q[2]) * (p[2] - q[2]);
      if (d2 <= adjacent2)
      {
        r = c->Rho;
        bound.BentAway = true;
        break;
      }
    }
    if (bound.BentAway)
    {
      break;
    }
  }
  return r;
}

//------------------------------------------------------------------------------
double DiscBound::BorderRadius(double r, SplatBound& bound) const
{
  // Where the data ends: the support of the points on the patch in
  // Directions directions of the plane (how far they reach each way). A
  // side that falls short of the disc by more than a band w has a border:
  // the disc may reach only BorderMargin spacings past it. w is where,
  // for points spread at random with the density found around the splat
  // (Poisson), the band would hold BorderPoints points on average, so that
  // irregular sampling does not pass for a border: a spacing or two.
  // The density from the this->Spacing (the mean distance of the 6 nearest is
  // about 1 / sqrt(density) for random points, 1.14 of it on a grid), not
  // from a count in the disc, which a thin strip of data would make small.
  const double density = 1.0 / (this->Spacing * this->Spacing);
  double cosine[Directions], sine[Directions], support[Directions];
  for (int k = 0; k < Directions; ++k)
  {
    cosine[k] = std::cos(2.0 * Pi * k / Directions);
    sine[k] = std::sin(2.0 * Pi * k / Directions);
    support[k] = 0.0;
  }
  // A point supports only the directions within BorderAngle of its own: a
  // point far to one side reaches past the band all the same (one stray
  // point across a hole, or a wall point that the patch curls through,
  // hid a border as wide as half the disc). The cone cuts the corners off
  // the caps whose statistics the band assumes, so that a disc meets a
  // border by chance more often where the sampling is random: on points
  // spread at random over the Bunny (200 000), 45 degrees gave 8 % more
  // splats and 30 degrees 37 %; on the benchmark scans at s = 1, 1 to 2 %
  // and 2 to 5 %, and a half (30 degrees: three quarters) fewer discs
  // straying a this->Spacing from the surface.
  const double coneCos = std::cos(std::min(std::abs(this->P.BorderAngle), 180.0) * Pi / 180.0);
  for (const Candidate& m : OnScratch())
  {
    for (int k = 0; k < Directions; ++k)
    {
      const double along = m.U * cosine[k] + m.V * sine[k];
      if (along >= coneCos * m.Rho)
      {
        support[k] = std::max(support[k], along);
      }
    }
  }
  // A cap of depth w of a disc of radius r has an area of about (4/3) sqrt(2 r w) w.
  const double band = density > 0.0 && r > 0.0
    ? std::pow(3.0 * this->P.BorderPoints / (4.0 * density * std::sqrt(2.0 * r)), 2.0 / 3.0)
    : r;
  const double shortest = *std::min_element(support, support + Directions);
  // A small disc holds too few points to tell a border from chance; half its
  // radius short is a border all the same (the cap of the band: a disc of a
  // this->Spacing or so, centred on the edge of a thin part, otherwise hung a
  // whole this->Spacing past it).
  if (shortest + std::min(std::max(band, this->P.BorderSlack * this->Spacing), 0.5 * r) < r)
  {
    r = std::min(r, shortest + this->P.BorderMargin * this->Spacing);
    bound.Border = true;
  }
  return r;
}

//------------------------------------------------------------------------------
double DiscBound::RimRadius(double r, SplatBound& bound) const
{
  // Last, the patch itself must stay by the data over its whole disc: its
  // rim, sampled in the same directions, must lie near a point on or near
  // the patch: within MaximumReach sampling distances (1 / sqrt(density))
  // along the plane and twice the tolerance (at least half a spacing) across
  // it. A patch fitted on one side of a border can turn steeply past it.
  // Shrink until it does.
  const double density = 1.0 / (this->Spacing * this->Spacing);
  const LocalFrame& f = this->F;
  const double h = this->H;
  const double along = std::abs(this->P.MaximumReach) / std::sqrt(std::max(density, 1e-300));
  const double across = std::max(2.0 * this->Tol, 0.5 * this->Spacing);
  for (int step = 0; step < 8 && r > 0.0; ++step)
  {
    bool inside = true;
    // A rim sample lies at rho = r: a point within `along` of it in the
    // plane has rho within `along` of r.
    const auto range = this->NearBand(r - along, r + along);
    for (int k = 0; k < Directions && inside; ++k)
    {
      const double u = r * std::cos(2.0 * Pi * k / Directions) / h,
                   v = r * std::sin(2.0 * Pi * k / Directions) / h;
      const double g = Evaluate(this->S.Fit.Coefficients, this->S.Fit.Degree, u, v);
      double p[3];
      for (int c = 0; c < 3; ++c)
      {
        p[c] = f.Origin[c] + h * (u * f.Tangent[c] + v * f.Bitangent[c] + g * f.Normal[c]);
      }
      inside = false;
      for (auto j = range.first; j != range.second && !inside; ++j)
      {
        const double* q = *j;
        const double d[3] = { p[0] - q[0], p[1] - q[1], p[2] - q[2] };
        const double dn = d[0] * f.Normal[0] + d[1] * f.Normal[1] + d[2] * f.Normal[2];
        const double dt2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - dn * dn;
        inside = dt2 / (along * along) + dn * dn / (across * across) <= 1.0;
      }
    }
    if (inside)
    {
      break;
    }
    r *= 0.8;
    bound.Border = true;
  }
  return r;
}

//------------------------------------------------------------------------------
SplatBound DiscBound::Finish(double r,
  SplatBound& bound,
  std::vector<int>* covered,
  std::vector<double>* rho) const
{
  bound.Radius = r;
  for (const Candidate& m : OnScratch())
  {
    if (m.Rho <= r)
    {
      bound.MaxDeviation = std::max(bound.MaxDeviation, m.E);
      if (covered)
      {
        covered->push_back(m.Index);
      }
      if (rho)
      {
        // A point farther off the patch than the disc is wide (a tolerance
        // above the radius: noise scales, wide discs cut short) is within
        // the tolerance but not on the disc as a renderer or an error
        // metric sees it: no claim may count on it (infinitely far).
        rho->push_back(m.E <= r ? m.Rho : std::numeric_limits<double>::infinity());
      }
    }
  }
  return bound;
}
} // namespace

double BoundSearchRadius(double radius, double spacing)
{
  return std::sqrt(2.0) * std::max(radius, 3.0 * spacing);
}

SplatBound BoundSplat(const Splat& splat,
  double radius,
  const double* points,
  int n,
  const BoundParameters& params,
  std::vector<int>* covered,
  std::vector<double>* rho,
  const double* normals)
{
  SplatBound bound;
  if (covered)
  {
    covered->clear();
  }
  if (rho)
  {
    rho->clear();
  }
  const double h = splat.Frame.Scale;
  if (splat.Fit.Degree <= 0 || !(h > 0.0) || !(radius > 0.0) || !std::isfinite(radius))
  {
    return bound;
  }
  DiscBound disc(splat, radius, points, n, params, normals);
  disc.Gather();
  if (params.MeasureOnly)
  {
    return disc.Finish(radius, bound, covered, rho);
  }
  disc.BinNearPoints();
  double r = disc.BendRadius(radius, bound);
  r = disc.BorderRadius(r, bound);
  r = disc.RimRadius(r, bound);
  return disc.Finish(r, bound, covered, rho);
}
} // namespace pointsurfaces
