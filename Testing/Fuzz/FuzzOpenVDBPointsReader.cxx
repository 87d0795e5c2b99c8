// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkOpenVDBPointsReader on arbitrary .vdb bytes. See README.md.
#include "psFuzzFile.h"
#include "vtkNew.h"
#include "vtkOpenVDBPointsReader.h"
#include "vtkPolyData.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string path = pointsurfaces::FuzzFile(data, size, "vdb");
  vtkNew<vtkOpenVDBPointsReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  // Touch what was read, so that a bad array shows up here.
  vtkPolyData* out = reader->GetOutput();
  double bounds[6];
  out->GetBounds(bounds);
  return 0;
}
