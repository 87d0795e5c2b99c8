// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkMetaballUploader (the GPU ray caster's upload, with no host copy)
// against the host path that the CPU ray caster reads (ExtractBalls, then
// MetaballBalls::Convert), ball for ball: 20 000 balls around 1e4 with a
// NaN centre, an infinite one, a zero and a NaN radius, in float, double and
// int points, with one radius, radius arrays (float, double, a second
// component), strength and density arrays under the SPH kernel, and mapped
// colours or one colour. The GPU's vec4 balls are read back: centres within
// a float rounding of the host's, radii within 2 float roundings, the same
// balls invalid (radius 0) and counted, strengths and colours as the host's.
// The smallest radius (the shadow rays' offset) may be that of a ball made
// invalid by its centre or strength: at most the host's, and positive.
// Then through vtkMetaballMapper on the GPU caster without statistics: the
// invalid balls of an upload are counted a frame or two late, also when the
// data do not change after it. Last, 27 balls near 1e7 with and without an
// infinite point, on both casters: the point is skipped and the picture is
// the same (the bounds, the camera and the float shift ignore it). The host times are printed;
// bench_metaball_upload.py measures them at size.
#include "vtkActor.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkMetaballField.h"
#include "vtkMetaballMapper.h"
#include "vtkMetaballUploader.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkShaderStorageBuffer.h"
#include "vtkUnsignedCharArray.h"

