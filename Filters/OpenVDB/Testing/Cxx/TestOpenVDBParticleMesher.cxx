// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkOpenVDBParticleMesher against exact references:
// - a lone ball, both methods, at the origin and at a 1e7 offset: every mesh
//   vertex within a quarter voxel of the exact iso-sphere, normals radial,
//   polygons wound outward (their normals agree with the point normals);
// - a cluster with strengths, MetaballField: the field's first-order
//   distance |f| / |grad f| at every vertex under a quarter voxel;
// - Spheres on two overlapping balls: vertices on the union of the spheres;
// - bad input: NaN and zero radii skipped and counted with one warning, an
//   empty input, a voxel beyond the budget (error, empty mesh), spheres under
//   1.5 voxels skipped by OpenVDB and counted with a warning.
#include "psIOTestSupport.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkOpenVDBParticleMesher.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "psMetaball.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <string>
#include <vector>

using namespace pointsurfaces_test;

namespace
{
// Fraction of polygons whose winding normal points along their vertices' normals.
double OutwardFraction(vtkPolyData* mesh)
{
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  vtkIdType outward = 0, total = 0;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    mesh->GetCellPoints(c, ids);
    double p0[3], p1[3], p2[3], n[3];
    mesh->GetPoint(ids->GetId(0), p0);
    mesh->GetPoint(ids->GetId(1), p1);
    mesh->GetPoint(ids->GetId(2), p2);
    const double a[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
    const double b[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };
    const double cross[3] = {
      a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]
    };
    normals->GetTuple(ids->GetId(0), n);
    outward += cross[0] * n[0] + cross[1] * n[1] + cross[2] * n[2] > 0.0;
    ++total;
  }
  return total ? static_cast<double>(outward) / total : 0.0;
}
} // namespace

