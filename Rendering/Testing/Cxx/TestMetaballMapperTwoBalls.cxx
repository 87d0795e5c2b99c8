// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Two metaballs melting into one blob, coloured red and blue through a
// lookup table (the colours blend with the kernel weights across the neck),
// with an ordinary polygonal plate cutting through both: the blob's true
// depth lets the plate pass in and out of it. The right half shows the same
// scene through the quartic kernel with a larger threshold.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkFloatArray.h"
#include "vtkMetaballMapper.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cstdlib>

int TestMetaballMapperTwoBalls(int argc, char* argv[])
{
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(-0.55, 0.0, 0.0);
  pts->InsertNextPoint(0.55, 0.1, 0.0);
  vtkNew<vtkFloatArray> radius, value;
  radius->SetName("Radius");
  radius->InsertNextValue(1.0f);
  radius->InsertNextValue(0.9f);
  value->SetName("Value");
  value->InsertNextValue(0.0f);
  value->InsertNextValue(1.0f);
  vtkNew<vtkPolyData> balls;
  balls->SetPoints(pts);
  balls->GetPointData()->AddArray(radius);
  balls->GetPointData()->SetScalars(value);

  vtkNew<vtkCubeSource> plate;
  plate->SetXLength(2.4);
  plate->SetYLength(0.05);
  plate->SetZLength(1.2);
  vtkNew<vtkPolyDataMapper> plateMapper;
  plateMapper->SetInputConnection(plate->GetOutputPort());

  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(400, 200);
  renWin->SetMultiSamples(0);
  for (int side = 0; side < 2; ++side)
  {
    vtkNew<vtkMetaballMapper> mapper;
    mapper->SetInputDataObject(balls);
    mapper->SetScalarRange(0.0, 1.0);
    if (side == 1)
    {
      mapper->GetField()->SetKernel(vtkMetaballField::Quartic);
      mapper->GetField()->SetThreshold(0.3);
    }
    vtkNew<vtkActor> blob;
    blob->SetMapper(mapper);
    blob->GetProperty()->SetSpecular(0.4);
    blob->GetProperty()->SetSpecularPower(30);
    vtkNew<vtkActor> plateActor;
    plateActor->SetMapper(plateMapper);
    plateActor->GetProperty()->SetColor(0.9, 0.9, 0.8);
    plateActor->RotateX(20);
    vtkNew<vtkRenderer> renderer;
    renderer->SetViewport(0.5 * side, 0, 0.5 * side + 0.5, 1);
    renderer->AddActor(blob);
    renderer->AddActor(plateActor);
    renderer->SetBackground(0.1, 0.1, 0.15);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(0.4, 1.2, 3.6);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewAngle(40);
    renderer->ResetCameraClippingRange();
    renWin->AddRenderer(renderer);
  }
  renWin->Render();
  const int retVal = vtkRegressionTestImage(renWin);
  return retVal == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
