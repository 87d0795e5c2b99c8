// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// What reading in a child process costs: vtkOpenVDBPointsReader on point
// data grids written here with OpenVDB (id, half-float pscale, double
// density, vec3 velocity, a string and a group per point), read with
// ReadInChildProcess on and off, the median of 3 reads each, in one
// process. Prints CSV: points, file MB, seconds in process, seconds in the
// child, and their ratio (the figure to quote).
//
//   BenchOpenVDBRead [--smoke] [--out DIR]   (DIR for the .vdb files; default .)
#include "psOpenVDBTestGrids.h"
#include "vtkNew.h"
#include "vtkOpenVDBPointsReader.h"
#include "vtkPolyData.h"
#include "vtksys/SystemTools.hxx"

#include <openvdb/io/File.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

using namespace pointsurfaces_test;

namespace
{
// The median time of `reps` reads of `path`, in seconds; -1 when a read fails.
double MedianRead(const std::string& path, bool inChild, vtkIdType expected, int reps)
{
  std::vector<double> times;
  for (int r = 0; r < reps; ++r)
  {
    vtkNew<vtkOpenVDBPointsReader> reader;
    reader->SetFileName(path.c_str());
    reader->SetReadInChildProcess(inChild);
    const auto start = std::chrono::steady_clock::now();
    reader->Update();
    times.push_back(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (reader->GetOutput()->GetNumberOfPoints() != expected)
    {
      return -1.0;
    }
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}
} // namespace

int main(int argc, char* argv[])
{
  bool smoke = false;
  std::string out = ".";
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--smoke")
    {
      smoke = true;
    }
    else if (arg == "--out" && i + 1 < argc)
    {
      out = argv[++i];
    }
  }
  openvdb::initialize();
  const std::vector<int> sizes =
    smoke ? std::vector<int>{ 10000 } : std::vector<int>{ 100000, 1000000, 3000000 };
  std::cout << "points,file_mb,in_process_s,child_s,child_over_in_process\n";
  std::mt19937 rng(5);
  for (int n : sizes)
  {
    const std::string path = out + "/bench-read-" + std::to_string(n) + ".vdb";
    openvdb::io::File(path).write(openvdb::GridPtrVec{ MakeGrid<ovp::NullCodec>(
      MakeSource(n, 0.0, 0, rng), 2.0 / std::cbrt(static_cast<double>(n) / 8.0), "bench") });
    const double mb = static_cast<double>(vtksys::SystemTools::FileLength(path)) / 1048576.0;
    const double inProcess = MedianRead(path, false, n, 3);
    const double child = MedianRead(path, true, n, 3);
    vtksys::SystemTools::RemoveFile(path);
    if (inProcess < 0.0 || child < 0.0)
    {
      std::cerr << "BenchOpenVDBRead: a read of " << n << " points failed\n";
      return 1;
    }
    std::printf("%d,%.1f,%.4f,%.4f,%.3f\n", n, mb, inProcess, child, child / inProcess);
  }
  return 0;
}
