// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// A dense cluster of 20 000 balls (Gaussian positions, radii 0.05 to 0.15),
// coloured by distance from the centre through the mapper's lookup table,
// then animated: a second frame with unchanged data must not upload it
// again, and a frame after the points move must upload them once and show
// them moved (the depth under the centre changes). The regression image is
// the last frame.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkMetaballMapper.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>

int TestMetaballMapperCluster(int argc, char* argv[])
{
  const int n = 20000;
  std::mt19937 gen(23);
  std::normal_distribution<double> normal(0.0, 0.6);
  std::uniform_real_distribution<double> rad(0.05, 0.15);
  vtkNew<vtkPoints> pts;
  vtkNew<vtkFloatArray> radius, distance;
  radius->SetName("Radius");
  distance->SetName("Distance");
  for (int i = 0; i < n; ++i)
  {
    const double p[3] = { normal(gen), normal(gen), normal(gen) };
    pts->InsertNextPoint(p);
    radius->InsertNextValue(static_cast<float>(rad(gen)));
    distance->InsertNextValue(
      static_cast<float>(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2])));
  }
  vtkNew<vtkPolyData> cluster;
  cluster->SetPoints(pts);
  cluster->GetPointData()->AddArray(radius);
  cluster->GetPointData()->SetScalars(distance);

  vtkNew<vtkMetaballMapper> mapper;
  mapper->CollectStatisticsOn(); // the frame's counts are checked
  mapper->SetInputDataObject(cluster);
  mapper->SetScalarRange(0.0, 2.0);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetSpecular(0.2);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(300, 300);
  renWin->SetMultiSamples(0);
  renWin->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.0, 0.0, 7.0);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewAngle(40);
  renderer->ResetCameraClippingRange();

  int failures = 0;
  renWin->Render();
  const int uploads = mapper->GetNumberOfUploads();
  const float before = renWin->GetZbufferDataAtPoint(150, 150);
  renWin->Render();
  if (mapper->GetNumberOfUploads() != uploads)
  {
    std::cerr << "unchanged data was uploaded again\n";
    ++failures;
  }
  // Move every ball 0.5 towards the camera.
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    pts->GetPoint(i, p);
    p[2] += 0.5;
    pts->SetPoint(i, p);
  }
  pts->Modified();
  renWin->Render();
  const float after = renWin->GetZbufferDataAtPoint(150, 150);
  std::cout << mapper->GetNumberOfPairs() << " pairs, at most " << mapper->GetMaximumBallsPerVoxel()
            << " balls per voxel, " << mapper->GetGridBuildTime() << " ms grid, "
            << mapper->GetRayCastTime() << " ms ray cast; " << mapper->GetNumberOfUploads()
            << " uploads; centre depth " << before << " then " << after << "\n";
  if (mapper->GetNumberOfUploads() != uploads + 1 || !(after < before) ||
    mapper->GetNumberOfIncompleteRays() != 0)
  {
    std::cerr << "the animated frame is wrong\n";
    ++failures;
  }
  const int retVal = vtkRegressionTestImage(renWin);
  return failures || retVal == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
