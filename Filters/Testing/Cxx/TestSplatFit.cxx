// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the splat kernel and the set builder (plain numerics):
// exact recovery through the whole kernel, convergence order on a sphere,
// invariance of the whole build under offsets of 1e7 and scales of 1e-6 and
// 1e6, LOP/WLOP uniformity, the octree's invariants, the error metric
// against exactly known distances, and the orientation of splat normals
// (a flipped splat is the same surface; propagation makes a sphere's and a
// torus's normals all point outward, each part of a two-part set too).
#include "psOctree.h"
#include "psPointIndex.h"
#include "psSplatBuilder.h"
#include "psSplatError.h"
#include "psSplatFit.h"
#include "psSplatOrientation.h"

#include "psFiltersTestSupport.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <random>
#include <vector>

using namespace pointsurfaces;

namespace
{

std::vector<double> FibonacciSphere(int n)
{
  std::vector<double> p(3 * n);
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), t = golden * i;
    p[3 * i] = r * std::cos(t);
    p[3 * i + 1] = r * std::sin(t);
    p[3 * i + 2] = z;
  }
  return p;
}

Splat FitAt(const PointIndex& index, const double* q, const SplatFitParameters& par)
{
  std::vector<int> ids;
  std::vector<double> d2, c;
  index.Nearest(q, std::max(par.NumberOfNeighbors, par.FeatureSizeNeighbors + 1), ids, d2);
  c.resize(3 * ids.size());
  for (size_t j = 0; j < ids.size(); ++j)
  {
    std::copy(index.Point(ids[j]), index.Point(ids[j]) + 3, &c[3 * j]);
  }
  return FitSplat(q, c.data(), static_cast<int>(ids.size()), par);
}

// Largest distance from the unit sphere of the patch, sampled on its disc of radius h.
double SphereError(const Splat& s)
{
  double worst = 0.0;
  for (double u = -1.0; u <= 1.0; u += 0.25)
  {
    for (double v = -1.0; v <= 1.0; v += 0.25)
    {
      if (u * u + v * v > 1.0)
      {
        continue;
      }
      const double g = Evaluate(s.Fit.Coefficients, s.Fit.Degree, u, v);
      double x[3];
      for (int k = 0; k < 3; ++k)
      {
        x[k] = s.Frame.Origin[k] +
          s.Frame.Scale *
            (u * s.Frame.Tangent[k] + v * s.Frame.Bitangent[k] + g * s.Frame.Normal[k]);
      }
      worst = std::max(worst, std::abs(std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - 1.0));
    }
  }
  return worst;
}

void TestConvergenceOrder()
{
  // Error of the patches against the exact sphere at spacing h, h/2, h/4 (k
  // fixed, so the support shrinks with h). Expected order h^(d+1); on a
  // sphere odd degrees gain one by symmetry: 2, 4, 4, 6.
  for (int degree = 1; degree <= 4; ++degree)
  {
    SplatFitParameters par;
    par.Degree = degree;
    par.FeatureSizeNeighbors = 20;
    double previous = 0.0;
    for (int n : { 2000, 8000, 32000 })
    {
      const std::vector<double> p = FibonacciSphere(n);
      PointIndex index(p.data(), n);
      double worst = 0.0;
      for (int t = 0; t < 100; ++t)
      {
        worst = std::max(worst, SphereError(FitAt(index, &p[3 * ((t * 7919LL) % n)], par)));
      }
      if (previous > 0.0)
      {
        const double rate = std::log2(previous / worst);
        std::cout << "degree " << degree << ", " << n << " points: max error " << worst
                  << ", order " << rate << "\n";
        Check(rate > degree + 1 - 0.2, "the sphere error falls at the rate of the degree");
      }
      previous = worst;
    }
  }
}

void TestParaboloidThroughKernel()
{
  // z = a (x^2 + y^2) on a symmetric grid: the frame is exactly the xy plane,
  // so the kernel must return g = a h (u^2 + v^2) - c0 to rounding.
  const double a = 0.3;
  std::vector<double> p;
  for (int i = -6; i <= 6; ++i)
  {
    for (int j = -6; j <= 6; ++j)
    {
      const double x = 0.1 * i, y = 0.1 * j;
      p.insert(p.end(), { x, y, a * (x * x + y * y) });
    }
  }
  const int n = static_cast<int>(p.size() / 3);
  PointIndex index(p.data(), n);
  SplatFitParameters par;
  par.NumberOfNeighbors = n;
  par.FeatureSizeNeighbors = 24;
  par.WeightScale = 2.0;
  const double q[3] = { 0, 0, 0 };
  for (int degree = 2; degree <= 4; ++degree)
  {
    par.Degree = degree;
    const Splat s = FitAt(index, q, par);
    const double h = s.Frame.Scale;
    const double* c = s.Fit.Coefficients;
    const double expected = a * h;
    bool ok = s.Fit.Status == FitStatus::Ok && std::abs(std::abs(s.Frame.Normal[2]) - 1.0) < 1e-12;
    ok = ok && std::abs(c[3] - expected) < 1e-9 * expected &&
      std::abs(c[5] - expected) < 1e-9 * expected;
    ok = ok && std::abs(c[1]) < 1e-9 && std::abs(c[2]) < 1e-9 && std::abs(c[4]) < 1e-9;
    for (int k = 6; k < MonomialCount(degree); ++k)
    {
      ok = ok && std::abs(c[k]) < 1e-9;
    }
    Check(ok, "a paraboloid is recovered exactly through the whole kernel");
  }
}

