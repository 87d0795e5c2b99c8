// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Accuracy of the ray-cast splats against an exact unit sphere: splats of
// degree 1 to 4 are fitted to 20 000 points of the sphere and rendered; the
// depth buffer is read back, every covered pixel is unprojected, and its
// distance to the sphere is measured. Coverage is checked against the exact
// silhouette (no holes inside it, nothing outside it).
//
// Bounds on the depth error, relative to the radius (measured values are
// printed): degree 1 (flat discs) 1e-2, degree 2 5e-5, degree 3 5e-4,
// degree 4 1e-5. Measured on llvmpipe: 4.1e-3, 7.8e-6, 9.1e-5, 1.2e-6.
#include "vtkActor.h"
#include "vtkAlgebraicSplatFitter.h"
#include "vtkAlgebraicSplatMapper.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include "psRenderTestSupport.h"

#include <cmath>
#include <cstdlib>
#include <iostream>

int TestAlgebraicSplatMapperSphere(int, char*[])
{
  vtkSmartPointer<vtkPolyData> sphere = psFibonacciSphere(20000);

  const int size = 200;
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(size, size);
  renWin->SetMultiSamples(0);
  vtkNew<vtkRenderer> renderer;
  renWin->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.3, 0.4, 4.0);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewAngle(40);
  camera->SetClippingRange(1.0, 8.0);

  vtkNew<vtkAlgebraicSplatFitter> fitter;
  fitter->SetInputData(sphere);
  vtkNew<vtkAlgebraicSplatMapper> mapper;
  mapper->SetInputConnection(fitter->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);

  const double bounds[5] = { 0, 1e-2, 5e-5, 5e-4, 1e-5 };
  int failures = 0;
  for (int degree = 1; degree <= 4; ++degree)
  {
    fitter->SetDegree(degree);
    renWin->Render();
    vtkNew<vtkFloatArray> z;
    renWin->GetZbufferData(0, 0, size - 1, size - 1, z);
    double worst = 0.0, sum2 = 0.0;
    int covered = 0, holes = 0, outside = 0, inside = 0;
    for (int y = 0; y < size; ++y)
    {
      for (int x = 0; x < size; ++x)
      {
        // Is the pixel centre's ray inside the exact silhouette?
        double nearP[3];
        psDisplayToWorld(renderer, x + 0.5, y + 0.5, 0.0, nearP);
        double dir[3], eye[3];
        camera->GetPosition(eye);
        for (int c = 0; c < 3; ++c)
        {
          dir[c] = nearP[c] - eye[c];
        }
        const double dd = dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2];
        const double along = -(eye[0] * dir[0] + eye[1] * dir[1] + eye[2] * dir[2]) / dd;
        double closest2 = 0.0;
        for (int c = 0; c < 3; ++c)
        {
          const double p = eye[c] + along * dir[c];
          closest2 += p * p;
        }
        const bool in = closest2 < 0.98 * 0.98; // a margin of 1 % at the silhouette
        const bool out = closest2 > 1.02 * 1.02;
        const float depth = z->GetValue(y * size + x);
        if (depth < 1.0f)
        {
          ++covered;
          double w[3];
          psDisplayToWorld(renderer, x + 0.5, y + 0.5, depth, w);
          const double r = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
          if (in)
          {
            worst = std::max(worst, std::abs(r - 1.0));
            sum2 += (r - 1.0) * (r - 1.0);
            ++inside;
          }
          outside += out ? 1 : 0;
        }
        else if (in)
        {
          ++holes;
        }
      }
    }
    const double rms = inside ? std::sqrt(sum2 / inside) : 0.0;
    std::cout << "degree " << degree << ": " << fitter->GetOutput()->GetNumberOfPoints()
              << " splats, " << covered << " pixels, depth error max " << worst << " rms " << rms
              << ", " << holes << " holes, " << outside << " pixels outside the silhouette\n";
    if (!(worst < bounds[degree]) || holes > 0 || outside > 0 || inside < 1000)
    {
      std::cerr << "degree " << degree << " is off its bound " << bounds[degree] << "\n";
      ++failures;
    }
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