#include "psBallExtraction.h"
#include "psMetaballFrame.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace
{
// Hits of 27 balls 0.1 apart near (1e7, -1e7, 0), with an infinite point or not.
vtkIdType HitsNear1e7(vtkRenderWindow* renWin, bool infinite, int caster)
{
  vtkNew<vtkPoints> points;
  for (int i = 0; i < 27; ++i)
  {
    points->InsertNextPoint(1e7 + 0.1 * (i % 3), -1e7 + 0.1 * (i / 3 % 3), 0.1 * (i / 9));
  }
  if (infinite)
  {
    points->InsertNextPoint(std::numeric_limits<double>::infinity(), 0.0, 0.0);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  vtkNew<vtkMetaballMapper> mapper;
  mapper->SetInputDataObject(poly);
  mapper->SetRayCaster(caster);
  mapper->CollectStatisticsOn();
  mapper->GetField()->SetRadius(0.15);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renWin->AddRenderer(renderer);
  renderer->ResetCamera();
  renWin->Render();
  const vtkIdType hits = mapper->GetNumberOfHits();
  renWin->RemoveRenderer(renderer);
  return hits;
}

struct Case
{
  std::string Name;
  int PointType;           // VTK_FLOAT, VTK_DOUBLE or VTK_INT
  std::string RadiusArray; // "" (one radius), "float", "double" or "float2"
  bool Weighted = false;   // strengths and densities, SPH kernel
  bool Colours = false;    // mapped rgba8 colours
};

int Run(vtkOpenGLRenderWindow* win, const Case& c)
{
  const vtkIdType n = 20000;
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> uni(-1.0, 1.0), rad(0.01, 0.08), pos(0.5, 2.0);
  vtkNew<vtkPoints> points;
  points->SetDataType(c.PointType);
  points->SetNumberOfPoints(n);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double s = c.PointType == VTK_INT ? 1000.0 : 1.0;
    double p[3] = { 1e4 + s * uni(gen), -2e4 + s * uni(gen), 5.0 + s * uni(gen) };
    if (i == 7 && c.PointType != VTK_INT)
    {
      p[1] = nan;
    }
    if (i == 8 && c.PointType != VTK_INT)
    {
      p[2] = inf;
    }
    points->SetPoint(i, p);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  vtkNew<vtkMetaballField> field;
  if (c.RadiusArray.empty())
  {
    field->SetRadius(0.05);
  }
  else
  {
    vtkSmartPointer<vtkDataArray> radii;
    if (c.RadiusArray == "double")
    {
      radii = vtkSmartPointer<vtkDoubleArray>::New();
    }
    else
    {
      radii = vtkSmartPointer<vtkFloatArray>::New();
    }
    radii->SetNumberOfComponents(c.RadiusArray == "float2" ? 2 : 1);
    radii->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      radii->SetComponent(i, 0, i == 9 ? 0.0 : (i == 10 ? nan : rad(gen)));
      if (radii->GetNumberOfComponents() == 2)
      {
        radii->SetComponent(i, 1, 100.0);
      }
    }
    radii->SetName("radius");
    poly->GetPointData()->AddArray(radii);
    field->SetRadiusScale(1.5);
  }
  if (c.Weighted)
  {
    vtkNew<vtkDoubleArray> mass, rho;
    mass->SetName("mass");
    rho->SetName("rho");
    mass->SetNumberOfTuples(n);
    rho->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      mass->SetValue(i, pos(gen));
      rho->SetValue(i, i == 11 ? 0.0 : pos(gen)); // a zero density: invalid
    }
    poly->GetPointData()->AddArray(mass);
    poly->GetPointData()->AddArray(rho);
    field->SetStrengthArrayName("mass");
    field->SetDensityArrayName("rho");
    field->SetKernel(vtkMetaballField::CubicSpline);
  }
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(4);
  colours->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < 4 * n; ++i)
  {
    colours->SetValue(i, static_cast<unsigned char>((i * 37) % 251));
  }
  vtkNew<vtkProperty> prop;
  prop->SetDiffuseColor(0.2, 0.4, 0.6);
  const double scale = 2.0;

  // The host path.
  pointsurfaces::MetaballBalls host;
  double bounds[6];
  points->GetBounds(bounds);
  for (int k = 0; k < 3; ++k)
  {
    // As the mapper: the bounds' centre rounded to float, 0 when not finite.
    const float centre = static_cast<float>(0.5 * (bounds[2 * k] + bounds[2 * k + 1]));
    host.Shift[k] = std::isfinite(centre) ? centre : 0.0;
  }
  const auto t0 = std::chrono::steady_clock::now();
  field->ExtractBalls(poly, scale, host.Extracted);
  const vtkIdType hostInvalid = host.Convert(host.Extracted.Set);
  host.ConvertColors(c.Colours ? colours.Get() : nullptr, prop, n);
  host.HasStrengths = host.Extracted.Set.Strengths != nullptr;
  const auto t1 = std::chrono::steady_clock::now();

  // The uploader.
  pointsurfaces::MetaballBalls gpu;
  std::copy_n(host.Shift, 3, gpu.Shift);
  vtkNew<vtkMetaballUploader> uploader;
  vtkIdType gpuInvalid = -1;
  const bool ok = uploader->Upload(
    win,
    poly,
    field->GetRule(),
    field->ChooseRadii(poly),
    scale,
    c.Colours ? colours.Get() : nullptr,
    pointsurfaces::PlainColor(prop),
    true,
    [&gpuInvalid](vtkIdType invalid) { gpuInvalid = invalid; },
    gpu);
  const auto t2 = std::chrono::steady_clock::now();
  std::vector<float> balls(4 * n), strengths(gpu.HasStrengths ? n : 1);
  std::vector<unsigned int> rgba(gpu.ColorPerBall ? n : 1);
  int failures = 0;
  if (!ok || gpu.Count != n || !gpu.Balls->Download(balls.data(), balls.size() * sizeof(float)) ||
    !gpu.Strengths->Download(strengths.data(), strengths.size() * sizeof(float)) ||
    !gpu.Colors->Download(rgba.data(), rgba.size() * sizeof(unsigned int)))
  {
    std::cerr << c.Name << ": the upload failed\n";
    return 1;
  }

  // Ball for ball.
  vtkIdType centreErrors = 0, radiusErrors = 0, validityErrors = 0, strengthErrors = 0,
            colourErrors = 0;
  const float eps = std::numeric_limits<float>::epsilon();
  for (vtkIdType i = 0; i < n; ++i)
  {
    const float* g = &balls[4 * i];
    const float* h = &host.HostBalls[4 * i];
    const bool hostValid = h[3] > 0.0f, gpuValid = g[3] > 0.0f;
    if (hostValid != gpuValid)
    {
      ++validityErrors;
      continue;
    }
    if (!hostValid)
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      // Both round the same difference of two floats (or of the same double).
      centreErrors += g[k] == h[k] ? 0 : 1;
    }
    radiusErrors += std::abs(g[3] - h[3]) <= 2.0f * eps * h[3] ? 0 : 1;
    if (gpu.HasStrengths)
    {
      const float q = host.HostStrengths[i];
      strengthErrors += std::abs(strengths[i] - q) <= 2.0f * eps * std::abs(q) ? 0 : 1;
    }
  }
  for (size_t i = 0; i < rgba.size(); ++i)
  {
    colourErrors += rgba[i] == host.HostColors[i] ? 0 : 1;
  }
  const double hostMs = std::chrono::duration<double, std::milli>(t1 - t0).count();
  const double gpuMs = std::chrono::duration<double, std::milli>(t2 - t1).count();
  std::cout << c.Name << ": " << gpuInvalid << " invalid (host " << hostInvalid << "), "
            << centreErrors << " centre, " << radiusErrors << " radius, " << strengthErrors
            << " strength, " << validityErrors << " validity and " << colourErrors
            << " colour differences; " << uploader->GetUploadedBytes() / n
            << " bytes a ball, positions "
            << (uploader->GetPositionsAsIs() ? "as they are" : "converted") << "; host path "
            << hostMs << " ms, uploader " << gpuMs << " ms\n";
  if (gpuInvalid != hostInvalid || centreErrors || radiusErrors || strengthErrors ||
    validityErrors || colourErrors || gpu.HasStrengths != host.HasStrengths ||
    gpu.ColorPerBall != c.Colours || uploader->GetPositionsAsIs() != (c.PointType == VTK_FLOAT) ||
    !(gpu.MinRadius > 0.0 && gpu.MinRadius <= host.MinRadius * (1.0 + 2.0 * eps)))
  {
    std::cerr << c.Name << ": the uploader's balls differ from the host's (smallest radius "
              << gpu.MinRadius << " against " << host.MinRadius << ")\n";
    ++failures;
  }
  uploader->ReleaseGraphicsResources(win);
  gpu.ReleaseGraphicsResources(win);
  return failures;
}
} // namespace