std::vector<double> Torus(int n, unsigned seed)
{
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> uni(0.0, 2.0 * 3.14159265358979323846);
  std::vector<double> p(3 * n);
  for (int i = 0; i < n; ++i)
  {
    const double s = uni(gen), t = uni(gen), R = 30.0, r = 10.0;
    p[3 * i] = (R + r * std::cos(t)) * std::cos(s);
    p[3 * i + 1] = (R + r * std::cos(t)) * std::sin(s);
    p[3 * i + 2] = r * std::sin(t);
  }
  return p;
}

void TestInvariance()
{
  // The same build after translating by 1e7 or scaling by 1e-6 and 1e6.
  const int n = 8000;
  const std::vector<double> base = Torus(n, 5u);
  BuildParameters params;
  params.VisitOrder = Order::Random;
  params.Fit.Degree = 3;
  const BuildResult ref = BuildSplats(base.data(), n, nullptr, params);
  Check(ref.Splats.size() > 100, "the torus gives splats");
  const double cases[][2] = { { 1e7, 1.0 }, { 0.0, 1e-6 }, { 0.0, 1e6 } };
  for (const auto& cs : cases)
  {
    std::vector<double> moved(base);
    for (double& v : moved)
    {
      v = v * cs[1] + cs[0];
    }
    const BuildResult got = BuildSplats(moved.data(), n, nullptr, params);
    bool same = got.Splats.size() == ref.Splats.size();
    double worst = 0.0;
    for (size_t i = 0; same && i < ref.Splats.size(); ++i)
    {
      const Splat& a = ref.Splats[i].Fitted;
      const Splat& b = got.Splats[i].Fitted;
      same = ref.Splats[i].Source == got.Splats[i].Source && a.Fit.Degree == b.Fit.Degree;
      double scale = 0.0;
      for (int k = 0; k < MonomialCount(a.Fit.Degree); ++k)
      {
        scale = std::max(scale, std::abs(a.Fit.Coefficients[k]));
      }
      for (int k = 0; k < MonomialCount(a.Fit.Degree); ++k)
      {
        worst = std::max(worst, std::abs(a.Fit.Coefficients[k] - b.Fit.Coefficients[k]) / scale);
      }
      worst = std::max(worst, std::abs(a.Frame.Scale * cs[1] - b.Frame.Scale) / b.Frame.Scale);
      for (int k = 0; k < 3; ++k)
      {
        worst = std::max(
          worst, std::abs(a.Frame.Origin[k] * cs[1] + cs[0] - b.Frame.Origin[k]) / b.Frame.Scale);
      }
    }
    std::cout << "offset " << cs[0] << ", scale " << cs[1] << ": " << got.Splats.size()
              << " splats, largest relative difference " << worst << "\n";
    Check(same && worst < 1e-6, "identical splats after translation or scaling");
  }
}

void TestFitModes()
{
  // A sphere patch with 15 % gross outliers: the Robust mode must recover the
  // curvature that the Linear mode loses; the Projected mode must put the
  // origin on the surface it fits (g(0, 0) = 0).
  const std::vector<double> sphere = FibonacciSphere(20000);
  PointIndex index(sphere.data(), 20000);
  const double q[3] = { 0.0, 0.0, 1.0 };
  std::vector<int> ids;
  std::vector<double> d2, c;
  index.Nearest(q, 121, ids, d2);
  c.resize(3 * ids.size());
  std::mt19937 gen(5);
  for (size_t j = 0; j < ids.size(); ++j)
  {
    std::copy(index.Point(ids[j]), index.Point(ids[j]) + 3, &c[3 * j]);
    if (j > 0 && gen() % 100 < 15)
    {
      c[3 * j + 2] += 0.02; // far above the surface: 1.2 point spacings
    }
  }
  SplatFitParameters par;
  par.FeatureSizeNeighbors = 120;
  const Splat linear = FitSplat(q, c.data(), static_cast<int>(ids.size()), par);
  par.Mode = FitMode::Robust;
  par.Loss = RobustLoss::Cauchy;
  par.LossScale = 0.02;
  const Splat robust = FitSplat(q, c.data(), static_cast<int>(ids.size()), par);
  // Exact curvature of the unit sphere in units of h: g ~ -(h / 2)(u^2 + v^2).
  const double expectedL = -0.5 * linear.Frame.Scale, expectedR = -0.5 * robust.Frame.Scale;
  const double errLinear = std::abs(linear.Fit.Coefficients[3] - expectedL) / std::abs(expectedL);
  const double errRobust = std::abs(robust.Fit.Coefficients[3] - expectedR) / std::abs(expectedR);
  std::cout << "outliers: curvature error linear " << errLinear << ", robust " << errRobust << " ("
            << robust.Iterations << " iterations)\n";
  Check(errRobust < 0.5 * errLinear && errRobust < 0.1, "the Robust mode resists outliers");

  // Projected: on a clean off-surface query the origin moves onto the fit.
  const double off[3] = { 0.0, 0.01, 1.02 };
  index.Nearest(off, 121, ids, d2);
  c.resize(3 * ids.size());
  for (size_t j = 0; j < ids.size(); ++j)
  {
    std::copy(index.Point(ids[j]), index.Point(ids[j]) + 3, &c[3 * j]);
  }
  par.Mode = FitMode::Linear;
  const Splat plain = FitSplat(off, c.data(), static_cast<int>(ids.size()), par);
  par.Mode = FitMode::Projected;
  const Splat projected = FitSplat(off, c.data(), static_cast<int>(ids.size()), par);
  const double* o = projected.Frame.Origin;
  std::cout << "projection: |g(0,0)| linear " << std::abs(plain.Fit.Coefficients[0])
            << ", projected " << std::abs(projected.Fit.Coefficients[0]) << " after "
            << projected.Iterations
            << " steps; |o| - 1 = " << std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]) - 1.0
            << "\n";
  Check(std::abs(projected.Fit.Coefficients[0]) < 1e-6 &&
      std::abs(projected.Fit.Coefficients[0]) < std::abs(plain.Fit.Coefficients[0]),
    "the Projected mode puts the origin on its surface");
  Check(std::abs(std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]) - 1.0) < 1e-5,
    "the projected origin lies on the sphere");
}

