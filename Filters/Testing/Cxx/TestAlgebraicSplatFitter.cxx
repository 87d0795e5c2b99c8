// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkAlgebraicSplatFitter and vtkSplatErrorMetric as pipeline filters: the
// output data model, attribute carry-over, determinism, levels, octree,
// fixed-count selection, and every kind of bad input (each must warn, give a
// valid output and never NaN).
#include "vtkAlgebraicSplatFitter.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkMultiResolutionSplatBuilder.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSplatErrorMetric.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace
{
int Failures = 0;
void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++Failures;
  }
}

vtkSmartPointer<vtkPolyData> Sphere(int n, double offset = 0.0)
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> temperature, normals;
  temperature->SetName("Temperature");
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("RGB");
  rgb->SetNumberOfComponents(3);
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), t = golden * i;
    const double p[3] = { r * std::cos(t), r * std::sin(t), z };
    pts->InsertNextPoint(p[0] + offset, p[1] + offset, p[2] + offset);
    temperature->InsertNextValue(z);
    normals->InsertNextTuple(p);
    const unsigned char c[3] = { static_cast<unsigned char>(z > 0 ? 200 : 50), 100, 30 };
    rgb->InsertNextTypedTuple(c);
  }
  pd->SetPoints(pts);
  pd->GetPointData()->AddArray(temperature);
  pd->GetPointData()->SetNormals(normals);
  pd->GetPointData()->SetScalars(rgb);
  return pd;
}

bool AllFinite(vtkDataArray* a)
{
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    if (!std::isfinite(
          a->GetComponent(i / a->GetNumberOfComponents(), i % a->GetNumberOfComponents())))
    {
      return false;
    }
  }
  return true;
}

// Run the fitter on `input`; expect a warning containing `warning` (if not empty).
vtkSmartPointer<vtkPolyData> Fit(vtkPolyData* input,
  const std::string& warning,
  int degree = 2,
  int neighbors = 40)
{
  vtkNew<vtkAlgebraicSplatFitter> fitter;
  vtkNew<vtkTest::ErrorObserver> observer;
  fitter->AddObserver(vtkCommand::WarningEvent, observer);
  fitter->AddObserver(vtkCommand::ErrorEvent, observer);
  fitter->SetInputData(input);
  fitter->SetDegree(degree);
  fitter->SetNumberOfNeighbors(neighbors);
  fitter->Update();
  vtkPolyData* out = fitter->GetOutput();
  Check(!observer->GetError(), "no error for " + warning);
  if (!warning.empty())
  {
    Check(
      observer->GetWarning() && observer->GetWarningMessage().find(warning) != std::string::npos,
      "a warning about '" + warning + "', got '" + observer->GetWarningMessage() + "'");
  }
  vtkDataArray* coeffs = out->GetPointData()->GetArray("SplatCoefficients");
  Check(coeffs && AllFinite(coeffs), "finite coefficients after '" + warning + "'");
  Check(out->GetFieldData()->GetArray("SplatDegree") != nullptr, "SplatDegree is always present");
  return out;
}

