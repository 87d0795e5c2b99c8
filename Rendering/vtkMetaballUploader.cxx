// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkMetaballUploader.h"

#include "vtkComputeShaderProgram.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkMetaballAssembleCS.h"
#include "vtkMetaballGPUCounters.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkShaderStorageBuffer.h"
#include "vtkUnsignedCharArray.h"

#include "psMetaball.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

vtkStandardNewMacro(vtkMetaballUploader);

namespace
{
const unsigned int Group = 256; // local_size_x of vtkMetaballAssembleCS

// Copies `bytes` from `from` to `to` in parallel blocks.
void ParallelCopy(void* to, const void* from, size_t bytes)
{
  const size_t block = size_t(1) << 20;
  const vtkIdType blocks = static_cast<vtkIdType>((bytes + block - 1) / block);
  vtkSMPTools::For(0,
    blocks,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType b = begin; b < end; ++b)
      {
        const size_t offset = static_cast<size_t>(b) * block;
        std::memcpy(static_cast<char*>(to) + offset,
          static_cast<const char*>(from) + offset,
          std::min(block, bytes - offset));
      }
    });
}

// The first component of `array` as float, `n` values, in parallel: a
// one-component float array as it is, double and others converted. Returns
// the smallest positive finite value (+infinity when none), found in the
// source: the mapped buffer is for writing only.
float FirstComponent(vtkDataArray* array, vtkIdType n, float* out)
{
  const int comps = array->GetNumberOfComponents();
  auto* floats = vtkFloatArray::FastDownCast(array);
  auto* doubles = vtkDoubleArray::FastDownCast(array);
  vtkSMPThreadLocal<float> least(std::numeric_limits<float>::infinity());
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      float& m = least.Local();
      const auto keep = [&m](float v)
      {
        if (v > 0.0f && v < m)
        {
          m = v;
        }
      };
      if (floats)
      {
        const float* v = floats->GetPointer(0);
        if (comps == 1)
        {
          std::memcpy(out + begin, v + begin, (end - begin) * sizeof(float));
        }
        for (vtkIdType i = begin; i < end; ++i)
        {
          if (comps != 1)
          {
            out[i] = v[i * comps];
          }
          keep(v[i * comps]);
        }
      }
      else if (doubles)
      {
        const double* v = doubles->GetPointer(0);
        for (vtkIdType i = begin; i < end; ++i)
        {
          out[i] = static_cast<float>(v[i * comps]);
          keep(static_cast<float>(v[i * comps]));
        }
      }
      else
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          const float v = static_cast<float>(array->GetComponent(i, 0));
          out[i] = v;
          keep(v);
        }
      }
    });
  float m = std::numeric_limits<float>::infinity();
  for (float x : least)
  {
    m = std::min(m, x);
  }
  return m;
}

// Does `array` (when there is one) have a value for each of `n` points?
bool Covers(vtkDataArray* array, vtkIdType n)
{
  return !array || array->GetNumberOfTuples() >= n;
}
} // namespace

//------------------------------------------------------------------------------
vtkMetaballUploader::vtkMetaballUploader()
{
  this->Invalid->SetSize(1);
}

//------------------------------------------------------------------------------
vtkMetaballUploader::~vtkMetaballUploader() = default;