void TestReweighting()
{
  // The bounded fit reweights its neighbours by their distance to the last
  // patch until no weight moves by more than 0.05 (or ReweightingIterations
  // steps): at once on a clean sphere, later where some neighbours lie
  // 1.5 bounds above the surface and the patch moves as they lose weight.
  const std::vector<double> sphere = FibonacciSphere(20000);
  PointIndex index(sphere.data(), 20000);
  const double q[3] = { 0.0, 0.0, 1.0 };
  std::vector<int> ids;
  std::vector<double> d2, clean, dirty;
  index.Nearest(q, 41, ids, d2);
  std::mt19937 gen(5);
  for (size_t j = 0; j < ids.size(); ++j)
  {
    clean.insert(clean.end(), index.Point(ids[j]), index.Point(ids[j]) + 3);
    dirty.insert(dirty.end(), index.Point(ids[j]), index.Point(ids[j]) + 3);
    if (j > 0 && gen() % 100 < 15)
    {
      dirty[3 * j + 2] += 0.02;
    }
  }
  const int n = static_cast<int>(ids.size());
  SplatFitParameters par;
  par.Degree = 2;
  par.FeatureSizeNeighbors = 24;
  par.MaximumDeviation = 0.5;
  const Splat settled = FitSplat(q, clean.data(), n, par);
  // Unit sphere: g ~ -(h / 2)(u^2 + v^2).
  const double curvatureError =
    std::abs(settled.Fit.Coefficients[3] + 0.5 * settled.Frame.Scale) / (0.5 * settled.Frame.Scale);
  std::cout << "reweighting: clean sphere " << settled.Iterations << " step(s), curvature error "
            << curvatureError << "\n";
  Check(settled.Fit.Status == FitStatus::Ok && settled.Iterations == 1 && curvatureError < 0.05,
    "the bounded fit of a clean patch settles after one step");
  par.ReweightingIterations = 1;
  const Splat once = FitSplat(q, clean.data(), n, par);
  Check(once.Iterations == 1 &&
      std::equal(once.Fit.Coefficients, once.Fit.Coefficients + 6, settled.Fit.Coefficients),
    "a settled fit is the fit of its first step");
  par.ReweightingIterations = 4;
  const Splat moving = FitSplat(q, dirty.data(), n, par);
  par.ReweightingIterations = 2;
  const Splat capped = FitSplat(q, dirty.data(), n, par);
  std::cout << "reweighting: outliers " << moving.Iterations << " steps (at most 4), "
            << capped.Iterations << " (at most 2)\n";
  Check(moving.Iterations > 2 && moving.Iterations <= 4 && capped.Iterations == 2,
    "reweighting goes on while the weights move, up to ReweightingIterations");
}

void TestThreadIndependence()
{
  // The parallel selection must not depend on the number of threads, with
  // narrow splats and with wide ones (bounded, MaximumFeatureScale 4: a
  // chosen point's front then sees more free neighbours than it queues).
  const int n = 20000;
  const std::vector<double> base = Torus(n, 9u);
  for (const double scale : { 1.0, 4.0 })
  {
    BuildParameters params;
    params.MaximumFeatureScale = scale;
    params.Fit.MaximumDeviation = scale > 1.0 ? 0.5 : 0.0;
    params.VisitOrder = Order::Front;
    vtkSMPTools::Initialize(1);
    const BuildResult one = BuildSplats(base.data(), n, nullptr, params);
    vtkSMPTools::Initialize(2);
    const BuildResult two = BuildSplats(base.data(), n, nullptr, params);
    bool same = one.Splats.size() == two.Splats.size() && !one.Splats.empty();
    for (size_t i = 0; same && i < one.Splats.size(); ++i)
    {
      same = one.Splats[i].Source == two.Splats[i].Source &&
        one.Splats[i].Fitted.Fit.Coefficients[3] == two.Splats[i].Fitted.Fit.Coefficients[3];
    }
    params.VisitOrder = Order::Random;
    const BuildResult random = BuildSplats(base.data(), n, nullptr, params);
    std::cout << "feature scale " << scale
              << ", Front order, 1 and 2 threads: " << one.Splats.size() << " and "
              << two.Splats.size() << " splats (Random " << random.Splats.size() << ")\n";
    Check(same, "the same splats with 1 and 2 threads");
    Check(one.Splats.size() < random.Splats.size(), "the Front order gives fewer splats");
  }
}

