// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkMetaballMapper.h"

#include "psMetaballCast.h"
#include "psMetaballShaderKernel.h"
#include "psShaderHooks.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkComputeShaderProgram.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkHardwareSelector.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMetaballCompositeFS.h"
#include "vtkMetaballGridBuilder.h"
#include "vtkMetaballKernel.h"
#include "vtkMetaballRayCastCS.h"
#include "vtkMetaballShadowCS.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderTimer.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkScalarsToColors.h"
#include "vtkShaderProgram.h"
#include "vtkShaderStorageBuffer.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMetaballMapper);

namespace
{
// Reads the counters of ring slot `k` when its fence has passed (or at once
// after waiting, with `wait`); true when read.
// The counters of a frame, as vtkMetaballRayCastCS.glsl lists them.
constexpr int CounterCount = 9;

bool ReadCounterSlot(vtkShaderStorageBuffer* buffer,
  GLsync& fence,
  bool wait,
  unsigned int out[CounterCount])
{
  if (!fence)
  {
    return false;
  }
  const GLenum status =
    glClientWaitSync(fence, wait ? GL_SYNC_FLUSH_COMMANDS_BIT : 0, wait ? 10000000000ull : 0);
  if (status != GL_ALREADY_SIGNALED && status != GL_CONDITION_SATISFIED)
  {
    return false;
  }
  glDeleteSync(fence);
  fence = nullptr;
  return buffer->Download(out, CounterCount * sizeof(unsigned int));
}

const int MaxShared = 256; // balls per voxel batch in shared memory

void ToFloat(vtkMatrix4x4* m, float out[16])
{
  for (int k = 0; k < 16; ++k)
  {
    out[k] = static_cast<float>(m->GetElement(k / 4, k % 4));
  }
}

// The composite shader's //VTK::Light::Impl: one psLight call per light of
// the renderer, with VTK's uniforms for it (vtkOpenGLRenderer's names: a
// headlight has lightColor0 only). The first four lights can be shadowed.
std::string LightCalls(int complexity, int count)
{
  std::string code;
  for (int k = 0; k < count; ++k)
  {
    const std::string i = std::to_string(k);
    const std::string lit = k < 4 ? "1.0 - blocked[" + i + "]" : "1.0";
    if (complexity == 1)
    {
      code +=
        "result += psLight(n, toEye, base.rgb, lightColor0, vec3(0.0, 0.0, 1.0), " + lit + ");\n";
      break;
    }
    code += "toLight = -lightDirectionVC" + i + ";\nstrength = 1.0;\n";
    if (complexity >= 3)
    {
      code += "if (lightPositional" + i + " != 0)\n{\n  toLight = psPositional(p.xyz, " +
        "lightPositionVC" + i + ", lightDirectionVC" + i + ", lightAttenuation" + i +
        ", lightConeAngle" + i + ", lightExponent" + i + ", strength);\n}\n";
    }
    code += "result += strength * psLight(n, toEye, base.rgb, lightColor" + i + ", toLight, " +
      lit + ");\n";
  }
  return code;
}

// Fills a whole texture from the host (rows from the bottom).
void UploadImage(vtkTextureObject* texture,
  int width,
  int height,
  GLenum format,
  GLenum type,
  const void* data)
{
  texture->Bind();
  texture->GetContext()->GetState()->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, format, type, data);
  texture->Deactivate();
}

// Reads a whole texture back (rows from the bottom, 4-byte pixels or
// larger, so that no row padding applies); false on a GL error of its own
// (errors left pending by others are cleared first).
bool ReadImage(vtkTextureObject* texture, GLenum format, GLenum type, void* data)
{
  for (int k = 0; k < 16 && glGetError() != GL_NO_ERROR; ++k)
  {
  }
  texture->Bind();
  glGetTexImage(GL_TEXTURE_2D, 0, format, type, data);
  texture->Deactivate();
  return glGetError() == GL_NO_ERROR;
}

// A selection pixel that no ray hit (PickBalls); -1 is a hit without a ball.
constexpr vtkIdType NoHit = -2;
// The screen tile side of the selection grid, in pixels.
constexpr int PickTile = 8;

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

// The slab of a perspective grid that holds view distance d, clamped.
int SlabOf(const std::vector<double>& planes, double d)
{
  const int k =
    static_cast<int>(std::upper_bound(planes.begin(), planes.end(), d) - planes.begin());
  return std::min(std::max(k - 1, 0), static_cast<int>(planes.size()) - 2);
}

// The view-space point at view distance `distance` on the ray through the
// centre of pixel (x, y), as the ray casters cast it.
void HitPoint(const double clipToView[16],
  int width,
  int height,
  int x,
  int y,
  double distance,
  double point[3])
{
  const double ndc[2] = { (x + 0.5) / width * 2.0 - 1.0, (y + 0.5) / height * 2.0 - 1.0 };
  double ends[2][4];
  for (int e = 0; e < 2; ++e)
  {
    const double clip[4] = { ndc[0], ndc[1], e == 0 ? -1.0 : 1.0, 1.0 };
    for (int r = 0; r < 4; ++r)
    {
      ends[e][r] = clipToView[4 * r] * clip[0] + clipToView[4 * r + 1] * clip[1] +
        clipToView[4 * r + 2] * clip[2] + clipToView[4 * r + 3] * clip[3];
    }
    for (int r = 0; r < 3; ++r)
    {
      ends[e][r] /= ends[e][3];
    }
  }
  const double dz = ends[1][2] - ends[0][2];
  const double t = dz != 0.0 ? (-distance - ends[0][2]) / dz : 0.0;
  for (int r = 0; r < 3; ++r)
  {
    point[r] = ends[0][r] + t * (ends[1][r] - ends[0][r]);
  }
}
// The composite passes' depth and blend state: depth-tested against the
// scene (LEQUAL, written), no blending; the previous state comes back when it
// goes out of scope. Only what is changed is saved, not Push and Pop: VTK
// 9.6's Pop binds again the buffers its cache holds, which may have been
// deleted since (by this mapper's shader rebuild or by another mapper).
struct CompositeDepthState
{
  vtkOpenGLState::ScopedglEnableDisable DepthTest;
  vtkOpenGLState::ScopedglEnableDisable Blend;
  vtkOpenGLState::ScopedglDepthFunc DepthFunc;
  vtkOpenGLState::ScopedglDepthMask DepthMask;

  explicit CompositeDepthState(vtkOpenGLState* ostate)
    : DepthTest(ostate, GL_DEPTH_TEST)
    , Blend(ostate, GL_BLEND)
    , DepthFunc(ostate)
    , DepthMask(ostate)
  {
    ostate->vtkglEnable(GL_DEPTH_TEST);
    ostate->vtkglDepthFunc(GL_LEQUAL);
    ostate->vtkglDepthMask(GL_TRUE);
    ostate->vtkglDisable(GL_BLEND);
  }
};
} // namespace

