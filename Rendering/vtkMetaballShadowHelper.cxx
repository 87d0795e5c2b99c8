// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkMetaballShadowHelper.h"

#include "vtkCamera.h"
#include "vtkComputeShaderProgram.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMetaballGridBuilder.h"
#include "vtkMetaballShadowCS.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkShaderStorageBuffer.h"
#include "vtkTextureObject.h"

#include "psMetaballShaderKernel.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkMetaballShadowHelper);

namespace
{
constexpr int LightSize = 256; // the light grid's viewport, pixels
constexpr int LightTile = 16;  // its tile side
constexpr int LightSlabs = 16; // its slabs
constexpr int MaxShadowedLights = 4;

// A camera at the light that frames the sphere (centre, radius): perspective
// from a positional light, parallel along a directional one's direction.
// False for a light without a direction.
bool LightCamera(vtkLight* light, const double centre[3], double radius, vtkCamera* eye)
{
  double position[3], focal[3], dir[3];
  light->GetTransformedPosition(position);
  light->GetTransformedFocalPoint(focal);
  vtkMath::Subtract(focal, position, dir);
  if (vtkMath::Normalize(dir) == 0.0)
  {
    return false;
  }
  double up[3] = { 0.0, 1.0, 0.0 };
  if (std::abs(dir[1]) > 0.9)
  {
    up[0] = 1.0;
    up[1] = 0.0;
  }
  if (light->GetPositional())
  {
    const double distance = std::sqrt(vtkMath::Distance2BetweenPoints(position, centre));
    eye->SetPosition(position);
    eye->SetFocalPoint(centre);
    eye->SetViewUp(up);
    const double half = distance > radius ? std::asin(radius / distance) : 1.45;
    eye->SetViewAngle(std::min(170.0, 2.0 * vtkMath::DegreesFromRadians(half) * 1.05));
    eye->SetClippingRange(std::max(distance - radius, 1e-3 * distance), distance + radius);
    return true;
  }
  eye->SetPosition(centre[0] - 2.0 * radius * dir[0],
    centre[1] - 2.0 * radius * dir[1],
    centre[2] - 2.0 * radius * dir[2]);
  eye->SetFocalPoint(centre);
  eye->SetViewUp(up);
  eye->ParallelProjectionOn();
  eye->SetParallelScale(radius);
  eye->SetClippingRange(0.5 * radius, 3.5 * radius);
  return true;
}
} // namespace

//------------------------------------------------------------------------------
vtkMetaballShadowHelper::vtkMetaballShadowHelper() = default;

//------------------------------------------------------------------------------
vtkMetaballShadowHelper::~vtkMetaballShadowHelper() = default;

//------------------------------------------------------------------------------
vtkComputeShaderProgram* vtkMetaballShadowHelper::Program(vtkOpenGLRenderWindow* renWin,
  pointsurfaces::MetaballKernel kernel)
{
  const std::string defines = pointsurfaces::MetaballKernelDefines(kernel);
  return pointsurfaces::ReadyMetaballProgram(
    this->Shadow, renWin, "vtkMetaballShadowCS", vtkMetaballShadowCS, defines, this->Defines, this);
}

