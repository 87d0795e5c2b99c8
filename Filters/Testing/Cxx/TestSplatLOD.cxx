// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the view-dependent selection over the splat octree
// (psSplatLOD), without GL: every splat is drawn once when nothing is
// culled; culling keeps every splat whose patch can reach into the frustum
// (checked splat by splat against the exact planes) and drops whole nodes
// that cannot; continuous LOD picks the coarsest level whose splats are
// small enough on screen, nearer leaves get finer levels, and parallel
// projection and a model matrix are honoured; an octree that the data
// model's checks reject is never used.
#include "psFiltersTestSupport.h"
#include "psOctree.h"
#include "psSplatLOD.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSplatDataModel.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <vector>

using namespace pointsurfaces;

namespace
{

// Splats in the unit cube [-1, 1]^3, radius s_l * 0.02 at level l.
struct Set
{
  std::vector<double> XYZ, Radius;
  std::vector<int> Level;
  std::vector<double> Quality{ 4.0, 2.0, 1.0 };
  LODOctree Tree;
};

Set MakeSet(long long n)
{
  Set set;
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  set.XYZ.resize(3 * n);
  set.Radius.resize(n);
  set.Level.resize(n);
  for (long long i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      set.XYZ[3 * i + c] = uni(gen);
    }
    set.Level[i] = static_cast<int>(gen() % 3);
    set.Radius[i] = 0.02 * set.Quality[set.Level[i]];
  }
  Octree tree =
    BuildOctree(set.XYZ.data(), set.Radius.data(), set.Level.data(), n, 3, /*bucket=*/16);
  // Radii and levels in the tree's order, as the fitter stores them.
  std::vector<double> radius(n);
  std::vector<int> level(n);
  for (long long k = 0; k < n; ++k)
  {
    radius[k] = set.Radius[tree.Order[k]];
    level[k] = set.Level[tree.Order[k]];
  }
  std::vector<double> xyz(3 * n);
  for (long long k = 0; k < n; ++k)
  {
    for (int c = 0; c < 3; ++c)
    {
      xyz[3 * k + c] = set.XYZ[3 * tree.Order[k] + c];
    }
  }
  set.XYZ = xyz;
  set.Radius = radius;
  set.Level = level;
  set.Tree = MakeLODOctree(tree, set.Quality, radius.data(), level.data());
  return set;
}

// A camera on the +z axis looking down -z at distance `d`: planes of a
// symmetric frustum with half angle `half` (radians), near 0.1, far 100.
LODView Camera(double d, double half)
{
  LODView view;
  const double c = std::cos(half), s = std::sin(half);
  // left, right, bottom, top: normals pointing inwards, through the eye.
  const double normals[4][3] = { { c, 0, -s }, { -c, 0, -s }, { 0, c, -s }, { 0, -c, -s } };
  for (int p = 0; p < 4; ++p)
  {
    for (int k = 0; k < 3; ++k)
    {
      view.Planes[4 * p + k] = normals[p][k];
    }
    view.Planes[4 * p + 3] = -normals[p][2] * d;
  }
  // near: z <= d - 0.1; far: z >= d - 100.
  const double rest[2][4] = { { 0, 0, -1, d - 0.1 }, { 0, 0, 1, -(d - 100.0) } };
  for (int p = 0; p < 2; ++p)
  {
    for (int k = 0; k < 4; ++k)
    {
      view.Planes[16 + 4 * p + k] = rest[p][k];
    }
  }
  view.Eye[2] = d;
  view.TanHalfAngle = std::tan(half);
  view.ViewportHeight = 500;
  return view;
}

void TestEverySplatOnce(const Set& set)
{
  LODView view = Camera(5.0, 0.5);
  view.Cull = false;
  const auto ranges = SelectDrawRanges(set.Tree, view);
  const long long n = static_cast<long long>(set.Radius.size());
  std::vector<int> drawn(n, 0);
  for (const DrawRange& r : ranges)
  {
    Check(r.Level == set.Tree.Tree.Levels - 1 && r.Quality == 1.0, "no LOD: the finest level");
    const bool leaf = r.Node >= 0 && r.Node < static_cast<int>(set.Tree.Tree.Nodes.size()) &&
      set.Tree.Tree.Nodes[r.Node].ChildCount == 0 && set.Tree.Tree.Nodes[r.Node].Begin == r.Begin;
    Check(leaf, "a range names the leaf it starts");
    for (long long k = r.Begin; k < r.End; ++k)
    {
      ++drawn[k];
    }
  }
  bool once = true;
  for (long long k = 0; k < n; ++k)
  {
    once = once && drawn[k] == 1;
  }
  Check(once, "without culling or LOD every splat is drawn exactly once");
}