int TestOpenVDBParticleMesher(int, char*[])
{
  vtkNew<vtkOpenVDBParticleMesher> mesher;
  vtkNew<vtkCallbackCommand> errors, warnings;
  errors->SetCallback(CountError);
  warnings->SetCallback(CountWarning);
  mesher->AddObserver(vtkCommand::ErrorEvent, errors);
  mesher->AddObserver(vtkCommand::WarningEvent, warnings);
  auto run = [&](vtkPolyData* balls)
  {
    Errors = Warnings = 0;
    mesher->SetInputData(balls);
    mesher->Modified();
    mesher->Update();
    return mesher->GetOutput();
  };

  // A lone ball: Wyvill's kernel at T = 0.5 reaches T at half the radius.
  const double radius = 2.0, iso = 1.0;
  for (int method : { vtkOpenVDBParticleMesher::Spheres, vtkOpenVDBParticleMesher::MetaballField })
  {
    for (double offset : { 0.0, 1e7 })
    {
      mesher->SetMethod(method);
      vtkPolyData* mesh = run(Balls({ offset, 1.0, -offset }, { radius }));
      const double voxel = mesher->GetUsedVoxelSize();
      double worst = 0.0, worstAngle = 0.0;
      vtkDataArray* normals = mesh->GetPointData()->GetNormals();
      for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
      {
        double p[3], n[3];
        mesh->GetPoint(i, p);
        normals->GetTuple(i, n);
        const double d[3] = { p[0] - offset, p[1] - 1.0, p[2] + offset };
        const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        worst = std::max(worst, std::abs(r - iso));
        const double cosine = (d[0] * n[0] + d[1] * n[1] + d[2] * n[2]) / r;
        worstAngle = std::max(worstAngle, std::acos(std::min(1.0, cosine)) * 180.0 / 3.14159265);
      }
      const double outward = OutwardFraction(mesh);
      std::cout << (method == 0 ? "Spheres" : "MetaballField") << ", offset " << offset << ": "
                << mesh->GetNumberOfPoints() << " vertices, voxel " << voxel
                << ", worst distance to the iso-sphere " << worst << " (" << worst / voxel
                << " voxel), worst normal " << worstAngle << " deg, outward polygons " << outward
                << ", level set " << mesher->GetLevelSetTime() << " ms, mesh "
                << mesher->GetMeshTime() << " ms\n";
      Check(Errors == 0 && Warnings == 0 && mesh->GetNumberOfPolys() > 100, "a clean mesh");
      Check(worst < 0.25 * voxel, "vertices within a quarter voxel of the iso-sphere");
      Check(worstAngle < 5.0, "normals within 5 degrees of radial");
      Check(outward == 1.0, "every polygon wound outward");
    }
  }

  // A cluster with strengths, the exact field.
  {
    std::mt19937 rng(5);
    const Cluster cluster(rng, 40);
    const std::vector<double>& xyz = cluster.Centers;
    const std::vector<double>& radii = cluster.Radii;
    const std::vector<double>& strengths = cluster.Strengths;
    mesher->SetMethod(vtkOpenVDBParticleMesher::MetaballField);
    mesher->GetField()->SetStrengthArrayName("Strength");
    mesher->SetVoxelSize(0.04);
    vtkPolyData* mesh = run(Balls(xyz, radii, strengths));
    pointsurfaces::MetaballSet set;
    set.Centers = xyz.data();
    set.Radii = radii.data();
    set.Strengths = strengths.data();
    set.Count = 40;
    std::vector<double> distance;
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      double p[3], g[3];
      mesh->GetPoint(i, p);
      const double f = pointsurfaces::FieldValue(set, p, g);
      distance.push_back(std::abs(f) / std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]));
    }
    std::sort(distance.begin(), distance.end());
    const double p99 = distance.empty() ? 1e9 : distance[distance.size() * 99 / 100];
    const double worst = distance.empty() ? 1e9 : distance.back();
    std::cout << "cluster, MetaballField, voxel 0.04: " << mesh->GetNumberOfPoints()
              << " vertices, |f| / |grad f| p99 " << p99 / 0.04 << " voxel, worst " << worst / 0.04
              << " voxel (near saddles, where |grad f| is small), outward polygons "
              << OutwardFraction(mesh) << "\n";
    Check(Errors == 0 && Warnings == 0 && p99 < 0.15 * 0.04 && worst < 1.0 * 0.04,
      "cluster vertices within 0.15 voxel of the metaball surface (p99), 1 voxel (all)");
    Check(OutwardFraction(mesh) > 0.999, "cluster polygons wound outward");

    // The same mesh, point for point, with 1 and 2 threads (the kernels are
    // splatted into per-thread grids and merged).
    std::vector<vtkSmartPointer<vtkPolyData>> meshes;
    for (int threads : { 1, 2 })
    {
      vtkSMPTools::Initialize(threads);
      mesher->Modified();
      meshes.push_back(vtkSmartPointer<vtkPolyData>::New());
      meshes.back()->DeepCopy(run(Balls(xyz, radii, strengths)));
    }
    vtkSMPTools::Initialize(0);
    bool same = meshes[0]->GetNumberOfPoints() == meshes[1]->GetNumberOfPoints() &&
      meshes[0]->GetNumberOfPolys() == meshes[1]->GetNumberOfPolys() &&
      meshes[0]->GetNumberOfPoints() > 1000;
    for (vtkIdType i = 0; same && i < meshes[0]->GetNumberOfPoints(); ++i)
    {
      double a[3], b[3];
      meshes[0]->GetPoint(i, a);
      meshes[1]->GetPoint(i, b);
      same = a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
    }
    std::cout << "1 and 2 threads: " << meshes[0]->GetNumberOfPoints() << " and "
              << meshes[1]->GetNumberOfPoints() << " vertices\n";
    Check(same, "the same cluster mesh with 1 and 2 threads");
    mesher->GetField()->SetStrengthArrayName(nullptr);
  }

  // Spheres: two overlapping balls mesh as the union of their iso-spheres.
  {
    mesher->SetMethod(vtkOpenVDBParticleMesher::Spheres);
    mesher->SetVoxelSize(0.05);
    vtkPolyData* mesh = run(Balls({ 0, 0, 0, 1.2, 0, 0 }, { 2.0, 2.0 }));
    double worst = 0.0;
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      double p[3];
      mesh->GetPoint(i, p);
      const double d0 = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1.0;
      const double d1 = std::sqrt((p[0] - 1.2) * (p[0] - 1.2) + p[1] * p[1] + p[2] * p[2]) - 1.0;
      worst = std::max(worst, std::abs(std::min(d0, d1)));
    }
    std::cout << "two spheres, voxel 0.05: worst distance to their union " << worst << "\n";
    Check(worst < 0.3 * 0.05, "vertices on the union of the spheres");
  }

  // Bad input.
  {
    const double nan = std::nan("");
    mesher->SetVoxelSize(0.0);
    vtkPolyData* mesh = run(Balls({ 0, 0, 0, 5, 0, 0, nan, 0, 0 }, { 1.0, 0.0, 1.0 }));
    Check(Errors == 0 && Warnings == 1 && mesher->GetNumberOfInvalidBalls() == 2 &&
        mesh->GetNumberOfPolys() > 0,
      "NaN centre and zero radius: skipped, counted, one warning, the valid ball meshed");
    mesh = run(Balls({}, {}));
    Check(Errors == 0 && Warnings == 1 && mesh->GetNumberOfPoints() == 0,
      "empty input: a warning and an empty mesh");
    mesher->SetVoxelSize(1e-4);
    mesh = run(Balls({ 0, 0, 0 }, { 1.0 }));
    Check(Errors == 1 && mesh->GetNumberOfPoints() == 0, "a voxel beyond the budget: one error");
    mesher->SetVoxelSize(0.1);
    mesh = run(Balls({ 0, 0, 0, 3, 0, 0 }, { 1.0, 0.1 }));
    std::cout << "tiny sphere: " << Errors << " errors, " << Warnings << " warnings, "
              << mesher->GetNumberOfSkippedParticles() << " skipped\n";
    Check(Errors == 0 && Warnings == 1 && mesher->GetNumberOfSkippedParticles() == 1,
      "a sphere under 1.5 voxels: skipped by OpenVDB, counted, one warning");
    mesher->SetVoxelSize(0.0);
  }
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
