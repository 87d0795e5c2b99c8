// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Octree culling and continuous LOD of vtkAlgebraicSplatMapper on the
// Bunny's multi-resolution splats (25 levels, s = 4 down to 0.5):
// - culling draws fewer splats when the camera sees part of the model, and
//   the picture is exactly the one drawn without culling;
// - the number of splats drawn falls as LODPixelError grows;
// - the image at LODPixelError = 8 is compared with its baseline.
#include "vtkActor.h"
#include "vtkAlgebraicSplatMapper.h"
#include "vtkCamera.h"
#include "vtkMultiResolutionSplatBuilder.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTestUtilities.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"

#include <cstdlib>
#include <iostream>

int TestAlgebraicSplatMapperLOD(int argc, char* argv[])
{
  char* file = vtkTestUtilities::ExpandDataFileName(argc, argv, "bunny.vtp");
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file);
  delete[] file;
  vtkNew<vtkMultiResolutionSplatBuilder> builder;
  builder->SetInputConnection(reader->GetOutputPort());
  builder->SetQualityFactor(0.5);
  builder->Update();
  const vtkIdType total = builder->GetOutput()->GetNumberOfPoints();

  vtkNew<vtkAlgebraicSplatMapper> mapper;
  mapper->SetInputConnection(builder->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(300, 300);
  renWin->SetMultiSamples(0);
  renWin->AddRenderer(renderer);
  renderer->ResetCamera();
  int failures = 0;

  // Culling: look at a small part of the body.
  renderer->GetActiveCamera()->Zoom(8.0);
  renderer->GetActiveCamera()->Azimuth(20);
  renderer->ResetCameraClippingRange();
  renWin->Render();
  const vtkIdType culled = mapper->GetNumberOfRenderedSplats();
  vtkNew<vtkUnsignedCharArray> withCulling, without;
  renWin->GetPixelData(0, 0, 299, 299, 0, withCulling);
  mapper->CullingOff();
  renWin->Render();
  renWin->GetPixelData(0, 0, 299, 299, 0, without);
  mapper->CullingOn();
  std::cout << total << " splats, " << culled << " drawn after culling\n";
  if (culled > 0.7 * total || culled == 0)
  {
    std::cerr << "Culling drew " << culled << " of " << total << " splats\n";
    ++failures;
  }
  for (vtkIdType i = 0; i < without->GetNumberOfValues(); ++i)
  {
    if (without->GetValue(i) != withCulling->GetValue(i))
    {
      std::cerr << "Culling changed the picture\n";
      ++failures;
      break;
    }
  }

  // LOD: fewer splats for a larger pixel error. The coarsest level of
  // error-bounded splats (its bound 8 times the finest's at s_0 = 4) holds
  // about a fifth of them: discs cannot outgrow their bound.
  renderer->ResetCamera();
  vtkIdType previous = total + 1;
  for (double error : { 0.0, 2.0, 8.0, 32.0 })
  {
    mapper->SetLODPixelError(error);
    renWin->Render();
    const vtkIdType drawn = mapper->GetNumberOfRenderedSplats();
    std::cout << "LODPixelError " << error << ": " << drawn << " splats\n";
    if (drawn > previous || (error == 0.0 && drawn != total) ||
      (error == 32.0 && drawn > total / 4))
    {
      std::cerr << "The LOD does not follow the pixel error\n";
      ++failures;
    }
    previous = drawn;
  }
  mapper->SetLODPixelError(8.0);
  renWin->Render();
  const int retVal = vtkRegressionTestImage(renWin);
  return (failures || retVal == vtkRegressionTester::FAILED) ? EXIT_FAILURE : EXIT_SUCCESS;
}
