// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The native CPU ray caster of the metaball mapper (psMetaballCast.h) against
// the double-precision reference ray caster (pointsurfaces::CastRay: dense
// sampling at 1/300 of the smallest radius, 50 bisections):
// - 60 balls of radii 0.3 to 0.6, strengths 0.6 to 1.4, for each kernel (the
//   SPH ones too, as shapes: their normalisation is the strengths'), in
//   perspective and in parallel projection, with a viewport that the tiles do
//   not divide: fewer than 1 % of the covered pixels may disagree on hit or
//   miss, and the 99th percentiles of the depth error (1e-3 of the smallest
//   radius) and of the normal error (0.5 degrees) are those the mapper's GPU
//   path is held to;
// - radii spread over 30x with 600 balls crowding one region (the SPH case):
//   the steps follow the radii of the balls a ray crosses, so where only the
//   large ones are the error is theirs; 5e-3 of the smallest radius (1.1e-4
//   of the large ones) is the bound;
// - the counters: rays, hits and voxel visits add up; empty voxels are
//   counted;
// - bad input: NaN centres, zero and NaN radii, infinite strengths are
//   skipped and counted; no balls, a zero viewport; a ball around the eye
//   starts rays inside;
// - a time series of 120 frames of moving particles (the asan preset's
//   check of the caster over a series).
#include "psFiltersTestSupport.h"
#include "psMetaball.h"
#include "psMetaballCast.h"
#include "psTestVortex.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

using namespace pointsurfaces;

namespace
{
const double Pi = 3.14159265358979323846;

// Identity view (the balls are given in view space), and a projection.
MetaballCastSettings MakeSettings(int width, int height, bool parallel)
{
  MetaballCastSettings s;
  for (int k = 0; k < 16; ++k)
  {
    s.WorldToView[k] = (k % 5 == 0) ? 1.0 : 0.0;
    s.ViewToClip[k] = s.ClipToView[k] = 0.0;
  }
  const double n = 1.0, f = 20.0, aspect = static_cast<double>(width) / height;
  if (parallel)
  {
    const double h = 1.6, w = h * aspect;
    s.ViewToClip[0] = 1.0 / w;
    s.ViewToClip[5] = 1.0 / h;
    s.ViewToClip[10] = -2.0 / (f - n);
    s.ViewToClip[11] = -(f + n) / (f - n);
    s.ViewToClip[15] = 1.0;
    s.ClipToView[0] = w;
    s.ClipToView[5] = h;
    s.ClipToView[10] = -(f - n) / 2.0;
    s.ClipToView[11] = -(f + n) / 2.0;
    s.ClipToView[15] = 1.0;
  }
  else
  {
    const double t = std::tan(35.0 / 2.0 * Pi / 180.0);
    const double a = 1.0 / (t * aspect), b = 1.0 / t, c = -(f + n) / (f - n),
                 d = -2.0 * f * n / (f - n);
    s.ViewToClip[0] = a;
    s.ViewToClip[5] = b;
    s.ViewToClip[10] = c;
    s.ViewToClip[11] = d;
    s.ViewToClip[14] = -1.0;
    s.ClipToView[0] = 1.0 / a;
    s.ClipToView[5] = 1.0 / b;
    s.ClipToView[11] = -1.0;
    s.ClipToView[14] = 1.0 / d;
    s.ClipToView[15] = c / d;
  }
  s.Parallel = parallel;
  s.Width = width;
  s.Height = height;
  return s;
}

// The ray through pixel (x, y), as the caster forms it, in double.
void PixelRay(const MetaballCastSettings& s, int x, int y, double origin[3], double dir[3])
{
  const double ndc[2] = { (x + 0.5) / s.Width * 2.0 - 1.0, (y + 0.5) / s.Height * 2.0 - 1.0 };
  double p[2][3];
  for (int e = 0; e < 2; ++e)
  {
    const double z = e == 0 ? -1.0 : 1.0;
    double h[4];
    for (int r = 0; r < 4; ++r)
    {
      const double* m = s.ClipToView + 4 * r;
      h[r] = m[0] * ndc[0] + m[1] * ndc[1] + m[2] * z + m[3];
    }
    for (int k = 0; k < 3; ++k)
    {
      p[e][k] = h[k] / h[3];
    }
  }
  double norm = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    dir[k] = p[1][k] - p[0][k];
    norm += dir[k] * dir[k];
  }
  for (int k = 0; k < 3; ++k)
  {
    dir[k] /= std::sqrt(norm);
  }
  origin[0] = s.Parallel ? p[0][0] : 0.0;
  origin[1] = s.Parallel ? p[0][1] : 0.0;
  origin[2] = 0.0;
}

