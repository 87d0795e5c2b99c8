// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Splat fitting against its peers, in one process on the same points:
//
// - mls: vtkAlgebraicSplatFitter (All: one fit per point, like PCL; and the
//   Quality selection at s = 1) against pcl::MovingLeastSquares (order 2,
//   the same k through a radius that holds k neighbours on average, the same
//   number of threads). Error: RMS and maximum distance of the input points
//   to each method's surface, relative to the bounding-box diagonal.
// - lop: LOP and WLOP against CGAL's wlop_simplify_and_regularize_point_set
//   at the same m, support radius and iteration count. Error: RMS distance of
//   the samples to the input points, and the spread of nearest-sample
//   distances (coefficient of variation, lower is more uniform).
//
// Prints CSV: bench,model,n,method,k_or_m,threads,seconds,rms_rel,max_rel,extra,time_vs_peer,rms_vs_peer
// (seconds: best of three runs)
// Usage: BenchFitPeers [--smoke] [--threads T] file.{ply,vtp,xyz}...
//
// Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
// M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
#include "psPointIndex.h"
#include "psSplatBuilder.h"
#include "vtkAlgebraicSplatFitter.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSplatErrorMetric.h"
#include "vtkXMLPolyDataReader.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/wlop_simplify_and_regularize_point_set.h>

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/surface/mls.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

vtkSmartPointer<vtkPolyData> Load(const std::string& path)
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  if (path.size() > 4 && path.substr(path.size() - 4) == ".xyz")
  {
    vtkNew<vtkPoints> pts;
    pts->SetDataTypeToDouble();
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line))
    {
      std::istringstream s(line);
      double x, y, z;
      if (s >> x >> y >> z)
      {
        pts->InsertNextPoint(x, y, z);
      }
    }
    pd->SetPoints(pts);
    return pd;
  }
  if (path.size() > 4 && path.substr(path.size() - 4) == ".vtp")
  {
    vtkNew<vtkXMLPolyDataReader> r;
    r->SetFileName(path.c_str());
    r->Update();
    pd->SetPoints(r->GetOutput()->GetPoints());
    return pd;
  }
  vtkNew<vtkPLYReader> r;
  r->SetFileName(path.c_str());
  r->Update();
  pd->SetPoints(r->GetOutput()->GetPoints());
  return pd;
}

std::string Base(const std::string& path)
{
  return path.substr(path.find_last_of('/') + 1);
}

// Radius that holds k neighbours on average (median of the k-th distance).
double RadiusForK(const pointsurfaces::PointIndex& index, int k)
{
  std::vector<double> r;
  std::vector<int> ids;
  std::vector<double> d2;
  std::mt19937 gen(4);
  for (int t = 0; t < 300; ++t)
  {
    index.Nearest(index.Point(gen() % index.Size()), k, ids, d2);
    r.push_back(std::sqrt(d2.back()));
  }
  std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
  return r[r.size() / 2];
}

