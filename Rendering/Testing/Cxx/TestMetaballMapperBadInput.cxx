// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkMetaballMapper on bad input and extremes; each case must render a valid
// image with no GL error:
// - 1 000 balls at one point: one voxel list far beyond the 256 balls of a
//   shared-memory batch; the sphere's silhouette must match the exact iso
//   radius (1000 f(r^2/R^2) = T) within 2 % of its area;
// - radii from 1e-4 to 1e2 in one scene;
// - NaN centres, NaN and zero radii: skipped, counted, one warning;
// - the camera inside a blob, and a ball crossing the near plane: a warning,
//   and the pixels that start inside are counted;
// - balls behind the camera: culled and counted, the others drawn;
// - more balls than a storage buffer may hold (a capped limit): one clear
//   error and an empty image, then a normal frame once the cap is lifted.
#include "psOpenGL.h"
#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkMetaballMapper.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkShaderStorageBuffer.h"

#include "psMetaball.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>

namespace
{
int Warnings = 0;
int Errors = 0;
void Count(vtkObject*, unsigned long event, void*, void*)
{
  (event == vtkCommand::WarningEvent ? Warnings : Errors)++;
}

vtkSmartPointer<vtkPolyData> Balls(const std::vector<double>& xyzr)
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkFloatArray> radius;
  radius->SetName("Radius");
  for (size_t i = 0; i + 3 < xyzr.size(); i += 4)
  {
    pts->InsertNextPoint(xyzr[i], xyzr[i + 1], xyzr[i + 2]);
    radius->InsertNextValue(static_cast<float>(xyzr[i + 3]));
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(pts);
  poly->GetPointData()->AddArray(radius);
  return poly;
}
} // namespace