int TestMetaballUploader(int, char*[])
{
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(16, 16);
  vtkNew<vtkRenderer> renderer;
  renWin->AddRenderer(renderer);
  renWin->Render();
  auto* win = vtkOpenGLRenderWindow::SafeDownCast(renWin);
  win->MakeCurrent();
  int failures = 0;
  for (const Case& c : { Case{ "float points, one radius", VTK_FLOAT, "" },
         Case{ "double points, one radius, colours", VTK_DOUBLE, "", false, true },
         Case{ "int points, float radii", VTK_INT, "float" },
         Case{ "float points, float radii, colours", VTK_FLOAT, "float", false, true },
         Case{ "float points, double radii", VTK_FLOAT, "double" },
         Case{ "double points, two-component radii", VTK_DOUBLE, "float2" },
         Case{ "float points, SPH masses and densities", VTK_FLOAT, "float", true },
         Case{ "double points, SPH, one radius", VTK_DOUBLE, "", true } })
  {
    failures += Run(win, c);
  }

  // The mapper, static data with two invalid balls, statistics off.
  vtkNew<vtkPoints> points;
  for (int i = 0; i < 50; ++i)
  {
    points->InsertNextPoint(0.1 * i, 0.0, 0.0);
  }
  points->SetPoint(3, std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);
  points->SetPoint(4, 0.0, std::numeric_limits<double>::infinity(), 0.0);
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  vtkNew<vtkMetaballMapper> mapper;
  mapper->SetInputDataObject(poly);
  mapper->SetRayCaster(vtkMetaballMapper::GPU);
  mapper->GetField()->SetRadius(0.2);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  renderer->ResetCamera();
  std::cout << "expect a warning: 2 invalid balls\n";
  for (int frame = 0; frame < 6; ++frame)
  {
    renWin->Render();
  }
  std::cout << "static data on the GPU caster: " << mapper->GetNumberOfUploads() << " upload(s), "
            << mapper->GetNumberOfInvalidBalls() << " invalid balls reported\n";
  if (mapper->GetNumberOfUploads() != 1 || mapper->GetNumberOfInvalidBalls() != 2)
  {
    std::cerr << "the invalid balls of a static upload were not reported\n";
    ++failures;
  }
  renWin->RemoveRenderer(renderer);
  renWin->SetSize(64, 64);
  for (const int caster : { vtkMetaballMapper::CPU, vtkMetaballMapper::GPU })
  {
    const vtkIdType plain = HitsNear1e7(renWin, false, caster);
    std::cout << "expect a warning: 1 invalid ball\n";
    const vtkIdType withInfinite = HitsNear1e7(renWin, true, caster);
    std::cout << "27 balls near 1e7, caster " << caster << ": " << plain << " hits, "
              << withInfinite << " with an infinite point\n";
    if (plain < 500 || withInfinite != plain)
    {
      std::cerr << "an infinite point changed the picture near 1e7\n";
      ++failures;
    }
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
