// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkMetaballGPURayCaster.h"

#include "vtkComputeShaderProgram.h"
#include "vtkMetaballGridBuilder.h"
#include "vtkMetaballLevelOfDetail.h"
#include "vtkMetaballRayCastCS.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderStorageBuffer.h"

#include "psMetaballShaderKernel.h"

vtkStandardNewMacro(vtkMetaballGPURayCaster);

namespace
{
const int MaxShared = 256; // balls per voxel batch in shared memory
}

//------------------------------------------------------------------------------
vtkMetaballGPURayCaster::vtkMetaballGPURayCaster() = default;

//------------------------------------------------------------------------------
vtkMetaballGPURayCaster::~vtkMetaballGPURayCaster() = default;

//------------------------------------------------------------------------------
vtkComputeShaderProgram* vtkMetaballGPURayCaster::Program(vtkOpenGLRenderWindow* renWin,
  const pointsurfaces::MetaballCastRequest& request)
{
  const std::string defines = "#define TILE_SIZE " + std::to_string(request.TileSize) +
    "\n#define MAX_SHARED " + std::to_string(MaxShared) + "\n" +
    pointsurfaces::MetaballKernelDefines(request.Kernel);
  return pointsurfaces::ReadyMetaballProgram(this->RayCast,
    renWin,
    "vtkMetaballRayCastCS",
    vtkMetaballRayCastCS,
    defines,
    this->Defines,
    this);
}

//------------------------------------------------------------------------------
bool vtkMetaballGPURayCaster::Cast(vtkOpenGLRenderWindow* renWin,
  const pointsurfaces::MetaballCastRequest& request,
  pointsurfaces::MetaballBalls& balls,
  pointsurfaces::MetaballImages& images,
  vtkShaderStorageBuffer* counters,
  pointsurfaces::MetaballCastStatistics& stats)
{
  const pointsurfaces::MetaballView& view = request.View;
  stats.Rays = static_cast<long long>(view.Width) * view.Height;
  // [Bolla 2010] Algorithm 2: the perspective grid.
  this->Grid->SetTileSize(request.TileSize);
  this->Grid->SetCollectStatistics(request.CollectStatistics);
  this->Grid->SetSlabs(request.Slabs);
  // The level of detail: small balls merged, the grid over the level's balls.
  const bool level = request.LevelOfDetailPixels > 0.0;
  if (level &&
    !this->Level->Build(
      renWin, balls, view, request.LevelOfDetailPixels, this->Grid, request.CollectStatistics))
  {
    return false;
  }
  stats.MergedBalls = level ? this->Level->GetNumberOfMergedBalls() : 0;
  stats.BallsMerged = level ? this->Level->GetNumberOfBallsMerged() : 0;
  vtkShaderStorageBuffer* gridBalls = level ? this->Level->GetLevelBalls() : balls.Balls.Get();
  if (!this->Grid->Build(renWin,
        gridBalls,
        level ? 2 * balls.Count : balls.Count,
        view.WorldToView,
        view.ViewToClip,
        view.Parallel,
        view.Width,
        view.Height))
  {
    return false;
  }
  stats.Pairs = this->Grid->GetNumberOfPairs();
  stats.MaxPerVoxel = this->Grid->GetMaximumBallsPerVoxel();
  stats.Culled = this->Grid->GetNumberOfCulledBalls();
  stats.GridSeconds = 1e-3 * this->Grid->GetBuildTime();

  // [Bolla 2010] Algorithm 3: coherent ray casting, into colour, normal and depth images.
  vtkComputeShaderProgram* program = this->Program(renWin, request);
  if (!program)
  {
    return false;
  }
  program->Bind(renWin);
  float m[16];
  pointsurfaces::ToFloat(view.WorldToView, m);
  program->SetUniformMatrix4x4("worldToView", m);
  pointsurfaces::ToFloat(view.ViewToClip, m);
  program->SetUniformMatrix4x4("viewToClip", m);
  pointsurfaces::ToFloat(view.ClipToView, m);
  program->SetUniformMatrix4x4("clipToView", m);
  program->SetUniformi("parallelProjection", view.Parallel ? 1 : 0);
  program->SetUniform2i("viewport", view.Width, view.Height);
  program->SetUniform2i("tiles", this->Grid->GetTilesX(), this->Grid->GetTilesY());
  program->SetUniformi("slabs", request.Slabs);
  program->SetUniformf("threshold", static_cast<float>(request.Threshold));
  program->SetUniformf("stepScale", static_cast<float>(request.StepScale));
  program->SetUniformi("bisections", request.Bisections);
  program->SetUniformi("useStrengths", balls.HasStrengths ? 1 : 0);
  program->SetUniformi("colorPerBall", balls.ColorPerBall ? 1 : 0);
  program->SetUniformui("baseCount", level ? static_cast<unsigned int>(balls.Count) : 0xFFFFFFFFu);
  gridBalls->BindBase(0);
  if (level)
  {
    this->Level->GetMergedStrengths()->BindBase(7);
    this->Level->GetMergedColors()->BindBase(8);
  }
  balls.Colors->BindBase(1);
  balls.Strengths->BindBase(2);
  this->Grid->GetVoxelOffsets()->BindBase(3);
  this->Grid->GetVoxelBalls()->BindBase(4);
  counters->BindBase(5);
  this->Grid->GetGridStatistics()->BindBase(6); // the slab range
  glBindImageTexture(0, images.Color->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
  glBindImageTexture(1, images.Normal->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(2, images.Depth->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  this->Timer.ReusableStart();
  const bool cast = program->Dispatch(this->Grid->GetTilesX(),
    this->Grid->GetTilesY(),
    1,
    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
      GL_SHADER_STORAGE_BARRIER_BIT);
  program->Unbind();
  this->Timer.ReusableStop();
  // The GPU time of the last frame whose query completed.
  stats.CastSeconds = this->Timer.GetReusableElapsedSeconds();
  return cast;
}

//------------------------------------------------------------------------------
vtkIdType vtkMetaballGPURayCaster::GetNumberOfReadBacks()
{
  return this->Grid->GetNumberOfReadBacks();
}

//------------------------------------------------------------------------------
vtkIdType vtkMetaballGPURayCaster::GetNumberOfOverflows()
{
  return this->Grid->GetNumberOfOverflows();
}

//------------------------------------------------------------------------------
void vtkMetaballGPURayCaster::ReleaseGraphicsResources(vtkWindow* win)
{
  this->Grid->ReleaseGraphicsResources(win);
  this->Level->ReleaseGraphicsResources(win);
  this->RayCast->ReleaseGraphicsResources(win);
  this->Defines.clear();
  this->Timer.ReleaseGraphicsResources();
}

//------------------------------------------------------------------------------
void vtkMetaballGPURayCaster::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Program compiled: " << this->RayCast->IsCompiled() << "\n";
}
