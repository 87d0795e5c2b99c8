// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Benchmark of the compute helper: counting N points into 16x16 screen tiles
// (the first pass of a screen-tiled grid build) with vtkPointTileCountCS,
// against the same count on the CPU with vtkSMPTools, in the same process.
// Prints CSV: n,width,height,gpu_ms,cpu_ms,cpu_over_gpu,upload_ms
//
// Usage: BenchComputeTiles [--smoke] [--size WxH] [--repeat R]
#include "vtkCamera.h"
#include "vtkComputeShaderProgram.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointTileCountCS.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkShaderStorageBuffer.h"

#include "psOpenGL.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace
{
double Milliseconds(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void CpuCount(const std::vector<float>& pts,
  const double m[16],
  int w,
  int h,
  int tile,
  int tx,
  int ty,
  std::vector<unsigned int>& counts)
{
  vtkSMPThreadLocal<std::vector<unsigned int>> local;
  const vtkIdType n = static_cast<vtkIdType>(pts.size() / 4);
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      auto& c = local.Local();
      c.resize(counts.size(), 0);
      for (vtkIdType i = begin; i < end; ++i)
      {
        const float* p = &pts[4 * i];
        double clip[4];
        for (int r = 0; r < 4; ++r)
        {
          clip[r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
        }
        if (clip[3] <= 0)
        {
          continue;
        }
        const double x = clip[0] / clip[3], y = clip[1] / clip[3], z = clip[2] / clip[3];
        if (x < -1 || y < -1 || z < -1 || x >= 1 || y >= 1 || z >= 1)
        {
          continue;
        }
        const int px = std::min(static_cast<int>((x * 0.5 + 0.5) * w) / tile, tx - 1);
        const int py = std::min(static_cast<int>((y * 0.5 + 0.5) * h) / tile, ty - 1);
        ++c[py * tx + px];
      }
    });
  std::fill(counts.begin(), counts.end(), 0u);
  for (auto& c : local)
  {
    for (size_t t = 0; t < c.size(); ++t)
    {
      counts[t] += c[t];
    }
  }
}
} // namespace

int main(int argc, char* argv[])
{
  bool smoke = false;
  int width = 1024, height = 1024, repeat = 5;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--smoke"))
    {
      smoke = true;
    }
    else if (!std::strcmp(argv[i], "--size") && i + 1 < argc)
    {
      std::sscanf(argv[++i], "%dx%d", &width, &height);
    }
    else if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc)
    {
      repeat = std::max(1, std::atoi(argv[++i]));
    }
  }
  if (smoke)
  {
    width = height = 128;
    repeat = 1;
  }
  vtkNew<vtkRenderWindow> renWin;
  vtkNew<vtkRenderer> renderer;
  renWin->AddRenderer(renderer);
  renWin->SetSize(width, height);
  renWin->SetMultiSamples(0);
  renWin->Render();
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(renWin);
  if (!gl || !pointsurfaces::HasOpenGLVersion(4, 3))
  {
    std::fprintf(stderr, "BenchComputeTiles: no OpenGL 4.3 context\n");
    return 1;
  }
  vtkCamera* cam = renderer->GetActiveCamera();
  cam->SetPosition(0, 0, 5);
  cam->SetFocalPoint(0, 0, 0);
  cam->SetClippingRange(0.5, 20);
  vtkMatrix4x4* mat = cam->GetCompositeProjectionTransformMatrix(1.0 * width / height, -1, 1);
  double m[16];
  float mf[16];
  for (int i = 0; i < 16; ++i)
  {
    m[i] = mat->GetElement(i / 4, i % 4);
    mf[i] = static_cast<float>(m[i]);
  }
  const int tile = 16, tx = (width + tile - 1) / tile, ty = (height + tile - 1) / tile;

  gl->MakeCurrent();
  vtkNew<vtkComputeShaderProgram> program;
  program->SetName("vtkPointTileCountCS");
  program->SetSource(vtkPointTileCountCS);
  if (!program->Compile(gl))
  {
    return 1;
  }
  vtkNew<vtkShaderStorageBuffer> points, counts, tiles;
  std::printf("n,width,height,gpu_ms,cpu_ms,cpu_over_gpu,upload_ms\n");
  const std::vector<size_t> sizes =
    smoke ? std::vector<size_t>{ 1000 } : std::vector<size_t>{ 10000, 100000, 1000000 };
  std::mt19937 gen(1);
  std::uniform_real_distribution<float> uni(-2.5f, 2.5f);
  int status = 0;
  for (size_t n : sizes)
  {
    std::vector<float> pts(4 * n);
    for (size_t i = 0; i < n; ++i)
    {
      pts[4 * i] = uni(gen);
      pts[4 * i + 1] = uni(gen);
      pts[4 * i + 2] = uni(gen);
      pts[4 * i + 3] = 1.f;
    }
    auto t0 = std::chrono::steady_clock::now();
    points->Upload(pts.data(), pts.size() * sizeof(float));
    glFinish();
    const double uploadMs = Milliseconds(t0);
    counts->Allocate(sizeof(unsigned int) * tx * ty);
    tiles->Allocate(sizeof(int) * n);
    std::vector<unsigned int> gpu(tx * ty), cpu(tx * ty);
    double gpuMs = 1e30, cpuMs = 1e30;
    for (int r = 0; r < repeat; ++r)
    {
      t0 = std::chrono::steady_clock::now();
      counts->Fill(0);
      program->Bind(gl);
      program->SetUniformMatrix4x4("worldToClip", mf);
      program->SetUniformui("numberOfPoints", static_cast<unsigned int>(n));
      program->SetUniform2i("viewportSize", width, height);
      program->SetUniformi("tileSize", tile);
      program->SetUniform2i("tileCount", tx, ty);
      points->BindBase(0);
      counts->BindBase(1);
      tiles->BindBase(2);
      program->Dispatch(vtkComputeShaderProgram::GroupCount(n, 128));
      program->Unbind();
      counts->Download(gpu.data(), gpu.size() * sizeof(unsigned int));
      gpuMs = std::min(gpuMs, Milliseconds(t0));
      t0 = std::chrono::steady_clock::now();
      CpuCount(pts, m, width, height, tile, tx, ty, cpu);
      cpuMs = std::min(cpuMs, Milliseconds(t0));
    }
    unsigned long total = 0, diff = 0;
    for (size_t t = 0; t < gpu.size(); ++t)
    {
      total += cpu[t];
      diff += gpu[t] > cpu[t] ? gpu[t] - cpu[t] : cpu[t] - gpu[t];
    }
    // Float rounding may move a handful of boundary points; more is a bug.
    if (diff > 1 + total / 1000)
    {
      std::fprintf(
        stderr, "BenchComputeTiles: GPU and CPU counts differ by %lu of %lu\n", diff, total);
      status = 1;
    }
    std::printf(
      "%zu,%d,%d,%.3f,%.3f,%.2f,%.3f\n", n, width, height, gpuMs, cpuMs, cpuMs / gpuMs, uploadMs);
  }
  program->ReleaseGraphicsResources(gl);
  points->ReleaseGraphicsResources(gl);
  counts->ReleaseGraphicsResources(gl);
  tiles->ReleaseGraphicsResources(gl);
  return status;
}
