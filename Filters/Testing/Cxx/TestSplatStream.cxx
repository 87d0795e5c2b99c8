// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The streaming fit (psSplatStream.h) against the in-memory one: a sphere
// cut across many chunks keeps the in-memory splat count, every point
// covered, every normal outward, no splat twice; the input's attributes
// arrive at the splats; bad input (NaN, too few points, FixedCount) gives
// an error or an empty result, never a crash.
#include "psFiltersTestSupport.h"
#include "psPolynomial.h"
#include "psSplatBuilder.h"
#include "psSplatError.h"
#include "psSplatStream.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace
{
using namespace pointsurfaces;

// n points on the sphere of radius r about c (a Fibonacci lattice).
std::vector<double> Sphere(long long n, double r, const double c[3])
{
  std::vector<double> p(static_cast<size_t>(3 * n));
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (long long i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const double s = std::sqrt(1.0 - z * z);
    p[3 * i] = c[0] + r * s * std::cos(golden * i);
    p[3 * i + 1] = c[1] + r * s * std::sin(golden * i);
    p[3 * i + 2] = c[2] + r * z;
  }
  return p;
}

BuildParameters Defaults()
{
  // vtkAlgebraicSplatFitter's defaults.
  BuildParameters b;
  b.Fit.Degree = 3;
  b.Fit.FeatureSizeNeighbors = 24;
  b.Fit.MaximumDeviation = 0.5;
  b.VisitOrder = Order::Random;
  return b;
}

struct Streamed
{
  std::vector<StreamedSplat> Splats;
  std::vector<float> Attributes;
  StreamStatistics Stats;
  bool Ok = false;
  std::string Error;
};

Streamed Stream(const std::vector<double>& pts,
  const BuildParameters& build,
  long long chunkPoints,
  const std::vector<float>* normals = nullptr,
  const std::vector<float>* attributes = nullptr,
  int components = 0)
{
  StreamParameters params;
  params.Build = build;
  params.ChunkPoints = chunkPoints;
  SplatStream stream(params, components, normals != nullptr);
  const long long n = static_cast<long long>(pts.size() / 3);
  // In batches, as a reader's pieces come.
  const long long batch = 7001;
  Streamed out;
  out.Ok = true;
  for (long long first = 0; first < n && out.Ok; first += batch)
  {
    const long long count = std::min(batch, n - first);
    out.Ok = stream.AddPoints(&pts[3 * first],
      normals ? &(*normals)[3 * first] : nullptr,
      attributes ? &(*attributes)[components * first] : nullptr,
      count);
  }
  out.Ok = out.Ok && stream.Run();
  out.Ok = out.Ok && stream.ReadSplats(0, stream.NumberOfSplats(), out.Splats, out.Attributes);
  out.Stats = stream.Statistics();
  out.Error = stream.Error();
  return out;
}

long long Uncovered(const std::vector<StreamedSplat>& splats,
  const std::vector<double>& pts,
  int degree)
{
  std::vector<double> origin, normal, tangent, scale, radius, coeffs;
  for (const StreamedSplat& b : splats)
  {
    const LocalFrame& f = b.Fitted.Frame;
    origin.insert(origin.end(), f.Origin, f.Origin + 3);
    normal.insert(normal.end(), f.Normal, f.Normal + 3);
    tangent.insert(tangent.end(), f.Tangent, f.Tangent + 3);
    scale.push_back(f.Scale);
    radius.push_back(b.Radius);
    for (int c = 0; c < MonomialCount(degree); ++c)
    {
      coeffs.push_back(c < MonomialCount(b.Fitted.Fit.Degree) ? b.Fitted.Fit.Coefficients[c] : 0.0);
    }
  }
  SplatArrays arrays;
  arrays.Origin = origin.data();
  arrays.Normal = normal.data();
  arrays.Tangent = tangent.data();
  arrays.Scale = scale.data();
  arrays.Radius = radius.data();
  arrays.Coefficients = coeffs.data();
  arrays.Degree = degree;
  arrays.Count = static_cast<long long>(splats.size());
  std::vector<double> delta, distance;
  std::vector<int> covering;
  return EvaluateSplatError(
    arrays, pts.data(), static_cast<long long>(pts.size() / 3), delta, distance, covering)
    .Uncovered;
}

long long Inward(const std::vector<StreamedSplat>& splats, const double c[3])
{
  long long inward = 0;
  for (const StreamedSplat& b : splats)
  {
    const LocalFrame& f = b.Fitted.Frame;
    double along = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      along += (f.Origin[k] - c[k]) * f.Normal[k];
    }
    inward += along < 0.0 ? 1 : 0;
  }
  return inward;
}

bool Distinct(const std::vector<StreamedSplat>& splats, long long n)
{
  std::set<long long> seen;
  for (const StreamedSplat& b : splats)
  {
    if (b.Source < 0 || b.Source >= n || !seen.insert(b.Source).second)
    {
      return false;
    }
  }
  return true;
}

