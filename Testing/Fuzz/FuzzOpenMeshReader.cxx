// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkOpenMeshReader on arbitrary bytes. The first byte
// picks the format (off, obj, om, stl), the rest is the file. See README.md.
#include "psFuzzFile.h"
#include "vtkNew.h"
#include "vtkOpenMeshReader.h"
#include "vtkPolyData.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  if (size == 0)
  {
    return 0;
  }
  static const char* const extensions[] = { "off", "obj", "om", "stl" };
  const std::string path = pointsurfaces::FuzzFile(data + 1, size - 1, extensions[data[0] % 4]);
  vtkNew<vtkOpenMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* out = reader->GetOutput();
  double bounds[6];
  out->GetBounds(bounds);
  return 0;
}