//------------------------------------------------------------------------------
bool vtkMetaballUploader::Upload(vtkOpenGLRenderWindow* renWin,
  vtkPointSet* input,
  const pointsurfaces::BallRule& rule,
  const pointsurfaces::RadiusSource& source,
  double scale,
  vtkUnsignedCharArray* mapped,
  unsigned int plain,
  bool wait,
  const Report& report,
  pointsurfaces::MetaballBalls& balls)
{
  balls.Count = 0;
  this->UploadedBytes = 0.0;
  if (!input || !input->GetPoints())
  {
    return true; // nothing to draw
  }
  const vtkIdType n = input->GetNumberOfPoints();
  const size_t count = static_cast<size_t>(n);
  vtkDataArray* strengths = pointsurfaces::StrengthArray(input, rule);
  vtkDataArray* densities = rule.DensityArrayName.empty()
    ? nullptr
    : input->GetPointData()->GetArray(rule.DensityArrayName.c_str());
  for (vtkDataArray* array : { source.Array, strengths, densities })
  {
    if (!Covers(array, n))
    {
      vtkErrorMacro(<< "The point array \"" << (array->GetName() ? array->GetName() : "")
                    << "\" has " << array->GetNumberOfTuples() << " values for " << n
                    << " points: nothing is drawn.");
      return false;
    }
  }
  const auto copyStart = std::chrono::steady_clock::now();
  const auto take = [&report](const unsigned int* invalid) { report(invalid[0]); };
  this->Invalid->BeginFrame(take);

  // Positions: float as it is (shifted on the GPU), others shifted and converted here.
  vtkDataArray* points = input->GetPoints()->GetData();
  auto* floats = vtkFloatArray::FastDownCast(points);
  auto* doubles = vtkDoubleArray::FastDownCast(points);
  this->PositionsAsIs = floats != nullptr && floats->GetNumberOfComponents() == 3;
  const double* shift = balls.Shift;
  auto* xyz = static_cast<float*>(this->Positions->MapForWrite(3 * count * sizeof(float)));
  if (!xyz)
  {
    return false;
  }
  if (this->PositionsAsIs)
  {
    ParallelCopy(xyz, floats->GetPointer(0), 3 * count * sizeof(float));
  }
  else if (doubles && doubles->GetNumberOfComponents() == 3)
  {
    // One tight pass over the 3n values, in blocks of whole points.
    const double* from = doubles->GetPointer(0);
    const double s[3] = { shift[0], shift[1], shift[2] };
    vtkSMPTools::For(0,
      n,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          xyz[3 * i] = static_cast<float>(from[3 * i] - s[0]);
          xyz[3 * i + 1] = static_cast<float>(from[3 * i + 1] - s[1]);
          xyz[3 * i + 2] = static_cast<float>(from[3 * i + 2] - s[2]);
        }
      });
  }
  else
  {
    vtkSMPTools::For(0,
      n,
      [&](vtkIdType begin, vtkIdType end)
      {
        double p[3];
        for (vtkIdType i = begin; i < end; ++i)
        {
          points->GetTuple(i, p);
          for (int k = 0; k < 3; ++k)
          {
            xyz[3 * i + k] = static_cast<float>(p[k] - shift[k]);
          }
        }
      });
  }
  bool ok = this->Positions->Unmap();
  this->UploadedBytes += 3.0 * sizeof(float) * n;

  // Radii: an array's first component, or one radius.
  const bool radiusArray = source.Array != nullptr;
  const double factor = scale * source.RadiusScale * (radiusArray ? source.ArrayFactor : 1.0);
  float smallest = static_cast<float>(factor * source.Radius);
  if (radiusArray && ok)
  {
    auto* radii = static_cast<float*>(this->Radii->MapForWrite(count * sizeof(float)));
    ok = radii != nullptr;
    if (ok)
    {
      smallest = static_cast<float>(factor * FirstComponent(source.Array, n, radii));
      ok = this->Radii->Unmap();
      this->UploadedBytes += sizeof(float) * static_cast<double>(n);
    }
  }
  balls.MinRadius = smallest > 0.0f && std::isfinite(smallest) ? smallest : 1.0;

  // Strengths: only when the rule weights the balls (arrays, SPH normalisation).
  const double normalization = pointsurfaces::KernelNormalization(rule.Kernel);
  balls.HasStrengths = strengths || densities || normalization > 0.0;
  if (balls.HasStrengths && ok)
  {
    auto* q = static_cast<float*>(balls.Strengths->MapForWrite(count * sizeof(float)));
    ok = q != nullptr;
    if (ok)
    {
      vtkSMPTools::For(0,
        n,
        [&](vtkIdType begin, vtkIdType end)
        {
          for (vtkIdType i = begin; i < end; ++i)
          {
            // As pointsurfaces::ExtractBalls: a bad density gives NaN (invalid).
            double s = strengths ? strengths->GetComponent(i, 0) : 1.0;
            if (densities)
            {
              const double rho = densities->GetComponent(i, 0);
              s = rho > 0.0 ? s / rho : std::numeric_limits<double>::quiet_NaN();
            }
            if (normalization > 0.0)
            {
              const double r = source.SupportRadius(i);
              s *= normalization / (r * r * r);
            }
            q[i] = static_cast<float>(s);
          }
        });
      ok = balls.Strengths->Unmap();
      this->UploadedBytes += sizeof(float) * static_cast<double>(n);
    }
  }
  else if (ok)
  {
    const float one = 1.0f;
    ok = balls.Strengths->Upload(&one, sizeof(one));
  }

  // Colours: rgba8 byte for byte, or one for all.
  balls.ColorPerBall =
    mapped && mapped->GetNumberOfComponents() == 4 && mapped->GetNumberOfTuples() >= n;
  if (balls.ColorPerBall && ok)
  {
    void* rgba = balls.Colors->MapForWrite(4 * count);
    ok = rgba != nullptr;
    if (ok)
    {
      ParallelCopy(rgba, mapped->GetPointer(0), 4 * count);
      ok = balls.Colors->Unmap();
      this->UploadedBytes += 4.0 * n;
    }
  }
  else if (ok)
  {
    ok = balls.Colors->Upload(&plain, sizeof(plain));
  }

  this->CopyTime =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - copyStart).count();

  // The vec4 balls, assembled on the GPU; invalid ones counted.
  ok = ok && balls.Balls->Allocate(std::max<size_t>(4 * count, 4) * sizeof(float));
  if (ok && !this->Assemble->IsCompiled())
  {
    this->Assemble->SetName("vtkMetaballAssembleCS");
    this->Assemble->SetSource(vtkMetaballAssembleCS);
    ok = this->Assemble->Compile(renWin);
  }
  if (ok)
  {
    this->Assemble->Bind(renWin);
    this->Assemble->SetUniformui("count", static_cast<unsigned int>(n));
    const float gpuShift[3] = { this->PositionsAsIs ? static_cast<float>(shift[0]) : 0.0f,
      this->PositionsAsIs ? static_cast<float>(shift[1]) : 0.0f,
      this->PositionsAsIs ? static_cast<float>(shift[2]) : 0.0f };
    this->Assemble->SetUniform3f("shift", gpuShift);
    this->Assemble->SetUniformi("radiusArray", radiusArray ? 1 : 0);
    this->Assemble->SetUniformf("radiusFactor", static_cast<float>(factor));
    this->Assemble->SetUniformf("radius", static_cast<float>(factor * source.Radius));
    this->Assemble->SetUniformi("useStrengths", balls.HasStrengths ? 1 : 0);
    balls.Balls->BindBase(0);
    this->Positions->BindBase(1);
    (radiusArray ? this->Radii.Get() : this->Positions.Get())->BindBase(2);
    balls.Strengths->BindBase(3);
    this->Invalid->GetFrameBuffer()->BindBase(4);
    ok = this->Assemble->Dispatch(vtkComputeShaderProgram::GroupCount(count, Group));
    this->Assemble->Unbind();
  }
  this->Invalid->EndFrame(take, wait);
  balls.Count = ok ? n : 0;
  return ok;
}

//------------------------------------------------------------------------------
void vtkMetaballUploader::Poll(const Report& report)
{
  this->Invalid->Poll([&report](const unsigned int* invalid) { report(invalid[0]); });
}

//------------------------------------------------------------------------------
void vtkMetaballUploader::ReleaseGraphicsResources(vtkWindow* win)
{
  this->Positions->ReleaseGraphicsResources(win);
  this->Radii->ReleaseGraphicsResources(win);
  this->Assemble->ReleaseGraphicsResources(win);
  this->Invalid->ReleaseGraphicsResources(win);
}

//------------------------------------------------------------------------------
void vtkMetaballUploader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "UploadedBytes: " << this->UploadedBytes << "\n";
  os << indent << "PositionsAsIs: " << this->PositionsAsIs << "\n";
}