void TestLOP()
{
  // A sphere sampled four times more densely on its northern half. WLOP must
  // even the density out, LOP must stay on the surface.
  std::mt19937 gen(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> p;
  while (p.size() < 3 * 20000)
  {
    double v[3] = { normal(gen), normal(gen), normal(gen) };
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (v[2] < 0 && (gen() % 4) != 0)
    {
      continue;
    }
    p.insert(p.end(), { v[0] / len, v[1] / len, v[2] / len });
  }
  const long long n = static_cast<long long>(p.size() / 3);
  auto spread = [](const std::vector<double>& x)
  {
    // coefficient of variation of nearest-neighbour distances, and radius error
    const long long m = static_cast<long long>(x.size() / 3);
    PointIndex index(x.data(), m);
    std::vector<int> ids;
    std::vector<double> d2;
    double sum = 0, sum2 = 0, radial = 0;
    for (long long i = 0; i < m; ++i)
    {
      index.Nearest(&x[3 * i], 2, ids, d2);
      const double d = std::sqrt(d2[1]);
      sum += d;
      sum2 += d * d;
      radial = std::max(radial,
        std::abs(std::sqrt(x[3 * i] * x[3 * i] + x[3 * i + 1] * x[3 * i + 1] +
                   x[3 * i + 2] * x[3 * i + 2]) -
          1));
    }
    const double mean = sum / m;
    return std::make_pair(std::sqrt(std::max(0.0, sum2 / m - mean * mean)) / mean, radial);
  };
  const long long m = 800;
  std::vector<double> start(3 * m);
  for (long long i = 0; i < m; ++i)
  {
    std::copy(&p[3 * (i * 23 % n)], &p[3 * (i * 23 % n)] + 3, &start[3 * i]);
  }
  const auto before = spread(start);
  for (bool weighted : { false, true })
  {
    std::vector<double> x(start);
    const int steps = LocallyOptimalProjection(p.data(), n, x, weighted, 60);
    const auto after = spread(x);
    std::cout << (weighted ? "WLOP" : "LOP") << ": " << steps << " steps, NN-distance variation "
              << before.first << " -> " << after.first << ", radial error " << after.second << "\n";
    Check(after.first < 0.75 * before.first, "(W)LOP spreads the samples more evenly");
    Check(after.second < 0.02, "(W)LOP keeps the samples on the surface");
  }
}

void TestOctree()
{
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const long long n = 5000;
  std::vector<double> xyz(3 * n), radius(n);
  std::vector<int> level(n);
  for (long long i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      xyz[3 * i + c] = uni(gen);
    }
    radius[i] = 0.01 + 0.02 * (uni(gen) + 1.0);
    level[i] = static_cast<int>(gen() % 5);
  }
  // A few coincident origins must not recurse forever.
  for (long long i = 0; i < 100; ++i)
  {
    std::fill(&xyz[3 * i], &xyz[3 * i] + 3, 0.5);
  }
  const Octree tree = BuildOctree(xyz.data(), radius.data(), level.data(), n, 5, 32);
  bool ok = tree.Nodes[0].Begin == 0 && tree.Nodes[0].End == n;
  std::vector<long long> seen(tree.Order);
  std::sort(seen.begin(), seen.end());
  for (long long i = 0; i < n; ++i)
  {
    ok = ok && seen[i] == i;
  }
  for (size_t id = 0; id < tree.Nodes.size(); ++id)
  {
    const OctreeNode& node = tree.Nodes[id];
    if (node.ChildCount > 0)
    {
      long long next = node.Begin;
      for (int c = 0; c < node.ChildCount; ++c)
      {
        const OctreeNode& child = tree.Nodes[node.FirstChild + c];
        ok = ok && child.Begin == next && child.Depth == node.Depth + 1;
        next = child.End;
      }
      ok = ok && next == node.End;
    }
    else
    {
      for (long long k = node.Begin + 1; k < node.End; ++k)
      {
        ok = ok && level[tree.Order[k - 1]] <= level[tree.Order[k]];
      }
      for (int l = 1; l < 5; ++l)
      {
        ok = ok && tree.LevelEnds[id * 5 + l - 1] <= tree.LevelEnds[id * 5 + l];
      }
      ok = ok && tree.LevelEnds[id * 5 + 4] == node.End;
    }
    for (long long k = node.Begin; k < node.End; ++k)
    {
      const long long i = tree.Order[k];
      double d2 = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        ok = ok && xyz[3 * i + c] - radius[i] >= node.Bounds[2 * c] - 1e-12 &&
          xyz[3 * i + c] + radius[i] <= node.Bounds[2 * c + 1] + 1e-12;
        d2 += (xyz[3 * i + c] - node.Sphere[c]) * (xyz[3 * i + c] - node.Sphere[c]);
      }
      ok = ok && std::sqrt(d2) + radius[i] <= node.Sphere[3] + 1e-12;
    }
  }
  Check(ok, "octree ranges, children, level order, bounds and spheres");
}

