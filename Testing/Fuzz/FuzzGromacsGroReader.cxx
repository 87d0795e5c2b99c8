// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkGromacsGroReader on arbitrary .gro bytes, every frame read. See README.md.
#include "psFuzzFile.h"
#include "vtkGromacsGroReader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  pointsurfaces::FuzzEveryTimeStep<vtkGromacsGroReader>(pointsurfaces::FuzzFile(data, size, "gro"));
  return 0;
}
