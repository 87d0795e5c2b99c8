// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkOpenVDBPointsReader on arbitrary .vdb bytes. See README.md.
#include "psFuzzFile.h"
#include "vtkNew.h"
#include "vtkOpenVDBPointsReader.h"
#include "vtkPolyData.h"

#include <tbb/global_control.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  // One TBB thread (OpenVDB's and VTK's SMP work): with threads, the
  // coverage that a run recorded for the same seeds varied from run to run,
  // and so did the inputs a seed-1 smoke run went on to try (see README.md).
  static tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
  const std::string path = pointsurfaces::FuzzFile(data, size, "vdb");
  vtkNew<vtkOpenVDBPointsReader> reader;
  reader->SetFileName(path.c_str());
  // In this process, not in the reader's child: libFuzzer sees only the
  // coverage, and AddressSanitizer only the faults, of its own process.
  // OpenVDB's own aborts (IO/Testing/Data/openvdb) therefore stop this
  // target, where the reader's default turns them into an error.
  reader->ReadInChildProcessOff();
  reader->Update();
  // Touch what was read, so that a bad array shows up here.
  vtkPolyData* out = reader->GetOutput();
  double bounds[6];
  out->GetBounds(bounds);
  return 0;
}
