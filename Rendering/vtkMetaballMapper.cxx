// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkMetaballMapper.h"

#include "psMetaballFrame.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkHardwareSelector.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMetaballCPURayCaster.h"
#include "vtkMetaballCompositor.h"
#include "vtkMetaballGPUCounters.h"
#include "vtkMetaballGPURayCaster.h"
#include "vtkMetaballSelectionHelper.h"
#include "vtkMetaballShadowHelper.h"
#include "vtkMetaballUploader.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkScalarsToColors.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMetaballMapper);

namespace
{
// The selector's bracket around one prop, as vtkOpenGLPolyDataMapper sets
// it: BeginRenderProp sets the actor and process passes' colour,
// RenderCompositeIndex the composite pass's (1 for a plain data set), and
// the largest ids tell the selector whether the high-24-bit passes run.
class SelectorProp
{
public:
  SelectorProp(vtkHardwareSelector* selector, vtkIdType count)
    : Selector(selector)
  {
    if (!selector)
    {
      return;
    }
    selector->BeginRenderProp();
    if (selector->GetCurrentPass() == vtkHardwareSelector::COMPOSITE_INDEX_PASS)
    {
      selector->RenderCompositeIndex(1);
    }
    selector->UpdateMaximumPointId(count - 1);
    selector->UpdateMaximumCellId(count - 1);
  }
  ~SelectorProp()
  {
    if (this->Selector)
    {
      this->Selector->EndRenderProp();
    }
  }
  SelectorProp(const SelectorProp&) = delete;
  SelectorProp& operator=(const SelectorProp&) = delete;

private:
  vtkHardwareSelector* Selector;
};

} // namespace

// The frame's data, the passes and the state kept between frames.
struct vtkMetaballMapper::Internals
{
  pointsurfaces::MetaballBalls Balls;
  pointsurfaces::MetaballImages Images;
  vtkNew<vtkMetaballGPURayCaster> GPUCaster;
  vtkNew<vtkMetaballCPURayCaster> CPUCaster;
  vtkNew<vtkMetaballShadowHelper> Shadows;
  vtkNew<vtkMetaballSelectionHelper> Selection;
  vtkNew<vtkMetaballGPUCounters> Counters;
  vtkIdType CounterReadBacks = 0; // the counters read at once (CollectStatistics)
  vtkNew<vtkMetaballUploader> Uploader;
  // The bounds of the finite points, when some point is not finite.
  double FiniteBounds[6] = { 1, -1, 1, -1, 1, -1 };
  vtkPoints* FiniteBoundsOf = nullptr;
  vtkMTimeType FiniteBoundsTime = 0;
  bool WarnedShadow = false;
  bool WarnedInside = false;
  bool WarnedBudget = false;
  vtkNew<vtkMetaballCompositor> Compositor;
  vtkTimeStamp UploadTime;
  // The view of the images' last cast. A selection's passes (the selector
  // renders once per pass) reuse its hits when the view, the viewport, the
  // balls and the settings are unchanged, so that every pass, and the frame
  // drawn before them, has the same hits and depths.
  pointsurfaces::MetaballView Cast;
  bool CastValid = false;
  unsigned long CastSerial = 0; // counts casts; the selection's cache names the one it is from
};

