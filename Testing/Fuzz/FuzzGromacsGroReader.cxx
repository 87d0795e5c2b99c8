// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkGromacsGroReader on arbitrary .gro bytes, every frame read. See README.md.
#include "psFuzzFile.h"
#include "vtkGromacsGroReader.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string path = pointsurfaces::FuzzFile(data, size, "gro");
  vtkNew<vtkGromacsGroReader> reader;
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(0);
  const int steps = info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const double* times = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const std::vector<double> all(times, times + (times ? steps : 0));
  for (double t : all)
  {
    reader->UpdateTimeStep(t);
    // Touch what was read, so that a bad array shows up here.
    double bounds[6];
    reader->GetOutput()->GetBounds(bounds);
  }
  return 0;
}