void TestErrorMetric()
{
  // One flat splat (z = 0.5 h) and points at known heights above it.
  const double origin[3] = { 0, 0, 0 }, normal[3] = { 0, 0, 1 }, tangent[3] = { 1, 0, 0 };
  const double scale = 2.0, radius = 4.0;
  const double coeffs[3] = { 0.25, 0.0, 0.0 }; // g = 0.25 in units of h: z = 0.5
  SplatArrays s;
  s.Origin = origin;
  s.Normal = normal;
  s.Tangent = tangent;
  s.Scale = &scale;
  s.Radius = &radius;
  s.Coefficients = coeffs;
  s.Degree = 1;
  s.Count = 1;
  const double pts[] = { 1.0, 1.0, 0.5, -2.0, 0.0, 1.5, 0.0, 3.0, -0.25, 10.0, 0.0, 0.5 };
  std::vector<double> delta, distance;
  std::vector<int> covering;
  const ErrorSummary sum = EvaluateSplatError(s, pts, 4, delta, distance, covering);
  Check(std::abs(distance[0]) < 1e-12 && std::abs(distance[1] - 1.0) < 1e-12 &&
      std::abs(distance[2] - 0.75) < 1e-12,
    "distances to a flat splat");
  Check(covering[0] == 1 && covering[3] == 0 && sum.Uncovered == 1,
    "the point outside the disc is uncovered");
  Check(std::abs(sum.Maximum - 1.0) < 1e-12, "maximum distance");
}
void TestOrientation()
{
  // A flipped splat describes the same surface: every point of the original
  // patch lies on the flipped one.
  Splat s;
  s.Frame.Origin[0] = 1.0;
  s.Frame.Origin[1] = -2.0;
  s.Frame.Origin[2] = 0.5;
  const double c = std::cos(0.3), sn = std::sin(0.3);
  const double normal[3] = { 0.0, -sn, c }, tangent[3] = { 1.0, 0.0, 0.0 };
  const double bitangent[3] = { 0.0, c, sn }; // normal x tangent
  std::copy(normal, normal + 3, s.Frame.Normal);
  std::copy(tangent, tangent + 3, s.Frame.Tangent);
  std::copy(bitangent, bitangent + 3, s.Frame.Bitangent);
  s.Frame.Scale = 0.25;
  s.Fit.Degree = 4;
  for (int k = 0; k < MonomialCount(4); ++k)
  {
    s.Fit.Coefficients[k] = 0.1 * std::sin(1.7 * k + 0.4);
  }
  Splat f = s;
  FlipSplat(f);
  double worst = 0.0;
  for (double u = -1.0; u <= 1.0; u += 0.25)
  {
    for (double v = -1.0; v <= 1.0; v += 0.25)
    {
      const double w = Evaluate(s.Fit.Coefficients, 4, u, v);
      double p[3], local[3];
      for (int k = 0; k < 3; ++k)
      {
        p[k] = s.Frame.Origin[k] +
          s.Frame.Scale *
            (u * s.Frame.Tangent[k] + v * s.Frame.Bitangent[k] + w * s.Frame.Normal[k]);
      }
      ToLocal(f.Frame, p, local);
      worst =
        std::max(worst, std::abs(Evaluate(f.Fit.Coefficients, 4, local[0], local[1]) - local[2]));
    }
  }
  Check(worst < 1e-12 && f.Frame.Normal[2] < 0.0, "a flipped splat is the same surface");
  FlipSplat(f);
  bool back = true;
  for (int k = 0; k < MonomialCount(4); ++k)
  {
    back = back && f.Fit.Coefficients[k] == s.Fit.Coefficients[k];
  }
  Check(back, "flipping twice gives the splat back");

  // Fitted without normals, then oriented: outward everywhere.
  auto outward =
    [](const std::vector<Splat*>& splats, const std::function<void(const double*, double*)>& out)
  {
    long long wrong = 0;
    for (const Splat* sp : splats)
    {
      double o[3];
      out(sp->Frame.Origin, o);
      wrong += (o[0] * sp->Frame.Normal[0] + o[1] * sp->Frame.Normal[1] +
                 o[2] * sp->Frame.Normal[2]) < 0.0;
    }
    return wrong;
  };
  BuildParameters params;
  params.Fit.Degree = 2;
  const int n = 6000;
  std::vector<double> two = FibonacciSphere(n);
  for (double v : FibonacciSphere(n))
  {
    two.push_back(v); // a second sphere, moved below: two parts
  }
  for (int i = n; i < 2 * n; ++i)
  {
    two[3 * i] += 5.0;
    two[3 * i + 2] -= 1.0;
  }
  BuildResult spheres = BuildSplats(two.data(), 2 * n, nullptr, params);
  std::vector<Splat*> fitted;
  for (BuiltSplat& b : spheres.Splats)
  {
    fitted.push_back(&b.Fitted);
  }
  auto fromCentre = [](const double* p, double* out)
  {
    const double centre[3] = { p[0] > 2.5 ? 5.0 : 0.0, 0.0, p[0] > 2.5 ? -1.0 : 0.0 };
    for (int k = 0; k < 3; ++k)
    {
      out[k] = p[k] - centre[k];
    }
  };
  const long long before = outward(fitted, fromCentre);
  long long parts = 0;
  const long long flipped = OrientSplats(fitted, 8, &parts);
  const long long after = outward(fitted, fromCentre);
  std::cout << "two spheres: " << fitted.size() << " splats, " << before << " inward before, "
            << flipped << " flipped, " << after << " inward after, " << parts << " parts\n";
  Check(before > 0 && after == 0 && parts == 2, "two spheres' splats all point outward");

  const std::vector<double> torus = Torus(8000, 7u);
  BuildResult ring = BuildSplats(torus.data(), 8000, nullptr, params);
  fitted.clear();
  for (BuiltSplat& b : ring.Splats)
  {
    fitted.push_back(&b.Fitted);
  }
  auto fromTube = [](const double* p, double* out)
  {
    const double rho = std::sqrt(p[0] * p[0] + p[1] * p[1]);
    out[0] = p[0] - 30.0 * p[0] / rho;
    out[1] = p[1] - 30.0 * p[1] / rho;
    out[2] = p[2];
  };
  OrientSplats(fitted, 8, &parts);
  const long long wrong = outward(fitted, fromTube);
  std::cout << "torus: " << fitted.size() << " splats, " << wrong << " inward after, " << parts
            << " parts\n";
  Check(wrong == 0 && parts == 1, "a torus's splats all point outward");

  // A thin plate: the surface of a closed 40 x 12 x 2 box, grid spacing 1,
  // fitted error-bounded as the fitter's defaults do. Its two faces lie two
  // spacings apart, so the neighbour graph joins them, and their
  // antiparallel normals cost nothing by angle alone: the orientation must
  // not cross from one face to the other.
  std::vector<double> plate;
  for (int i = 0; i <= 40; ++i)
  {
    for (int j = 0; j <= 12; ++j)
    {
      for (int k = 0; k <= 2; ++k)
      {
        if (i == 0 || i == 40 || j == 0 || j == 12 || k == 0 || k == 2)
        {
          plate.insert(plate.end(), { double(i), double(j), double(k) });
        }
      }
    }
  }
  BuildParameters bounded;
  bounded.Fit.Degree = 3;
  bounded.Fit.FeatureSizeNeighbors = 24;
  bounded.Fit.MaximumDeviation = 0.5;
  BuildResult box =
    BuildSplats(plate.data(), static_cast<long long>(plate.size() / 3), nullptr, bounded);
  fitted.clear();
  for (BuiltSplat& b : box.Splats)
  {
    fitted.push_back(&b.Fitted);
  }
  OrientSplats(fitted, 8, &parts);
  // Splats on the two large faces, two spacings or more from their rims:
  // outward is -z on the bottom face and +z on the top.
  long long faces = 0, inward = 0;
  for (const Splat* sp : fitted)
  {
    const double* o = sp->Frame.Origin;
    if (o[0] < 2.0 || o[0] > 38.0 || o[1] < 2.0 || o[1] > 10.0)
    {
      continue;
    }
    ++faces;
    inward += (o[2] > 1.0 ? sp->Frame.Normal[2] : -sp->Frame.Normal[2]) < 0.0;
  }
  std::cout << "thin plate: " << fitted.size() << " splats, " << inward << " of " << faces
            << " on its faces inward after, " << parts << " parts\n";
  Check(faces > 100 && inward == 0, "a thin plate's faces point outward, each its own way");

  // Orient built splats as the fitter does: with their discs' radii.
  auto orientBuilt = [&](BuildResult& built)
  {
    fitted.clear();
    std::vector<double> radii;
    for (BuiltSplat& b : built.Splats)
    {
      fitted.push_back(&b.Fitted);
      radii.push_back(b.Radius);
    }
    OrientSplats(fitted, 8, &parts, &radii);
  };
  // Two spheres a point spacing apart: the graph joins them only across the
  // gap, where their outward normals point at each other, so the tree
  // passes the first sphere's sign to the second reversed, and the flux,
  // summed over both, nearly cancels and decides nothing: the second
  // sphere came out inward. Seen from outside, each sphere seeds its own
  // sign; the few splats hidden in the gap follow their sphere. The same
  // near 1e7, where depths in floats from the coordinates' origin would
  // keep no digit of the gap.
  const double gap = std::sqrt(4.0 * 3.14159265358979 / n);
  for (const double offset : { 0.0, 1e7 })
  {
    std::vector<double> touching = FibonacciSphere(n);
    for (double v : FibonacciSphere(n))
    {
      touching.push_back(v);
    }
    for (int i = 0; i < 2 * n; ++i)
    {
      touching[3 * i] += (i < n ? 0.0 : 2.0 + gap) + offset;
      touching[3 * i + 1] += offset;
      touching[3 * i + 2] += offset;
    }
    BuildResult pair = BuildSplats(touching.data(), 2 * n, nullptr, bounded);
    orientBuilt(pair);
    auto fromEither = [gap, offset](const double* p, double* out)
    {
      const double cx = p[0] - offset > 1.0 + 0.5 * gap ? 2.0 + gap : 0.0;
      out[0] = p[0] - offset - cx;
      out[1] = p[1] - offset;
      out[2] = p[2] - offset;
    };
    const long long wrongPair = outward(fitted, fromEither);
    std::cout << "touching spheres at " << offset << ": " << fitted.size() << " splats, "
              << wrongPair << " inward after, " << parts << " parts\n";
    Check(parts == 1 && wrongPair == 0, "two spheres a spacing apart both point outward");
  }

  // A sphere and a small one far away: the depth images span both, so
  // their pixels are far coarser than the discs; such views must give no
  // votes rather than wrong ones (a plane extended from a disc to a pixel's
  // centre many radii off), which seeded and turned patches the tree and
  // the flux had right.
  std::vector<double> lone = FibonacciSphere(n);
  for (double v : FibonacciSphere(400))
  {
    lone.push_back(0.1 * v);
  }
  for (int i = n; i < n + 400; ++i)
  {
    lone[3 * i] += 5000.0;
  }
  BuildResult apart = BuildSplats(lone.data(), n + 400, nullptr, bounded);
  orientBuilt(apart);
  auto fromTheirCentres = [](const double* p, double* out)
  {
    out[0] = p[0] - (p[0] > 2500.0 ? 5000.0 : 0.0);
    out[1] = p[1];
    out[2] = p[2];
  };
  const long long wrongApart = outward(fitted, fromTheirCentres);
  std::cout << "spheres 5000 apart: " << fitted.size() << " splats, " << wrongApart
            << " inward after, " << parts << " parts\n";
  Check(wrongApart == 0 && parts == 2, "spheres far apart point outward");

  // A closed surface whose highest splat faces sideways, a little up (as on
  // the underside of a thin tip): "up" at the seed does not tell out, and
  // the sign it passes on may reach the sphere inward. The part's flux
  // (the sum of (x - c).n over its splats) must turn it outward.
  const std::vector<double> ball = FibonacciSphere(n);
  BuildResult one = BuildSplats(ball.data(), n, nullptr, params);
  fitted.clear();
  for (BuiltSplat& b : one.Splats)
  {
    fitted.push_back(&b.Fitted);
  }
  Splat tip;
  tip.Fit.Degree = 1;
  tip.Fit.Status = FitStatus::Ok;
  tip.Frame.Scale = 0.05;
  const double tipOrigin[3] = { -0.03, 0.0, 1.01 }, tipNormal[3] = { 0.998, 0.0, 0.05 };
  std::copy(tipOrigin, tipOrigin + 3, tip.Frame.Origin);
  std::copy(tipNormal, tipNormal + 3, tip.Frame.Normal);
  tip.Frame.Tangent[2] = 1.0;
  tip.Frame.Bitangent[1] = 1.0;
  std::vector<Splat*> tipped = fitted;
  tipped.push_back(&tip);
  OrientSplats(tipped, 8, &parts);
  auto fromOrigin = [](const double* p, double* out) { std::copy(p, p + 3, out); };
  const long long wrongBall = outward(fitted, fromOrigin);
  std::cout << "sphere under a sideways tip: " << wrongBall << " of " << fitted.size()
            << " inward after, " << parts << " parts\n";
  Check(wrongBall == 0, "a closed surface under a sideways highest splat points outward");
  Check(OrientSplats({}) == 0, "no splats, nothing to orient");
}
} // namespace