void TestCulling(const Set& set)
{
  // Narrow view: a quarter of the cube's width at distance 3.
  const LODView view = Camera(3.0, 0.08);
  const auto ranges = SelectDrawRanges(set.Tree, view);
  const long long n = static_cast<long long>(set.Radius.size());
  std::vector<int> drawn(n, 0);
  long long count = 0;
  for (const DrawRange& r : ranges)
  {
    for (long long k = r.Begin; k < r.End; ++k)
    {
      ++drawn[k];
      ++count;
    }
  }
  // Every splat whose bounding sphere (origin, sqrt(2) R) meets the frustum is drawn.
  long long missing = 0, visible = 0;
  for (long long k = 0; k < n; ++k)
  {
    bool inside = true;
    for (int p = 0; p < 6; ++p)
    {
      const double* e = view.Planes + 4 * p;
      inside = inside &&
        e[0] * set.XYZ[3 * k] + e[1] * set.XYZ[3 * k + 1] + e[2] * set.XYZ[3 * k + 2] + e[3] >=
          -std::sqrt(2.0) * set.Radius[k];
    }
    visible += inside ? 1 : 0;
    missing += inside && drawn[k] != 1 ? 1 : 0;
  }
  std::cout << "culling: " << visible << " splats reach into the view, " << count << " of " << n
            << " drawn\n";
  Check(missing == 0, "culling keeps every splat that reaches into the frustum");
  Check(count < n / 2, "culling drops most of the splats outside a narrow view");
  LODView open = view;
  open.Cull = false;
  long long all = 0;
  for (const DrawRange& r : SelectDrawRanges(set.Tree, open))
  {
    all += r.End - r.Begin;
  }
  Check(all == n, "Cull off draws everything");
}

