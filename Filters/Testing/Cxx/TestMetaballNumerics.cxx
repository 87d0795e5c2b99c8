// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The metaball reference numerics (psMetaball.h), against exact answers:
// - kernels: f(0) = 1, f(1) = 0, decreasing, derivative against central
//   differences;
// - the field's gradient against central differences over overlapping balls;
// - the reference ray caster on single balls, whose iso-surface is a sphere
//   of known radius, for each kernel and for radii from 1e-4 to 1e2, at an
//   offset of 1e7 too: hit distance and normal;
// - the perspective grid: lists ordered and consistent with the scan, and
//   complete: every point of every ball's support inside the view falls in
//   a voxel that lists the ball;
// - bad input: NaN centres and radii, zero radii skipped and counted; balls
//   behind the eye culled; a ball around the eye covers every tile; all
//   balls at one point;
// - ghost balls for a split set (SupportBounds, BallsReachingBox): a box
//   corner a ball's bounding box reaches but its sphere does not; and,
//   split into three slabs, each part's field (own and ghosts) equals the
//   whole field wherever one of its own balls reaches, while without the
//   ghosts it does not.
#include "psFiltersTestSupport.h"
#include "psMetaball.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

using namespace pointsurfaces;

namespace
{

// A camera at `eye` looking down -z, 60 degree view angle, square viewport.
GridView MakeView(const double eye[3], int size, int tile, int slabs)
{
  GridView v;
  const double m[16] = { 1, 0, 0, -eye[0], 0, 1, 0, -eye[1], 0, 0, 1, -eye[2], 0, 0, 0, 1 };
  const double n = 0.1, f = 100.0, t = std::tan(3.14159265358979323846 / 6.0);
  const double p[16] = {
    1 / t, 0, 0, 0, 0, 1 / t, 0, 0, 0, 0, -(f + n) / (f - n), -2 * f * n / (f - n), 0, 0, -1, 0
  };
  for (int k = 0; k < 16; ++k)
  {
    v.WorldToView[k] = m[k];
    v.ViewToClip[k] = p[k];
  }
  v.Width = v.Height = size;
  v.TileSize = tile;
  v.Slabs = slabs;
  return v;
}

// The iso radius of one ball of radius R, strength 1, threshold T.
double IsoRadius(MetaballKernel kernel, double R, double T)
{
  return R * LoneBallIsoRadius(kernel, T);
}
} // namespace

