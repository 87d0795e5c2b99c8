// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkGromacsXtcReader on arbitrary .xtc bytes, every frame read. See README.md.
#include "psFuzzFile.h"
#include "vtkGromacsXtcReader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  pointsurfaces::FuzzEveryTimeStep<vtkGromacsXtcReader>(pointsurfaces::FuzzFile(data, size, "xtc"));
  return 0;
}
