// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkMetaballLevelOfDetail.h"

#include "vtkComputeShaderProgram.h"
#include "vtkMetaballGPUCounters.h"
#include "vtkMetaballGridBuilder.h"
#include "vtkMetaballLevelOfDetailCS.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderStorageBuffer.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkMetaballLevelOfDetail);

namespace
{
enum Pass
{
  Classify = 0,
  Key = 1,
  Place = 2,
  Merge = 3,
  NumberOfPasses = 4
};
const unsigned int Group = 256; // local_size_x of every pass
// The keys (cells times depth bins) a frame may use: 64 MiB of histogram.
const size_t KeyBudget = size_t(1) << 24;

// Grows `buffer` to at least `bytes` (never shrinks).
bool Reserve(vtkShaderStorageBuffer* buffer, size_t bytes)
{
  bytes = std::max<size_t>(bytes, 16);
  return buffer->GetSize() >= bytes || buffer->Allocate(bytes);
}
} // namespace

struct vtkMetaballLevelOfDetail::Internals
{
  vtkNew<vtkComputeShaderProgram> Programs[NumberOfPasses];
  vtkNew<vtkShaderStorageBuffer> LevelBalls, KeyOf, BinOf, Histogram, Cursor, CellBalls,
    MergedStrengths, MergedColors, FrontBin;
  vtkNew<vtkMetaballGPUCounters> Counts; // [0] merged balls, [1] balls merged

  vtkComputeShaderProgram* Use(vtkOpenGLRenderWindow* renWin, int pass)
  {
    vtkComputeShaderProgram* p = this->Programs[pass];
    return p->ReadyPass(renWin, "vtkMetaballLevelOfDetailCS", vtkMetaballLevelOfDetailCS, pass)
      ? p
      : nullptr;
  }
};

//------------------------------------------------------------------------------
vtkMetaballLevelOfDetail::vtkMetaballLevelOfDetail()
  : Impl(new Internals)
{
  this->Impl->Counts->SetSize(2);
}

//------------------------------------------------------------------------------
vtkMetaballLevelOfDetail::~vtkMetaballLevelOfDetail()
{
  delete this->Impl;
}

//------------------------------------------------------------------------------
vtkShaderStorageBuffer* vtkMetaballLevelOfDetail::GetLevelBalls()
{
  return this->Impl->LevelBalls;
}

//------------------------------------------------------------------------------
vtkShaderStorageBuffer* vtkMetaballLevelOfDetail::GetMergedStrengths()
{
  return this->Impl->MergedStrengths;
}

//------------------------------------------------------------------------------
vtkShaderStorageBuffer* vtkMetaballLevelOfDetail::GetMergedColors()
{
  return this->Impl->MergedColors;
}

