// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// A time series through vtkMetaballMapper: 220 frames of 4000 particles
// swirling into a vortex (new positions every frame, as a simulation gives
// them) on the CPU ray caster, then 12 on the GPU one. Every changed frame is
// uploaded once, every frame finds the surface, the grid is rebuilt each
// time, and nothing grows: the resident memory grows by at most 4 MB over
// the last 100 CPU frames (a GL driver may take memory for a while first:
// NVIDIA's 580 driver took 8.5 MB over frames 20 to 120, with any number of
// threads or malloc arenas, where llvmpipe took 0.04 MB; a leak grows as
// much in every stretch). Not checked under AddressSanitizer, whose quarantine
// holds freed memory; the asan preset runs only the unit tests, and
// TestMetaballCast's time series is the CPU caster's check there. The
// per-frame upload, grid and ray-cast times are printed;
// bench_metaball_series.py measures them at full size. Last, 12 GPU frames
// without statistics: none of them waits on a read-back, and the counters
// that arrive late still show the surface.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkMetaballMapper.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include "psTestVortex.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <random>
#include <unistd.h>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#define PS_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PS_ASAN 1
#endif
#endif

namespace
{
// Resident set size in MB (Linux).
double ResidentMB()
{
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}
} // namespace

int TestMetaballMapperTimeSeries(int, char*[])
{
  const int n = 4000;
  std::mt19937 gen(5);
  pointsurfaces::TestVortex<std::mt19937> vortex(n, gen);
  vtkNew<vtkPolyData> poly;
  vtkNew<vtkMetaballMapper> mapper;
  mapper->SetInputDataObject(poly);
  mapper->GetField()->SetRadius(0.12);
  mapper->SetCollectStatistics(true);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(96, 96);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.0, -4.0, 1.2);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetViewUp(0.0, 0.0, 1.0);
  camera->SetClippingRange(1.0, 8.0);

  int failures = 0;
  const int cpuFrames = 220, gpuFrames = 12;
  std::vector<double> uploads, grids, casts;
  double residentAfterWarmUp = 0.0, residentMiddle = 0.0, residentEnd = 0.0;
  for (int frame = 0; frame < cpuFrames + gpuFrames; ++frame)
  {
    vortex.Step();
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(n);
    for (int i = 0; i < n; ++i)
    {
      points->SetPoint(i, vortex.Position(i));
    }
    poly->SetPoints(points);
    mapper->SetRayCaster(frame < cpuFrames ? vtkMetaballMapper::CPU : vtkMetaballMapper::GPU);
    const int uploadsBefore = mapper->GetNumberOfUploads();
    window->Render();
    if (mapper->GetNumberOfUploads() != uploadsBefore + 1)
    {
      std::cerr << "frame " << frame << ": " << mapper->GetNumberOfUploads() - uploadsBefore
                << " uploads, not one\n";
      ++failures;
    }
    if (mapper->GetNumberOfHits() < 500 || mapper->GetNumberOfPairs() < n)
    {
      std::cerr << "frame " << frame << ": " << mapper->GetNumberOfHits() << " hits, "
                << mapper->GetNumberOfPairs() << " pairs\n";
      ++failures;
    }
    if (frame < cpuFrames)
    {
      uploads.push_back(mapper->GetUploadTime());
      grids.push_back(mapper->GetGridBuildTime());
      casts.push_back(mapper->GetRayCastTime());
    }
    if (frame == 19)
    {
      residentAfterWarmUp = ResidentMB();
    }
    if (frame == cpuFrames - 101)
    {
      residentMiddle = ResidentMB();
    }
    if (frame == cpuFrames - 1)
    {
      residentEnd = ResidentMB();
    }
  }
  std::cout << cpuFrames << " CPU frames of " << n << " particles at 96x96: median upload "
            << Median(uploads) << " ms, grid " << Median(grids) << " ms, ray cast " << Median(casts)
            << " ms; resident memory " << residentAfterWarmUp << " MB at frame 20, "
            << residentMiddle << " MB at frame " << cpuFrames - 100 << ", " << residentEnd
            << " MB at frame " << cpuFrames << "; then " << gpuFrames << " GPU frames\n";
  // Without statistics: no read-back in any frame.
  mapper->SetCollectStatistics(false);
  const vtkIdType readBacks = mapper->GetNumberOfReadBacks();
  for (int frame = 0; frame < 12; ++frame)
  {
    vortex.Step();
    vtkNew<vtkPoints> points;
    points->SetNumberOfPoints(n);
    for (int i = 0; i < n; ++i)
    {
      points->SetPoint(i, vortex.Position(i));
    }
    poly->SetPoints(points);
    window->Render();
  }
  std::cout << "12 GPU frames without statistics: " << mapper->GetNumberOfReadBacks() - readBacks
            << " read-backs (" << readBacks << " before, with statistics), "
            << mapper->GetNumberOfGridOverflows() << " grid overflows, "
            << mapper->GetNumberOfHits() << " hits in a late frame\n";
  if (mapper->GetNumberOfReadBacks() != readBacks || mapper->GetNumberOfHits() < 500 ||
    mapper->GetNumberOfGridOverflows() != 0)
  {
    std::cerr << "a frame without statistics read back, overflowed or lost its counters\n";
    ++failures;
  }
#ifndef PS_ASAN
  if (residentEnd - residentMiddle > 4.0)
  {
    std::cerr << "the memory grows over the series\n";
    ++failures;
  }
#endif
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
