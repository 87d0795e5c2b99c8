// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Renders a lit, scalar-coloured scene through whatever vtkRenderWindow::New()
// returns, checks that it is the window the POINTSURFACES_RENDER_WINDOW switch
// asked for, and compares the image with the shared baseline: the EGL and the
// X11 variants of this test must draw the same picture.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkConeSource.h"
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkElevationFilter.h"
#include "vtkNew.h"
#include "vtkPointSurfacesRenderWindowFactory.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

#include <cstdlib>
#include <iostream>
#include <string>

int TestEGLHeadlessRenderWindow(int argc, char* argv[])
{
  vtkNew<vtkRenderWindow> renWin;
  const char* env = std::getenv("POINTSURFACES_RENDER_WINDOW");
  const std::string mode = env ? env : "auto";
  const std::string expected = mode == "egl"
    ? vtkPointSurfacesRenderWindowFactory::GetEGLWindowClassName()
    : (mode == "x11" ? "vtkXOpenGLRenderWindow" : "");
  if (!expected.empty() && expected != renWin->GetClassName())
  {
    std::cerr << "POINTSURFACES_RENDER_WINDOW=" << mode << " gave a " << renWin->GetClassName()
              << ", expected a " << expected << "\n";
    return EXIT_FAILURE;
  }
  if (vtkPointSurfacesRenderWindowFactory::GetSelectedWindowClassName() !=
    std::string(renWin->GetClassName()))
  {
    std::cerr << "The factory reports "
              << vtkPointSurfacesRenderWindowFactory::GetSelectedWindowClassName()
              << " but created a " << renWin->GetClassName() << "\n";
    return EXIT_FAILURE;
  }
  renWin->SetSize(300, 300);
  renWin->SetMultiSamples(0);

  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(32);
  vtkNew<vtkElevationFilter> elevation;
  elevation->SetInputConnection(sphere->GetOutputPort());
  elevation->SetLowPoint(0, -0.5, 0);
  elevation->SetHighPoint(0, 0.5, 0);
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(elevation->GetOutputPort());
  vtkNew<vtkActor> sphereActor;
  sphereActor->SetMapper(sphereMapper);
  sphereActor->GetProperty()->SetSpecular(0.4);
  sphereActor->GetProperty()->SetSpecularPower(30);

  vtkNew<vtkConeSource> cone;
  cone->SetResolution(32);
  cone->SetCenter(0.9, 0, 0);
  cone->SetHeight(0.8);
  cone->SetRadius(0.3);
  vtkNew<vtkPolyDataMapper> coneMapper;
  coneMapper->SetInputConnection(cone->GetOutputPort());
  vtkNew<vtkActor> coneActor;
  coneActor->SetMapper(coneMapper);
  coneActor->GetProperty()->SetColor(0.9, 0.6, 0.2);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(sphereActor);
  renderer->AddActor(coneActor);
  renderer->SetBackground(0.1, 0.15, 0.25);
  renWin->AddRenderer(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Elevation(20);
  renderer->GetActiveCamera()->Azimuth(30);
  renderer->ResetCameraClippingRange();
  renWin->Render();

  if (auto* egl = vtkEGLHeadlessRenderWindow::SafeDownCast(renWin))
  {
    if (!egl->IsInitialized())
    {
      std::cerr << "The EGL window did not initialise: " << egl->GetLastError() << "\n";
      return EXIT_FAILURE;
    }
    std::cout << "EGL platform: " << egl->GetPlatformName()
              << ", renderer: " << egl->GetRendererName() << "\n";
  }

  const int retVal = vtkRegressionTestImage(renWin);
  return retVal == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
