// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkMetaballCPURayCaster.h"

#include "vtkMetaballGPUCounters.h"
#include "vtkObjectFactory.h"
#include "vtkShaderStorageBuffer.h"

#include <algorithm>

vtkStandardNewMacro(vtkMetaballCPURayCaster);

//------------------------------------------------------------------------------
vtkMetaballCPURayCaster::vtkMetaballCPURayCaster() = default;

//------------------------------------------------------------------------------
vtkMetaballCPURayCaster::~vtkMetaballCPURayCaster() = default;

//------------------------------------------------------------------------------
bool vtkMetaballCPURayCaster::Cast(vtkOpenGLRenderWindow*,
  const pointsurfaces::MetaballCastRequest& request,
  pointsurfaces::MetaballBalls& balls,
  pointsurfaces::MetaballImages& images,
  vtkShaderStorageBuffer* counters,
  pointsurfaces::MetaballCastStatistics& stats)
{
  const pointsurfaces::MetaballView& view = request.View;
  pointsurfaces::MetaballCastInput input;
  input.Balls = balls.HostBalls.data();
  input.Strengths = balls.HasStrengths ? balls.HostStrengths.data() : nullptr;
  input.Colors = balls.HostColors.data();
  input.Count = balls.Count;
  input.Kernel = request.Kernel;
  input.Threshold = request.Threshold;
  pointsurfaces::MetaballCastSettings settings;
  std::copy_n(view.WorldToView, 16, settings.WorldToView);
  std::copy_n(view.ViewToClip, 16, settings.ViewToClip);
  std::copy_n(view.ClipToView, 16, settings.ClipToView);
  settings.Parallel = view.Parallel;
  settings.Width = view.Width;
  settings.Height = view.Height;
  settings.TileSize = request.TileSize;
  settings.Slabs = request.Slabs;
  settings.StepScale = request.StepScale;
  settings.Bisections = request.Bisections;
  settings.MemoryLimit = request.MemoryLimit;
  pointsurfaces::CastMetaballs(input, settings, this->Images, &stats);
  if (!stats.Error.empty())
  {
    return false; // the mapper reports stats.Error
  }
  // The count of rays starting inside goes through the ring like the
  // shaders' counts (the shadow rays add to it).
  const unsigned int initial[vtkMetaballGPUCounters::Count] = { static_cast<unsigned int>(
    std::min<long long>(stats.StartingInside, 0xffffffffLL)) };
  counters->Upload(initial, sizeof(initial));
  // Into the textures that the shading pass and the shadow rays read.
  const pointsurfaces::MetaballCastImages& cast = this->Images;
  pointsurfaces::UploadTexture(
    images.Color, view.Width, view.Height, GL_RGBA, GL_UNSIGNED_BYTE, cast.Color.data());
  pointsurfaces::UploadTexture(
    images.Normal, view.Width, view.Height, GL_RGBA, GL_FLOAT, cast.NormalDistance.data());
  pointsurfaces::UploadTexture(
    images.Depth, view.Width, view.Height, GL_RED, GL_FLOAT, cast.Depth.data());
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    vtkErrorMacro(<< "The CPU ray caster's images did not reach the GPU (GL error " << error
                  << "): nothing is drawn.");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMetaballCPURayCaster::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Last images: " << this->Images.Width << " x " << this->Images.Height << "\n";
}
