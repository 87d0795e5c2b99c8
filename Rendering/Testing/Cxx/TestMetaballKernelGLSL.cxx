// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The GLSL kernels of the metaball shaders (vtkMetaballKernel.glsl, with the
// defines the mapper gives them) against the kernel table (psMetaballKernels.h)
// in float: every kernel at 4097 values of x = r^2 / R^2 from -0.01 to 1.01,
// the ends, the cubic spline's break at q = 1/2 and points next to it. The
// value and dK/dx must agree to a few float ulps of the terms they sum (the
// shader's exp and sqrt are not the C library's), and the slope bound
// exactly; outside [0, 1) both must be 0 as the double reference is.
#include "vtkComputeShaderProgram.h"
#include "vtkMetaballKernel.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkShaderStorageBuffer.h"

#include "TestMetaballKernelCS.h"
#include "psMetaball.h"
#include "psMetaballShaderKernel.h"
#include "psShaderHooks.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <vector>

using namespace pointsurfaces;

namespace
{
// The shader's results for `arguments`: (value, slope, slope bound, 0) each.
bool RunShader(vtkOpenGLRenderWindow* win,
  MetaballKernel kernel,
  const std::vector<float>& arguments,
  std::vector<float>& results)
{
  std::string source = TestMetaballKernelCS;
  if (!ReplaceHook(source, "//VTK::Defines::Dec", MetaballKernelDefines(kernel)) ||
    !ReplaceHook(source, "//VTK::Kernel::Dec", vtkMetaballKernel))
  {
    std::cerr << "the probe shader lacks a hook\n";
    return false;
  }
  vtkNew<vtkComputeShaderProgram> program;
  program->SetName("TestMetaballKernelCS");
  program->SetSource(source.c_str());
  if (!program->Compile(win))
  {
    program->ReleaseGraphicsResources(win);
    return false;
  }
  const auto count = static_cast<unsigned int>(arguments.size());
  vtkNew<vtkShaderStorageBuffer> in, out;
  in->Upload(arguments.data(), arguments.size() * sizeof(float));
  out->Allocate(4 * arguments.size() * sizeof(float));
  program->Bind(win);
  program->SetUniformui("count", count);
  in->BindBase(0);
  out->BindBase(1);
  bool ok = program->Dispatch(vtkComputeShaderProgram::GroupCount(count, 64));
  program->Unbind();
  results.assign(4 * arguments.size(), 0.0f);
  ok = ok && out->Download(results.data(), results.size() * sizeof(float));
  program->ReleaseGraphicsResources(win);
  in->ReleaseGraphicsResources(win);
  out->ReleaseGraphicsResources(win);
  return ok;
}

// The table's value and slope in float, with the double reference's clamping.
template<typename K>
void Table(float x, float& value, float& slope)
{
  value = slope = 0.0f;
  if (x < 1.0f)
  {
    value = K::Value(std::max(x, 0.0f), slope);
  }
}

// How many arguments at which the shader of `shader` and the table's `table`
// differ by more than float rounding (each difference printed when `report`).
int Differences(vtkOpenGLRenderWindow* win,
  MetaballKernel shader,
  MetaballKernel table,
  const std::vector<float>& arguments,
  bool report)
{
  std::vector<float> results;
  const char* name = MetaballKernelName(table);
  if (!RunShader(win, shader, arguments, results))
  {
    std::cerr << name << ": the probe did not run\n";
    return static_cast<int>(arguments.size());
  }
  int failures = 0;
  double worstValue = 0.0, worstSlope = 0.0;
  VisitMetaballKernel<float>(table,
    [&](auto k)
    {
      using K = decltype(k);
      for (size_t i = 0; i < arguments.size(); ++i)
      {
        float value, slope;
        Table<K>(arguments[i], value, slope);
        const float* r = &results[4 * i];
        // A few ulps of terms of size up to about 10 (the slopes' coefficients).
        const double valueError = std::abs(r[0] - value), slopeError = std::abs(r[1] - slope);
        worstValue = std::max(worstValue, valueError);
        worstSlope = std::max(worstSlope, slopeError);
        const bool differs = !(valueError <= 4e-6) ||
          !(slopeError <= 2e-5 * (1.0 + std::abs(slope))) || r[2] != K::SlopeBound;
        if (differs && report && ++failures <= 5)
        {
          std::cerr << name << " at x = " << arguments[i] << ": GLSL (" << r[0] << ", " << r[1]
                    << ", bound " << r[2] << "), table (" << value << ", " << slope << ", bound "
                    << K::SlopeBound << ")\n";
        }
        else if (differs)
        {
          ++failures;
        }
      }
    });
  if (report)
  {
    std::cout << name << ": largest difference " << worstValue << " in value, " << worstSlope
              << " in dK/dx over " << arguments.size() << " arguments\n";
  }
  return failures;
}
} // namespace

int TestMetaballKernelGLSL(int, char*[])
{
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(16, 16);
  vtkNew<vtkRenderer> renderer;
  renWin->AddRenderer(renderer);
  renWin->Render();
  auto* win = vtkOpenGLRenderWindow::SafeDownCast(renWin);
  win->MakeCurrent();

  std::vector<float> arguments;
  for (int i = 0; i <= 4096; ++i)
  {
    arguments.push_back(-0.01f + 1.02f * static_cast<float>(i) / 4096.0f);
  }
  for (float x : { 0.0f,
         1.0f,
         0.25f,
         std::nextafter(0.25f, 0.0f),
         std::nextafter(0.25f, 1.0f),
         std::nextafter(1.0f, 0.0f),
         1e-30f,
         1e-8f })
  {
    arguments.push_back(x);
  }

  int failures = 0;
  for (int k = 0; k < NumberOfMetaballKernels; ++k)
  {
    const auto kernel = static_cast<MetaballKernel>(k);
    failures += Differences(win, kernel, kernel, arguments, true);
  }
  // The comparison must see a wrong formula: each shader against the next
  // kernel's table differs almost everywhere.
  for (int k = 0; k < NumberOfMetaballKernels; ++k)
  {
    const auto kernel = static_cast<MetaballKernel>(k);
    const auto other = static_cast<MetaballKernel>((k + 1) % NumberOfMetaballKernels);
    const int wrong = Differences(win, kernel, other, arguments, false);
    if (wrong < static_cast<int>(arguments.size()) / 2)
    {
      std::cerr << MetaballKernelName(kernel) << "'s shader differs from "
                << MetaballKernelName(other) << "'s table at only " << wrong
                << " arguments: the check cannot tell kernels apart\n";
      ++failures;
    }
  }
  if (failures)
  {
    std::cerr << failures << " differences between the GLSL kernels and the table\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