struct vtkMetaballMapper::Internals
{
  vtkNew<vtkMetaballGridBuilder> Grid;
  vtkNew<vtkMetaballGridBuilder> LightGrid;
  vtkNew<vtkComputeShaderProgram> Shadow;
  std::string ShadowDefines;
  vtkNew<vtkTextureObject> ShadowImage;
  double MinRadius = 1.0;
  bool WarnedShadow = false;
  vtkNew<vtkShaderStorageBuffer> Balls, Colors, Strengths;
  // The shaders' counters (pixels starting inside, rays and shadow rays cut
  // by the loop limit) in a ring of buffers: each frame adds into a fresh
  // one and fences it, and a later frame reads those whose fence the GPU has
  // passed, so that no frame waits to read them (CollectStatistics waits).
  static constexpr int Ring = 3;
  vtkNew<vtkShaderStorageBuffer> Counters[Ring];
  GLsync Fences[Ring] = { nullptr, nullptr, nullptr };
  int Next = 0;
  vtkOpenGLRenderTimer CastTimer, ShadowTimer; // GPU times, read a frame late
  bool WarnedInside = false;
  bool WarnedBudget = false;
  vtkNew<vtkComputeShaderProgram> RayCast;
  std::string RayCastDefines;
  vtkNew<vtkTextureObject> ColorImage, NormalImage, DepthImage;
  std::unique_ptr<vtkOpenGLQuadHelper> Composite;
  int CompositeLighting = -1; // the lighting complexity and light count it was built for
  int CompositeLights = -1;
  vtkTimeStamp UploadTime;
  double Shift[3] = { 0.0, 0.0, 0.0 };
  vtkIdType Count = 0;
  bool HasStrengths = false;
  // The input's balls in double, and what went to the GPU (kept for the CPU
  // ray caster); reused frame after frame, so that a series of 10M balls
  // does not allocate and fault in half a gigabyte a frame. Its last images.
  pointsurfaces::BallArrays Extracted;
  std::vector<float> HostBalls, HostStrengths;
  std::vector<unsigned int> HostColors;
  pointsurfaces::MetaballCastImages CastImages;
  int Width = 0;
  int Height = 0;

  // The view of the images' last cast. A selection's passes (the selector
  // renders once per pass) reuse its hits when the view, the viewport, the
  // balls and the settings are unchanged, so that every pass, and the frame
  // drawn before them, has the same hits and depths.
  struct CastView
  {
    double WorldToView[16] = {}; // the float balls (shifted) to view
    double ViewToClip[16] = {};
    double ClipToView[16] = {};
    bool Parallel = false;
    int Width = 0, Height = 0;
    vtkMTimeType Upload = 0, Mapper = 0;