void TestDataModel()
{
  auto sphere = Sphere(6000);
  vtkNew<vtkAlgebraicSplatFitter> fitter;
  fitter->SetInputData(sphere);
  fitter->SetDegree(3);
  fitter->Update();
  vtkPolyData* out = fitter->GetOutput();
  const vtkIdType n = out->GetNumberOfPoints();
  std::cout << "sphere: " << n << " splats of 6000 points\n";
  Check(n > 50 && n < 1000, "quality selection decimates");
  Check(out->GetNumberOfVerts() == n, "one vertex per splat");
  vtkPointData* pd = out->GetPointData();
  const std::pair<const char*, int> arrays[] = { { "SplatNormal", 3 },
    { "SplatTangent", 3 },
    { "SplatFeatureSize", 1 },
    { "SplatCoefficients", 10 },
    { "SplatRadius", 1 },
    { "SplatLOD", 1 },
    { "Temperature", 1 },
    { "RGB", 3 },
    { "Normals", 3 } };
  for (const auto& a : arrays)
  {
    Check(pd->GetArray(a.first) && pd->GetArray(a.first)->GetNumberOfComponents() == a.second &&
        pd->GetArray(a.first)->GetNumberOfTuples() == n,
      std::string("array ") + a.first);
  }
  Check(pd->GetArray("RGB") && pd->GetArray("RGB")->GetDataType() == VTK_UNSIGNED_CHAR,
    "colours keep their type");
  Check(out->GetFieldData()->GetArray("SplatDegree")->GetTuple1(0) == 3, "SplatDegree");
  double worstT = 0.0, worstN = 2.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double o[3], nrm[3];
    out->GetPoint(i, o);
    pd->GetArray("SplatNormal")->GetTuple(i, nrm);
    worstT = std::max(worstT, std::abs(pd->GetArray("Temperature")->GetTuple1(i) - o[2]));
    worstN = std::min(worstN, nrm[0] * o[0] + nrm[1] * o[1] + nrm[2] * o[2]);
  }
  Check(worstT < 0.02, "Temperature (= z) carried over by weighted averaging");
  Check(worstN > 0.99, "splat normals follow the input normals");

  // The same seed gives the same splats; another seed other ones.
  vtkNew<vtkAlgebraicSplatFitter> again;
  again->SetInputData(sphere);
  again->SetDegree(3);
  again->Update();
  bool same = again->GetOutput()->GetNumberOfPoints() == n;
  for (vtkIdType i = 0; same && i < n; ++i)
  {
    double a[3], b[3];
    out->GetPoint(i, a);
    again->GetOutput()->GetPoint(i, b);
    same = a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
  }
  Check(same, "deterministic under a seed");
  again->SetRandomSeed(99);
  again->Update();
  double a[3], b[3];
  out->GetPoint(0, a);
  again->GetOutput()->GetPoint(0, b);
  Check(a[0] != b[0] || a[1] != b[1], "another seed, another selection");

  // The Front order needs fewer splats than Random.
  fitter->SetSelectionOrder(vtkAlgebraicSplatFitter::Front);
  fitter->Update();
  std::cout << "front order: " << fitter->GetOutput()->GetNumberOfPoints() << " splats\n";
  Check(fitter->GetOutput()->GetNumberOfPoints() < n, "the Front order gives fewer splats");

  // The error metric on the same points.
  vtkNew<vtkSplatErrorMetric> metric;
  metric->SetInputData(sphere);
  metric->SetSplatConnection(fitter->GetOutputPort());
  metric->Update();
  std::cout << "error: RMS " << metric->GetRMSDistance() << ", max " << metric->GetMaximumDistance()
            << ", uncovered " << metric->GetNumberOfUncoveredPoints() << "\n";
  Check(metric->GetRMSDistance() < 1e-4 && metric->GetMaximumDistance() < 1e-3,
    "cubic splats lie on the unit sphere");
  Check(metric->GetNumberOfUncoveredPoints() == 0, "no holes at s = 1");
  Check(metric->GetOutput()->GetPointData()->GetArray("SurfaceDistance") != nullptr &&
      metric->GetOutput()->GetFieldData()->GetArray("SplatErrorPhi") != nullptr,
    "error arrays");
}