//------------------------------------------------------------------------------
bool vtkMetaballLevelOfDetail::Build(vtkOpenGLRenderWindow* renWin,
  const pointsurfaces::MetaballBalls& balls,
  const pointsurfaces::MetaballView& view,
  double pixels,
  vtkMetaballGridBuilder* scanner,
  bool wait)
{
  Internals& in = *this->Impl;
  const size_t n = static_cast<size_t>(balls.Count);
  const double cellPixels = std::max(pixels, 1e-3);
  const int cellsX = static_cast<int>(std::ceil(view.Width / cellPixels));
  const int cellsY = static_cast<int>(std::ceil(view.Height / cellPixels));
  const size_t cells = static_cast<size_t>(cellsX) * cellsY;
  // Depth bins a cell keeps behind its front one (the deeper balls share
  // the last, hidden behind the front on a closed surface): as many as the
  // key budget allows, 4 to 64.
  const int depthBins = static_cast<int>(
    std::min<size_t>(64, std::max<size_t>(4, KeyBudget / std::max<size_t>(cells, 1))));
  const size_t keys = cells * depthBins;
  // Depth bins as deep as a cell is wide: the cell's side over the view
  // distance is constant in a perspective view (log bins), the side itself
  // in a parallel one.
  const double perUnit = 0.5 * view.Height * view.ViewToClip[5]; // pixels per unit at distance 1
  const double binStep =
    view.Parallel ? cellPixels / perUnit : std::log1p(cellPixels / std::max(perUnit, 1e-30));
  const auto take = [this](const unsigned int* counts)
  {
    this->NumberOfMergedBalls = counts[0];
    this->NumberOfBallsMerged = counts[1];
  };
  in.Counts->BeginFrame(take);
  bool ok = Reserve(in.LevelBalls, 2 * std::max<size_t>(n, 1) * 4 * sizeof(float)) &&
    Reserve(in.KeyOf, n * sizeof(unsigned int)) && Reserve(in.BinOf, n * sizeof(int)) &&
    Reserve(in.Histogram, (keys + 1) * sizeof(unsigned int)) &&
    Reserve(in.Cursor, keys * sizeof(unsigned int)) && Reserve(in.FrontBin, cells * sizeof(int)) &&
    Reserve(in.CellBalls, n * sizeof(unsigned int)) &&
    Reserve(in.MergedStrengths, n * sizeof(float)) &&
    Reserve(in.MergedColors, n * sizeof(unsigned int));
  if (ok)
  {
    in.Histogram->Fill(0, (keys + 1) * sizeof(unsigned int));
    in.FrontBin->Fill(0x7FFFFFFFu, cells * sizeof(int));
  }
  float m[16];
  const auto common = [&](vtkComputeShaderProgram* p, size_t count)
  {
    pointsurfaces::ToFloat(view.WorldToView, m);
    p->SetUniformMatrix4x4("worldToView", m);
    pointsurfaces::ToFloat(view.ViewToClip, m);
    p->SetUniformMatrix4x4("viewToClip", m);
    p->SetUniformui("count", static_cast<unsigned int>(count));
    p->SetUniformui("ballCount", static_cast<unsigned int>(n));
    p->SetUniformi("parallelProjection", view.Parallel ? 1 : 0);
    p->SetUniform2i("viewport", view.Width, view.Height);
    p->SetUniformf("lodPixels", static_cast<float>(cellPixels));
    p->SetUniform2i("cells", cellsX, cellsY);
    p->SetUniformi("depthBins", depthBins);
    p->SetUniformf("binStep", static_cast<float>(binStep));
    p->SetUniformi("useStrengths", balls.HasStrengths ? 1 : 0);
    p->SetUniformi("colorPerBall", balls.ColorPerBall ? 1 : 0);
    balls.Balls->BindBase(0);
    balls.Colors->BindBase(1);
    balls.Strengths->BindBase(2);
    in.LevelBalls->BindBase(3);
    in.KeyOf->BindBase(4);
    in.BinOf->BindBase(5);
    in.Histogram->BindBase(6);
    in.Cursor->BindBase(7);
    in.CellBalls->BindBase(8);
    in.MergedStrengths->BindBase(9);
    in.MergedColors->BindBase(10);
    in.Counts->GetFrameBuffer()->BindBase(11);
    in.FrontBin->BindBase(12);
  };
  // Classify (cells and each cell's front bin), key and count per key; scan
  // the counts into each key's first place.
  for (const int pass : { Classify, Key })
  {
    vtkComputeShaderProgram* program = ok ? in.Use(renWin, pass) : nullptr;
    ok = program != nullptr;
    if (ok)
    {
      common(program, n);
      ok = program->Dispatch(vtkComputeShaderProgram::GroupCount(std::max<size_t>(n, 1), Group));
    }
  }
  ok = ok && scanner->ExclusiveScan(renWin, in.Histogram, keys + 1);
  if (ok)
  {
    glBindBuffer(GL_COPY_READ_BUFFER, in.Histogram->GetHandle());
    glBindBuffer(GL_COPY_WRITE_BUFFER, in.Cursor->GetHandle());
    glCopyBufferSubData(
      GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, keys * sizeof(unsigned int));
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
  }
  // The small balls into their keys' lists, then one ball per key.
  vtkComputeShaderProgram* place = ok ? in.Use(renWin, Place) : nullptr;
  ok = place != nullptr;
  if (ok)
  {
    common(place, n);
    ok = place->Dispatch(vtkComputeShaderProgram::GroupCount(std::max<size_t>(n, 1), Group));
  }
  vtkComputeShaderProgram* merge = ok ? in.Use(renWin, Merge) : nullptr;
  ok = merge != nullptr;
  if (ok)
  {
    common(merge, keys);
    ok = merge->Dispatch(vtkComputeShaderProgram::GroupCount(keys, Group));
  }
  if (ok)
  {
    merge->Unbind();
  }
  in.Counts->EndFrame(take, wait);
  return ok;
}

//------------------------------------------------------------------------------
void vtkMetaballLevelOfDetail::ReleaseGraphicsResources(vtkWindow* win)
{
  Internals& in = *this->Impl;
  for (auto& p : in.Programs)
  {
    p->ReleaseGraphicsResources(win);
  }
  for (vtkShaderStorageBuffer* b : { in.LevelBalls.Get(),
         in.FrontBin.Get(),
         in.KeyOf.Get(),
         in.BinOf.Get(),
         in.Histogram.Get(),
         in.Cursor.Get(),
         in.CellBalls.Get(),
         in.MergedStrengths.Get(),
         in.MergedColors.Get() })
  {
    b->ReleaseGraphicsResources(win);
  }
  in.Counts->ReleaseGraphicsResources(win);
}

//------------------------------------------------------------------------------
void vtkMetaballLevelOfDetail::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfMergedBalls: " << this->NumberOfMergedBalls << "\n";
  os << indent << "NumberOfBallsMerged: " << this->NumberOfBallsMerged << "\n";
}
