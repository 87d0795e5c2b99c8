// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkPCDReader on arbitrary .pcd bytes. See README.md.
#include "psFuzzFile.h"
#include "vtkNew.h"
#include "vtkPCDReader.h"
#include "vtkPolyData.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string path = pointsurfaces::FuzzFile(data, size, "pcd");
  vtkNew<vtkPCDReader> reader;
  reader->SetFileName(path.c_str());
  // In this process, not in the reader's child: libFuzzer sees only the
  // coverage, and AddressSanitizer only the faults, of its own process.
  reader->ReadInChildProcessOff();
  reader->Update();
  // Touch what was read, so that a bad array shows up here.
  vtkPolyData* out = reader->GetOutput();
  double bounds[6];
  out->GetBounds(bounds);
  return 0;
}