void BenchMLS(const std::string& path, vtkPolyData* pd, int k, int threads)
{
  const vtkIdType n = pd->GetNumberOfPoints();
  const double diag = pd->GetLength();
  std::vector<double> xyz(3 * n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    pd->GetPoint(i, &xyz[3 * i]);
  }
  pointsurfaces::PointIndex index(xyz.data(), n);

  // PCL, order 2. Its float cloud is centred first, to be fair to it.
  double c[3] = { 0, 0, 0 };
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      c[a] += xyz[3 * i + a] / n;
    }
  }
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (vtkIdType i = 0; i < n; ++i)
  {
    cloud->push_back(pcl::PointXYZ(static_cast<float>(xyz[3 * i] - c[0]),
      static_cast<float>(xyz[3 * i + 1] - c[1]),
      static_cast<float>(xyz[3 * i + 2] - c[2])));
  }
  const double radius = RadiusForK(index, k);
  pcl::MovingLeastSquares<pcl::PointXYZ, pcl::PointNormal> mls;
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  mls.setInputCloud(cloud);
  mls.setSearchMethod(tree);
  mls.setPolynomialOrder(2);
  mls.setSearchRadius(radius);
  mls.setSqrGaussParam(radius * radius / 4.0);
  mls.setComputeNormals(true);
  mls.setNumberOfThreads(threads);
  // Every timing is the best of three runs, for PCL and for us alike.
  pcl::PointCloud<pcl::PointNormal> projected;
  double pclTime = 1e300;
  for (int rep = 0; rep < 3; ++rep)
  {
    projected.clear();
    const double t0 = Now();
    mls.process(projected);
    pclTime = std::min(pclTime, Now() - t0);
  }
  // PCL's surface error: each input point against its projection.
  double sum2 = 0.0, worst = 0.0;
  const auto& corr = *mls.getCorrespondingIndices();
  for (size_t j = 0; j < projected.size(); ++j)
  {
    const int i = corr.indices.empty() ? static_cast<int>(j) : corr.indices[j];
    const double dx = projected[j].x + c[0] - xyz[3 * i],
                 dy = projected[j].y + c[1] - xyz[3 * i + 1],
                 dz = projected[j].z + c[2] - xyz[3 * i + 2];
    const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
    sum2 += d * d;
    worst = std::max(worst, d);
  }
  const double pclRMS = std::sqrt(sum2 / std::max<size_t>(1, projected.size())) / diag;
  std::printf("mls,%s,%lld,pcl-mls-order2,%d,%d,%.4f,%.3e,%.3e,%zu fits,1.000,1.000\n",
    Base(path).c_str(),
    static_cast<long long>(n),
    k,
    threads,
    pclTime,
    pclRMS,
    worst / diag,
    projected.size());

  // Ours: a splat per point, the s = 1 of [Bolla 2010], and s = 0.8 at degrees 3
  // and 4 (the operating points that match PCL's error), all with k = 40.
  struct Setting
  {
    const char* Name;
    int Selection;
    int Degree;
    double S;
  };
  const Setting settings[] = { { "splats-all-degree2", vtkAlgebraicSplatFitter::All, 2, 1.0 },
    { "splats-s1-degree2", vtkAlgebraicSplatFitter::Quality, 2, 1.0 },
    { "splats-s0.8-degree3", vtkAlgebraicSplatFitter::Quality, 3, 0.8 },
    { "splats-s0.8-degree4", vtkAlgebraicSplatFitter::Quality, 4, 0.8 } };
  for (const Setting& setting : settings)
  {
    vtkNew<vtkAlgebraicSplatFitter> fitter;
    fitter->SetInputData(pd);
    fitter->SetDegree(setting.Degree);
    fitter->SetQualityFactor(setting.S);
    fitter->SetNumberOfNeighbors(k);
    fitter->SetSelectionMode(setting.Selection);
    double ours = 1e300;
    for (int rep = 0; rep < 3; ++rep)
    {
      fitter->Modified();
      const double t0 = Now();
      fitter->Update();
      ours = std::min(ours, Now() - t0);
    }
    vtkNew<vtkSplatErrorMetric> metric;
    metric->SetInputData(pd);
    metric->SetSplatData(fitter->GetOutput());
    metric->Update();
    const double rms = metric->GetRMSDistance() / diag;
    std::printf("mls,%s,%lld,%s,%d,%d,%.4f,%.3e,%.3e,%lld splats,%.3f,%.3f\n",
      Base(path).c_str(),
      static_cast<long long>(n),
      setting.Name,
      k,
      threads,
      ours,
      rms,
      metric->GetMaximumDistance() / diag,
      static_cast<long long>(fitter->GetOutput()->GetNumberOfPoints()),
      ours / pclTime,
      rms / pclRMS);
  }
}

// RMS distance of samples to the input points (relative) and NN-distance variation.
std::pair<double, double> SampleQuality(const pointsurfaces::PointIndex& data,
  const std::vector<double>& x,
  double diag)
{
  const long long m = static_cast<long long>(x.size() / 3);
  pointsurfaces::PointIndex samples(x.data(), m);
  std::vector<int> ids;
  std::vector<double> d2;
  double sum2 = 0, s = 0, s2 = 0;
  for (long long i = 0; i < m; ++i)
  {
    data.Nearest(&x[3 * i], 1, ids, d2);
    sum2 += d2[0];
    samples.Nearest(&x[3 * i], 2, ids, d2);
    const double d = d2.size() > 1 ? std::sqrt(d2[1]) : 0.0;
    s += d;
    s2 += d * d;
  }
  const double mean = s / m;
  return { std::sqrt(sum2 / m) / diag, std::sqrt(std::max(0.0, s2 / m - mean * mean)) / mean };
}