// SpatialOrder: a permutation in Morton order, whatever the input's order.
void TestSpatialOrder()
{
  Check(SpatialOrder(nullptr, 0).empty(), "SpatialOrder of no points is empty");
  const double one[3] = { 1e7, -1e7, 3.0 };
  Check(SpatialOrder(one, 1) == std::vector<long long>{ 0 }, "SpatialOrder of one point");
  const std::vector<double> same = { 2, 2, 2, 2, 2, 2, 2, 2, 2 };
  Check(SpatialOrder(same.data(), 3) == std::vector<long long>({ 0, 1, 2 }),
    "coincident points keep their order");
  // A 4 x 4 x 4 grid near 1e7, shuffled: the Z curve visits each 2 x 2 x 2
  // octant whole before the next, x fastest.
  std::vector<std::array<int, 3>> cells;
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        cells.push_back({ x, y, z });
  std::shuffle(cells.begin(), cells.end(), std::mt19937(9));
  std::vector<double> grid;
  for (const auto& c : cells)
  {
    grid.insert(grid.end(), { 1e7 + 0.5 * c[0], 1e7 + 0.5 * c[1], -1e7 + 0.5 * c[2] });
  }
  const std::vector<long long> order = SpatialOrder(grid.data(), 64);
  std::vector<long long> sorted(order);
  std::sort(sorted.begin(), sorted.end());
  bool permutation = true;
  for (long long i = 0; i < 64; ++i)
  {
    permutation = permutation && sorted[i] == i;
  }
  Check(permutation, "SpatialOrder is a permutation");
  bool octants = true, first = true;
  for (size_t k = 0; k < order.size(); ++k)
  {
    const auto& c = cells[order[k]];
    const int octant = (c[0] / 2) | (c[1] / 2) << 1 | (c[2] / 2) << 2;
    octants = octants && octant == static_cast<int>(k / 8);
    if (k < 8)
    {
      const int inner = (c[0] % 2) | (c[1] % 2) << 1 | (c[2] % 2) << 2;
      first = first && inner == static_cast<int>(k);
    }
  }
  Check(octants && first, "SpatialOrder follows the Z curve");
}