int TestMetaballMapperBadInput(int, char*[])
{
  const int size = 128;
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(size, size);
  renWin->SetMultiSamples(0);
  vtkNew<vtkRenderer> renderer;
  renWin->AddRenderer(renderer);
  vtkNew<vtkMetaballMapper> mapper;
  mapper->CollectStatisticsOn(); // each frame's counters and warnings are checked
  vtkNew<vtkCallbackCommand> counter;
  counter->SetCallback(Count);
  mapper->AddObserver(vtkCommand::WarningEvent, counter);
  mapper->AddObserver(vtkCommand::ErrorEvent, counter);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  vtkCamera* camera = renderer->GetActiveCamera();
  int failures = 0;
  auto render = [&](const char* what)
  {
    renWin->Render();
    vtkOpenGLRenderWindow::SafeDownCast(renWin)->MakeCurrent();
    const GLenum e = glGetError();
    if (e != GL_NO_ERROR)
    {
      std::cerr << what << ": GL error " << e << "\n";
      ++failures;
    }
    vtkNew<vtkFloatArray> z;
    renWin->GetZbufferData(0, 0, size - 1, size - 1, z);
    int covered = 0;
    for (vtkIdType k = 0; k < z->GetNumberOfTuples(); ++k)
    {
      covered += z->GetValue(k) < 1.0f ? 1 : 0;
    }
    return covered;
  };
  auto look = [&](double x, double y, double z, double distance)
  {
    camera->SetFocalPoint(x, y, z);
    camera->SetPosition(x, y, z + distance);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(30);
    camera->SetClippingRange(0.01 * distance, 10 * distance);
  };

  // 1 000 balls at one point.
  std::vector<double> same;
  for (int i = 0; i < 1000; ++i)
  {
    same.insert(same.end(), { 0.0, 0.0, 0.0, 1.0 });
  }
  mapper->SetInputDataObject(Balls(same));
  look(0, 0, 0, 6.0);
  Warnings = Errors = 0;
  const int coveredSame = render("coincident balls");
  // 1000 f(x) = T: a lone ball at T / 1000.
  const double iso =
    pointsurfaces::LoneBallIsoRadius(pointsurfaces::MetaballKernel::Wyvill, 0.5 / 1000.0);
  // The silhouette of a sphere of radius a seen from distance D: half-angle asin(a / D).
  const double halfAngle = std::asin(iso / 6.0);
  const double pixels = size / (2.0 * std::tan(3.14159265358979 / 12.0)) * std::tan(halfAngle);
  const double expected = 3.14159265358979 * pixels * pixels;
  std::cout << "coincident: " << coveredSame << " pixels (expected " << expected << "), at most "
            << mapper->GetMaximumBallsPerVoxel() << " balls per voxel\n";
  if (std::abs(coveredSame - expected) > 0.02 * expected ||
    mapper->GetMaximumBallsPerVoxel() != 1000)
  {
    std::cerr << "coincident balls are wrong\n";
    ++failures;
  }

  // Radii from 1e-4 to 1e2, side by side.
  std::vector<double> spread;
  double x = 0.0;
  for (int k = -4; k <= 2; ++k)
  {
    const double r = std::pow(10.0, k);
    spread.insert(spread.end(), { x + r, 0.0, 0.0, r });
    x += 2.2 * r;
  }
  mapper->SetInputDataObject(Balls(spread));
  look(0.5 * x, 0, 0, 1.5 * x);
  const int coveredSpread = render("radii 1e-4 to 1e2");
  std::cout << "radii 1e-4 to 1e2: " << coveredSpread << " pixels\n";
  if (coveredSpread < 100)
  {
    ++failures;
  }

  // NaN centres, NaN and zero radii among valid balls.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  mapper->SetInputDataObject(
    Balls({ 0, 0, 0, 1, nan, 0, 0, 1, 0.5, 0, 0, nan, 0.5, 0.5, 0, 0, 0, 0.8, 0, 1 }));
  look(0, 0, 0, 6.0);
  Warnings = Errors = 0;
  const int coveredNaN = render("NaN balls");
  std::cout << "NaN: " << mapper->GetNumberOfInvalidBalls() << " invalid, " << Warnings
            << " warnings, " << coveredNaN << " pixels\n";
  if (mapper->GetNumberOfInvalidBalls() != 3 || Warnings != 1 || coveredNaN < 500 || Errors)
  {
    ++failures;
  }

  // The camera inside a blob; then a ball crossing the near plane.
  mapper->SetInputDataObject(Balls({ 0, 0, 0, 2, 0.8, 0, 0, 2 }));
  look(0.4, 0, -0.1, 0.1);
  camera->SetClippingRange(0.01, 10.0);
  Warnings = 0;
  const int coveredInside = render("camera inside");
  std::cout << "camera inside: " << mapper->GetNumberOfPixelsStartingInside()
            << " pixels start inside, " << Warnings << " warnings, " << coveredInside
            << " pixels\n";
  if (mapper->GetNumberOfPixelsStartingInside() < size * size / 2 || Warnings != 1 ||
    coveredInside < size * size / 2)
  {
    ++failures;
  }
  mapper->SetInputDataObject(Balls({ 0, 0, 0, 1, 0, 0, 5.9, 0.5 }));
  look(0, 0, 0, 6.0);
  camera->SetClippingRange(0.2, 20);
  render("near plane");
  std::cout << "near plane: " << mapper->GetNumberOfPixelsStartingInside()
            << " pixels start inside\n";
  if (mapper->GetNumberOfPixelsStartingInside() == 0)
  {
    ++failures;
  }

  // Balls behind the camera are culled; the one in front is drawn.
  mapper->SetInputDataObject(Balls({ 0, 0, 0, 1, 0, 0, 10, 1, 1, 0, 12, 1 }));
  look(0, 0, 0, 6.0);
  const int coveredBehind = render("behind");
  if (coveredBehind < 500 || mapper->GetNumberOfCulledBalls() != 2)
  {
    std::cerr << "balls behind the camera: " << coveredBehind << " pixels, "
              << mapper->GetNumberOfCulledBalls() << " culled\n";
    ++failures;
  }
  // More balls than a storage buffer holds: a clear error, an empty but valid
  // image. The cap stands in for a driver limit (about 2 GB on llvmpipe,
  // which would take 130M balls to reach).
  {
    std::vector<double> many;
    for (int i = 0; i < 5000; ++i)
    {
      many.insert(many.end(), { 0.01 * (i % 70), 0.01 * (i / 70), 0.0, 0.05 });
    }
    mapper->SetInputDataObject(Balls(many));
    look(0.35, 0.35, 0, 3.0);
    vtkShaderStorageBuffer::SetMaximumSizeLimit(16 * 4096); // 4 096 balls of 16 bytes
    Warnings = Errors = 0;
    const int coveredOver = render("beyond the buffer limit");
    vtkShaderStorageBuffer::SetMaximumSizeLimit(0);
    std::cout << "5 000 balls, buffers capped at 4 096 balls: " << Errors << " errors, "
              << coveredOver << " pixels drawn\n";
    if (Errors != 1 || coveredOver != 0)
    {
      ++failures;
    }
    Warnings = Errors = 0;
    mapper->Modified();
    const int coveredUnder = render("below the buffer limit again");
    if (Errors != 0 || coveredUnder < 1000)
    {
      std::cerr << "after the cap is lifted: " << Errors << " errors, " << coveredUnder
                << " pixels\n";
      ++failures;
    }
  }
  // The CPU caster over its memory limit: one error (not one a frame), no
  // balls drawn; the limit lifted, the balls are drawn again.
  {
    mapper->SetRayCasterToCPU();
    mapper->SetMemoryLimit(100); // KiB: less than 5 000 balls' copy (64 bytes each)
    Warnings = Errors = 0;
    const int coveredOver = render("CPU caster beyond its memory limit");
    render("CPU caster beyond its memory limit, a second frame");
    std::cout << "CPU caster, 5 000 balls in 100 KiB: " << Errors << " errors over 2 frames, "
              << coveredOver << " pixels drawn\n";
    if (Errors != 1 || coveredOver != 0)
    {
      ++failures;
    }
    mapper->SetMemoryLimit(0);
    Warnings = Errors = 0;
    const int coveredUnder = render("CPU caster, the limit lifted");
    if (Errors != 0 || coveredUnder < 1000)
    {
      std::cerr << "CPU caster after the limit is lifted: " << Errors << " errors, " << coveredUnder
                << " pixels\n";
      ++failures;
    }
    mapper->SetRayCasterToAutomatic();
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
