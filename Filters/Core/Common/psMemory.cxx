// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psMemory.h"

#include "vtksys/SystemInformation.hxx"

namespace pointsurfaces
{
//------------------------------------------------------------------------------
double MemoryLimitBytes(double requested)
{
  if (requested > 0.0)
  {
    return requested;
  }
  vtksys::SystemInformation system;
  return 1048576.0 * static_cast<double>(system.GetAvailablePhysicalMemory()); // MiB
}

//------------------------------------------------------------------------------
std::string FormatBytes(double bytes)
{
  return bytes >= 1048576.0 ? std::to_string(static_cast<long long>(bytes / 1048576.0)) + " MiB"
                            : std::to_string(static_cast<long long>(bytes / 1024.0)) + " KiB";
}
} // namespace pointsurfaces