struct Scene
{
  std::vector<double> Centers, Radii, Strengths;
  std::vector<float> Balls, Q;
  void Add(double x, double y, double z, double r, double q)
  {
    Centers.insert(Centers.end(), { x, y, z });
    Radii.push_back(r);
    Strengths.push_back(q);
    Balls.insert(Balls.end(),
      { static_cast<float>(x),
        static_cast<float>(y),
        static_cast<float>(z),
        static_cast<float>(r) });
    Q.push_back(static_cast<float>(q));
  }
};

// Casts the scene and compares every pixel with the reference; returns false
// when the errors exceed the mapper's bounds.
bool Compare(const Scene& scene,
  MetaballKernel kernel,
  const MetaballCastSettings& s,
  const char* what,
  double depthBound = 1e-3)
{
  MetaballCastInput in;
  in.Balls = scene.Balls.data();
  in.Strengths = scene.Q.data();
  in.Count = static_cast<long long>(scene.Radii.size());
  in.Kernel = kernel;
  in.Threshold = 0.5;
  MetaballCastImages images;
  MetaballCastStatistics stats;
  CastMetaballs(in, s, images, &stats);

  MetaballSet set;
  set.Centers = scene.Centers.data();
  set.Radii = scene.Radii.data();
  set.Strengths = scene.Strengths.data();
  set.Count = in.Count;
  set.Kernel = kernel;
  set.Threshold = in.Threshold;
  const double minRadius = *std::min_element(scene.Radii.begin(), scene.Radii.end());
  long long covered = 0, mismatched = 0, hits = 0;
  std::vector<double> depthErrors, normalErrors;
  for (int y = 0; y < s.Height; ++y)
  {
    for (int x = 0; x < s.Width; ++x)
    {
      const int pixel = y * s.Width + x;
      double origin[3], dir[3];
      PixelRay(s, x, y, origin, dir);
      // The reference samples only the span of the supports on the ray.
      double tMin = std::numeric_limits<double>::max(), tMax = 0.0;
      for (size_t i = 0; i < scene.Radii.size(); ++i)
      {
        const double* c = &scene.Centers[3 * i];
        const double oc[3] = { c[0] - origin[0], c[1] - origin[1], c[2] - origin[2] };
        const double b = oc[0] * dir[0] + oc[1] * dir[1] + oc[2] * dir[2];
        const double disc =
          b * b - (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2]) + scene.Radii[i] * scene.Radii[i];
        if (disc > 0.0)
        {
          tMin = std::min(tMin, std::max(b - std::sqrt(disc), 0.0));
          tMax = std::max(tMax, b + std::sqrt(disc));
        }
      }
      RayHit ref;
      if (tMax > tMin)
      {
        ref = CastRay(set, origin, dir, tMin, tMax, minRadius / 300.0, 50);
      }
      const bool mine = (images.Color[pixel] >> 24) != 0;
      hits += mine;
      covered += mine || ref.Hit;
      if (mine != ref.Hit)
      {
        ++mismatched;
        continue;
      }
      if (!mine)
      {
        Check(images.Depth[pixel] == 1.0f, "a miss has depth 1");
        continue;
      }
      const float* nd = &images.NormalDistance[4 * pixel];
      depthErrors.push_back(std::abs(nd[3] - (-ref.Point[2])) / minRadius);
      const double dot = std::min(
        1.0, std::abs(nd[0] * ref.Normal[0] + nd[1] * ref.Normal[1] + nd[2] * ref.Normal[2]));
      normalErrors.push_back(std::acos(dot) * 180.0 / Pi);
    }
  }
  auto p99 = [](std::vector<double> v)
  {
    if (v.empty())
    {
      return 0.0;
    }
    std::sort(v.begin(), v.end());
    return v[static_cast<size_t>(0.99 * (v.size() - 1))];
  };
  const double depth99 = p99(depthErrors), normal99 = p99(normalErrors);
  std::cout << what << ": " << hits << " hits, " << mismatched << " of " << covered
            << " covered pixels disagree on hit or miss, depth error p99 " << depth99
            << " of the smallest radius, normal error p99 " << normal99 << " deg; " << stats.Pairs
            << " pairs, " << stats.MaxPerVoxel << " balls in the fullest voxel, "
            << stats.VoxelVisits << " voxel visits (" << stats.EmptyVoxelVisits << " empty), "
            << stats.SupportTests << " support tests, " << stats.Samples << " samples, "
            << stats.BisectionSamples << " bisection samples, " << stats.KernelTerms
            << " kernel terms\n";
  Check(stats.Rays == static_cast<long long>(s.Width) * s.Height, "one ray per pixel");
  Check(stats.Hits == hits, "the hit counter counts the hits written");
  Check(stats.EmptyVoxelVisits <= stats.VoxelVisits, "empty visits are visits");
  return covered > 500 && mismatched <= covered / 100 && depth99 < depthBound && normal99 < 0.5;
}
} // namespace

