// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Shadows ([Bolla 2010] 4.3.2) through VTK's vtkShadowMapBakerPass and
// vtkShadowMapPass: the Bunny's cubic splats, blended, stand on a polygonal
// floor under a light from the side. The light's depth map is drawn from
// the ray-cast hits (the mapper gives vtkShadowMapBakerPass the hit's depth
// instead of gl_FragCoord's). The floor behind the Bunny must darken, and
// most of the Bunny must keep its brightness (no self-shadowing all over):
// both are measured against the same scene rendered without the shadow
// passes.
//
// Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
// M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
#include "vtkActor.h"
#include "vtkAlgebraicSplatFitter.h"
#include "vtkAlgebraicSplatMapper.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkTestUtilities.h"
#include "vtkXMLPolyDataReader.h"

#include "psRenderTestSupport.h"

#include <cstdlib>
#include <iostream>
#include <vector>

int TestAlgebraicSplatMapperShadows(int argc, char* argv[])
{
  char* file = vtkTestUtilities::ExpandDataFileName(argc, argv, "bunny.vtp");
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file);
  delete[] file;
  vtkNew<vtkAlgebraicSplatFitter> fitter;
  fitter->SetInputConnection(reader->GetOutputPort());
  fitter->SetDegree(3);
  vtkNew<vtkAlgebraicSplatMapper> mapper;
  mapper->SetInputConnection(fitter->GetOutputPort());
  vtkNew<vtkActor> bunny;
  bunny->SetMapper(mapper);
  bunny->GetProperty()->SetColor(0.95, 0.8, 0.6);
  bunny->GetProperty()->SetAmbient(0.2);
  bunny->GetProperty()->SetDiffuse(0.8);

  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-0.2, 0.033, -0.15);
  plane->SetPoint1(0.15, 0.033, -0.15);
  plane->SetPoint2(-0.2, 0.033, 0.2);
  vtkNew<vtkPolyDataMapper> planeMapper;
  planeMapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> floor;
  floor->SetMapper(planeMapper);
  floor->GetProperty()->SetAmbient(0.2);
  floor->GetProperty()->SetDiffuse(0.8);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(bunny);
  renderer->AddActor(floor);
  renderer->SetBackground(0.3, 0.4, 0.6);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetFocalPoint(-0.02, 0.03, 0.0);
  light->SetPosition(0.6, 0.7, 0.2);
  light->SetIntensity(1.0);
  renderer->AddLight(light);
  const int size = 300;
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(size, size);
  renWin->SetMultiSamples(0);
  renWin->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(-0.02, 0.09, 0.0);
  camera->SetPosition(0.05, 0.35, 0.45);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCameraClippingRange();

  auto grab = [&](std::vector<double>& luminance) { luminance = psRenderLuminance(renWin, size); };
  // Which pixels are the Bunny's: depth with the floor hidden.
  floor->VisibilityOff();
  renWin->Render();
  vtkNew<vtkFloatArray> depth;
  renWin->GetZbufferData(0, 0, size - 1, size - 1, depth);
  floor->VisibilityOn();
  std::vector<double> lit, shadowed;
  grab(lit);

  psUseShadowMapPasses(renderer);
  grab(shadowed);

  int bunnyPixels = 0, bunnyDark = 0, floorPixels = 0, floorDark = 0;
  for (int k = 0; k < size * size; ++k)
  {
    const bool onBunny = depth->GetValue(k) < 1.0f;
    const bool dark = shadowed[k] < 0.7 * lit[k];
    if (onBunny)
    {
      ++bunnyPixels;
      bunnyDark += dark ? 1 : 0;
    }
    else if (lit[k] > 0.0 && std::abs(lit[k] - 0.433) > 0.01) // not the background
    {
      ++floorPixels;
      floorDark += dark ? 1 : 0;
    }
  }
  std::cout << "shadowed: " << floorDark << " of " << floorPixels << " floor pixels, " << bunnyDark
            << " of " << bunnyPixels << " Bunny pixels\n";
  int failures = 0;
  if (floorPixels == 0 || bunnyPixels == 0 || floorDark < floorPixels / 20 ||
    bunnyDark > bunnyPixels / 3)
  {
    std::cerr << "the splats' shadows are wrong\n";
    ++failures;
  }
  const int retVal = vtkRegressionTestImage(renWin);
  return failures || retVal == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
