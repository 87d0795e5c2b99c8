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

#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>
#include <vector>

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
      for (const char* ext :
        { "pcd", "off", "obj", "om", "stl", "vdb", "lammpstrj", "gro", "0.hdf5", "ply", "psplat" })
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

/**
 * Run a trajectory reader over `path`: every time step it offers is read,
 * and what was read is touched, so that a bad array shows up here.
 */
template<typename Reader>
void FuzzEveryTimeStep(const std::string& path)
{
  vtkNew<Reader> reader;
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(0);
  const int steps = info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const double* times = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const std::vector<double> all(times, times + (times ? steps : 0));
  for (double t : all)
  {
    reader->UpdateTimeStep(t);
    double bounds[6];
    reader->GetOutput()->GetBounds(bounds);
  }
}
} // namespace pointsurfaces

#endif