int TestMetaballCast(int, char*[])
{
  std::mt19937 gen(17);
  std::uniform_real_distribution<double> uni(-1.0, 1.0), rad(0.3, 0.6), str(0.6, 1.4);
  Scene scene;
  for (int i = 0; i < 60; ++i)
  {
    scene.Add(uni(gen), uni(gen), -5.0 + uni(gen), rad(gen), str(gen));
  }
  for (int k = 0; k < 6; ++k)
  {
    const std::string what =
      std::string(pointsurfaces::MetaballKernelName(MetaballKernels[k])) + ", perspective";
    Check(Compare(scene, MetaballKernels[k], MakeSettings(100, 90, false), what.c_str()),
      "the CPU caster matches the reference in perspective");
  }
  Check(Compare(scene, MetaballKernel::Wyvill, MakeSettings(96, 80, true), "Wyvill, parallel"),
    "the CPU caster matches the reference in parallel projection");

  // Radii spread over 30x, 600 small balls crowding inside a few large ones.
  {
    Scene crowd;
    std::uniform_real_distribution<double> small(0.02, 0.06);
    for (int i = 0; i < 600; ++i)
    {
      crowd.Add(0.3 * uni(gen), 0.3 * uni(gen), -5.0 + 0.3 * uni(gen), small(gen), 1.0);
    }
    for (int i = 0; i < 6; ++i)
    {
      crowd.Add(0.8 * uni(gen), 0.8 * uni(gen), -5.0 + 0.5 * uni(gen), 0.9, 0.8);
    }
    Check(Compare(
            crowd, MetaballKernel::Wyvill, MakeSettings(80, 80, false), "crowded, 30x radii", 5e-3),
      "the CPU caster matches the reference on crowded balls of spread radii");
  }

  // SPH gas: 400 cubic-spline supports overlapping in a Gaussian cloud, the
  // threshold crossed only in its core. Crowded voxels (at least 32 balls)
  // are bounded part by part; rays skip the parts where the bound stays
  // below T and must still find the same surface.
  {
    Scene gas;
    std::normal_distribution<double> cloud(0.0, 0.4);
    for (int i = 0; i < 400; ++i)
    {
      gas.Add(cloud(gen), cloud(gen), -5.0 + cloud(gen), 0.5, 0.08);
    }
    MetaballCastStatistics probe;
    MetaballCastInput in;
    in.Balls = gas.Balls.data();
    in.Strengths = gas.Q.data();
    in.Count = 400;
    in.Kernel = MetaballKernel::CubicSpline;
    MetaballCastImages images;
    CastMetaballs(in, MakeSettings(64, 64, false), images, &probe);
    Check(probe.MaxPerVoxel >= 64, "the gas crowds its voxels (their field is bounded)");
    Check(Compare(gas, MetaballKernel::CubicSpline, MakeSettings(64, 64, false), "SPH gas"),
      "the CPU caster matches the reference in overlapping SPH supports");
    Check(
      Compare(gas, MetaballKernel::CubicSpline, MakeSettings(64, 64, true), "SPH gas, parallel"),
      "the CPU caster matches the reference in overlapping SPH supports, parallel projection");
  }

  // Bad input: skipped and counted; the rest drawn.
  {
    Scene bad = scene;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    bad.Balls[0] = nan;                                // centre
    bad.Balls[4 + 3] = 0.0f;                           // zero radius
    bad.Balls[8 + 3] = nan;                            // NaN radius
    bad.Q[3] = std::numeric_limits<float>::infinity(); // strength
    MetaballCastInput in;
    in.Balls = bad.Balls.data();
    in.Strengths = bad.Q.data();
    in.Count = 60;
    MetaballCastImages images;
    MetaballCastStatistics stats;
    CastMetaballs(in, MakeSettings(64, 64, false), images, &stats);
    std::cout << "bad balls: " << stats.Invalid << " invalid, " << stats.Hits << " hits\n";
    Check(stats.Invalid == 4 && stats.Hits > 200, "bad balls are skipped and counted");

    in.Count = 0;
    CastMetaballs(in, MakeSettings(64, 64, false), images, &stats);
    Check(stats.Hits == 0 && images.Color.size() == 64 * 64 && images.Depth[100] == 1.0f,
      "no balls: an image of misses");
    MetaballCastSettings none = MakeSettings(64, 64, false);
    none.Width = 0;
    in.Count = 60;
    CastMetaballs(in, none, images, &stats);
    Check(images.Color.empty() && stats.Rays == 0, "a zero viewport: no image, no rays");
  }

  // The eye inside a ball: rays start inside, and the surface behind is seen
  // from inside.
  {
    Scene around;
    around.Add(0.0, 0.0, -0.5, 3.0, 1.0);
    MetaballCastInput in;
    in.Balls = around.Balls.data();
    in.Count = 1;
    MetaballCastImages images;
    MetaballCastStatistics stats;
    CastMetaballs(in, MakeSettings(32, 32, false), images, &stats);
    std::cout << "eye inside: " << stats.StartingInside << " rays start inside, " << stats.Hits
              << " hits\n";
    Check(stats.StartingInside == 32 * 32 && stats.Hits == 32 * 32,
      "a ball around the eye: every ray starts inside and finds its surface");
  }

  // A ball whose front lies a float's step in front of the eye: its box
  // corners project far out of the viewport (tile ranges are clamped before
  // they become ints), it covers the whole view, and the near plane cuts
  // into it.
  {
    Scene close;
    close.Add(0.0, 0.0, -(3.0 + 4e-7), 3.0, 1.0);
    MetaballCastInput in;
    in.Balls = close.Balls.data();
    in.Count = 1;
    MetaballCastImages images;
    MetaballCastStatistics stats;
    CastMetaballs(in, MakeSettings(32, 32, false), images, &stats);
    std::cout << "ball at the eye plane: " << stats.Hits << " hits, " << stats.StartingInside
              << " rays start inside\n";
    Check(
      stats.Culled == 0 && stats.Hits == 32 * 32, "a ball reaching the eye plane covers the view");
  }

  // A time series: 120 frames of 3000 particles swirling into a vortex, new
  // positions every frame, through one image set. Every frame finds the
  // surface; under the asan preset (which runs the unit tests) this is the
  // caster's check for leaks and misuse over a series.
  {
    const int n = 3000;
    TestVortex<std::mt19937> vortex(n, gen);
    MetaballCastImages images;
    MetaballCastStatistics stats;
    int framesWithSurface = 0;
    for (int frame = 0; frame < 120; ++frame)
    {
      vortex.Step();
      std::vector<float> balls(4 * n);
      for (int i = 0; i < n; ++i)
      {
        const double* p = vortex.Position(i);
        // Seen from 4 units away along +y, view space = (x, z, y - 4).
        balls[4 * i] = static_cast<float>(p[0]);
        balls[4 * i + 1] = static_cast<float>(p[2]);
        balls[4 * i + 2] = static_cast<float>(p[1] - 4.0);
        balls[4 * i + 3] = 0.12f;
      }
      MetaballCastInput in;
      in.Balls = balls.data();
      in.Count = n;
      CastMetaballs(in, MakeSettings(64, 64, false), images, &stats);
      framesWithSurface += stats.Hits > 300 && stats.Error.empty();
    }
    std::cout << "time series: " << framesWithSurface << " of 120 frames show the surface\n";
    Check(framesWithSurface == 120, "every frame of a time series finds the surface");
  }

  // Memory limits: below the balls' copy, nothing is cast and the error
  // names the limit; room for the balls but not for the grid's pairs, the
  // error names the pairs; no image is half drawn.
  {
    MetaballCastInput in;
    in.Balls = scene.Balls.data();
    in.Strengths = scene.Q.data();
    in.Count = 60;
    MetaballCastSettings s = MakeSettings(64, 64, false);
    MetaballCastImages images;
    MetaballCastStatistics stats;
    s.MemoryLimit = MetaballCastBallBytes(60) / 2.0;
    CastMetaballs(in, s, images, &stats);
    std::cout << "memory limit below the balls: " << stats.Error << "\n";
    Check(stats.Error.find("memory limit") != std::string::npos && stats.Hits == 0 &&
        images.Depth.size() == 64 * 64 && images.Depth[2080] == 1.0f,
      "a limit below the balls' copy: an error naming it, an image of misses");
    s.MemoryLimit = MetaballCastBallBytes(60) + 8.0 * 10;
    CastMetaballs(in, s, images, &stats);
    std::cout << "memory limit below the pairs: " << stats.Error << "\n";
    Check(stats.Error.find("pairs") != std::string::npos && stats.Hits == 0 &&
        std::all_of(images.Color.begin(), images.Color.end(), [](unsigned c) { return c == 0; }),
      "room for 10 pairs only: an error naming the pairs, an image of misses");
    s.MemoryLimit = 0.0;
    CastMetaballs(in, s, images, &stats);
    Check(stats.Error.empty() && stats.Hits > 200, "no limit: the frame is cast");
  }

  // The same images and counters with 1, 2 and 3 threads: each pixel is one
  // thread's work, the grid is sorted whatever the threads' order (the
  // crowded scene, in both projections).
  {
    Scene crowd;
    std::mt19937 g(5);
    for (int i = 0; i < 800; ++i)
    {
      crowd.Add(uni(g), uni(g), -5.0 + uni(g), i % 40 == 0 ? 0.9 : 0.12, str(g));
    }
    MetaballCastInput in;
    in.Balls = crowd.Balls.data();
    in.Strengths = crowd.Q.data();
    in.Count = static_cast<long long>(crowd.Radii.size());
    in.Kernel = MetaballKernel::WendlandC2;
    for (bool parallel : { false, true })
    {
      std::vector<MetaballCastImages> images(3);
      std::vector<MetaballCastStatistics> stats(3);
      for (int t = 0; t < 3; ++t)
      {
        vtkSMPTools::Initialize(t + 1);
        CastMetaballs(in, MakeSettings(120, 100, parallel), images[t], &stats[t]);
      }
      vtkSMPTools::Initialize(0);
      bool same = stats[0].Hits > 1000;
      for (int t = 1; t < 3; ++t)
      {
        same = same && images[t].Color == images[0].Color && images[t].Depth == images[0].Depth &&
          images[t].NormalDistance == images[0].NormalDistance && stats[t].Hits == stats[0].Hits &&
          stats[t].Pairs == stats[0].Pairs && stats[t].VoxelVisits == stats[0].VoxelVisits;
      }
      std::cout << "threads 1, 2, 3 (" << (parallel ? "parallel" : "perspective")
                << "): " << stats[0].Hits << " hits, " << stats[0].Pairs << " pairs\n";
      Check(same, "the CPU caster gives the same images and counters with 1, 2 and 3 threads");
    }
  }

  if (Failures == 0)
  {
    std::cout << "metaball CPU caster: all checks passed\n";
  }
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