//------------------------------------------------------------------------------
int vtkMetaballShadowHelper::Cast(vtkRenderer* ren,
  const pointsurfaces::MetaballCastRequest& request,
  const pointsurfaces::MetaballBalls& balls,
  const pointsurfaces::MetaballImages& images,
  vtkMatrix4x4* model,
  const double bounds[6],
  vtkShaderStorageBuffer* counters)
{
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  const pointsurfaces::MetaballView& view = request.View;
  const int width = view.Width, height = view.Height;
  // The GPU time of the light grids and shadow rays, stopped on every way out.
  this->Timer.ReusableStart();
  struct StopAtExit
  {
    vtkOpenGLRenderTimer& Timer;
    ~StopAtExit() { this->Timer.ReusableStop(); }
  } stop{ this->Timer };
  if (this->ShadowImage->GetWidth() != static_cast<unsigned int>(width) ||
    this->ShadowImage->GetHeight() != static_cast<unsigned int>(height) ||
    !this->ShadowImage->GetHandle())
  {
    this->ShadowImage->SetContext(renWin);
    this->ShadowImage->Allocate2D(width, height, 4, VTK_FLOAT);
  }
  const float clear[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  glClearTexImage(this->ShadowImage->GetHandle(), 0, GL_RGBA, GL_FLOAT, clear);
  vtkComputeShaderProgram* shadow = this->Program(renWin, request.Kernel);
  if (!shadow)
  {
    return 0;
  }
  // The light cameras frame the balls' bounds (all of them: casters may lie
  // outside the view).
  double centre[3], radius = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    centre[k] = 0.5 * (bounds[2 * k] + bounds[2 * k + 1]);
    radius += 0.25 * (bounds[2 * k + 1] - bounds[2 * k]) * (bounds[2 * k + 1] - bounds[2 * k]);
  }
  radius = std::max(std::sqrt(radius), 1e-30);
  vtkNew<vtkMatrix4x4> worldToView, viewToModel;
  worldToView->DeepCopy(view.WorldToView);
  vtkMatrix4x4::Invert(worldToView, viewToModel);
  this->LightGrid->SetTileSize(LightTile);
  this->LightGrid->SetSlabs(LightSlabs);
  int lights = 0;
  vtkCollectionSimpleIterator it;
  ren->GetLights()->InitTraversal(it);
  while (vtkLight* light = ren->GetLights()->GetNextLight(it))
  {
    if (!light->GetSwitch() || lights >= MaxShadowedLights)
    {
      continue;
    }
    const int index = lights++;
    vtkNew<vtkCamera> eye;
    if (!LightCamera(light, centre, radius, eye))
    {
      continue;
    }
    vtkNew<vtkMatrix4x4> modelToLight, lightToClip;
    vtkMatrix4x4::Multiply4x4(eye->GetViewTransformMatrix(), model, modelToLight);
    lightToClip->DeepCopy(eye->GetProjectionTransformMatrix(1.0, -1, 1));
    if (!this->LightGrid->Build(renWin,
          balls.Balls,
          balls.Count,
          modelToLight->GetData(),
          lightToClip->GetData(),
          eye->GetParallelProjection() != 0,
          LightSize,
          LightSize))
    {
      return 0;
    }
    shadow->Bind(renWin);
    float m[16];
    pointsurfaces::ToFloat(view.ClipToView, m);
    shadow->SetUniformMatrix4x4("clipToView", m);
    pointsurfaces::ToFloat(viewToModel->GetData(), m);
    shadow->SetUniformMatrix4x4("viewToModel", m);
    pointsurfaces::ToFloat(modelToLight->GetData(), m);
    shadow->SetUniformMatrix4x4("modelToLight", m);
    pointsurfaces::ToFloat(lightToClip->GetData(), m);
    shadow->SetUniformMatrix4x4("lightToClip", m);
    shadow->SetUniformi("lightParallel", eye->GetParallelProjection());
    shadow->SetUniform2i("viewport", width, height);
    shadow->SetUniform2i("lightViewport", LightSize, LightSize);
    shadow->SetUniformi("tileSize", LightTile);
    shadow->SetUniform2i("tiles", this->LightGrid->GetTilesX(), this->LightGrid->GetTilesY());
    shadow->SetUniformi("slabs", LightSlabs);
    shadow->SetUniformf("threshold", static_cast<float>(request.Threshold));
    shadow->SetUniformf("stepScale", static_cast<float>(request.StepScale));
    shadow->SetUniformf("selfOffset", static_cast<float>(0.05 * balls.MinRadius));
    shadow->SetUniformi("lightIndex", index);
    shadow->SetUniformi("useStrengths", balls.HasStrengths ? 1 : 0);
    balls.Balls->BindBase(0);
    balls.Strengths->BindBase(2);
    this->LightGrid->GetVoxelOffsets()->BindBase(3);
    this->LightGrid->GetVoxelBalls()->BindBase(4);
    counters->BindBase(5);                             // this frame's counters
    this->LightGrid->GetGridStatistics()->BindBase(6); // the slab range
    glBindImageTexture(2, images.Depth->GetHandle(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
    glBindImageTexture(
      3, this->ShadowImage->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    shadow->Dispatch(vtkComputeShaderProgram::GroupCount(width, 16),
      vtkComputeShaderProgram::GroupCount(height, 16),
      1,
      GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    shadow->Unbind();
  }
  return lights;
}

//------------------------------------------------------------------------------
vtkTextureObject* vtkMetaballShadowHelper::GetShadowImage()
{
  return this->ShadowImage;
}

//------------------------------------------------------------------------------
vtkIdType vtkMetaballShadowHelper::GetNumberOfReadBacks()
{
  return this->LightGrid->GetNumberOfReadBacks();
}

//------------------------------------------------------------------------------
vtkIdType vtkMetaballShadowHelper::GetNumberOfOverflows()
{
  return this->LightGrid->GetNumberOfOverflows();
}

//------------------------------------------------------------------------------
double vtkMetaballShadowHelper::GetElapsedSeconds()
{
  return this->Timer.GetReusableElapsedSeconds();
}

//------------------------------------------------------------------------------
void vtkMetaballShadowHelper::ReleaseGraphicsResources(vtkWindow* win)
{
  this->Timer.ReleaseGraphicsResources();
  this->LightGrid->ReleaseGraphicsResources(win);
  this->Shadow->ReleaseGraphicsResources(win);
  this->Defines.clear();
  this->ShadowImage->ReleaseGraphicsResources(win);
}

//------------------------------------------------------------------------------
void vtkMetaballShadowHelper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Program compiled: " << this->Shadow->IsCompiled() << "\n";
}
