// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The Bunny's 35 947 points as 1 344 cubic splats, ray cast and coloured by
// a scalar (height) through the usual lookup table, with an ordinary
// polygonal cone passing through the surface: the splats' true depth must
// let the cone cut in and out of it.
#include "vtkActor.h"
#include "vtkAlgebraicSplatFitter.h"
#include "vtkAlgebraicSplatMapper.h"
#include "vtkCamera.h"
#include "vtkConeSource.h"
#include "vtkElevationFilter.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTestUtilities.h"
#include "vtkXMLPolyDataReader.h"

#include <cstdlib>

int TestAlgebraicSplatMapperBunny(int argc, char* argv[])
{
  char* file = vtkTestUtilities::ExpandDataFileName(argc, argv, "bunny.vtp");
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file);
  delete[] file;
  vtkNew<vtkElevationFilter> height;
  height->SetInputConnection(reader->GetOutputPort());
  height->SetLowPoint(0, 0.03, 0);
  height->SetHighPoint(0, 0.19, 0);
  vtkNew<vtkAlgebraicSplatFitter> fitter;
  fitter->SetInputConnection(height->GetOutputPort());
  fitter->SetDegree(3);
  vtkNew<vtkAlgebraicSplatMapper> mapper;
  mapper->SetInputConnection(fitter->GetOutputPort());
  mapper->SetScalarRange(0.0, 1.0);
  vtkNew<vtkActor> bunny;
  bunny->SetMapper(mapper);
  bunny->GetProperty()->SetSpecular(0.3);
  bunny->GetProperty()->SetSpecularPower(20);

  vtkNew<vtkConeSource> cone;
  cone->SetCenter(-0.02, 0.11, 0.0);
  cone->SetDirection(1, 0.2, 0.6);
  cone->SetHeight(0.16);
  cone->SetRadius(0.025);
  cone->SetResolution(24);
  vtkNew<vtkPolyDataMapper> coneMapper;
  coneMapper->SetInputConnection(cone->GetOutputPort());
  vtkNew<vtkActor> coneActor;
  coneActor->SetMapper(coneMapper);
  coneActor->GetProperty()->SetColor(0.9, 0.9, 0.9);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(bunny);
  renderer->AddActor(coneActor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(300, 300);
  renWin->SetMultiSamples(0);
  renWin->AddRenderer(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.4);
  renWin->Render();
  if (fitter->GetOutput()->GetNumberOfPoints() < 1000)
  {
    return EXIT_FAILURE;
  }
  const int retVal = vtkRegressionTestImage(renWin);
  return retVal == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
