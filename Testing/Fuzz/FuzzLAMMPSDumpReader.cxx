// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkLAMMPSDumpReader on arbitrary dump bytes, every snapshot read. See README.md.
#include "psFuzzFile.h"
#include "vtkLAMMPSDumpReader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  pointsurfaces::FuzzEveryTimeStep<vtkLAMMPSDumpReader>(
    pointsurfaces::FuzzFile(data, size, "lammpstrj"));
  return 0;
}
