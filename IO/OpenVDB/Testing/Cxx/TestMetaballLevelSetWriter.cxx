// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkMetaballLevelSetWriter against exact references, read back with OpenVDB:
// - one ball, each kernel: the level set is the signed distance to the
//   exact iso-sphere |x| = R sqrt(K^-1(T)) within a small fraction of a voxel
//   across the narrow band; also at a 1e7 offset;
// - a cluster of balls with strengths: along rays, the level set's zero
//   crossing matches the first hit of the double-precision reference ray
//   caster (psMetaball CastRay);
// - bad input: NaN and zero radii are skipped and counted with one warning,
//   an empty input writes an empty level set with a warning, a voxel size
//   beyond the budget is an error and writes nothing, automatic voxels are
//   coarsened within the budget with a warning.
#include "psIOTestSupport.h"
#include "vtkCallbackCommand.h"
#include "vtkDoubleArray.h"
#include "vtkMetaballLevelSetWriter.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "psMetaball.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

using namespace pointsurfaces_test;

namespace
{
openvdb::FloatGrid::Ptr ReadBack(const std::string& path)
{
  openvdb::io::File file(path);
  file.open();
  openvdb::GridPtrVecPtr grids = file.getGrids();
  file.close();
  return grids->empty() ? nullptr : openvdb::gridPtrCast<openvdb::FloatGrid>(grids->front());
}

double Sample(const openvdb::FloatGrid& grid, const double p[3])
{
  openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(grid);
  return sampler.wsSample(openvdb::Vec3d(p[0], p[1], p[2]));
}
} // namespace