void TestLevels(const Set& set)
{
  // Splats at level l are 2 s_l 0.02 across; pixels per unit at distance d
  // are 500 / (2 d tan(half)).
  LODView view = Camera(30.0, 0.5);
  view.Cull = false;
  view.PixelError = 1e6;
  for (const DrawRange& r : SelectDrawRanges(set.Tree, view))
  {
    Check(r.Level == 0 && r.Quality == 4.0, "a huge pixel error draws the coarsest level");
  }
  view.PixelError = 1e-6;
  for (const DrawRange& r : SelectDrawRanges(set.Tree, view))
  {
    Check(r.Level == 2, "a tiny pixel error draws every level");
  }
  // Between: the level chosen is the coarsest whose splats are small enough,
  // computed here from the leaf's own numbers.
  view.PixelError = 2.0;
  long long leaves = 0, wrong = 0;
  double sum = 0.0;
  for (const DrawRange& r : SelectDrawRanges(set.Tree, view))
  {
    // Find the leaf of this range.
    for (size_t id = 0; id < set.Tree.Tree.Nodes.size(); ++id)
    {
      const OctreeNode& node = set.Tree.Tree.Nodes[id];
      if (node.ChildCount == 0 && node.Begin == r.Begin && node.End > node.Begin)
      {
        const double* c = node.Sphere;
        const double d =
          std::sqrt(c[0] * c[0] + c[1] * c[1] + (c[2] - 30.0) * (c[2] - 30.0)) - set.Tree.Reach[id];
        const double ppu = 500.0 / (2.0 * d * std::tan(0.5));
        int expected = 2;
        for (int l = 0; l < 3; ++l)
        {
          if (2.0 * set.Quality[l] * set.Tree.MeanScale[id] * ppu <= 2.0)
          {
            expected = l;
            break;
          }
        }
        wrong += expected != r.Level ? 1 : 0;
        sum += r.Level;
        ++leaves;
      }
    }
  }
  std::cout << "LOD at 2 px: " << leaves << " leaves, mean level " << sum / std::max(1LL, leaves)
            << "\n";
  Check(leaves > 0 && wrong == 0, "each leaf draws the coarsest level small enough on screen");
  // Nearer is finer: the mean level rises when the camera comes closer.
  LODView near = Camera(3.0, 0.5);
  near.Cull = false;
  near.PixelError = 2.0;
  double nearSum = 0.0;
  long long nearLeaves = 0;
  for (const DrawRange& r : SelectDrawRanges(set.Tree, near))
  {
    nearSum += r.Level;
    ++nearLeaves;
  }
  Check(nearSum / std::max(1LL, nearLeaves) > sum / std::max(1LL, leaves),
    "a nearer camera draws finer levels");
  // Parallel projection: pixels per unit = 500 / (2 scale), no distance.
  LODView parallel = view;
  parallel.Parallel = true;
  parallel.ParallelScale = 0.5 * 500.0 * 2.0 * 4.0 * 0.02 / 1.5; // level 0 is 1.5 px
  for (const DrawRange& r : SelectDrawRanges(set.Tree, parallel))
  {
    Check(r.Level == 0, "parallel: the level follows the parallel scale only");
  }
  // A model matrix that scales by 10 makes the splats ten times larger on
  // screen: finer levels than without it.
  LODView scaled = view;
  scaled.ModelIsIdentity = false;
  const double m[16] = { 10, 0, 0, 0, 0, 10, 0, 0, 0, 0, 10, 0, 0, 0, 0, 1 };
  std::copy(m, m + 16, scaled.ModelToWorld);
  double scaledSum = 0.0;
  long long scaledLeaves = 0;
  for (const DrawRange& r : SelectDrawRanges(set.Tree, scaled))
  {
    scaledSum += r.Level;
    ++scaledLeaves;
  }
  Check(scaledSum / std::max(1LL, scaledLeaves) > sum / std::max(1LL, leaves),
    "a model scale of 10 draws finer levels");
  // A translated model moves the culling with it.
  LODView moved = Camera(3.0, 0.08);
  moved.ModelIsIdentity = false;
  const double t[16] = { 1, 0, 0, 100, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  std::copy(t, t + 16, moved.ModelToWorld);
  Check(SelectDrawRanges(set.Tree, moved).empty(), "a model moved out of view draws nothing");
}

void TestDataModelChecks(const Set& set)
{
  // The octree survives the field data round trip, and is refused once the
  // points move or their count changes.
  const long long n = static_cast<long long>(set.Radius.size());
  vtkNew<vtkPolyData> pd;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkDoubleArray> radius;
  radius->SetName(vtkSplatDataModel::RadiusName());
  radius->SetNumberOfTuples(n);
  vtkNew<vtkDoubleArray> lod;
  lod->SetName(vtkSplatDataModel::LODName());
  lod->SetNumberOfTuples(n);
  for (long long k = 0; k < n; ++k)
  {
    points->SetPoint(k, &set.XYZ[3 * k]);
    radius->SetValue(k, set.Radius[k]);
    lod->SetValue(k, set.Level[k]);
  }
  pd->SetPoints(points);
  pd->GetPointData()->AddArray(radius);
  pd->GetPointData()->AddArray(lod);
  Octree tree;
  std::vector<double> quality;
  Check(vtkSplatDataModel::GetOctree(pd, tree, quality) == vtkSplatDataModel::NoOctree,
    "no octree arrays: NoOctree");
  vtkSplatDataModel::AddOctree(pd, set.Tree.Tree);
  vtkNew<vtkDoubleArray> levels;
  levels->SetName(vtkSplatDataModel::LODQualityName());
  for (double s : set.Quality)
  {
    levels->InsertNextValue(s);
  }
  pd->GetFieldData()->AddArray(levels);
  Check(vtkSplatDataModel::GetOctree(pd, tree, quality) == vtkSplatDataModel::ValidOctree,
    "the stored octree reads back");
  bool same = tree.Nodes.size() == set.Tree.Tree.Nodes.size() && quality == set.Quality &&
    tree.LevelEnds == set.Tree.Tree.LevelEnds && tree.Levels == set.Tree.Tree.Levels;
  for (size_t i = 0; same && i < tree.Nodes.size(); ++i)
  {
    const OctreeNode& a = tree.Nodes[i];
    const OctreeNode& b = set.Tree.Tree.Nodes[i];
    same = a.Begin == b.Begin && a.End == b.End && a.FirstChild == b.FirstChild &&
      a.ChildCount == b.ChildCount && a.Sphere[3] == b.Sphere[3] && a.Bounds[1] == b.Bounds[1];
  }
  Check(same, "the octree reads back unchanged");
  points->SetPoint(0, 50.0, 0.0, 0.0);
  Check(vtkSplatDataModel::GetOctree(pd, tree, quality) == vtkSplatDataModel::MovedSplats,
    "a moved splat: MovedSplats");
  points->SetPoint(0, &set.XYZ[0]);
  lod->SetValue(3, 7.0);
  Check(vtkSplatDataModel::GetOctree(pd, tree, quality) == vtkSplatDataModel::StaleIndex,
    "a level beyond the octree's: StaleIndex");
  lod->SetValue(3, set.Level[3]);
  // Two splats of different leaves swapped, with their arrays: the ranges
  // still look valid, but the leaves no longer hold their splats.
  // Splat `from` of the set at position `at`.
  auto place = [&](vtkIdType at, vtkIdType from)
  {
    points->SetPoint(at, &set.XYZ[3 * from]);
    radius->SetValue(at, set.Radius[from]);
    lod->SetValue(at, set.Level[from]);
  };
  place(0, n - 1);
  place(n - 1, 0);
  Check(vtkSplatDataModel::GetOctree(pd, tree, quality) == vtkSplatDataModel::StaleIndex,
    "two splats of different leaves swapped (reordered): StaleIndex");
  place(0, 0);
  place(n - 1, n - 1);
  Check(vtkSplatDataModel::GetOctree(pd, tree, quality) == vtkSplatDataModel::ValidOctree,
    "swapped back: ValidOctree");
  points->SetNumberOfPoints(n - 1);
  radius->SetNumberOfTuples(n - 1);
  lod->SetNumberOfTuples(n - 1);
  Check(vtkSplatDataModel::GetOctree(pd, tree, quality) == vtkSplatDataModel::StaleIndex,
    "a splat removed: StaleIndex");
}
} // namespace

int TestSplatLOD(int, char*[])
{
  const Set set = MakeSet(4000);
  TestEverySplatOnce(set);
  TestCulling(set);
  TestLevels(set);
  TestDataModelChecks(set);
  Check(SelectDrawRanges(LODOctree(), LODView()).empty(), "an empty octree draws nothing");
  if (Failures)
  {
    std::cerr << Failures << " checks failed\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
