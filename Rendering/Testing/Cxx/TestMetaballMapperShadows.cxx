// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Metaball shadows from secondary rays: a floor of 900 overlapping balls and
// a blob of seven balls above it, under a directional scene light from above
// and the side. With Shadows on, the floor under the blob must darken (the
// rays toward the light meet the blob), nothing may get brighter, and the
// blob's lit top must keep its brightness (no self-shadowing). Both renders
// are compared pixel by pixel; the regression image has shadows on.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkMetaballMapper.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include "psRenderTestSupport.h"

#include <cstdlib>
#include <iostream>
#include <vector>

int TestMetaballMapperShadows(int argc, char* argv[])
{
  vtkNew<vtkPoints> pts;
  vtkNew<vtkFloatArray> radius;
  radius->SetName("Radius");
  for (int i = 0; i < 30; ++i)
  {
    for (int j = 0; j < 30; ++j)
    {
      pts->InsertNextPoint(-2.2 + 0.15 * i, 0.0, -2.2 + 0.15 * j);
      radius->InsertNextValue(0.3f);
    }
  }
  const double blob[7][3] = { { 0, 1.2, 0 },
    { 0.3, 1.2, 0 },
    { -0.3, 1.2, 0 },
    { 0, 1.5, 0 },
    { 0, 0.9, 0 },
    { 0, 1.2, 0.3 },
    { 0, 1.2, -0.3 } };
  for (const auto& b : blob)
  {
    pts->InsertNextPoint(b);
    radius->InsertNextValue(0.5f);
  }
  vtkNew<vtkPolyData> balls;
  balls->SetPoints(pts);
  balls->GetPointData()->AddArray(radius);

  vtkNew<vtkMetaballMapper> mapper;
  mapper->SetInputDataObject(balls);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.9, 0.85, 0.7);
  actor->GetProperty()->SetAmbient(0.15);
  actor->GetProperty()->SetDiffuse(0.85);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.3, 0.4, 0.6);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetPosition(1.0, 3.0, 0.5);
  light->SetFocalPoint(0, 0, 0);
  renderer->AddLight(light);
  const int size = 240;
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(size, size);
  renWin->SetMultiSamples(0);
  renWin->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.5, 3.5, 5.0);
  camera->SetFocalPoint(0, 0.4, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(40);
  renderer->ResetCameraClippingRange();

  auto grab = [&](std::vector<double>& luminance) { luminance = psRenderLuminance(renWin, size); };
  std::vector<double> lit, shaded;
  grab(lit);
  mapper->ShadowsOn();
  grab(shaded);
  int darker = 0, brighter = 0;
  for (int k = 0; k < size * size; ++k)
  {
    darker += shaded[k] < 0.7 * lit[k] ? 1 : 0;
    brighter += shaded[k] > lit[k] + 2.0 / 255.0 ? 1 : 0;
  }
  // The blob's top, seen at the image's upper middle, must stay lit.
  double topLit = 0.0, topShaded = 0.0;
  for (int y = size * 55 / 100; y < size * 65 / 100; ++y)
  {
    for (int x = size * 45 / 100; x < size * 55 / 100; ++x)
    {
      topLit += lit[y * size + x];
      topShaded += shaded[y * size + x];
    }
  }
  std::cout << darker << " pixels in shadow, " << brighter << " brighter; blob top "
            << topShaded / topLit << " of its unshadowed brightness; " << mapper->GetShadowTime()
            << " ms for the shadows, " << mapper->GetRayCastTime() << " ms for the primary rays\n";
  int failures = 0;
  if (darker < size * size / 80 || brighter > 0 || topShaded < 0.95 * topLit)
  {
    std::cerr << "the metaball shadows are wrong\n";
    ++failures;
  }
  const int retVal = vtkRegressionTestImage(renWin);
  return failures || retVal == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