void TestLevelsAndOctree()
{
  auto sphere = Sphere(8000);
  vtkNew<vtkAlgebraicSplatFitter> coarse;
  coarse->SetInputData(sphere);
  coarse->SetQualityFactor(3.0);
  coarse->Update();
  vtkNew<vtkAlgebraicSplatFitter> fitter;
  fitter->SetInputData(sphere);
  fitter->SetNumberOfLevels(5);
  fitter->SetCoarsestQualityFactor(3.0);
  fitter->SetQualityFactor(1.0);
  fitter->SetOctreeBucketSize(32);
  fitter->Update();
  vtkPolyData* out = fitter->GetOutput();
  vtkDataArray* lod = out->GetPointData()->GetArray("SplatLOD");
  vtkIdType level0 = 0;
  int maxLevel = 0;
  for (vtkIdType i = 0; i < lod->GetNumberOfTuples(); ++i)
  {
    level0 += lod->GetTuple1(i) == 0 ? 1 : 0;
    maxLevel = std::max(maxLevel, static_cast<int>(lod->GetTuple1(i)));
  }
  std::cout << "levels: " << level0 << " splats at level 0, " << out->GetNumberOfPoints()
            << " in all\n";
  Check(level0 == coarse->GetOutput()->GetNumberOfPoints(), "level 0 is the s_0 representation");
  Check(maxLevel == 4 && out->GetNumberOfPoints() > 2 * level0, "finer levels add splats");

  vtkFieldData* fd = out->GetFieldData();
  auto* range = vtkIdTypeArray::SafeDownCast(fd->GetArray("OctreeNodeRange"));
  auto* children = vtkIdTypeArray::SafeDownCast(fd->GetArray("OctreeNodeChildren"));
  auto* ends = vtkIdTypeArray::SafeDownCast(fd->GetArray("OctreeNodeLevelEnds"));
  bool ok = range && children && ends && fd->GetArray("OctreeNodeBounds") &&
    fd->GetArray("OctreeNodeSphere") && ends->GetNumberOfComponents() == 5 &&
    range->GetTypedComponent(0, 0) == 0 &&
    range->GetTypedComponent(0, 1) == out->GetNumberOfPoints();
  for (vtkIdType id = 0; ok && id < range->GetNumberOfTuples(); ++id)
  {
    if (children->GetTypedComponent(id, 1) == 0)
    {
      for (vtkIdType k = range->GetTypedComponent(id, 0) + 1; k < range->GetTypedComponent(id, 1);
           ++k)
      {
        ok = ok && lod->GetTuple1(k - 1) <= lod->GetTuple1(k);
      }
      ok = ok && ends->GetTypedComponent(id, 4) == range->GetTypedComponent(id, 1);
    }
  }
  Check(ok, "octree node arrays, leaves sorted by level");

  // The multi-resolution builder: 25 levels from s_0 = 4 by default.
  vtkNew<vtkMultiResolutionSplatBuilder> builder;
  builder->SetInputData(sphere);
  builder->Update();
  vtkNew<vtkAlgebraicSplatFitter> s0;
  s0->SetInputData(sphere);
  s0->SetQualityFactor(4.0);
  // Level l's error bound is MaximumDeviation s_l / s: 4 times the finest's at s_0 = 4.
  s0->SetMaximumDeviation(4.0 * builder->GetMaximumDeviation());
  s0->Update();
  vtkDataArray* levels = builder->GetOutput()->GetFieldData()->GetArray("SplatLODQuality");
  vtkDataArray* tags = builder->GetOutput()->GetPointData()->GetArray("SplatLOD");
  vtkIdType first = 0;
  for (vtkIdType i = 0; i < tags->GetNumberOfTuples(); ++i)
  {
    first += tags->GetTuple1(i) == 0 ? 1 : 0;
  }
  Check(levels && levels->GetNumberOfTuples() == 25 && levels->GetTuple1(0) == 4.0 &&
      levels->GetTuple1(24) == 1.0,
    "25 levels from s = 4 to s = 1");
  Check(first == s0->GetOutput()->GetNumberOfPoints(), "the builder's level 0 is the s = 4 set");
}

// The splats do not depend on the order of the input points (the fitter
// sorts them spatially first): a shuffled sphere gives the same splats, and
// the same attributes on them.
void TestInputOrder()
{
  auto sphere = Sphere(6000);
  const vtkIdType n = sphere->GetNumberOfPoints();
  std::vector<vtkIdType> perm(static_cast<size_t>(n));
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(3));
  auto shuffled = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  shuffled->GetPointData()->CopyAllocate(sphere->GetPointData(), n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    pts->InsertNextPoint(sphere->GetPoint(perm[i]));
    shuffled->GetPointData()->CopyData(sphere->GetPointData(), perm[i], i);
  }
  shuffled->SetPoints(pts);
  for (double scale : { 1.0, 4.0 })
  {
    // Each splat's origin and Temperature, sorted.
    std::vector<std::array<double, 4>> found[2];
    int which = 0;
    for (vtkPolyData* input : { sphere.GetPointer(), shuffled.GetPointer() })
    {
      vtkNew<vtkAlgebraicSplatFitter> fitter;
      fitter->SetInputData(input);
      fitter->SetDegree(3);
      fitter->SetMaximumFeatureScale(scale);
      fitter->Update();
      vtkPolyData* out = fitter->GetOutput();
      vtkDataArray* temperature = out->GetPointData()->GetArray("Temperature");
      for (vtkIdType i = 0; temperature && i < out->GetNumberOfPoints(); ++i)
      {
        const double* p = out->GetPoint(i);
        found[which].push_back({ p[0], p[1], p[2], temperature->GetTuple1(i) });
      }
      std::sort(found[which].begin(), found[which].end());
      ++which;
    }
    std::printf("MaximumFeatureScale %g: %zu splats in input order, %zu shuffled\n",
      scale,
      found[0].size(),
      found[1].size());
    Check(!found[0].empty() && found[0] == found[1],
      "a shuffled input gives the same splats and attributes at MaximumFeatureScale " +
        std::to_string(scale));
  }
}