void CompareWithInMemory(const char* name, const double centre[3], int levels)
{
  const long long n = 40000;
  const std::vector<double> pts = Sphere(n, 1.0, centre);
  BuildParameters build = Defaults();
  build.Levels = levels;
  build.CoarsestQuality = 4.0;
  const BuildResult memory = BuildSplats(pts.data(), n, nullptr, build);
  // About 5000 points a chunk: the 64^3 grid's octree cuts the sphere into
  // a dozen chunks or more, every splat near some border.
  const Streamed s = Stream(pts, build, 5000);
  const double ratio =
    static_cast<double>(s.Splats.size()) / std::max<size_t>(1, memory.Splats.size());
  std::cout << name << ": in memory " << memory.Splats.size() << " splats, streamed "
            << s.Splats.size() << " (" << ratio << "x) over " << s.Stats.Chunks
            << " chunks, largest " << s.Stats.LargestChunk << " points with its halo, "
            << s.Stats.HaloPoints << " halo points in all, " << s.Stats.Parts
            << " oriented parts\n";
  const std::string tag = std::string(name) + ": ";
  Check(s.Ok, (tag + "the stream runs (" + s.Error + ")").c_str());
  Check(s.Stats.Chunks >= 8, (tag + "the sphere is cut across 8 chunks or more").c_str());
  Check(s.Stats.HaloPoints > 0, (tag + "chunks see their neighbours' points").c_str());
  Check(std::abs(ratio - 1.0) <= 0.03,
    (tag + "the streamed count is within 3 % of the in-memory one").c_str());
  Check(Distinct(s.Splats, n), (tag + "no point grows two splats").c_str());
  Check(Uncovered(s.Splats, pts, build.Fit.Degree) == 0,
    (tag + "no point is left uncovered at the chunks' borders").c_str());
  Check(Inward(s.Splats, centre) == 0, (tag + "every normal faces outward").c_str());
  Check(s.Stats.Parts == 1, (tag + "the parts of the chunks join into one").c_str());
  for (int l = 0; l < levels; ++l)
  {
    long long a = 0, b = 0;
    for (const BuiltSplat& m : memory.Splats)
    {
      a += m.Level == l ? 1 : 0;
    }
    for (const StreamedSplat& m : s.Splats)
    {
      b += m.Level == l ? 1 : 0;
    }
    std::cout << "  level " << l << ": " << a << " in memory, " << b << " streamed\n";
    Check(std::abs(static_cast<double>(b) / std::max(1LL, a) - 1.0) <= 0.05,
      (tag + "each level's count is within 5 % of the in-memory one").c_str());
  }
}

void InputNormalsAndAttributes()
{
  const double centre[3] = { 0.0, 0.0, 0.0 };
  const long long n = 20000;
  const std::vector<double> pts = Sphere(n, 1.0, centre);
  std::vector<float> normals(pts.begin(), pts.end()), attributes(static_cast<size_t>(2 * n));
  for (long long i = 0; i < n; ++i)
  {
    attributes[2 * i] = static_cast<float>(pts[3 * i + 2]); // z
    attributes[2 * i + 1] = 7.0f;                           // a constant
  }
  const Streamed s = Stream(pts, Defaults(), 3000, &normals, &attributes, 2);
  Check(s.Ok, "normals: the stream runs");
  Check(Inward(s.Splats, centre) == 0, "normals: input normals orient every splat outward");
  double worst = 0.0, constant = 0.0;
  for (size_t k = 0; k < s.Splats.size(); ++k)
  {
    worst = std::max(worst, std::abs(s.Attributes[2 * k] - s.Splats[k].Fitted.Frame.Origin[2]));
    constant = std::max(constant, std::abs(s.Attributes[2 * k + 1] - 7.0));
  }
  std::cout << "attributes: largest |z carried - z of the origin| " << worst << ", constant off by "
            << constant << "\n";
  Check(s.Attributes.size() == 2 * s.Splats.size(), "attributes: two components a splat");
  Check(worst < 0.05, "attributes: a point's z arrives MLS-weighted at its splat");
  Check(constant < 1e-5, "attributes: a constant stays constant");
}

void BadInput()
{
  const double centre[3] = { 0.0, 0.0, 0.0 };
  std::vector<double> pts = Sphere(5000, 1.0, centre);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  pts[0] = nan;
  pts[301] = std::numeric_limits<double>::infinity();
  const Streamed s = Stream(pts, Defaults(), 1000);
  Check(s.Ok && s.Stats.Dropped == 2, "NaN and inf points are dropped and counted");
  Check(!s.Splats.empty(), "the finite points are fitted");

  const Streamed none = Stream({}, Defaults(), 1000);
  Check(none.Ok && none.Splats.empty(), "no point: no splat, no error");
  const Streamed two = Stream({ 0, 0, 0, 1, 0, 0 }, Defaults(), 1000);
  Check(two.Ok && two.Splats.empty(), "two points: no splat, no error");
  const Streamed same = Stream(std::vector<double>(3000, 2.5), Defaults(), 1000);
  Check(same.Ok && same.Splats.empty() && same.Stats.Merged > 0,
    "a thousand copies of one point: merged, no splat");

  BuildParameters lop = Defaults();
  lop.Select = Selection::FixedCount;
  const Streamed refused = Stream(pts, lop, 1000);
  Check(!refused.Ok && refused.Error.find("FixedCount") != std::string::npos,
    "FixedCount is refused with a clear error");
  std::cout << "FixedCount: " << refused.Error << "\n";

  StreamParameters nowhere;
  nowhere.ScratchDirectory = "/nonexistent/scratch";
  SplatStream lost(nowhere, 0, false);
  Check(!lost.AddPoints(pts.data(), nullptr, nullptr, 10) && !lost.Run() &&
      lost.Error().find("/nonexistent/scratch") != std::string::npos,
    "a scratch directory that cannot be made is a clear error");
  std::cout << "scratch: " << lost.Error() << "\n";
}
} // namespace

int TestSplatStream(int, char*[])
{
  const double origin[3] = { 0.0, 0.0, 0.0 };
  CompareWithInMemory("sphere", origin, 1);
  CompareWithInMemory("sphere, 3 levels", origin, 3);
  const double far[3] = { 1e7, -2e7, 3e6 };
  CompareWithInMemory("sphere near 1e7", far, 1);
  InputNormalsAndAttributes();
  BadInput();
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