void BenchLOP(const std::string& path, vtkPolyData* pd, long long m, int iterations)
{
  using Kernel = CGAL::Simple_cartesian<double>;
  const vtkIdType n = pd->GetNumberOfPoints();
  const double diag = pd->GetLength();
  std::vector<double> xyz(3 * n);
  std::vector<Kernel::Point_3> cgalIn(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    pd->GetPoint(i, &xyz[3 * i]);
    cgalIn[i] = Kernel::Point_3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  }
  pointsurfaces::PointIndex data(xyz.data(), n);
  // One support radius for everyone: that of m evenly spread samples.
  std::vector<int> ids;
  std::vector<double> d2;
  double spacing = 0.0;
  for (int t = 0; t < 200; ++t)
  {
    data.Nearest(data.Point((t * 7919LL) % n), 7, ids, d2);
    for (size_t j = 1; j < d2.size(); ++j)
    {
      spacing += std::sqrt(d2[j]) / (200.0 * (d2.size() - 1));
    }
  }
  const double h = 4.0 * std::sqrt(n * spacing * spacing / static_cast<double>(m));

  std::vector<Kernel::Point_3> cgalOut;
  double t0 = Now();
  CGAL::wlop_simplify_and_regularize_point_set<CGAL::Parallel_if_available_tag>(cgalIn,
    std::back_inserter(cgalOut),
    CGAL::parameters::select_percentage(100.0 * m / n)
      .neighbor_radius(h)
      .number_of_iterations(iterations));
  const double cgalTime = Now() - t0;
  std::vector<double> cg(3 * cgalOut.size());
  for (size_t i = 0; i < cgalOut.size(); ++i)
  {
    cg[3 * i] = cgalOut[i].x();
    cg[3 * i + 1] = cgalOut[i].y();
    cg[3 * i + 2] = cgalOut[i].z();
  }
  auto q = SampleQuality(data, cg, diag);
  const double cgalRMS = q.first;
  std::printf("lop,%s,%lld,cgal-wlop,%lld,%d,%.4f,%.3e,,%.3f nn-variation,1.000,1.000\n",
    Base(path).c_str(),
    static_cast<long long>(n),
    static_cast<long long>(cgalOut.size()),
    vtkSMPTools::GetEstimatedNumberOfThreads(),
    cgalTime,
    q.first,
    q.second);

  for (bool weighted : { false, true })
  {
    std::vector<double> x(3 * m);
    std::mt19937 gen(1);
    for (long long i = 0; i < m; ++i)
    {
      const long long j = gen() % n;
      std::copy(&xyz[3 * j], &xyz[3 * j] + 3, &x[3 * i]);
    }
    t0 = Now();
    const int steps =
      pointsurfaces::LocallyOptimalProjection(xyz.data(), n, x, weighted, iterations, h);
    const double ours = Now() - t0;
    q = SampleQuality(data, x, diag);
    std::printf("lop,%s,%lld,%s,%lld,%d,%.4f,%.3e,,%.3f nn-variation %d steps,%.3f,%.3f\n",
      Base(path).c_str(),
      static_cast<long long>(n),
      weighted ? "ours-wlop" : "ours-lop",
      static_cast<long long>(m),
      vtkSMPTools::GetEstimatedNumberOfThreads(),
      ours,
      q.first,
      q.second,
      steps,
      ours / cgalTime,
      q.first / cgalRMS);
  }
}
} // namespace

int main(int argc, char* argv[])
{
  bool smoke = false;
  int threads = 2;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--smoke"))
    {
      smoke = true;
    }
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc)
    {
      threads = std::atoi(argv[++i]);
    }
    else
    {
      files.emplace_back(argv[i]);
    }
  }
  vtkSMPTools::Initialize(threads);
  std::printf(
    "bench,model,n,method,k_or_m,threads,seconds,rms_rel,max_rel,extra,time_vs_peer,rms_vs_peer\n");
  for (const auto& f : files)
  {
    auto pd = Load(f);
    if (smoke)
    {
      // Every 8th point: a few seconds in all.
      vtkNew<vtkPoints> sub;
      for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); i += 8)
      {
        sub->InsertNextPoint(pd->GetPoint(i));
      }
      pd->SetPoints(sub);
    }
    if (pd->GetNumberOfPoints() < 100)
    {
      std::fprintf(stderr, "BenchFitPeers: %s has too few points\n", f.c_str());
      return 1;
    }
    BenchMLS(f, pd, 40, threads);
    const long long m = std::max<long long>(50, pd->GetNumberOfPoints() / 30);
    BenchLOP(f, pd, m, smoke ? 5 : 35);
  }
  return 0;
}
