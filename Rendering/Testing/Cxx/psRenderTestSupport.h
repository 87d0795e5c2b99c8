// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// What several render tests share: points spread evenly over the unit
// sphere, the exact surface most splat tests check against, the world point
// behind a pixel of the rendered image, a rendered image's luminance, and
// VTK's shadow map passes.
#ifndef psRenderTestSupport_h
#define psRenderTestSupport_h

#include "vtkCameraPass.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderPassCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSequencePass.h"
#include "vtkShadowMapBakerPass.h"
#include "vtkShadowMapPass.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <vector>

// n points of the unit sphere on a Fibonacci spiral, in double precision.
inline vtkSmartPointer<vtkPolyData> psFibonacciSphere(int n)
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), t = golden * i;
    pts->InsertNextPoint(r * std::cos(t), r * std::sin(t), z);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(pts);
  return poly;
}

// The world point at display position (x, y) and depth z (0 at the near
// plane, 1 at the far one) of ren's current view.
inline void psDisplayToWorld(vtkRenderer* ren, double x, double y, double z, double world[3])
{
  ren->SetDisplayPoint(x, y, z);
  ren->DisplayToWorld();
  double p[4];
  ren->GetWorldPoint(p);
  for (int c = 0; c < 3; ++c)
  {
    world[c] = p[c] / p[3];
  }
}

// Renders `window` and returns the luminance (mean of R, G and B, 0 to 1) of
// its lower-left size x size pixels, row by row from the bottom.
inline std::vector<double> psRenderLuminance(vtkRenderWindow* window, int size)
{
  window->Render();
  vtkNew<vtkUnsignedCharArray> rgb;
  window->GetPixelData(0, 0, size - 1, size - 1, 0, rgb);
  std::vector<double> luminance(static_cast<std::size_t>(size) * size);
  for (std::size_t k = 0; k < luminance.size(); ++k)
  {
    luminance[k] =
      (rgb->GetValue(3 * k) + rgb->GetValue(3 * k + 1) + rgb->GetValue(3 * k + 2)) / (3.0 * 255.0);
  }
  return luminance;
}

// Draw `renderer` with shadows through VTK's passes: the lights' depth maps
// (vtkShadowMapBakerPass), then the frame that looks them up.
inline void psUseShadowMapPasses(vtkRenderer* renderer)
{
  vtkNew<vtkShadowMapPass> shadows;
  vtkNew<vtkSequencePass> sequence;
  vtkNew<vtkRenderPassCollection> passes;
  passes->AddItem(shadows->GetShadowMapBakerPass());
  passes->AddItem(shadows);
  sequence->SetPasses(passes);
  vtkNew<vtkCameraPass> cameraPass;
  cameraPass->SetDelegatePass(sequence);
  vtkOpenGLRenderer::SafeDownCast(renderer)->SetPass(cameraPass);
}

#endif