int TestMetaballNumerics(int, char*[])
{

  // Kernels.
  for (MetaballKernel k : MetaballKernels)
  {
    Check(std::abs(KernelValue(k, 0.0) - 1.0) < 1e-14, "kernel f(0) = 1");
    Check(std::abs(KernelValue(k, 1.0)) < 1e-14 && KernelValue(k, 2.0) == 0.0, "kernel f(1) = 0");
    double previous = 2.0;
    for (int i = 0; i <= 100; ++i)
    {
      const double x = i / 100.0;
      double slope;
      const double f = KernelValue(k, x, &slope);
      Check(f <= previous, "kernel decreasing");
      previous = f;
      if (i > 0 && i < 100)
      {
        const double h = 1e-6;
        const double numeric = (KernelValue(k, x + h) - KernelValue(k, x - h)) / (2 * h);
        Check(std::abs(numeric - slope) < 1e-5, "kernel derivative");
      }
    }
  }

  // The SPH kernels: N / R^3 K integrates to 1 over space (midpoint rule in
  // q = r / R), the slope bound is the largest |dK/dq|, and the closed forms
  // of the cubic spline's two pieces and the Wendland polynomials hold.
  for (MetaballKernel k : MetaballKernels)
  {
    double largest = 0.0;
    for (int i = 1; i < 100000; ++i)
    {
      const double q = i / 100000.0;
      double slope;
      KernelValue(k, q * q, &slope);
      largest = std::max(largest, std::abs(2.0 * q * slope)); // dK/dq = 2 q dK/dx
    }
    Check(largest <= KernelSlopeBound(k) && largest > 0.99 * KernelSlopeBound(k),
      "the slope bound is the largest |dK/dq|");
    if (!IsSPHKernel(k))
    {
      Check(KernelNormalization(k) == 0.0 && SWIFTSupportFactor(k) == 1.0,
        "the blob kernels are not normalised");
      continue;
    }
    const int steps = 200000;
    double integral = 0.0;
    for (int i = 0; i < steps; ++i)
    {
      const double q = (i + 0.5) / steps;
      integral += 4.0 * 3.14159265358979323846 * q * q * KernelValue(k, q * q) / steps;
    }
    Check(
      std::abs(KernelNormalization(k) * integral - 1.0) < 1e-9, "an SPH kernel integrates to 1");
    Check(SWIFTSupportFactor(k) > 1.8 && SWIFTSupportFactor(k) < 2.3, "SWIFT's gamma");
  }
  Check(std::abs(KernelValue(MetaballKernel::CubicSpline, 0.04) - (1.0 - 6 * 0.04 + 6 * 0.008)) <
        1e-15 &&
      std::abs(KernelValue(MetaballKernel::CubicSpline, 0.49) - 2.0 * 0.3 * 0.3 * 0.3) < 1e-15,
    "cubic spline pieces (q = 0.2 and 0.7)");
  Check(std::abs(KernelValue(MetaballKernel::WendlandC2, 0.25) - 0.0625 * 3.0) < 1e-15 &&
      std::abs(KernelValue(MetaballKernel::WendlandC4, 0.25) -
        std::pow(0.5, 6) * (1.0 + 3.0 + 35.0 / 12.0)) < 1e-15,
    "Wendland C2 and C4 at q = 1/2");

  // A lone ball's iso radius, against closed forms: the quartic reaches T at
  // x = 1 - sqrt(T), the Gaussian at x = -ln(T (1 - e^-4) + e^-4) / 4;
  // Wyvill's cubic has K(x) = T there. No surface when T >= K(0) = 1.
  for (double T : { 1e-4, 0.1, 0.3, 0.5, 0.9 })
  {
    const double quartic = LoneBallIsoRadius(MetaballKernel::Quartic, T);
    const double gaussian = LoneBallIsoRadius(MetaballKernel::Gaussian, T);
    const double wyvill = LoneBallIsoRadius(MetaballKernel::Wyvill, T);
    const double floor = std::exp(-4.0);
    Check(std::abs(quartic - std::sqrt(1.0 - std::sqrt(T))) < 1e-12, "quartic iso radius");
    Check(std::abs(gaussian - std::sqrt(-std::log(T * (1.0 - floor) + floor) / 4.0)) < 1e-12,
      "Gaussian iso radius");
    Check(std::abs(KernelValue(MetaballKernel::Wyvill, wyvill * wyvill) - T) < 1e-12,
      "Wyvill iso radius");
  }
  Check(LoneBallIsoRadius(MetaballKernel::Wyvill, 1.0) == 0.0 &&
      LoneBallIsoRadius(MetaballKernel::Quartic, 2.0) == 0.0,
    "no iso radius when T >= K(0)");

  // Field gradient over overlapping balls.
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> uni(-1.0, 1.0), rad(0.3, 0.8);
  const int n = 200;
  std::vector<double> centres(3 * n), radii(n), strengths(n);
  for (int i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      centres[3 * i + c] = 2.0 * uni(gen);
    }
    radii[i] = rad(gen);
    strengths[i] = 0.5 + 0.5 * (uni(gen) + 1.0);
  }
  for (MetaballKernel k : MetaballKernels)
  {
    MetaballSet set;
    set.Centers = centres.data();
    set.Radii = radii.data();
    set.Strengths = strengths.data();
    set.Count = n;
    set.Kernel = k;
    set.Threshold = 0.5;
    double worst = 0.0;
    for (int s = 0; s < 200; ++s)
    {
      const double x[3] = { 2 * uni(gen), 2 * uni(gen), 2 * uni(gen) };
      double g[3];
      FieldValue(set, x, g);
      for (int c = 0; c < 3; ++c)
      {
        double a[3] = { x[0], x[1], x[2] }, b[3] = { x[0], x[1], x[2] };
        a[c] += 1e-6;
        b[c] -= 1e-6;
        worst = std::max(worst, std::abs((FieldValue(set, a) - FieldValue(set, b)) / 2e-6 - g[c]));
      }
    }
    Check(worst < 1e-5, "field gradient");
  }

  // Ray casts on single balls: exact iso-spheres, radii 1e-4 to 1e2, offset 1e7 too.
  for (MetaballKernel k : MetaballKernels)
  {
    for (double R : { 1e-4, 1e-2, 1.0, 1e2 })
    {
      for (double offset : { 0.0, 1e7 })
      {
        const double c[3] = { offset, 0.5 * offset, 0.0 };
        const double one = 1.0;
        MetaballSet set;
        set.Centers = c;
        set.Radii = &R;
        set.Strengths = &one;
        set.Count = 1;
        set.Kernel = k;
        set.Threshold = 0.3;
        const double iso = IsoRadius(k, R, 0.3);
        // A ray from 3R away, slanted so that it hits at half the iso radius off-centre.
        const double o[3] = { c[0] - 3 * R, c[1] + 0.5 * iso, c[2] };
        const double d[3] = { 1.0, 0.0, 0.0 };
        const RayHit hit = CastRay(set, o, d, 0.0, 6 * R, R / 50, 40);
        const double expected = 3 * R - std::sqrt(iso * iso - 0.25 * iso * iso);
        // Bisection leaves step / 2^40; the coordinates carry 1e7 ulps.
        const double tolerance = 1e-9 * R + 4e-16 * offset;
        Check(hit.Hit && std::abs(hit.T - expected) < tolerance, "ray cast hit distance");
        double radial[3], len = 0.0;
        for (int a = 0; a < 3; ++a)
        {
          radial[a] = hit.Point[a] - c[a];
          len += radial[a] * radial[a];
        }
        len = std::sqrt(len);
        double dot = 0.0;
        for (int a = 0; a < 3; ++a)
        {
          dot += hit.Normal[a] * radial[a] / len;
        }
        Check(dot > 1.0 - (offset > 0 ? 1e-6 : 1e-12), "ray cast normal is radial");
        if (!hit.Hit || std::abs(hit.T - expected) >= tolerance)
        {
          std::cerr << "  kernel " << static_cast<int>(k) << " R " << R << " offset " << offset
                    << ": t " << hit.T << " expected " << expected << "\n";
        }
      }
    }
  }

  // The perspective grid.
  {
    const double eye[3] = { 0.0, 0.0, 6.0 };
    GridView view = MakeView(eye, 256, 16, 12);
    MetaballSet set;
    set.Centers = centres.data();
    set.Radii = radii.data();
    set.Count = n;
    const PerspectiveGrid grid = BuildPerspectiveGrid(set, view);
    const long long voxels = static_cast<long long>(grid.TilesX) * grid.TilesY * grid.Slabs;
    Check(grid.TilesX == 16 && grid.TilesY == 16 && grid.Slabs == 12, "grid size");
    Check(static_cast<long long>(grid.Offsets.size()) == voxels + 1 &&
        grid.Offsets.back() == grid.Balls.size() &&
        static_cast<long long>(grid.Balls.size()) == grid.Pairs,
      "grid offsets");
    bool ordered = true;
    for (long long v = 0; v < voxels; ++v)
    {
      for (unsigned k = grid.Offsets[v] + 1; k < grid.Offsets[v + 1]; ++k)
      {
        ordered = ordered && grid.Balls[k - 1] < grid.Balls[k];
      }
    }
    Check(ordered, "ball ids ascend within a voxel");
    // Completeness: points of each ball's support land in voxels listing it.
    long long missing = 0, checked = 0;
    for (int i = 0; i < n; ++i)
    {
      for (int s = 0; s < 50; ++s)
      {
        double p[3];
        do
        {
          p[0] = uni(gen);
          p[1] = uni(gen);
          p[2] = uni(gen);
        } while (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] > 1.0);
        for (int c = 0; c < 3; ++c)
        {
          p[c] = centres[3 * i + c] + radii[i] * p[c];
        }
        const double vz = p[2] - eye[2];
        const double depth = -vz;
        const double t = std::tan(3.14159265358979323846 / 6.0);
        const double ndcX = (p[0] - eye[0]) / (t * depth), ndcY = (p[1] - eye[1]) / (t * depth);
        if (depth <= grid.SlabPlanes.front() || depth >= grid.SlabPlanes.back() ||
          std::abs(ndcX) >= 1.0 || std::abs(ndcY) >= 1.0)
        {
          continue;
        }
        const int tx = static_cast<int>((0.5 * ndcX + 0.5) * 256) / 16;
        const int ty = static_cast<int>((0.5 * ndcY + 0.5) * 256) / 16;
        int slab = 0;
        while (slab + 1 < grid.Slabs && depth >= grid.SlabPlanes[slab + 1])
        {
          ++slab;
        }
        const long long v = (static_cast<long long>(slab) * grid.TilesY + ty) * grid.TilesX + tx;
        bool found = false;
        for (unsigned k = grid.Offsets[v]; k < grid.Offsets[v + 1] && !found; ++k)
        {
          found = grid.Balls[k] == static_cast<unsigned>(i);
        }
        missing += found ? 0 : 1;
        ++checked;
      }
    }
    std::cout << "grid: " << grid.Pairs << " pairs, at most " << grid.MaxPerVoxel
              << " balls per voxel, " << grid.Culled << " culled; " << checked
              << " support points checked, " << missing << " missing\n";
    Check(checked > 1000 && missing == 0, "every ball is listed where its support reaches");
  }

  // Bad input and extremes.
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double eye[3] = { 0.0, 0.0, 6.0 };
    const GridView view = MakeView(eye, 64, 16, 4);
    std::vector<double> c = { 0, 0, 0, nan, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 20, 0, 0, 5.9 };
    std::vector<double> r = { 1, 1, nan, 0, 1, 0.5 };
    MetaballSet set;
    set.Centers = c.data();
    set.Radii = r.data();
    set.Count = 6;
    const PerspectiveGrid grid = BuildPerspectiveGrid(set, view);
    Check(grid.Invalid == 3, "NaN and zero radii are skipped and counted");
    Check(grid.Culled == 1, "a ball behind the eye is culled");
    // The ball around the eye (z = 5.9, R = 0.5) covers every tile of its slabs.
    long long tilesWithEyeBall = 0;
    for (long long v = 0; v < grid.TilesX * grid.TilesY; ++v)
    {
      for (unsigned k = grid.Offsets[v]; k < grid.Offsets[v + 1]; ++k)
      {
        tilesWithEyeBall += grid.Balls[k] == 5 ? 1 : 0;
      }
    }
    Check(tilesWithEyeBall == grid.TilesX * grid.TilesY, "a ball around the eye covers every tile");

    // All balls at one point: a single blob, found by the ray caster.
    std::vector<double> same(3 * 100, 0.0), ones(100, 1.0);
    MetaballSet clump;
    clump.Centers = same.data();
    clump.Radii = ones.data();
    clump.Count = 100;
    clump.Kernel = MetaballKernel::Quartic;
    clump.Threshold = 50.0; // 100 (1 - x)^2 = 50
    const double o[3] = { 0, 0, 5 }, d[3] = { 0, 0, -1 };
    const RayHit hit = CastRay(clump, o, d, 0.0, 10.0, 0.01, 40);
    const double iso = std::sqrt(1.0 - std::sqrt(0.5));
    Check(hit.Hit && std::abs(hit.T - (5.0 - iso)) < 1e-9, "coincident balls");
    const PerspectiveGrid one = BuildPerspectiveGrid(clump, MakeView(o, 64, 16, 4));
    Check(one.Culled == 0 && one.Pairs >= 100 && one.MaxPerVoxel == 100, "coincident balls grid");
  }

  // Ghost balls for a split set.
  {
    const double c[6] = { 0, 0, 0, 3, 3, 3 }, r[2] = { 1, 1 };
    MetaballSet two;
    two.Centers = c;
    two.Radii = r;
    two.Count = 2;
    double b[6];
    SupportBounds(two, b);
    Check(b[0] == -1 && b[1] == 4 && b[2] == -1 && b[5] == 4, "support bounds");
    // The first ball's bounding box reaches the box's corner (0.9, 0.9, 0.9),
    // its sphere does not (1.56 away); the second's sphere does (0.87 away).
    const double corner[6] = { 0.9, 2.5, 0.9, 2.5, 0.9, 2.5 },
                 far[6] = { 0.5, 2.5, 0.5, 2.5, 0.5, 2.5 };
    Check(BallsReachingBox(two, corner) == std::vector<long long>{ 1 }, "sphere misses box corner");
    Check(BallsReachingBox(two, far).size() == 2, "sphere meets box");
    const double nan[3] = { std::numeric_limits<double>::quiet_NaN(), 0, 0 }, zero[1] = { 0 };
    MetaballSet bad;
    bad.Centers = nan;
    bad.Radii = r;
    bad.Count = 1;
    SupportBounds(bad, b);
    Check(b[0] > b[1] && BallsReachingBox(two, b).empty(), "no valid ball: empty bounds");
    bad.Centers = c;
    bad.Radii = zero;
    Check(BallsReachingBox(bad, far).empty(), "zero radius reaches nothing");

    // 3000 balls split into three slabs along x.
    std::mt19937 split(5);
    std::uniform_real_distribution<double> pos(-4.0, 4.0), rr(0.2, 0.6), qq(0.5, 1.5);
    const int m = 3000;
    std::vector<double> cs(3 * m), rs(m), qs(m);
    for (int i = 0; i < m; ++i)
    {
      for (int a = 0; a < 3; ++a)
      {
        cs[3 * i + a] = pos(split);
      }
      rs[i] = rr(split);
      qs[i] = qq(split);
    }
    MetaballSet all;
    all.Centers = cs.data();
    all.Radii = rs.data();
    all.Strengths = qs.data();
    all.Count = m;
    all.Kernel = MetaballKernel::Wyvill;
    // Appends balls `ids` of (c, r, q) to (pc, pr, pq).
    auto take = [](const std::vector<long long>& ids,
                  const std::vector<double>& c,
                  const std::vector<double>& r,
                  const std::vector<double>& q,
                  std::vector<double>& pc,
                  std::vector<double>& pr,
                  std::vector<double>& pq)
    {
      for (long long i : ids)
      {
        pc.insert(pc.end(), c.begin() + 3 * i, c.begin() + 3 * i + 3);
        pr.push_back(r[i]);
        pq.push_back(q[i]);
      }
    };
    // The set `all` describes, over other storage.
    auto over = [&all](const std::vector<double>& c,
                  const std::vector<double>& r,
                  const std::vector<double>& q)
    {
      MetaballSet set = all;
      set.Centers = c.data();
      set.Radii = r.data();
      set.Strengths = q.data();
      set.Count = static_cast<long long>(r.size());
      return set;
    };
    std::vector<long long> own[3];
    for (int i = 0; i < m; ++i)
    {
      own[cs[3 * i] < -1.3 ? 0 : (cs[3 * i] < 1.4 ? 1 : 2)].push_back(i);
    }
    long long exact = 0, wrongWithout = 0, ghosts = 0;
    for (int k = 0; k < 3; ++k)
    {
      std::vector<double> oc, orr, oq;
      take(own[k], cs, rs, qs, oc, orr, oq);
      const MetaballSet mine = over(oc, orr, oq);
      double box[6];
      SupportBounds(mine, box);
      std::vector<double> gc = oc, gr = orr, gq = oq;
      for (int j = 0; j < 3; ++j)
      {
        if (j == k)
        {
          continue;
        }
        std::vector<double> jc, jr, jq;
        take(own[j], cs, rs, qs, jc, jr, jq);
        std::vector<long long> reach = BallsReachingBox(over(jc, jr, jq), box);
        ghosts += static_cast<long long>(reach.size());
        take(reach, jc, jr, jq, gc, gr, gq);
      }
      const MetaballSet withGhosts = over(gc, gr, gq);
      // Points inside one of the part's own supports.
      std::uniform_real_distribution<double> dir(-1.0, 1.0);
      for (int s = 0; s < 2000; ++s)
      {
        const long long b = std::uniform_int_distribution<long long>(0, mine.Count - 1)(split);
        double x[3];
        for (int a = 0; a < 3; ++a)
        {
          x[a] = oc[3 * b + a] + 0.57 * orr[b] * dir(split);
        }
        const double whole = FieldValue(all, x);
        exact += std::abs(FieldValue(withGhosts, x) - whole) <= 1e-12 * (1.0 + std::abs(whole));
        wrongWithout += std::abs(FieldValue(mine, x) - whole) > 1e-6;
      }
    }
    std::cout << "ghost balls: " << ghosts << " of " << m << " balls sent, " << exact
              << " of 6000 samples exact with ghosts, " << wrongWithout << " wrong without\n";
    Check(exact == 6000, "own and ghost balls give the whole field inside own supports");
    Check(
      wrongWithout > 100 && ghosts < 3 * m / 5, "the split matters and not every ball is a ghost");
  }

  if (Failures == 0)
  {
    std::cout << "metaball numerics: all checks passed\n";
  }
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