void TestFixedCount()
{
  auto sphere = Sphere(5000);
  for (int variant : { vtkAlgebraicSplatFitter::LOP, vtkAlgebraicSplatFitter::WLOP })
  {
    vtkNew<vtkAlgebraicSplatFitter> fitter;
    fitter->SetInputData(sphere);
    fitter->SetSelectionMode(vtkAlgebraicSplatFitter::FixedCount);
    fitter->SetNumberOfSplats(300);
    fitter->SetLOPVariant(variant);
    fitter->Update();
    Check(fitter->GetOutput()->GetNumberOfPoints() == 300, "FixedCount gives m splats");
  }
  vtkNew<vtkAlgebraicSplatFitter> all;
  all->SetInputData(sphere);
  all->SetSelectionMode(vtkAlgebraicSplatFitter::All);
  all->Update();
  Check(all->GetOutput()->GetNumberOfPoints() == 5000, "All gives a splat per point");
}

void TestMemoryLimit()
{
  // A limit below the estimate: one error that names it, an empty but valid
  // output; the same filter fits once the limit is raised.
  auto sphere = Sphere(20000);
  vtkNew<vtkAlgebraicSplatFitter> fitter;
  vtkNew<vtkTest::ErrorObserver> observer;
  fitter->AddObserver(vtkCommand::ErrorEvent, observer);
  int errors = 0;
  vtkNew<vtkCallbackCommand> counter;
  counter->SetClientData(&errors);
  counter->SetCallback(
    [](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
  fitter->AddObserver(vtkCommand::ErrorEvent, counter);
  fitter->SetInputData(sphere);
  const vtkIdType need = vtkAlgebraicSplatFitter::EstimateMemorySize(20000);
  Check(need == 12500, "20 000 points: an estimate of 12 500 KiB (640 bytes a point)");
  fitter->SetMemoryLimit(need / 2);
  fitter->Update();
  const std::string message = observer->GetErrorMessage();
  std::cout << "memory limit: " << message << "\n";
  Check(errors == 1 && message.find("MemoryLimit") != std::string::npos &&
      message.find("20000 points") != std::string::npos,
    "a fit beyond MemoryLimit: one error naming the limit and the points");
  Check(fitter->GetOutput()->GetNumberOfPoints() == 0 &&
      fitter->GetOutput()->GetFieldData()->GetArray("SplatDegree") != nullptr,
    "beyond MemoryLimit: an empty splat set");
  observer->Clear();
  fitter->SetMemoryLimit(need);
  fitter->Update();
  Check(!observer->GetError() && fitter->GetOutput()->GetNumberOfPoints() > 100,
    "within MemoryLimit again: the fit runs");
  fitter->SetMemoryLimit(0);
  fitter->Modified();
  fitter->Update();
  Check(!observer->GetError() && fitter->GetOutput()->GetNumberOfPoints() > 100,
    "MemoryLimit 0: the free memory, ample here");
}

void TestBadInput()
{
  vtkNew<vtkPolyData> empty;
  Check(Fit(empty, "at least 3 finite points")->GetNumberOfPoints() == 0, "empty input");

  vtkNew<vtkPolyData> two;
  vtkNew<vtkPoints> twoPts;
  twoPts->InsertNextPoint(0, 0, 0);
  twoPts->InsertNextPoint(1, 0, 0);
  two->SetPoints(twoPts);
  Check(Fit(two, "at least 3 finite points")->GetNumberOfPoints() == 0, "N < 3");

  auto withNaN = Sphere(3000);
  withNaN->GetPoints()->SetPoint(10, std::nan(""), 0, 0);
  withNaN->GetPoints()->SetPoint(20, 0, std::numeric_limits<double>::infinity(), 0);
  Check(Fit(withNaN, "Dropped 2 of 3000")->GetNumberOfPoints() > 0, "NaN and Inf are dropped");

  auto doubled = Sphere(3000);
  for (vtkIdType i = 0; i < 3000; ++i)
  {
    double p[3];
    doubled->GetPoint(i, p);
    doubled->GetPoints()->InsertNextPoint(p);
  }
  doubled->GetPointData()->Initialize();
  Check(Fit(doubled, "")->GetNumberOfPoints() > 0, "duplicated points still fit");

  vtkNew<vtkPolyData> same;
  vtkNew<vtkPoints> samePts;
  for (int i = 0; i < 100; ++i)
  {
    samePts->InsertNextPoint(1.5, 2.5, 3.5);
  }
  same->SetPoints(samePts);
  Check(Fit(same, "distinct ones")->GetNumberOfPoints() == 0, "coincident points give no splat");

  vtkNew<vtkPolyData> line;
  vtkNew<vtkPoints> linePts;
  for (int i = 0; i < 200; ++i)
  {
    linePts->InsertNextPoint(0.1 * i, 0.2 * i, -0.05 * i);
  }
  line->SetPoints(linePts);
  Check(Fit(line, "degenerate")->GetNumberOfPoints() == 0, "collinear points give no splat");

  vtkNew<vtkPolyData> plane;
  vtkNew<vtkPoints> planePts;
  for (int i = 0; i < 40; ++i)
  {
    for (int j = 0; j < 40; ++j)
    {
      planePts->InsertNextPoint(0.1 * i, 0.1 * j, 0.0);
    }
  }
  plane->SetPoints(planePts);
  auto flat = Fit(plane, "", 4);
  vtkDataArray* c = flat->GetPointData()->GetArray("SplatCoefficients");
  double largest = 0.0;
  for (vtkIdType i = 0; i < c->GetNumberOfValues(); ++i)
  {
    largest = std::max(largest, std::abs(c->GetComponent(i / 15, i % 15)));
  }
  Check(flat->GetNumberOfPoints() > 0 && largest < 1e-9, "a plane fits with zero coefficients");

  vtkNew<vtkPolyData> few;
  vtkNew<vtkPoints> fewPts;
  for (int i = 0; i < 10; ++i)
  {
    fewPts->InsertNextPoint(std::cos(i), std::sin(i), 0.01 * i);
  }
  few->SetPoints(fewPts);
  Check(Fit(few, "exceed the 10 points", 4, 40)->GetNumberOfPoints() > 0, "k > N is clamped");

  // Coordinates near 1e7: the same splats as at the origin.
  vtkNew<vtkAlgebraicSplatFitter> near, far;
  auto s0 = Sphere(4000), s1 = Sphere(4000, 1e7);
  near->SetInputData(s0);
  far->SetInputData(s1);
  near->Update();
  far->Update();
  Check(near->GetOutput()->GetNumberOfPoints() == far->GetOutput()->GetNumberOfPoints(),
    "coordinates near 1e7 give the same splats");
  // Without input normals, oriented by the fitter the same way: outward,
  // from the sphere's centre.
  auto bare = [](vtkPolyData* in)
  {
    auto out = vtkSmartPointer<vtkPolyData>::New();
    out->SetPoints(in->GetPoints());
    return out;
  };
  vtkNew<vtkAlgebraicSplatFitter> nearBare, farBare;
  nearBare->SetInputData(bare(s0));
  farBare->SetInputData(bare(s1));
  nearBare->Update();
  farBare->Update();
  auto inward = [](vtkPolyData* splats, double offset)
  {
    vtkDataArray* normals = splats->GetPointData()->GetArray("SplatNormal");
    vtkIdType count = 0;
    for (vtkIdType i = 0; normals && i < splats->GetNumberOfPoints(); ++i)
    {
      double p[3], m[3];
      splats->GetPoint(i, p);
      normals->GetTuple(i, m);
      count += (p[0] - offset) * m[0] + (p[1] - offset) * m[1] + (p[2] - offset) * m[2] < 0.0;
    }
    return normals ? count : -1;
  };
  const vtkIdType inwardNear = inward(nearBare->GetOutput(), 0.0);
  const vtkIdType inwardFar = inward(farBare->GetOutput(), 1e7);
  std::cout << "sphere near the origin: " << inwardNear << " splats inward; near 1e7: " << inwardFar
            << "\n";
  Check(inwardNear == 0 && inwardFar == 0, "coordinates near 1e7: the splats face outward");

  // The error metric refuses what is not a splat set, with a clear error.
  vtkNew<vtkSplatErrorMetric> metric;
  vtkNew<vtkTest::ErrorObserver> observer;
  metric->AddObserver(vtkCommand::ErrorEvent, observer);
  metric->SetInputData(s0);
  metric->SetSplatData(s0);
  metric->Update();
  Check(observer->GetError() &&
      observer->GetErrorMessage().find("not a splat set") != std::string::npos,
    "the metric explains what input 1 lacks");
}
} // namespace

int TestAlgebraicSplatFitter(int, char*[])
{
  TestDataModel();
  TestLevelsAndOctree();
  TestFixedCount();
  TestInputOrder();
  TestMemoryLimit();
  TestBadInput();
  if (Failures)
  {
    std::cerr << Failures << " checks failed\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
