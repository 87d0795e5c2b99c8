// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// A torus (R = 1, r = 0.4) of 20 000 points as quartic splats, blended and
// coloured by height, seen through its hole at a slant, with 2 x 2 adaptive
// anti-aliasing. The ring's inner side, where the surface is saddle-shaped,
// is what linear and quadratic splats render worst. Its depth and normal
// accuracy are checked by TestAlgebraicSplatMapperAccuracy.
#include "vtkActor.h"
#include "vtkAlgebraicSplatFitter.h"
#include "vtkAlgebraicSplatMapper.h"
#include "vtkCamera.h"
#include "vtkElevationFilter.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cmath>
#include <cstdlib>
#include <random>

int TestAlgebraicSplatMapperTorus(int argc, char* argv[])
{
  const double pi = 3.14159265358979323846, R = 1.0, r = 0.4;
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  while (pts->GetNumberOfPoints() < 20000)
  {
    const double u = 2.0 * pi * uni(gen), v = 2.0 * pi * uni(gen);
    if (uni(gen) * (R + r) > R + r * std::cos(v))
    {
      continue; // uniform over the area
    }
    const double ring = R + r * std::cos(v);
    pts->InsertNextPoint(ring * std::cos(u), ring * std::sin(u), r * std::sin(v));
  }
  vtkNew<vtkPolyData> torus;
  torus->SetPoints(pts);
  vtkNew<vtkElevationFilter> height;
  height->SetInputData(torus);
  height->SetLowPoint(0, 0, -r);
  height->SetHighPoint(0, 0, r);
  vtkNew<vtkAlgebraicSplatFitter> fitter;
  fitter->SetInputConnection(height->GetOutputPort());
  fitter->SetDegree(4);
  vtkNew<vtkAlgebraicSplatMapper> mapper;
  mapper->SetInputConnection(fitter->GetOutputPort());
  mapper->SetScalarRange(0.0, 1.0);
  mapper->SetAntiAliasing(2);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetSpecular(0.4);
  actor->GetProperty()->SetSpecularPower(30);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(300, 300);
  renWin->SetMultiSamples(0);
  renWin->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.5, -2.5, 2.8);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(40);
  renderer->ResetCameraClippingRange();
  renWin->Render();
  if (fitter->GetOutput()->GetNumberOfPoints() < 300)
  {
    return EXIT_FAILURE;
  }
  const int retVal = vtkRegressionTestImage(renWin);
  return retVal == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