// The index against brute force: the k nearest and the points within a
// radius, sorted by (distance, id), on a grid near 1e7 (ties everywhere,
// points exactly on the radius) with duplicates, and the degenerate asks.
void TestPointIndex()
{
  std::vector<double> x;
  for (int z = 0; z < 6; ++z)
    for (int y = 0; y < 6; ++y)
      for (int k = 0; k < 6; ++k)
        x.insert(x.end(), { 1e7 + 0.25 * k, -1e7 + 0.25 * y, 3.0 + 0.25 * z });
  std::mt19937 random(4);
  std::uniform_int_distribution<int> pick(0, 215);
  for (int d = 0; d < 20; ++d)
  {
    const int j = pick(random);
    x.insert(x.end(), { x[3 * j], x[3 * j + 1], x[3 * j + 2] });
  }
  const long long n = static_cast<long long>(x.size() / 3);
  const PointIndex index(x.data(), n);
  auto brute = [&](const double* q)
  {
    std::vector<std::pair<double, int>> all;
    for (long long i = 0; i < n; ++i)
    {
      const double* p = &x[3 * i];
      const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
      all.emplace_back(dx * dx + dy * dy + dz * dz, static_cast<int>(i));
    }
    std::sort(all.begin(), all.end());
    return all;
  };
  bool nearest = true, within = true, unsorted = true;
  std::vector<int> ids;
  std::vector<double> d2;
  for (int t = 0; t < 40; ++t)
  {
    const int j = pick(random);
    // On a point, or between points (at a half-step, on many ties).
    double q[3] = { x[3 * j], x[3 * j + 1], x[3 * j + 2] };
    if (t % 2)
    {
      q[0] += 0.125;
      q[2] -= 0.125;
    }
    const auto all = brute(q);
    for (int k : { 1, 7, 27, 50, 300 })
    {
      index.Nearest(q, k, ids, d2);
      const size_t want = std::min<size_t>(static_cast<size_t>(k), all.size());
      nearest = nearest && ids.size() == want && d2.size() == want;
      for (size_t i = 0; nearest && i < want; ++i)
      {
        nearest = ids[i] == all[i].second && d2[i] == all[i].first;
      }
    }
    for (double r : { 0.25, 0.5, std::sqrt(2.0) * 0.25, 0.6 })
    {
      index.Within(q, r, ids, d2);
      size_t want = 0;
      while (want < all.size() && all[want].first <= r * r)
      {
        ++want;
      }
      within = within && ids.size() == want;
      for (size_t i = 0; within && i < want; ++i)
      {
        within = ids[i] == all[i].second && d2[i] == all[i].first;
      }
      index.Within(q, r, ids, d2, false);
      std::vector<int> got(ids);
      std::sort(got.begin(), got.end());
      std::vector<int> expected;
      for (size_t i = 0; i < want; ++i)
      {
        expected.push_back(all[i].second);
      }
      std::sort(expected.begin(), expected.end());
      unsorted = unsorted && got == expected;
    }
  }
  Check(nearest, "PointIndex::Nearest matches brute force, ties by id, near 1e7");
  Check(within, "PointIndex::Within matches brute force, points on the radius included");
  Check(unsorted, "PointIndex::Within unsorted finds the same points");
  const double q[3] = { 1e7, -1e7, 3.0 };
  index.Nearest(q, 0, ids, d2);
  bool degenerate = ids.empty() && d2.empty();
  index.Within(q, 0.0, ids, d2);
  degenerate = degenerate && ids.empty();
  index.Within(q, std::nan(""), ids, d2);
  degenerate = degenerate && ids.empty();
  const PointIndex empty(nullptr, 0);
  empty.Nearest(q, 5, ids, d2);
  degenerate = degenerate && ids.empty();
  empty.Within(q, 1.0, ids, d2);
  degenerate = degenerate && ids.empty() && empty.Size() == 0;
  Check(degenerate, "PointIndex: k 0, radius 0 or NaN, and an empty index give nothing");
}

int TestSplatFit(int, char*[])
{
  TestPointIndex();
  TestSpatialOrder();
  TestParaboloidThroughKernel();
  TestConvergenceOrder();
  TestInvariance();
  TestThreadIndependence();
  TestFitModes();
  TestReweighting();
  TestLOP();
  TestOctree();
  TestErrorMetric();
  TestOrientation();
  if (Failures)
  {
    std::cerr << Failures << " checks failed\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
