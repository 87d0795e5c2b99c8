// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkSplatFileReader on arbitrary .psplat bytes (HDF5 with
// the splat file's layout, or anything else). See README.md.
#include "psFuzzFile.h"
#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSplatFileReader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string path = pointsurfaces::FuzzFile(data, size, "psplat");
  for (const double budget : { 0.0, 0.01 })
  {
    vtkNew<vtkSplatFileReader> reader;
    reader->SetFileName(path.c_str());
    reader->SetMemoryBudget(budget);
    reader->Update();
    // Touch what was read, so that a bad array or range shows up here.
    vtkPolyData* out = reader->GetOutput();
    double bounds[6];
    out->GetBounds(bounds);
    vtkPointData* pd = out->GetPointData();
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
    {
      double range[2];
      pd->GetArray(a)->GetRange(range, -1);
      if (pd->GetArray(a)->GetNumberOfTuples() != out->GetNumberOfPoints())
      {
        __builtin_trap(); // an array that does not fit the points
      }
    }
  }
  return 0;
}
