// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psFuzzFile.h
 * @brief The bytes of a libFuzzer input as a file, for readers that take a file name.
 *
 * Every reader of PointSurfaces reads from a file (PCL, OpenMesh and
 * OpenVDB open their own streams), so each fuzz input is written to one
 * scratch file per process (under $TMPDIR, default /tmp) with the extension
 * that selects the format. VTK's error and warning output is switched off:
 * the fuzzer looks for crashes, hangs, leaks and sanitizer reports, and the
 * readers' clear errors on bad input are tested by the unit tests.
 */
#ifndef psFuzzFile_h
#define psFuzzFile_h

#include "vtkObject.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

namespace pointsurfaces
{
inline std::string FuzzFile(const uint8_t* data, size_t size, const std::string& extension)
{
  static bool quiet = (vtkObject::GlobalWarningDisplayOff(), true);
  (void)quiet;
  const char* tmp = std::getenv("TMPDIR");
  static const std::string base = std::string(tmp && *tmp ? tmp : "/tmp") + "/psfuzz-" +
    std::to_string(static_cast<long>(getpid())) + ".";
  static const int cleanup = std::atexit(
    []
    {
      for (const char* ext : { "pcd", "off", "obj", "om", "stl", "vdb" })
      {
        std::remove((base + ext).c_str());
      }
    });
  (void)cleanup;
  const std::string path = base + extension;
  if (FILE* f = std::fopen(path.c_str(), "wb"))
  {
    if (size > 0)
    {
      std::fwrite(data, 1, size, f);
    }
    std::fclose(f);
  }
  return path;
}
} // namespace pointsurfaces

#endif
