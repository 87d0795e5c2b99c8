// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The reconstruction peer of the splat quality benchmark (bench_splat_quality.py):
// what a user picks today to see a scan as a surface, a triangle mesh
// reconstructed from the points by CGAL's advancing front surface
// reconstruction (Cohen-Steiner and Da, 2004), at a given primitive budget.
//
// The scan's points (the vertices of a .ply or .vtp, faces ignored) are
// subsampled at random (seeded) to half the triangle budget (a closed
// surface of n points has about 2n triangles), reconstructed, and written as
// a .vtp of triangles that bench_splat_quality.py --peer-mesh scores against
// the original mesh from the same cameras.
//
// Prints CSV: model,points,triangles,seconds (seconds: the reconstruction
// alone, wall clock, one run).
// Usage: BenchReconstructPeer [--triangles N] [--seed S] in.{ply,vtp} out.vtp
#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Facet = std::array<std::size_t, 3>;

vtkSmartPointer<vtkPolyData> Load(const std::string& path)
{
  vtkSmartPointer<vtkPolyData> pd;
  if (path.size() > 4 && path.compare(path.size() - 4, 4, ".vtp") == 0)
  {
    vtkNew<vtkXMLPolyDataReader> r;
    r->SetFileName(path.c_str());
    r->Update();
    pd = r->GetOutput();
  }
  else
  {
    vtkNew<vtkPLYReader> r;
    r->SetFileName(path.c_str());
    r->Update();
    pd = r->GetOutput();
  }
  return pd;
}

std::string Stem(const std::string& path)
{
  const size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  return name.substr(0, name.find_last_of('.'));
}
} // namespace

int main(int argc, char* argv[])
{
  long long triangles = 0;
  unsigned int seed = 1;
  std::vector<std::string> files;
  for (int a = 1; a < argc; ++a)
  {
    if (!std::strcmp(argv[a], "--triangles") && a + 1 < argc)
    {
      triangles = std::atoll(argv[++a]);
    }
    else if (!std::strcmp(argv[a], "--seed") && a + 1 < argc)
    {
      seed = static_cast<unsigned int>(std::atoi(argv[++a]));
    }
    else
    {
      files.emplace_back(argv[a]);
    }
  }
  if (files.size() != 2)
  {
    std::fprintf(
      stderr, "usage: BenchReconstructPeer [--triangles N] [--seed S] in.{ply,vtp} out.vtp\n");
    return 2;
  }
  vtkSmartPointer<vtkPolyData> scan = Load(files[0]);
  const vtkIdType n = scan && scan->GetPoints() ? scan->GetNumberOfPoints() : 0;
  if (n < 4)
  {
    std::fprintf(stderr, "BenchReconstructPeer: no points in %s\n", files[0].c_str());
    return 1;
  }
  std::vector<vtkIdType> ids(static_cast<size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    ids[i] = i;
  }
  std::mt19937 gen(seed);
  std::shuffle(ids.begin(), ids.end(), gen);
  const vtkIdType keep =
    triangles > 0 ? std::min<vtkIdType>(n, std::max<vtkIdType>(4, triangles / 2)) : n;
  std::vector<Point> points;
  points.reserve(static_cast<size_t>(keep));
  for (vtkIdType k = 0; k < keep; ++k)
  {
    double p[3];
    scan->GetPoint(ids[k], p);
    points.emplace_back(p[0], p[1], p[2]);
  }

  std::vector<Facet> facets;
  const auto start = std::chrono::steady_clock::now();
  CGAL::advancing_front_surface_reconstruction(
    points.begin(), points.end(), std::back_inserter(facets));
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  vtkNew<vtkPoints> out;
  out->SetDataTypeToDouble();
  out->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  for (size_t k = 0; k < points.size(); ++k)
  {
    out->SetPoint(static_cast<vtkIdType>(k), points[k].x(), points[k].y(), points[k].z());
  }
  vtkNew<vtkCellArray> polys;
  for (const Facet& f : facets)
  {
    const vtkIdType tri[3] = {
      static_cast<vtkIdType>(f[0]), static_cast<vtkIdType>(f[1]), static_cast<vtkIdType>(f[2])
    };
    polys->InsertNextCell(3, tri);
  }
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(out);
  mesh->SetPolys(polys);
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName(files[1].c_str());
  writer->SetInputData(mesh);
  if (!writer->Write())
  {
    std::fprintf(stderr, "BenchReconstructPeer: cannot write %s\n", files[1].c_str());
    return 1;
  }
  std::printf("model,points,triangles,seconds\n%s,%lld,%zu,%.3f\n",
    Stem(files[0]).c_str(),
    static_cast<long long>(points.size()),
    facets.size(),
    seconds);
  return facets.empty() ? 1 : 0;
}
