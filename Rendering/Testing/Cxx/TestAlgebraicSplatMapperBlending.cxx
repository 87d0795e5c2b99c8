// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Two-pass blending ([Bolla 2010] 4.2) on a close-up of the Bunny's cubic splats,
// each coloured by its own random scalar so that the splats' borders show.
// Left: Blending off, each pixel shows its nearest splat, with hard seams.
// Right: Blending on, the colours of the splats within delta of the nearest
// hit are averaged with Gaussian weights. The blended half must be smoother:
// its total variation (the sum of colour differences between neighbouring
// pixels) must be at most 0.7 times the opaque half's, while both cover the
// same pixels. An ordinary polygonal sphere cuts through both surfaces.
//
// Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
// M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
#include "vtkActor.h"
#include "vtkAlgebraicSplatFitter.h"
#include "vtkAlgebraicSplatMapper.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTestUtilities.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>

int TestAlgebraicSplatMapperBlending(int argc, char* argv[])
{
  char* file = vtkTestUtilities::ExpandDataFileName(argc, argv, "bunny.vtp");
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file);
  delete[] file;
  vtkNew<vtkAlgebraicSplatFitter> fitter;
  fitter->SetInputConnection(reader->GetOutputPort());
  fitter->SetDegree(3);
  fitter->Update();
  vtkNew<vtkPolyData> splats;
  splats->ShallowCopy(fitter->GetOutput());
  vtkNew<vtkFloatArray> random;
  random->SetName("SplatRandom");
  random->SetNumberOfTuples(splats->GetNumberOfPoints());
  std::mt19937 gen(7);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  for (vtkIdType i = 0; i < splats->GetNumberOfPoints(); ++i)
  {
    random->SetValue(i, uni(gen));
  }
  splats->GetPointData()->SetScalars(random);

  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(-0.03, 0.12, 0.03);
  ball->SetRadius(0.02);
  ball->SetThetaResolution(32);
  ball->SetPhiResolution(32);
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(ball->GetOutputPort());

  const int width = 200, height = 200;
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(2 * width, height);
  renWin->SetMultiSamples(0);
  vtkAlgebraicSplatMapper* mappers[2];
  for (int side = 0; side < 2; ++side)
  {
    vtkNew<vtkAlgebraicSplatMapper> mapper;
    mapper->SetInputData(splats);
    mapper->SetScalarRange(0.0, 1.0);
    mapper->SetBlending(side == 1);
    mappers[side] = mapper;
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    vtkNew<vtkActor> ballActor;
    ballActor->SetMapper(ballMapper);
    ballActor->GetProperty()->SetColor(0.9, 0.9, 0.9);
    vtkNew<vtkRenderer> renderer;
    renderer->SetViewport(0.5 * side, 0.0, 0.5 * side + 0.5, 1.0);
    renderer->AddActor(actor);
    renderer->AddActor(ballActor);
    renderer->SetBackground(0.1, 0.1, 0.15);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetFocalPoint(-0.03, 0.12, 0.0);
    camera->SetPosition(-0.03, 0.12, 0.25);
    camera->SetViewAngle(30);
    renderer->ResetCameraClippingRange();
    renWin->AddRenderer(renderer);
  }
  renWin->Render();

  vtkNew<vtkUnsignedCharArray> rgb;
  renWin->GetPixelData(0, 0, 2 * width - 1, height - 1, 0, rgb);
  double variation[2] = { 0.0, 0.0 };
  int covered[2] = { 0, 0 };
  const int background[3] = { 26, 26, 38 };
  for (int side = 0; side < 2; ++side)
  {
    for (int y = 0; y + 1 < height; ++y)
    {
      for (int x = side * width; x + 1 < (side + 1) * width; ++x)
      {
        const unsigned char* p = rgb->GetPointer(3 * (y * 2 * width + x));
        const unsigned char* right = p + 3;
        const unsigned char* up = p + 3 * 2 * width;
        bool isBackground = true;
        for (int c = 0; c < 3; ++c)
        {
          isBackground = isBackground && std::abs(p[c] - background[c]) <= 1;
          variation[side] += std::abs(p[c] - right[c]) + std::abs(p[c] - up[c]);
        }
        covered[side] += isBackground ? 0 : 1;
      }
    }
  }
  std::cout << "total variation: opaque " << variation[0] << ", blended " << variation[1]
            << " (ratio " << variation[1] / variation[0] << "); covered pixels " << covered[0]
            << ", " << covered[1] << "; splats drawn " << mappers[1]->GetNumberOfRenderedSplats()
            << "\n";
  int failures = 0;
  if (!(variation[1] < 0.7 * variation[0]) || covered[0] < width * height / 2 ||
    std::abs(covered[0] - covered[1]) > covered[0] / 50)
  {
    std::cerr << "blending does not smooth the seams between splats\n";
    ++failures;
  }
  const int retVal = vtkRegressionTestImage(renWin);
  return failures || retVal == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