    bool Same(const CastView& o) const
    {
      return std::equal(this->WorldToView, this->WorldToView + 16, o.WorldToView) &&
        std::equal(this->ViewToClip, this->ViewToClip + 16, o.ViewToClip) &&
        this->Parallel == o.Parallel && this->Width == o.Width && this->Height == o.Height &&
        this->Upload == o.Upload && this->Mapper == o.Mapper;
    }
  };
  CastView Cast;
  bool CastValid = false;
  unsigned long CastSerial = 0; // counts casts; selection caches name the one they come from
  // Selection: the ball id per pixel of the area (NoHit, -1: hit, no ball),
  // for the cast CastSerial; the pass's colours, the texture and the shader.
  std::vector<vtkIdType> PickIds;
  unsigned long PickSerial = 0;
  int PickArea[4] = { 0, 0, -1, -1 };
  std::vector<unsigned char> PickPixels;
  vtkNew<vtkTextureObject> PickImage;
  std::unique_ptr<vtkOpenGLQuadHelper> PickComposite;
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
void vtkMetaballMapper::ComputeBounds()
{
  vtkPointSet* input = vtkPointSet::SafeDownCast(this->GetInputDataObject(0, 0));
  if (!input || input->GetNumberOfPoints() == 0)
  {
    vtkMath::UninitializeBounds(this->Bounds);
    return;
  }
  input->GetPoints()->GetBounds(this->Bounds);
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
  vtkMTimeType latest = std::max(input->GetMTime(), this->GetMTime());
  latest = std::max(latest, act->GetProperty()->GetMTime());
  latest = std::max(latest, act->GetMTime());
  if (this->LookupTable)
  {
    latest = std::max(latest, this->LookupTable->GetMTime());
  }
  if (in.UploadTime.GetMTime() > latest && in.Count == input->GetNumberOfPoints())
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
    in.Count = 0;
    return false;
  }
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
  this->Field->ExtractBalls(input, scale, in.Extracted);
  const pointsurfaces::BallArrays& extracted = in.Extracted;
  const std::string strengthWarning =
    pointsurfaces::MissingStrengthsWarning(extracted, this->Field->GetStrengthArrayName());
  if (!strengthWarning.empty())
  {
    vtkWarningMacro(<< strengthWarning);
  }
  const pointsurfaces::MetaballSet& set = extracted.Set;
  const bool strengths = set.Strengths != nullptr;
  double bounds[6];
  input->GetPoints()->GetBounds(bounds);
  for (int k = 0; k < 3; ++k)
  {
    const double c = 0.5 * (bounds[2 * k] + bounds[2 * k + 1]);
    in.Shift[k] = std::isfinite(c) ? c : 0.0;
  }
  // Float, relative to the centre; an invalid ball gets radius 0, which the
  // grid skips.
  std::vector<float>& balls = in.HostBalls;
  std::vector<float>& q = in.HostStrengths;
  balls.resize(4 * n);
  q.assign(strengths ? n : 1, 1.0f);
  std::atomic<vtkIdType> invalidCount(0);
  struct Smallest
  {
    double Value = std::numeric_limits<double>::max();
  };
  vtkSMPThreadLocal<Smallest> smallest;
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      vtkIdType bad = 0;
      double& least = smallest.Local().Value;
      for (vtkIdType i = begin; i < end; ++i)
      {
        const double r = set.Radii[i];
        for (int k = 0; k < 3; ++k)
        {
          balls[4 * i + k] = static_cast<float>(set.Centers[3 * i + k] - in.Shift[k]);
        }
        balls[4 * i + 3] = static_cast<float>(r);
        if (strengths)
        {
          q[i] = static_cast<float>(set.Strengths[i]);
        }
        // Usable as psMetaball's ValidBall says, with a strength that
        // stays finite in float.
        if (!pointsurfaces::ValidBall(set, i) || (strengths && !std::isfinite(q[i])))
        {
          balls[4 * i + 3] = 0.0f;
          ++bad;
        }
        else
        {
          least = std::min(least, r);
        }
      }
      invalidCount += bad;
    });
  const vtkIdType invalid = invalidCount;
  double minRadius = std::numeric_limits<double>::max();
  for (const Smallest& s : smallest)
  {
    minRadius = std::min(minRadius, s.Value);
  }
  in.MinRadius = invalid < n ? minRadius : 1.0;
  if (invalid > 0)
  {
    vtkWarningMacro(<< pointsurfaces::InvalidBallsWarning(invalid, n));
  }
  // Colours: the usual scalar colouring, or the actor's colour.
  std::vector<unsigned int>& colors = in.HostColors;
  colors.resize(std::max<vtkIdType>(n, 1));
  vtkUnsignedCharArray* mapped = this->MapScalars(input, 1.0);
  const unsigned char* rgba =
    mapped && mapped->GetNumberOfComponents() == 4 ? mapped->GetPointer(0) : nullptr;
  double* diffuse = act->GetProperty()->GetDiffuseColor();
  const unsigned int plain = static_cast<unsigned int>(vtkMath::Round(255 * diffuse[0])) |
    (static_cast<unsigned int>(vtkMath::Round(255 * diffuse[1])) << 8) |
    (static_cast<unsigned int>(vtkMath::Round(255 * diffuse[2])) << 16) | (255u << 24);
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const unsigned char* c = rgba ? rgba + 4 * i : nullptr;
        colors[i] =
          c ? c[0] | (c[1] << 8) | (c[2] << 16) | (static_cast<unsigned int>(c[3]) << 24) : plain;
      }
    });
  bool ok = in.Balls->Upload(balls.data(), std::max<size_t>(balls.size(), 4) * sizeof(float));
  ok = ok && in.Colors->Upload(colors.data(), colors.size() * sizeof(unsigned int));
  ok = ok && in.Strengths->Upload(q.data(), q.size() * sizeof(float));
  in.HasStrengths = strengths;
  in.Count = ok ? n : 0;
  this->NumberOfInvalidBalls = invalid;
  ++this->NumberOfUploads;
  in.UploadTime.Modified();
  (void)ren;
  return ok;
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
  if (!this->Upload(ren, act, input) || in.Count == 0)
  {
    return;
  }
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  if (width <= 0 || height <= 0)
  {
    return;
  }

  // The view: world (shifted) to view, and the projection.
  vtkCamera* cam = ren->GetActiveCamera();
  vtkNew<vtkMatrix4x4> model;
  for (int k = 0; k < 3; ++k)
  {
    model->SetElement(k, 3, in.Shift[k]);
  }
  if (!act->GetIsIdentity())
  {
    vtkMatrix4x4::Multiply4x4(act->GetMatrix(), model, model);
  }
  vtkNew<vtkMatrix4x4> worldToView, viewToClip, clipToView;
  vtkMatrix4x4::Multiply4x4(cam->GetViewTransformMatrix(), model, worldToView);
  viewToClip->DeepCopy(cam->GetProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1));
  vtkMatrix4x4::Invert(viewToClip, clipToView);
  const bool parallel = cam->GetParallelProjection() != 0;

  // [Bolla 2010] Algorithms 2 and 3: the perspective grid, and coherent ray
  // casting into colour, normal and depth images, on the GPU or the CPU.
  if (width != in.Width || height != in.Height)
  {
    in.ColorImage->SetContext(renWin);
    in.NormalImage->SetContext(renWin);
    in.DepthImage->SetContext(renWin);
    in.ColorImage->Allocate2D(width, height, 4, VTK_UNSIGNED_CHAR);
    in.NormalImage->Allocate2D(width, height, 4, VTK_FLOAT);
    in.DepthImage->Allocate2D(width, height, 1, VTK_FLOAT);
    in.Width = width;
    in.Height = height;
  }
  // A selection pass reuses the last cast when it had this view and these balls.
  Internals::CastView view;
  std::copy_n(worldToView->GetData(), 16, view.WorldToView);
  std::copy_n(viewToClip->GetData(), 16, view.ViewToClip);
  std::copy_n(clipToView->GetData(), 16, view.ClipToView);
  view.Parallel = parallel;
  view.Width = width;
  view.Height = height;
  view.Upload = in.UploadTime.GetMTime();
  view.Mapper = this->GetMTime();
  if (selector && in.CastValid && view.Same(in.Cast))
  {
    this->DrawSelection(ren, selector, x0, y0);
    this->InvokeEvent(vtkCommand::EndEvent, nullptr);
    return;
  }
  in.Cast = view;
  in.CastValid = false;
  ++in.CastSerial;
  const bool cpu = this->RayCaster == CPU || (this->RayCaster == AUTOMATIC && IsSoftwareRenderer());
  this->RayCasterInUse = cpu ? CPU : GPU;
  // This frame's counters: a ring slot whose last use the GPU has passed
  // (read first; waited for only when the GPU is a whole ring behind).
  unsigned int counters[CounterCount] = {};
  for (int k = 0; k < Internals::Ring; ++k)
  {
    const int slot = (in.Next + k) % Internals::Ring; // oldest first: the one to reuse
    if (ReadCounterSlot(in.Counters[slot], in.Fences[slot], k == 0, counters))
    {
      this->ReportCounters(counters);
    }
  }
  unsigned int inside = 0;
  const bool cast = cpu
    ? this->CastOnCPU(worldToView, viewToClip, clipToView, parallel, width, height, inside)
    : this->CastOnGPU(renWin, worldToView, viewToClip, clipToView, parallel, width, height);
  // The CPU's count of rays starting inside goes through the ring like the
  // shaders' counts (the shadow rays add to it).
  vtkShaderStorageBuffer* frameCounters = in.Counters[in.Next];
  if (cpu)
  {
    const unsigned int initial[CounterCount] = { inside };
    frameCounters->Upload(initial, sizeof(initial));
  }
  // Shadows: secondary rays toward the lights (none for a selection).
  int shadowLights = 0;
  if (cast && this->Shadows && !selector)
  {
    vtkNew<vtkMatrix4x4> viewToModel;
    vtkMatrix4x4::Invert(worldToView, viewToModel);
    shadowLights = this->CastShadows(ren, act, model, viewToModel, clipToView, width, height);
  }
  else
  {
    this->ShadowTime = 0.0;
  }
  // The frame's counters are complete: fence them, and read them now only
  // when asked to wait.
  // glGetBufferSubData reads what the shaders wrote once this barrier passed.
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  if (in.Fences[in.Next])
  {
    glDeleteSync(in.Fences[in.Next]); // its wait timed out: that frame's counters are lost
  }
  in.Fences[in.Next] = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  if (this->CollectStatistics && ReadCounterSlot(frameCounters, in.Fences[in.Next], true, counters))
  {
    this->ReportCounters(counters);
  }
  in.Next = (in.Next + 1) % Internals::Ring;
  // GPU times of the last frame whose queries completed.
  const double castSeconds = cpu ? 0.0 : in.CastTimer.GetReusableElapsedSeconds();
  this->RayCastTime = castSeconds > 0.0 ? 1000.0 * castSeconds : this->RayCastTime;
  if (shadowLights > 0)
  {
    // Read after CastShadows stopped its flight (reading resets it).
    const double shadowSeconds = in.ShadowTimer.GetReusableElapsedSeconds();
    this->ShadowTime = shadowSeconds > 0.0 ? 1000.0 * shadowSeconds : this->ShadowTime;
  }
  if (!cpu)
  {
    this->GridBuildTime = in.Grid->GetBuildTime();
  }
  in.CastValid = cast;
  if (!cast)
  {
    return;
  }
  if (selector)
  {
    this->DrawSelection(ren, selector, x0, y0);
    this->InvokeEvent(vtkCommand::EndEvent, nullptr);
    return;
  }

  // Shade and composite with the true depth, depth-tested against the scene.
  // VTK's lights: the renderer's declarations and uniforms, one light
  // call per light compiled in; rebuilt when the lighting changes.
  vtkProperty* prop = act->GetProperty();
  auto* oren = vtkOpenGLRenderer::SafeDownCast(ren);
  const int complexity = oren && prop->GetLighting() ? oren->GetLightingComplexity() : 0;
  const int lights = complexity > 0 ? oren->GetLightingCount() : 0;
  if (!in.Composite || complexity != in.CompositeLighting || lights != in.CompositeLights)
  {
    std::string source = vtkMetaballCompositeFS;
    const std::string declarations = "#define LIGHTING_COMPLEXITY " + std::to_string(complexity) +
      "\n" + (complexity > 0 ? oren->GetLightingUniforms() : "");
    if (!pointsurfaces::ReplaceHook(source, "//VTK::Light::Dec", declarations) ||
      !pointsurfaces::ReplaceHook(source, "//VTK::Light::Impl", LightCalls(complexity, lights)))
    {
      vtkErrorMacro(<< "vtkMetaballCompositeFS lacks its //VTK::Light hooks: nothing is drawn.");
      return;
    }
    if (in.Composite)
    {
      in.Composite->ReleaseGraphicsResources(renWin);
    }
    in.Composite.reset(new vtkOpenGLQuadHelper(renWin, nullptr, source.c_str(), ""));
    in.CompositeLighting = complexity;
    in.CompositeLights = lights;
  }
  else
  {
    renWin->GetShaderCache()->ReadyShaderProgram(in.Composite->Program);
  }
  vtkShaderProgram* program = in.Composite->Program;
  if (!program)
  {
    vtkErrorMacro(<< "The metaball shading shader did not compile.");
    return;
  }
  const CompositeDepthState depthState(renWin->GetState());
  in.ColorImage->Activate();
  in.NormalImage->Activate();
  in.DepthImage->Activate();
  program->SetUniformi("colorTexture", in.ColorImage->GetTextureUnit());
  program->SetUniformi("normalTexture", in.NormalImage->GetTextureUnit());
  program->SetUniformi("depthTexture", in.DepthImage->GetTextureUnit());
  program->SetUniformi("shadows", shadowLights > 0 ? 1 : 0);
  if (shadowLights > 0)
  {
    in.ShadowImage->Activate();
    program->SetUniformi("shadowTexture", in.ShadowImage->GetTextureUnit());
  }
  program->SetUniformMatrix("clipToView", clipToView);
  program->SetUniformi("parallelProjection", parallel ? 1 : 0);
  if (complexity > 0)
  {
    oren->UpdateLightingUniforms(program);
  }
  const double* ambientColor = prop->GetAmbientColor();
  const double* specularColor = prop->GetSpecularColor();
  const float ac[3] = { static_cast<float>(ambientColor[0]),
    static_cast<float>(ambientColor[1]),
    static_cast<float>(ambientColor[2]) };
  const float sc[3] = { static_cast<float>(specularColor[0]),
    static_cast<float>(specularColor[1]),
    static_cast<float>(specularColor[2]) };
  program->SetUniformf("ambient", static_cast<float>(prop->GetAmbient()));
  program->SetUniformf("diffuse", static_cast<float>(prop->GetDiffuse()));
  program->SetUniformf("specular", static_cast<float>(prop->GetSpecular()));
  program->SetUniformf("specularPower", static_cast<float>(prop->GetSpecularPower()));
  program->SetUniform3f("ambientColor", ac);
  program->SetUniform3f("specularColor", sc);
  program->SetUniformf("opacity", static_cast<float>(prop->GetOpacity()));
  in.Composite->Render();
  in.ColorImage->Deactivate();
  in.NormalImage->Deactivate();
  in.DepthImage->Deactivate();
  if (shadowLights > 0)
  {
    in.ShadowImage->Deactivate();
  }
  this->InvokeEvent(vtkCommand::EndEvent, nullptr);
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
bool vtkMetaballMapper::CastOnGPU(vtkOpenGLRenderWindow* renWin,
  vtkMatrix4x4* worldToView,
  vtkMatrix4x4* viewToClip,
  vtkMatrix4x4* clipToView,
  bool parallel,
  int width,
  int height)
{
  Internals& in = *this->Impl;
  // The others come with the shaders' counters (ReportCounters).
  this->NumberOfRays = static_cast<vtkIdType>(width) * height;
  this->NumberOfSupportTests = 0;
  // [Bolla 2010] Algorithm 2: the perspective grid.
  in.Grid->SetTileSize(this->TileSize);
  in.Grid->SetCollectStatistics(this->CollectStatistics);
  in.Grid->SetSlabs(this->Slabs);
  if (!in.Grid->Build(renWin,
        in.Balls,
        in.Count,
        worldToView->GetData(),
        viewToClip->GetData(),
        parallel,
        width,
        height))
  {
    return false;
  }
  this->NumberOfPairs = in.Grid->GetNumberOfPairs();
  this->MaximumBallsPerVoxel = in.Grid->GetMaximumBallsPerVoxel();
  this->NumberOfCulledBalls = in.Grid->GetNumberOfCulledBalls();

  // [Bolla 2010] Algorithm 3: coherent ray casting, into colour, normal and depth images.
  const std::string defines = "#define TILE_SIZE " + std::to_string(this->TileSize) +
    "\n#define MAX_SHARED " + std::to_string(MaxShared) + "\n" +
    pointsurfaces::MetaballKernelDefines(this->Field->GetKernelId());
  if (defines != in.RayCastDefines)
  {
    std::string source = vtkMetaballRayCastCS;
    if (!pointsurfaces::ReplaceHook(source, "//VTK::Defines::Dec", defines) ||
      !pointsurfaces::ReplaceHook(source, "//VTK::Kernel::Dec", vtkMetaballKernel))
    {
      vtkErrorMacro(<< "vtkMetaballRayCastCS lacks its //VTK::Defines::Dec or //VTK::Kernel::Dec "
                       "hook: nothing is drawn.");
      return false;
    }
    in.RayCast->ReleaseGraphicsResources(renWin);
    in.RayCast->SetName("vtkMetaballRayCastCS");
    in.RayCast->SetSource(source);
    in.RayCastDefines = defines;
  }
  if (!in.RayCast->IsCompiled() && !in.RayCast->Compile(renWin))
  {
    return false;
  }
  in.RayCast->Bind(renWin);
  float m[16];
  ToFloat(worldToView, m);
  in.RayCast->SetUniformMatrix4x4("worldToView", m);
  ToFloat(viewToClip, m);
  in.RayCast->SetUniformMatrix4x4("viewToClip", m);
  ToFloat(clipToView, m);
  in.RayCast->SetUniformMatrix4x4("clipToView", m);
  in.RayCast->SetUniformi("parallelProjection", parallel ? 1 : 0);
  in.RayCast->SetUniform2i("viewport", width, height);
  in.RayCast->SetUniform2i("tiles", in.Grid->GetTilesX(), in.Grid->GetTilesY());
  in.RayCast->SetUniformi("slabs", this->Slabs);
  in.RayCast->SetUniformf("slabNear", static_cast<float>(in.Grid->GetSlabPlane(0)));
  in.RayCast->SetUniformf("slabFar", static_cast<float>(in.Grid->GetSlabPlane(this->Slabs)));
  in.RayCast->SetUniformf("threshold", static_cast<float>(this->Field->GetThreshold()));
  in.RayCast->SetUniformf("stepScale", static_cast<float>(this->StepScale));
  in.RayCast->SetUniformi("bisections", this->Bisections);
  in.RayCast->SetUniformi("useStrengths", in.HasStrengths ? 1 : 0);
  in.Balls->BindBase(0);
  in.Colors->BindBase(1);
  in.Strengths->BindBase(2);
  in.Grid->GetVoxelOffsets()->BindBase(3);
  in.Grid->GetVoxelBalls()->BindBase(4);
  vtkShaderStorageBuffer* frameCounters = in.Counters[in.Next];
  const unsigned int zeros[CounterCount] = {};
  frameCounters->Upload(zeros, sizeof(zeros));
  frameCounters->BindBase(5);

  glBindImageTexture(0, in.ColorImage->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
  glBindImageTexture(1, in.NormalImage->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(2, in.DepthImage->GetHandle(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  in.CastTimer.ReusableStart();
  const bool cast = in.RayCast->Dispatch(in.Grid->GetTilesX(),
    in.Grid->GetTilesY(),
    1,
    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
      GL_SHADER_STORAGE_BARRIER_BIT);
  in.RayCast->Unbind();
  in.CastTimer.ReusableStop();
  return cast;
}

//------------------------------------------------------------------------------
bool vtkMetaballMapper::CastOnCPU(vtkMatrix4x4* worldToView,
  vtkMatrix4x4* viewToClip,
  vtkMatrix4x4* clipToView,
  bool parallel,
  int width,
  int height,
  unsigned int& inside)
{
  Internals& in = *this->Impl;
  pointsurfaces::MetaballCastInput input;
  input.Balls = in.HostBalls.data();
  input.Strengths = in.HasStrengths ? in.HostStrengths.data() : nullptr;
  input.Colors = in.HostColors.data();
  input.Count = in.Count;
  input.Kernel = this->Field->GetKernelId();
  input.Threshold = this->Field->GetThreshold();
  pointsurfaces::MetaballCastSettings settings;
  std::copy_n(worldToView->GetData(), 16, settings.WorldToView);
  std::copy_n(viewToClip->GetData(), 16, settings.ViewToClip);
  std::copy_n(clipToView->GetData(), 16, settings.ClipToView);
  settings.Parallel = parallel;
  settings.Width = width;
  settings.Height = height;
  settings.TileSize = this->TileSize;
  settings.Slabs = this->Slabs;
  settings.StepScale = this->StepScale;
  settings.Bisections = this->Bisections;
  pointsurfaces::MetaballCastStatistics stats;
  pointsurfaces::MetaballCastImages& images = in.CastImages;
  pointsurfaces::CastMetaballs(input, settings, images, &stats);
  if (!stats.Error.empty())
  {
    vtkErrorMacro(<< "The CPU ray caster cast nothing: " << stats.Error << ".");
    return false;
  }
  this->NumberOfPairs = stats.Pairs;
  this->MaximumBallsPerVoxel = stats.MaxPerVoxel;
  this->NumberOfCulledBalls = stats.Culled;
  this->NumberOfRays = stats.Rays;
  this->NumberOfHits = stats.Hits;
  this->NumberOfVoxelVisits = stats.VoxelVisits;
  this->NumberOfEmptyVoxelVisits = stats.EmptyVoxelVisits;
  this->NumberOfSupportTests = stats.SupportTests;
  this->NumberOfSamples = stats.Samples;
  this->NumberOfBisectionSamples = stats.BisectionSamples;
  this->NumberOfKernelTerms = stats.KernelTerms;
  this->GridBuildTime = 1000.0 * stats.GridSeconds;
  this->RayCastTime = 1000.0 * stats.CastSeconds;
  inside = static_cast<unsigned int>(std::min<long long>(stats.StartingInside, 0xffffffffLL));
  // Into the textures that the shading pass and the shadow rays read.
  UploadImage(in.ColorImage, width, height, GL_RGBA, GL_UNSIGNED_BYTE, images.Color.data());
  UploadImage(in.NormalImage, width, height, GL_RGBA, GL_FLOAT, images.NormalDistance.data());
  UploadImage(in.DepthImage, width, height, GL_RED, GL_FLOAT, images.Depth.data());
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
int vtkMetaballMapper::CastShadows(vtkRenderer* ren,
  vtkActor* act,
  vtkMatrix4x4* model,
  vtkMatrix4x4* viewToModel,
  vtkMatrix4x4* clipToView,
  int width,
  int height)
{
  Internals& in = *this->Impl;
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  // The GPU time of the light grids and shadow rays, stopped on every way out.
  in.ShadowTimer.ReusableStart();
  struct StopAtExit
  {
    vtkOpenGLRenderTimer& Timer;
    ~StopAtExit() { this->Timer.ReusableStop(); }
  } stop{ in.ShadowTimer };
  if (in.ShadowImage->GetWidth() != static_cast<unsigned int>(width) ||
    in.ShadowImage->GetHeight() != static_cast<unsigned int>(height) ||
    !in.ShadowImage->GetHandle())
  {
    in.ShadowImage->SetContext(renWin);
    in.ShadowImage->Allocate2D(width, height, 4, VTK_FLOAT);
  }
  const float clear[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  glClearTexImage(in.ShadowImage->GetHandle(), 0, GL_RGBA, GL_FLOAT, clear);
  const std::string defines = pointsurfaces::MetaballKernelDefines(this->Field->GetKernelId());
  if (defines != in.ShadowDefines)
  {
    std::string source = vtkMetaballShadowCS;
    if (!pointsurfaces::ReplaceHook(source, "//VTK::Defines::Dec", defines) ||
      !pointsurfaces::ReplaceHook(source, "//VTK::Kernel::Dec", vtkMetaballKernel))
    {
      vtkErrorMacro(<< "vtkMetaballShadowCS lacks its //VTK::Defines::Dec or //VTK::Kernel::Dec "
                       "hook: nothing is drawn.");
      return 0;
    }
    in.Shadow->ReleaseGraphicsResources(renWin);
    in.Shadow->SetName("vtkMetaballShadowCS");
    in.Shadow->SetSource(source);
    in.ShadowDefines = defines;
  }
  if (!in.Shadow->IsCompiled() && !in.Shadow->Compile(renWin))
  {
    return 0;
  }
  // The light cameras frame the balls' bounds (all of them: casters may lie
  // outside the view).
  double bounds[6];
  this->GetBounds(bounds);
  double corner[4], centre[3] = { 0, 0, 0 }, radius = 0.0;
  if (!act->GetIsIdentity())
  {
    act->GetBounds(bounds);
  }
  for (int k = 0; k < 3; ++k)
  {
    centre[k] = 0.5 * (bounds[2 * k] + bounds[2 * k + 1]);
    radius += 0.25 * (bounds[2 * k + 1] - bounds[2 * k]) * (bounds[2 * k + 1] - bounds[2 * k]);
  }
  radius = std::max(std::sqrt(radius), 1e-30);
  (void)corner;
  const int lightSize = 256;
  in.LightGrid->SetTileSize(16);
  in.LightGrid->SetSlabs(16);
  int lights = 0;
  vtkLightCollection* collection = ren->GetLights();
  vtkCollectionSimpleIterator it;
  collection->InitTraversal(it);
  while (vtkLight* light = collection->GetNextLight(it))
  {
    if (!light->GetSwitch() || lights >= 4)
    {
      continue;
    }
    const int index = lights++;
    double position[3], focal[3], dir[3];
    light->GetTransformedPosition(position);
    light->GetTransformedFocalPoint(focal);
    vtkMath::Subtract(focal, position, dir);
    if (vtkMath::Normalize(dir) == 0.0)
    {
      continue;
    }
    vtkNew<vtkCamera> eye;
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
    }
    else
    {
      eye->SetPosition(centre[0] - 2.0 * radius * dir[0],
        centre[1] - 2.0 * radius * dir[1],
        centre[2] - 2.0 * radius * dir[2]);
      eye->SetFocalPoint(centre);
      eye->SetViewUp(up);
      eye->ParallelProjectionOn();
      eye->SetParallelScale(radius);
      eye->SetClippingRange(0.5 * radius, 3.5 * radius);
    }
    vtkNew<vtkMatrix4x4> modelToLight, lightToClip;
    vtkMatrix4x4::Multiply4x4(eye->GetViewTransformMatrix(), model, modelToLight);
    lightToClip->DeepCopy(eye->GetProjectionTransformMatrix(1.0, -1, 1));
    if (!in.LightGrid->Build(renWin,
          in.Balls,
          in.Count,
          modelToLight->GetData(),
          lightToClip->GetData(),
          eye->GetParallelProjection() != 0,
          lightSize,
          lightSize))
    {
      return 0;
    }
    in.Shadow->Bind(renWin);
    float m[16];
    ToFloat(clipToView, m);
    in.Shadow->SetUniformMatrix4x4("clipToView", m);
    ToFloat(viewToModel, m);
    in.Shadow->SetUniformMatrix4x4("viewToModel", m);
    ToFloat(modelToLight, m);
    in.Shadow->SetUniformMatrix4x4("modelToLight", m);
    ToFloat(lightToClip, m);
    in.Shadow->SetUniformMatrix4x4("lightToClip", m);
    in.Shadow->SetUniformi("lightParallel", eye->GetParallelProjection());
    in.Shadow->SetUniform2i("viewport", width, height);
    in.Shadow->SetUniform2i("lightViewport", lightSize, lightSize);
    in.Shadow->SetUniformi("tileSize", 16);
    in.Shadow->SetUniform2i("tiles", in.LightGrid->GetTilesX(), in.LightGrid->GetTilesY());
    in.Shadow->SetUniformi("slabs", 16);
    in.Shadow->SetUniformf("slabNear", static_cast<float>(in.LightGrid->GetSlabPlane(0)));
    in.Shadow->SetUniformf("slabFar", static_cast<float>(in.LightGrid->GetSlabPlane(16)));
    in.Shadow->SetUniformf("threshold", static_cast<float>(this->Field->GetThreshold()));
    in.Shadow->SetUniformf("stepScale", static_cast<float>(this->StepScale));
    in.Shadow->SetUniformf("selfOffset", static_cast<float>(0.05 * in.MinRadius));
    in.Shadow->SetUniformi("lightIndex", index);
    in.Shadow->SetUniformi("useStrengths", in.HasStrengths ? 1 : 0);
    in.Balls->BindBase(0);
    in.Strengths->BindBase(2);
    in.LightGrid->GetVoxelOffsets()->BindBase(3);
    in.LightGrid->GetVoxelBalls()->BindBase(4);
    in.Counters[in.Next]->BindBase(5); // this frame's counters
    glBindImageTexture(2, in.DepthImage->GetHandle(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
    glBindImageTexture(3, in.ShadowImage->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    in.Shadow->Dispatch(vtkComputeShaderProgram::GroupCount(width, 16),
      vtkComputeShaderProgram::GroupCount(height, 16),
      1,
      GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    in.Shadow->Unbind();
  }
  return lights;
}

//------------------------------------------------------------------------------
bool vtkMetaballMapper::ReadHitBuffer(vtkFloatArray* hits)
{
  Internals& in = *this->Impl;
  if (!hits || in.Width <= 0 || !in.NormalImage->GetHandle())
  {
    return false;
  }
  hits->SetNumberOfComponents(4);
  hits->SetNumberOfTuples(static_cast<vtkIdType>(in.Width) * in.Height);
  in.NormalImage->Bind();
  glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, hits->GetPointer(0));
  in.NormalImage->Deactivate();
  return glGetError() == GL_NO_ERROR;
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::DrawSelection(vtkRenderer* ren,
  vtkHardwareSelector* selector,
  int x0,
  int y0)
{
  Internals& in = *this->Impl;
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  const int width = in.Cast.Width, height = in.Cast.Height;
  // The selector's area (window pixels) in the viewport: only it is read.
  const unsigned int* a = selector->GetArea();
  const int area[4] = { std::max(static_cast<int>(a[0]) - x0, 0),
    std::max(static_cast<int>(a[1]) - y0, 0),
    std::min(static_cast<int>(a[2]) - x0, width - 1),
    std::min(static_cast<int>(a[3]) - y0, height - 1) };
  if (area[0] > area[2] || area[1] > area[3])
  {
    return;
  }
  if (in.PickSerial != in.CastSerial || !std::equal(area, area + 4, in.PickArea))
  {
    this->PickBalls(area);
  }

  // The pass's colour per hit pixel, as vtkHardwareSelector reads it (red
  // the low byte): the prop's colour (the actor pass's prop id, the process
  // pass's process id, the composite pass's index, each plus one), or the
  // ball id, its low or high 24 bits.
  const int pass = selector->GetCurrentPass();
  const float* propColor = selector->GetPropColorValue();
  unsigned int prop = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double c = std::min(std::max(static_cast<double>(propColor[k]), 0.0), 1.0);
    prop |= static_cast<unsigned int>(vtkMath::Round(255.0 * c)) << (8 * k);
  }
  const bool low =
    pass == vtkHardwareSelector::POINT_ID_LOW24 || pass == vtkHardwareSelector::CELL_ID_LOW24;
  const bool high =
    pass == vtkHardwareSelector::POINT_ID_HIGH24 || pass == vtkHardwareSelector::CELL_ID_HIGH24;
  // Ids through the input's id array when it has one (ParaView's original ids).
  vtkPointSet* input = this->GetInput();
  vtkDataArray* idArray = input && !this->PointIdArrayName.empty()
    ? input->GetPointData()->GetArray(this->PointIdArrayName.c_str())
    : nullptr;
  if (idArray && idArray->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    idArray = nullptr;
  }
  std::vector<unsigned char>& pixels = in.PickPixels;
  pixels.assign(4 * static_cast<size_t>(width) * height, 0);
  const int areaWidth = area[2] - area[0] + 1;
  for (int y = area[1]; y <= area[3]; ++y)
  {
    for (int x = area[0]; x <= area[2]; ++x)
    {
      vtkIdType id = in.PickIds[static_cast<size_t>(y - area[1]) * areaWidth + x - area[0]];
      if (id == NoHit)
      {
        continue;
      }
      if (idArray && id >= 0)
      {
        id = static_cast<vtkIdType>(idArray->GetComponent(id, 0));
      }
      // VTK 9.1's selector reads the id as written (the actor pass tells hits
      // from the background); a hit without a ball (id -1) writes 0.
      const long long value = std::max<long long>(id, 0);
      const unsigned int rgb = low ? static_cast<unsigned int>(value & 0xffffff)
        : high                     ? static_cast<unsigned int>((value >> 24) & 0xffffff)
                                   : prop;
      unsigned char* p = &pixels[4 * (static_cast<size_t>(y) * width + x)];
      p[0] = static_cast<unsigned char>(rgb & 0xff);
      p[1] = static_cast<unsigned char>((rgb >> 8) & 0xff);
      p[2] = static_cast<unsigned char>((rgb >> 16) & 0xff);
      p[3] = 255;
    }
  }
  if (in.PickImage->GetWidth() != static_cast<unsigned int>(width) ||
    in.PickImage->GetHeight() != static_cast<unsigned int>(height) || !in.PickImage->GetHandle())
  {
    in.PickImage->SetContext(renWin);
    in.PickImage->Allocate2D(width, height, 4, VTK_UNSIGNED_CHAR);
  }
  UploadImage(in.PickImage, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());

  // The composite shader with lighting off writes the colours as they are
  // (nearest texels of an rgba8 image: the same bytes), with the hits' depth.
  if (!in.PickComposite)
  {
    std::string source = vtkMetaballCompositeFS;
    if (!pointsurfaces::ReplaceHook(
          source, "//VTK::Light::Dec", "#define LIGHTING_COMPLEXITY 0\n") ||
      !pointsurfaces::ReplaceHook(source, "//VTK::Light::Impl", ""))
    {
      vtkErrorMacro(<< "vtkMetaballCompositeFS lacks its //VTK::Light hooks: nothing is selected.");
      return;
    }
    in.PickComposite.reset(new vtkOpenGLQuadHelper(renWin, nullptr, source.c_str(), ""));
  }
  else
  {
    renWin->GetShaderCache()->ReadyShaderProgram(in.PickComposite->Program);
  }
  vtkShaderProgram* program = in.PickComposite->Program;
  if (!program)
  {
    vtkErrorMacro(<< "The metaball selection shader did not compile.");
    return;
  }
  const CompositeDepthState depthState(renWin->GetState());
  in.PickImage->Activate();
  in.DepthImage->Activate();
  program->SetUniformi("colorTexture", in.PickImage->GetTextureUnit());
  program->SetUniformi("depthTexture", in.DepthImage->GetTextureUnit());
  program->SetUniformi("shadows", 0);
  program->SetUniformf("opacity", 1.0f);
  in.PickComposite->Render();
  in.PickImage->Deactivate();
  in.DepthImage->Deactivate();
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::PickBalls(const int area[4])
{
  Internals& in = *this->Impl;
  const Internals::CastView& cast = in.Cast;
  const int width = cast.Width, height = cast.Height;
  const int areaWidth = area[2] - area[0] + 1, areaHeight = area[3] - area[1] + 1;
  in.PickIds.assign(static_cast<size_t>(areaWidth) * areaHeight, NoHit);
  in.PickSerial = in.CastSerial;
  std::copy_n(area, 4, in.PickArea);

  // The hits (colour alpha: 0 where none) and their view distances.
  std::vector<unsigned char> colors(4 * static_cast<size_t>(width) * height);
  std::vector<float> hits(4 * static_cast<size_t>(width) * height);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  if (!ReadImage(in.ColorImage, GL_RGBA, GL_UNSIGNED_BYTE, colors.data()) ||
    !ReadImage(in.NormalImage, GL_RGBA, GL_FLOAT, hits.data()))
  {
    vtkErrorMacro(<< "The ray-cast hits could not be read back: nothing is selected.");
    return;
  }
  const pointsurfaces::MetaballSet& set = in.Extracted.Set;
  if (set.Count != in.Count)
  {
    return;
  }

  // The area's own projection: the viewport's, scaled and moved so that its
  // clip-space square is the area.
  double areaToClip[16];
  std::copy_n(cast.ViewToClip, 16, areaToClip);
  const double sx = static_cast<double>(width) / areaWidth;
  const double tx = static_cast<double>(width - 2 * area[0]) / areaWidth - 1.0;
  const double sy = static_cast<double>(height) / areaHeight;
  const double ty = static_cast<double>(height - 2 * area[1]) / areaHeight - 1.0;
  for (int c = 0; c < 4; ++c)
  {
    areaToClip[c] = sx * cast.ViewToClip[c] + tx * cast.ViewToClip[12 + c];
    areaToClip[4 + c] = sy * cast.ViewToClip[4 + c] + ty * cast.ViewToClip[12 + c];
  }
  double planes[24];
  pointsurfaces::FrustumPlanes(areaToClip, planes);
  // The input's points to view: the cast's view without the balls' shift.
  double toView[16];
  std::copy_n(cast.WorldToView, 16, toView);
  for (int r = 0; r < 3; ++r)
  {
    for (int k = 0; k < 3; ++k)
    {
      toView[4 * r + 3] -= cast.WorldToView[4 * r + k] * in.Shift[k];
    }
  }
  const auto centreInView = [&](vtkIdType i, double out[3])
  {
    const double* c = set.Centers + 3 * i;
    for (int r = 0; r < 3; ++r)
    {
      out[r] = toView[4 * r] * c[0] + toView[4 * r + 1] * c[1] + toView[4 * r + 2] * c[2] +
        toView[4 * r + 3];
    }
  };

  // The balls that the ray casters draw (a positive float radius) whose
  // support reaches into the area's frustum, ascending.
  vtkSMPThreadLocal<std::vector<unsigned>> reaching;
  vtkSMPTools::For(0,
    set.Count,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<unsigned>& ids = reaching.Local();
      for (vtkIdType i = begin; i < end; ++i)
      {
        if (!(in.HostBalls[4 * i + 3] > 0.0f))
        {
          continue;
        }
        double c[3];
        centreInView(i, c);
        bool inside = true;
        for (int k = 0; k < 6 && inside; ++k)
        {
          const double* e = planes + 4 * k;
          inside = e[0] * c[0] + e[1] * c[1] + e[2] * c[2] + e[3] >= -set.Radii[i];
        }
        if (inside)
        {
          ids.push_back(static_cast<unsigned>(i));
        }
      }
    });
  std::vector<unsigned> ids;
  for (const std::vector<unsigned>& part : reaching)
  {
    ids.insert(ids.end(), part.begin(), part.end());
  }
  std::sort(ids.begin(), ids.end());

  // Those balls in view space, binned into a perspective grid over the area.
  const size_t count = ids.size();
  std::vector<double> centres(3 * count), radii(count), strengths(set.Strengths ? count : 0);
  for (size_t k = 0; k < count; ++k)
  {
    centreInView(ids[k], &centres[3 * k]);
    radii[k] = set.Radii[ids[k]];
    if (set.Strengths)
    {
      strengths[k] = set.Strengths[ids[k]];
    }
  }
  pointsurfaces::MetaballSet nearby = set;
  nearby.Centers = centres.data();
  nearby.Radii = radii.data();
  nearby.Strengths = set.Strengths ? strengths.data() : nullptr;
  nearby.Count = static_cast<long long>(count);
  pointsurfaces::GridView grid;
  for (int k = 0; k < 16; ++k)
  {
    grid.WorldToView[k] = k % 5 == 0 ? 1.0 : 0.0;
    grid.ViewToClip[k] = areaToClip[k];
  }
  grid.Parallel = cast.Parallel;
  grid.Width = areaWidth;
  grid.Height = areaHeight;
  grid.TileSize = PickTile;
  grid.Slabs = 16;
  const pointsurfaces::PerspectiveGrid voxels = pointsurfaces::BuildPerspectiveGrid(nearby, grid);
  if (voxels.SlabPlanes.size() < 2)
  {
    return;
  }

  // Each hit pixel's surface point against its voxel's balls, which hold
  // every ball whose support contains it (all of the area's balls where a
  // rounding error leaves the voxel empty).
  vtkSMPTools::For(0,
    areaHeight,
    [&](vtkIdType rowBegin, vtkIdType rowEnd)
    {
      for (vtkIdType row = rowBegin; row < rowEnd; ++row)
      {
        const int y = area[1] + static_cast<int>(row);
        for (int x = area[0]; x <= area[2]; ++x)
        {
          const size_t pixel = static_cast<size_t>(y) * width + x;
          if (colors[4 * pixel + 3] == 0)
          {
            continue;
          }
          const double distance = hits[4 * pixel + 3];
          double point[3];
          HitPoint(cast.ClipToView, width, height, x, y, distance, point);
          const size_t slab = SlabOf(voxels.SlabPlanes, distance);
          const size_t voxel =
            (slab * voxels.TilesY + row / PickTile) * voxels.TilesX + (x - area[0]) / PickTile;
          long long best = -1;
          if (voxel + 1 < voxels.Offsets.size() &&
            voxels.Offsets[voxel + 1] > voxels.Offsets[voxel])
          {
            const unsigned first = voxels.Offsets[voxel];
            best = pointsurfaces::DominantBall(
              nearby, point, voxels.Balls.data() + first, voxels.Offsets[voxel + 1] - first);
          }
          if (best < 0)
          {
            best = pointsurfaces::DominantBall(nearby, point);
          }
          in.PickIds[static_cast<size_t>(row) * areaWidth + x - area[0]] =
            best >= 0 ? static_cast<vtkIdType>(ids[best]) : -1;
        }
      }
    });
}

//------------------------------------------------------------------------------
void vtkMetaballMapper::ReleaseGraphicsResources(vtkWindow* win)
{
  Internals& in = *this->Impl;
  in.Grid->ReleaseGraphicsResources(win);
  in.Balls->ReleaseGraphicsResources(win);
  in.Colors->ReleaseGraphicsResources(win);
  in.Strengths->ReleaseGraphicsResources(win);
  for (int k = 0; k < Internals::Ring; ++k)
  {
    in.Counters[k]->ReleaseGraphicsResources(win);
    if (in.Fences[k])
    {
      glDeleteSync(in.Fences[k]);
      in.Fences[k] = nullptr;
    }
  }
  in.CastTimer.ReleaseGraphicsResources();
  in.ShadowTimer.ReleaseGraphicsResources();
  in.LightGrid->ReleaseGraphicsResources(win);
  in.Shadow->ReleaseGraphicsResources(win);
  in.ShadowDefines.clear();
  in.ShadowImage->ReleaseGraphicsResources(win);
  in.RayCast->ReleaseGraphicsResources(win);
  in.RayCastDefines.clear();
  in.ColorImage->ReleaseGraphicsResources(win);
  in.NormalImage->ReleaseGraphicsResources(win);
  in.DepthImage->ReleaseGraphicsResources(win);
  if (in.Composite)
  {
    in.Composite->ReleaseGraphicsResources(win);
    in.Composite.reset();
  }
  in.CompositeLighting = in.CompositeLights = -1;
  in.PickImage->ReleaseGraphicsResources(win);
  if (in.PickComposite)
  {
    in.PickComposite->ReleaseGraphicsResources(win);
    in.PickComposite.reset();
  }
  in.CastValid = false;
  in.PickSerial = 0;
  in.Width = in.Height = 0;
  in.Count = 0;
  in.UploadTime = vtkTimeStamp();
  this->Superclass::ReleaseGraphicsResources(win);
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
  os << indent << "Shadows: " << this->Shadows << "\n";
}