//------------------------------------------------------------------------------
void vtkMetaballMapper::ReportCounters(const unsigned int counters[9])
{
  Internals& in = *this->Impl;
  if (this->RayCasterInUse == GPU)
  {
    // Where the shaders' time went (the CPU ray caster sets its own, in 64 bits).
    this->NumberOfSamples = counters[3];
    this->NumberOfBisectionSamples = counters[4];
    this->NumberOfVoxelVisits = counters[5];
    this->NumberOfEmptyVoxelVisits = counters[6];
    this->NumberOfKernelTerms = counters[7];
    this->NumberOfHits = counters[8];
  }
  this->NumberOfPixelsStartingInside = counters[0];
  this->NumberOfIncompleteRays = counters[1];
  if (counters[1] > 0 && !in.WarnedBudget)
  {
    vtkWarningMacro(<< counters[1]
                    << " rays stopped before finding the surface: they ran out of the GL "
                       "driver's loop iterations (llvmpipe allows 65535 per shader invocation). "
                       "Raise StepScale, or use more Slabs or a smaller TileSize so that voxels "
                       "hold fewer balls.");
  }
  in.WarnedBudget = counters[1] > 0;
  if (counters[0] > 0 && !in.WarnedInside)
  {
    vtkWarningMacro(<< "The near clipping plane cuts into the metaball surface (the camera is "
                       "inside it, or a ball crosses the near plane): "
                    << counters[0] << " pixels show the surface from within.");
  }
  in.WarnedInside = counters[0] > 0;
  if (counters[2] > 0 && !in.WarnedShadow)
  {
    vtkWarningMacro(<< counters[2]
                    << " shadow rays stopped short of the light: they ran out of the GL "
                       "driver's loop iterations (llvmpipe allows 65535 per shader "
                       "invocation) and are left lit.");
  }
  in.WarnedShadow = counters[2] > 0;
}