int TestMetaballLevelSetWriter(int, char*[])
{
  const char* temp = std::getenv("POINTSURFACES_TEMP_DIR");
  const std::string dir = temp ? temp : ".";
  openvdb::initialize();
  vtkNew<vtkMetaballLevelSetWriter> writer;
  vtkNew<vtkCallbackCommand> errors, warnings;
  errors->SetCallback(CountError);
  warnings->SetCallback(CountWarning);
  writer->AddObserver(vtkCommand::ErrorEvent, errors);
  writer->AddObserver(vtkCommand::WarningEvent, warnings);
  auto write = [&](vtkPolyData* balls, const std::string& name)
  {
    Errors = Warnings = 0;
    const std::string path = dir + "/" + name;
    std::remove(path.c_str());
    writer->SetInputData(balls);
    writer->SetFileName(path.c_str());
    writer->Write();
    return path;
  };

  // One ball: signed distance to the exact iso-sphere, for each kernel and at 1e7.
  const double radius = 2.0;
  const char* kernelNames[] = { "Wyvill", "quartic", "Gaussian" };
  for (int kernel = 0; kernel < 3; ++kernel)
  {
    for (double offset : { 0.0, 1e7 })
    {
      writer->GetField()->SetKernel(kernel);
      writer->GetField()->SetThreshold(0.5);
      writer->SetVoxelSize(0.0);
      const std::string path = write(Balls({ offset, -offset, 3.0 }, { radius }), "ball.vdb");
      Check(Errors == 0 && Warnings == 0, "one ball writes cleanly");
      openvdb::FloatGrid::Ptr grid = ReadBack(path);
      Check(grid && grid->getGridClass() == openvdb::GRID_LEVEL_SET && grid->getName() == "surface",
        "a level set named surface");
      if (!grid)
      {
        return EXIT_FAILURE;
      }
      const double voxel = writer->GetUsedVoxelSize();
      const double iso = radius *
        pointsurfaces::LoneBallIsoRadius(static_cast<pointsurfaces::MetaballKernel>(kernel), 0.5);
      double worst = 0.0;
      std::mt19937 rng(1);
      std::normal_distribution<double> g;
      for (int s = 0; s < 400; ++s)
      {
        double d[3] = { g(rng), g(rng), g(rng) };
        const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        // Within 1.5 voxels of the surface: trilinear samples there only
        // read voxels inside the 3-voxel band.
        const double at = iso + voxel * (-1.5 + 3.0 * (s % 11) / 10.0);
        const double p[3] = {
          offset + at * d[0] / len, -offset + at * d[1] / len, 3.0 + at * d[2] / len
        };
        worst = std::max(worst, std::abs(Sample(*grid, p) - (at - iso)));
      }
      std::cout << kernelNames[kernel] << " ball at offset " << offset << ": voxel " << voxel
                << ", iso-radius " << iso << ", worst |phi - exact distance| " << worst << " ("
                << worst / voxel << " voxel), active voxels " << writer->GetNumberOfActiveVoxels()
                << "\n";
      Check(worst < 0.25 * voxel, "level set within 0.25 voxel of the exact signed distance");
      Check(
        Sample(*grid, std::vector<double>{ offset, -offset, 3.0 }.data()) < 0.0, "negative inside");
    }
  }

  // A cluster with strengths: zero crossings along rays vs the reference ray caster.
  {
    std::mt19937 rng(3);
    const Cluster cluster(rng, 40);
    const std::vector<double>& xyz = cluster.Centers;
    const std::vector<double>& radii = cluster.Radii;
    const std::vector<double>& strengths = cluster.Strengths;
    writer->GetField()->SetKernel(vtkMetaballField::Wyvill);
    writer->GetField()->SetStrengthArrayName("Strength");
    writer->SetVoxelSize(0.04);
    const std::string path = write(Balls(xyz, radii, strengths), "cluster.vdb");
    Check(Errors == 0 && Warnings == 0, "cluster writes cleanly");
    openvdb::FloatGrid::Ptr grid = ReadBack(path);
    pointsurfaces::MetaballSet set;
    set.Centers = xyz.data();
    set.Radii = radii.data();
    set.Strengths = strengths.data();
    set.Count = 40;
    set.Threshold = 0.5;
    double worst = 0.0;
    int hits = 0;
    std::normal_distribution<double> g;
    for (int s = 0; s < 300 && grid; ++s)
    {
      double d[3] = { g(rng), g(rng), g(rng) };
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (double& c : d)
      {
        c /= len;
      }
      const double origin[3] = { -6 * d[0], -6 * d[1], -6 * d[2] };
      const pointsurfaces::RayHit hit = pointsurfaces::CastRay(set, origin, d, 0.0, 12.0, 1e-3, 40);
      if (!hit.Hit)
      {
        continue;
      }
      ++hits;
      // The level set along the ray near the hit: its zero by bisection.
      double lo = hit.T - 0.1, hi = hit.T + 0.1;
      auto phi = [&](double t)
      {
        const double p[3] = { origin[0] + t * d[0], origin[1] + t * d[1], origin[2] + t * d[2] };
        return Sample(*grid, p);
      };
      if (!(phi(lo) > 0.0 && phi(hi) < 0.0))
      {
        worst = std::max(worst, 1.0);
        continue;
      }
      for (int k = 0; k < 40; ++k)
      {
        const double mid = 0.5 * (lo + hi);
        (phi(mid) > 0.0 ? lo : hi) = mid;
      }
      worst = std::max(worst, std::abs(0.5 * (lo + hi) - hit.T));
    }
    std::cout << "cluster of 40 balls with strengths, voxel 0.04: " << hits
              << " rays hit, worst zero-crossing error " << worst << " (" << worst / 0.04
              << " voxel)\n";
    Check(hits > 100 && worst < 0.25 * 0.04, "zero crossings within 0.25 voxel of the reference");
    writer->GetField()->SetStrengthArrayName(nullptr);
  }

  // Bad input.
  {
    const double nan = std::nan("");
    writer->SetVoxelSize(0.0);
    write(Balls({ 0, 0, 0, 1, 0, 0, nan, 0, 0, 0, 1, 0 }, { 1.0, 0.0, 1.0, nan }), "bad.vdb");
    Check(Errors == 0 && Warnings == 1 && writer->GetNumberOfInvalidBalls() == 3,
      "NaN centre, zero and NaN radius: skipped, counted, one warning");
    Check(ReadBack(dir + "/bad.vdb")->activeVoxelCount() > 0, "the valid ball is written");

    const std::string empty = write(Balls({}, {}), "empty.vdb");
    Check(
      Errors == 0 && Warnings == 1 && ReadBack(empty) && ReadBack(empty)->activeVoxelCount() == 0,
      "empty input: an empty level set and a warning");

    writer->SetVoxelSize(1e-4);
    const std::string tooFine = write(Balls({ 0, 0, 0 }, { 1.0 }), "too-fine.vdb");
    Check(Errors == 1 && !std::ifstream(tooFine).good(),
      "a voxel size beyond MaximumVoxels: one error, nothing written");

    writer->SetVoxelSize(0.0);
    writer->SetMaximumVoxels(1e5);
    write(Balls({ 0, 0, 0, 50, 0, 0 }, { 1e-3, 1e2 }), "spread.vdb");
    Check(Errors == 0 && Warnings == 1 && writer->GetUsedVoxelSize() > 1e-3 / 10,
      "radii 1e-3 to 1e2, automatic voxel: coarsened within budget, one warning");
    writer->SetMaximumVoxels(2e8);

    writer->GetField()->SetThreshold(0.0);
    write(Balls({ 0, 0, 0 }, { 1.0 }), "zero-threshold.vdb");
    Check(Errors == 1, "threshold 0: one error");
    writer->GetField()->SetThreshold(0.5);
  }
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