//------------------------------------------------------------------------------
vtkMetaballMapper::vtkMetaballMapper()
  : Field(vtkSmartPointer<vtkMetaballField>::New())
  , Impl(new Internals)
{
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::SetField(vtkMetaballField* field)
{
  vtkMetaballField::Assign(this->Field, field, this);
}

//------------------------------------------------------------------------------
vtkMTimeType vtkMetaballMapper::GetMTime()
{
  return std::max(this->Superclass::GetMTime(), this->Field->GetMTime());
}

//------------------------------------------------------------------------------
vtkMetaballMapper::~vtkMetaballMapper() = default;

//------------------------------------------------------------------------------
int vtkMetaballMapper::CanUseTextureMapForColoring(vtkDataObject*)
{
  return 0;
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::SetInputData(vtkPointSet* input)
{
  this->SetInputDataInternal(0, input);
}

//------------------------------------------------------------------------------
vtkPointSet* vtkMetaballMapper::GetInput()
{
  return vtkPointSet::SafeDownCast(this->GetInputDataObject(0, 0));
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::UpdateInput()
{
  if (this->Static || this->GetNumberOfInputConnections(0) == 0)
  {
    return;
  }
  int port = 0;
  if (vtkAlgorithm* producer = this->GetInputAlgorithm(0, 0, port))
  {
    producer->Update(port);
  }
}

//------------------------------------------------------------------------------
double* vtkMetaballMapper::GetBounds()
{
  this->UpdateInput();
  this->ComputeBounds();
  return this->Bounds;
}

//------------------------------------------------------------------------------
int vtkMetaballMapper::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::FiniteBounds(vtkPointSet* input, double bounds[6])
{
  // One NaN or infinite point (an invalid ball, skipped and counted) must
  // not make the bounds infinite or stretch them along its finite
  // coordinates: the camera would be lost, and the shift that keeps
  // coordinates near 1e7 precise in float would be 0.
  vtkPoints* points = input->GetPoints();
  points->GetBounds(bounds); // cached by VTK
  if (std::all_of(bounds, bounds + 6, [](double v) { return std::isfinite(v); }))
  {
    // The usual case, at no cost. (VTK skips NaN values per coordinate, so
    // a point with a NaN and far finite coordinates still stretches them.)
    return;
  }
  Internals& in = *this->Impl;
  const vtkMTimeType time = points->GetMTime();
  if (in.FiniteBoundsOf != points || in.FiniteBoundsTime != time)
  {
    struct Box
    {
      double B[6] = { VTK_DOUBLE_MAX,
        VTK_DOUBLE_MIN,
        VTK_DOUBLE_MAX,
        VTK_DOUBLE_MIN,
        VTK_DOUBLE_MAX,
        VTK_DOUBLE_MIN };
    };
    vtkSMPThreadLocal<Box> boxes;
    vtkDataArray* xyz = points->GetData();
    vtkSMPTools::For(0,
      points->GetNumberOfPoints(),
      [&](vtkIdType begin, vtkIdType end)
      {
        double* b = boxes.Local().B;
        double p[3];
        for (vtkIdType i = begin; i < end; ++i)
        {
          xyz->GetTuple(i, p);
          if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
          {
            for (int k = 0; k < 3; ++k)
            {
              b[2 * k] = std::min(b[2 * k], p[k]);
              b[2 * k + 1] = std::max(b[2 * k + 1], p[k]);
            }
          }
        }
      });
    Box all;
    for (const Box& box : boxes)
    {
      for (int k = 0; k < 3; ++k)
      {
        all.B[2 * k] = std::min(all.B[2 * k], box.B[2 * k]);
        all.B[2 * k + 1] = std::max(all.B[2 * k + 1], box.B[2 * k + 1]);
      }
    }
    std::copy_n(all.B, 6, in.FiniteBounds);
    if (!(all.B[0] <= all.B[1]))
    {
      vtkMath::UninitializeBounds(in.FiniteBounds); // no finite point
    }
    in.FiniteBoundsOf = points;
    in.FiniteBoundsTime = time;
  }
  std::copy_n(in.FiniteBounds, 6, bounds);
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::ComputeBounds()
{
  vtkPointSet* input = vtkPointSet::SafeDownCast(this->GetInputDataObject(0, 0));
  if (!input || input->GetNumberOfPoints() == 0)
  {
    vtkMath::UninitializeBounds(this->Bounds);
    return;
  }
  FiniteBounds(input, this->Bounds);
  const double pad = this->Field->GetLargestRadius(input);
  for (int k = 0; k < 3; ++k)
  {
    this->Bounds[2 * k] -= pad;
    this->Bounds[2 * k + 1] += pad;
  }
}

//------------------------------------------------------------------------------
bool vtkMetaballMapper::Upload(vtkRenderer* ren, vtkActor* act, vtkPointSet* input)
{
  Internals& in = *this->Impl;
  pointsurfaces::MetaballBalls& balls = in.Balls;
  // The invalid balls of earlier GPU uploads that the GPU has counted since
  // (also when nothing changes now).
  const auto report = [this](vtkIdType invalid) { this->ReportInvalidBalls(invalid); };
  in.Uploader->Poll(report);
  vtkMTimeType latest = std::max(input->GetMTime(), this->GetMTime());
  latest = std::max(latest, act->GetProperty()->GetMTime());
  latest = std::max(latest, act->GetMTime());
  if (this->LookupTable)
  {
    latest = std::max(latest, this->LookupTable->GetMTime());
  }
  if (in.UploadTime.GetMTime() > latest && balls.Count == input->GetNumberOfPoints())
  {
    this->UploadTime = 0.0;
    return true; // nothing changed: nothing is uploaded
  }
  const auto start = std::chrono::steady_clock::now();
  struct Stopwatch // the upload's wall time, on every way out
  {
    double& Milliseconds;
    std::chrono::steady_clock::time_point Start;
    ~Stopwatch()
    {
      this->Milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - this->Start)
          .count();
    }
  } stopwatch{ this->UploadTime, start };
  const vtkIdType n = input->GetNumberOfPoints();
  if (static_cast<size_t>(n) * 4 * sizeof(float) > vtkShaderStorageBuffer::GetMaximumSize())
  {
    vtkErrorMacro(<< n << " balls exceed the GPU's shader storage buffer limit of "
                  << vtkShaderStorageBuffer::GetMaximumSize() << " bytes: nothing is drawn.");
    balls.Count = 0;
    return false;
  }
  // Float, relative to the centre of the points' bounds, rounded to float so
  // that float positions shifted on the GPU land where the host puts them.
  double bounds[6];
  FiniteBounds(input, bounds);
  for (int k = 0; k < 3; ++k)
  {
    const float c = static_cast<float>(0.5 * (bounds[2 * k] + bounds[2 * k + 1]));
    balls.Shift[k] = std::isfinite(c) ? c : 0.0;
  }
  vtkUnsignedCharArray* mapped = this->MapScalars(input, 1.0);
  bool ok = false;
  if (this->UsesCPUCaster())
  {
    // The CPU ray caster reads the host's float balls: made, then sent.
    this->HostCopy(act, input, mapped, true);
    const std::vector<float>& hostBalls = balls.HostBalls;
    ok =
      balls.Balls->Upload(hostBalls.data(), std::max<size_t>(hostBalls.size(), 4) * sizeof(float));
    ok = ok &&
      balls.Colors->Upload(balls.HostColors.data(), balls.HostColors.size() * sizeof(unsigned int));
    ok = ok &&
      balls.Strengths->Upload(
        balls.HostStrengths.data(), balls.HostStrengths.size() * sizeof(float));
    balls.ColorPerBall = true;
    balls.Count = ok ? n : 0;
    this->UploadCopyTime = 0.0;
    this->UploadedBytes = static_cast<double>(n) * (4 + 1 + (balls.HasStrengths ? 1 : 0)) * 4.0;
  }
  else
  {
    // The GPU's balls straight from the input's arrays; no host copy.
    const pointsurfaces::RadiusSource source = this->Field->ChooseRadii(input);
    const pointsurfaces::BallRule rule = this->Field->GetRule();
    pointsurfaces::BallArrays missing;
    missing.MissingStrengths =
      !rule.StrengthArrayName.empty() && !pointsurfaces::StrengthArray(input, rule);
    if (!rule.DensityArrayName.empty() &&
      !input->GetPointData()->GetArray(rule.DensityArrayName.c_str()))
    {
      missing.MissingDensityName = rule.DensityArrayName;
    }
    const std::string strengthWarning =
      pointsurfaces::MissingStrengthsWarning(missing, this->Field->GetStrengthArrayName());
    if (!strengthWarning.empty())
    {
      vtkWarningMacro(<< strengthWarning);
    }
    balls.HostValid = false;
    ok = in.Uploader->Upload(static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow()),
      input,
      rule,
      source,
      ActorScale(act),
      mapped,
      pointsurfaces::PlainColor(act->GetProperty()),
      this->CollectStatistics,
      report,
      balls);
    in.CounterReadBacks += this->CollectStatistics ? 1 : 0;
    this->UploadedBytes = in.Uploader->GetUploadedBytes();
    this->UploadCopyTime = in.Uploader->GetCopyTime();
  }
  ++this->NumberOfUploads;
  in.UploadTime.Modified();
  return ok;
}

//------------------------------------------------------------------------------
double vtkMetaballMapper::ActorScale(vtkActor* act)
{
  // Radii grow with the actor's largest axis scale.
  double scale = 1.0;
  if (!act->GetIsIdentity())
  {
    vtkMatrix4x4* m = act->GetMatrix();
    scale = 0.0;
    for (int a = 0; a < 3; ++a)
    {
      scale = std::max(scale,
        std::sqrt(m->GetElement(0, a) * m->GetElement(0, a) +
          m->GetElement(1, a) * m->GetElement(1, a) + m->GetElement(2, a) * m->GetElement(2, a)));
    }
  }
  return scale;
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::ReportInvalidBalls(vtkIdType invalid)
{
  this->NumberOfInvalidBalls = invalid;
  if (invalid > 0)
  {
    vtkWarningMacro(<< pointsurfaces::InvalidBallsWarning(invalid, this->Impl->Balls.Count));
  }
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::HostCopy(vtkActor* act,
  vtkPointSet* input,
  vtkUnsignedCharArray* mapped,
  bool warn)
{
  // The balls in double (Extracted), and in float relative to Shift with
  // their colours (the host arrays), as the CPU ray caster and a selection
  // read them.
  pointsurfaces::MetaballBalls& balls = this->Impl->Balls;
  const vtkIdType n = input->GetNumberOfPoints();
  this->Field->ExtractBalls(input, ActorScale(act), balls.Extracted);
  const std::string strengthWarning =
    pointsurfaces::MissingStrengthsWarning(balls.Extracted, this->Field->GetStrengthArrayName());
  if (warn && !strengthWarning.empty())
  {
    vtkWarningMacro(<< strengthWarning);
  }
  const vtkIdType invalid = balls.Convert(balls.Extracted.Set);
  if (warn && invalid > 0)
  {
    vtkWarningMacro(<< pointsurfaces::InvalidBallsWarning(invalid, n));
  }
  if (warn)
  {
    this->NumberOfInvalidBalls = invalid;
  }
  balls.ConvertColors(mapped, act->GetProperty(), n);
  balls.HasStrengths = balls.Extracted.Set.Strengths != nullptr;
  balls.HostValid = true;
}

//------------------------------------------------------------------------------
bool vtkMetaballMapper::UsesCPUCaster()
{
  return this->RayCaster == CPU || (this->RayCaster == AUTOMATIC && IsSoftwareRenderer());
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::Render(vtkRenderer* ren, vtkActor* act)
{
  Internals& in = *this->Impl;
  this->UpdateInput();
  vtkPointSet* input = this->GetInput();
  this->NumberOfPairs = this->MaximumBallsPerVoxel = this->NumberOfCulledBalls = 0;
  if (!input || input->GetNumberOfPoints() == 0)
  {
    return;
  }
  auto* renWin = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!renWin)
  {
    return;
  }
  // A hardware selection's pass (rare: a click or a drag) draws ball ids.
  vtkHardwareSelector* selector = ren->GetSelector();
  const SelectorProp selecting(selector, input->GetNumberOfPoints());
  this->InvokeEvent(vtkCommand::StartEvent, nullptr);
  if (!this->Upload(ren, act, input) || in.Balls.Count == 0)
  {
    return;
  }
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  if (width <= 0 || height <= 0)
  {
    return;
  }
  vtkNew<vtkMatrix4x4> model;
  pointsurfaces::MetaballCastRequest request;
  this->MakeRequest(ren, act, width, height, model, request);
  in.Images.Resize(renWin, width, height);
  // A selection pass reuses the last cast when it had this view and these balls.
  if (!(selector && in.CastValid && request.View.Same(in.Cast)))
  {
    const int shadowLights = this->CastFrame(ren, act, model, request, selector == nullptr);
    if (shadowLights < 0)
    {
      return;
    }
    if (!selector)
    {
      // Shade and composite with the true depth, depth-tested against the scene.
      if (in.Compositor->Draw(ren,
            act->GetProperty(),
            in.Cast,
            in.Images,
            shadowLights > 0 ? in.Shadows->GetShadowImage() : nullptr))
      {
        this->InvokeEvent(vtkCommand::EndEvent, nullptr);
      }
      return;
    }
  }
  this->DrawSelection(ren, act, selector, x0, y0);
  this->InvokeEvent(vtkCommand::EndEvent, nullptr);
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::MakeRequest(vtkRenderer* ren,
  vtkActor* act,
  int width,
  int height,
  vtkMatrix4x4* model,
  pointsurfaces::MetaballCastRequest& request)
{
  // The view: world (shifted) to view, and the projection.
  const Internals& in = *this->Impl;
  vtkCamera* cam = ren->GetActiveCamera();
  model->Identity();
  for (int k = 0; k < 3; ++k)
  {
    model->SetElement(k, 3, in.Balls.Shift[k]);
  }
  if (!act->GetIsIdentity())
  {
    vtkMatrix4x4::Multiply4x4(act->GetMatrix(), model, model);
  }
  vtkNew<vtkMatrix4x4> worldToView, viewToClip, clipToView;
  vtkMatrix4x4::Multiply4x4(cam->GetViewTransformMatrix(), model, worldToView);
  viewToClip->DeepCopy(cam->GetProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1));
  vtkMatrix4x4::Invert(viewToClip, clipToView);
  pointsurfaces::MetaballView& view = request.View;
  std::copy_n(worldToView->GetData(), 16, view.WorldToView);
  std::copy_n(viewToClip->GetData(), 16, view.ViewToClip);
  std::copy_n(clipToView->GetData(), 16, view.ClipToView);
  view.Parallel = cam->GetParallelProjection() != 0;
  view.Width = width;
  view.Height = height;
  view.Upload = in.UploadTime.GetMTime();
  view.Mapper = this->GetMTime();
  request.TileSize = this->TileSize;
  request.Slabs = this->Slabs;
  request.StepScale = this->StepScale;
  request.Bisections = this->Bisections;
  request.LevelOfDetailPixels = this->LevelOfDetailPixels;
  request.MemoryLimit = 1024.0 * static_cast<double>(this->MemoryLimit);
  request.Kernel = this->Field->GetKernelId();
  request.Threshold = this->Field->GetThreshold();
  request.CollectStatistics = this->CollectStatistics;
}

//------------------------------------------------------------------------------
int vtkMetaballMapper::CastFrame(vtkRenderer* ren,
  vtkActor* act,
  vtkMatrix4x4* model,
  const pointsurfaces::MetaballCastRequest& request,
  bool shadows)
{
  Internals& in = *this->Impl;
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  in.Cast = request.View;
  in.CastValid = false;
  ++in.CastSerial;
  in.Selection->Invalidate();
  // [Bolla 2010] Algorithms 2 and 3: the perspective grid, and coherent ray
  // casting into colour, normal and depth images, on the GPU or the CPU.
  const bool cpu = this->UsesCPUCaster();
  this->RayCasterInUse = cpu ? CPU : GPU;
  vtkMetaballRayCaster* caster = cpu ? static_cast<vtkMetaballRayCaster*>(in.CPUCaster)
                                     : static_cast<vtkMetaballRayCaster*>(in.GPUCaster);
  // The counters of earlier frames that the GPU has finished.
  const auto report = [this](const unsigned int counters[vtkMetaballGPUCounters::Count])
  { this->ReportCounters(counters); };
  in.Counters->BeginFrame(report);
  vtkShaderStorageBuffer* counters = in.Counters->GetFrameBuffer();
  pointsurfaces::MetaballCastStatistics stats;
  const bool cast = caster->Cast(renWin, request, in.Balls, in.Images, counters, stats);
  // A caster's reason for casting nothing, once while it lasts (not a frame).
  if (!cast && !stats.Error.empty() && stats.Error != this->LastCastError)
  {
    vtkErrorMacro(<< "The " << (cpu ? "CPU" : "GPU") << " ray caster cast nothing: " << stats.Error
                  << ".");
  }
  this->LastCastError = cast ? std::string() : stats.Error;
  this->TakeStatistics(stats, caster->CountsOnHost());
  // Shadows: secondary rays toward the lights (none for a selection).
  int shadowLights = 0;
  if (cast && this->Shadows && shadows)
  {
    // The light cameras frame all the balls: casters may lie outside the view.
    double bounds[6];
    this->GetBounds(bounds);
    if (!act->GetIsIdentity())
    {
      act->GetBounds(bounds);
    }
    shadowLights = in.Shadows->Cast(ren, request, in.Balls, in.Images, model, bounds, counters);
  }
  else
  {
    this->ShadowTime = 0.0;
  }
  // The frame's counters are complete: fenced, and read now only when asked to wait.
  in.Counters->EndFrame(report, this->CollectStatistics);
  in.CounterReadBacks += this->CollectStatistics ? 1 : 0;
  if (shadowLights > 0)
  {
    const double shadowSeconds = in.Shadows->GetElapsedSeconds();
    this->ShadowTime = shadowSeconds > 0.0 ? 1000.0 * shadowSeconds : this->ShadowTime;
  }
  in.CastValid = cast;
  return cast ? shadowLights : -1;
}

//------------------------------------------------------------------------------
vtkIdType vtkMetaballMapper::GetNumberOfReadBacks()
{
  const Internals& in = *this->Impl;
  return in.GPUCaster->GetNumberOfReadBacks() + in.Shadows->GetNumberOfReadBacks() +
    in.CounterReadBacks;
}

//------------------------------------------------------------------------------
vtkIdType vtkMetaballMapper::GetNumberOfGridOverflows()
{
  const Internals& in = *this->Impl;
  return in.GPUCaster->GetNumberOfOverflows() + in.Shadows->GetNumberOfOverflows();
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::TakeStatistics(const pointsurfaces::MetaballCastStatistics& stats,
  bool march)
{
  this->NumberOfPairs = stats.Pairs;
  this->NumberOfMergedBalls = stats.MergedBalls;
  this->NumberOfBallsMerged = stats.BallsMerged;
  this->MaximumBallsPerVoxel = stats.MaxPerVoxel;
  this->NumberOfCulledBalls = stats.Culled;
  this->NumberOfRays = stats.Rays;
  this->NumberOfSupportTests = stats.SupportTests;
  this->GridBuildTime = 1000.0 * stats.GridSeconds;
  // The GPU's time comes a frame late: 0 until then.
  this->RayCastTime = stats.CastSeconds > 0.0 ? 1000.0 * stats.CastSeconds : this->RayCastTime;
  if (march)
  {
    // Else they come with the shaders' counters (ReportCounters).
    this->NumberOfHits = stats.Hits;
    this->NumberOfVoxelVisits = stats.VoxelVisits;
    this->NumberOfEmptyVoxelVisits = stats.EmptyVoxelVisits;
    this->NumberOfSamples = stats.Samples;
    this->NumberOfBisectionSamples = stats.BisectionSamples;
    this->NumberOfKernelTerms = stats.KernelTerms;
  }
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::DrawSelection(vtkRenderer* ren,
  vtkActor* act,
  vtkHardwareSelector* selector,
  int x0,
  int y0)
{
  Internals& in = *this->Impl;
  // Ids through the input's id array when it has one (ParaView's original ids).
  vtkPointSet* input = this->GetInput();
  if (!in.Balls.HostValid && input)
  {
    // The GPU's balls came straight from the arrays: the selection reads the
    // host's (the upload has warned already; colours are not needed).
    this->HostCopy(act, input, nullptr, false);
  }
  vtkDataArray* ids = input && !this->PointIdArrayName.empty()
    ? input->GetPointData()->GetArray(this->PointIdArrayName.c_str())
    : nullptr;
  if (ids && ids->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    ids = nullptr;
  }
  in.Selection->Draw(static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow()),
    selector,
    x0,
    y0,
    in.Cast,
    in.CastSerial,
    in.Balls,
    in.Images,
    ids);
}

//------------------------------------------------------------------------------
bool vtkMetaballMapper::ReadHitBuffer(vtkFloatArray* hits)
{
  const pointsurfaces::MetaballImages& images = this->Impl->Images;
  if (!hits || images.Width <= 0 || !images.Normal->GetHandle())
  {
    return false;
  }
  hits->SetNumberOfComponents(4);
  hits->SetNumberOfTuples(static_cast<vtkIdType>(images.Width) * images.Height);
  return pointsurfaces::ReadTexture(images.Normal, GL_RGBA, GL_FLOAT, hits->GetPointer(0));
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::ReleaseGraphicsResources(vtkWindow* win)
{
  Internals& in = *this->Impl;
  in.Balls.ReleaseGraphicsResources(win);
  in.Images.ReleaseGraphicsResources(win);
  in.GPUCaster->ReleaseGraphicsResources(win);
  in.CPUCaster->ReleaseGraphicsResources(win);
  in.Shadows->ReleaseGraphicsResources(win);
  in.Selection->ReleaseGraphicsResources(win);
  in.Counters->ReleaseGraphicsResources(win);
  in.Uploader->ReleaseGraphicsResources(win);
  in.Compositor->ReleaseGraphicsResources(win);
  in.CastValid = false;
  in.UploadTime = vtkTimeStamp();
  this->Superclass::ReleaseGraphicsResources(win);
}

//------------------------------------------------------------------------------
bool vtkMetaballMapper::IsSoftwareRenderer()
{
  const char* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  std::string renderer = name ? name : "";
  std::transform(renderer.begin(),
    renderer.end(),
    renderer.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* software : { "llvmpipe", "softpipe", "swr", "software", "swiftshader" })
  {
    if (renderer.find(software) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Field:\n";
  this->Field->PrintSelf(os, indent.GetNextIndent());
  os << indent << "TileSize: " << this->TileSize << "\n";
  os << indent << "Slabs: " << this->Slabs << "\n";
  os << indent << "StepScale: " << this->StepScale << "\n";
  os << indent << "Bisections: " << this->Bisections << "\n";
  os << indent << "LevelOfDetailPixels: " << this->LevelOfDetailPixels << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " KiB\n";
  os << indent << "Shadows: " << this->Shadows << "\n";
}
