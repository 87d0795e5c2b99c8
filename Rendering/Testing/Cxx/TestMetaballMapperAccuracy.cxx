// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkMetaballMapper against the double-precision reference ray caster
// (pointsurfaces::CastRay: dense sampling at 1/400 of the smallest radius,
// then 50 bisections on the exact field). 60 balls of radii 0.3 to 0.6 with
// strengths from 0.6 to 1.4 are rendered with each kernel (the SPH ones
// normalised by R^3, the threshold scaled to match); every pixel's
// hit (view distance and normal, read back from the mapper) is compared with
// the reference ray through the pixel centre. The error is reported as a
// function of the step scale and the bisection count; at the defaults
// (0.1, 10) and finer, fewer than 1 % of the covered pixels may disagree on
// hit or miss (they lie on silhouettes), and the 99th percentile of the
// depth error must stay below 1e-3 of the smallest radius, of the normal
// error below 0.5 degrees. Both ray casters, the GPU's compute shaders and
// the native CPU one, are held to the same bounds.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkMatrix4x4.h"
#include "vtkMetaballMapper.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include "psMetaball.h"

#include "psTestHitMapper.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <vector>

int TestMetaballMapperAccuracy(int, char*[])
{
  const int n = 60;
  std::mt19937 gen(17);
  std::uniform_real_distribution<double> uni(-1.0, 1.0), rad(0.3, 0.6), str(0.6, 1.4);
  std::vector<double> centres(3 * n), radii(n), strengths(n);
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkFloatArray> radius, strength;
  radius->SetName("Radius");
  strength->SetName("Strength");
  for (int i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      centres[3 * i + c] = uni(gen);
    }
    radii[i] = rad(gen);
    strengths[i] = str(gen);
    pts->InsertNextPoint(&centres[3 * i]);
    radius->InsertNextValue(static_cast<float>(radii[i]));
    strength->InsertNextValue(static_cast<float>(strengths[i]));
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(pts);
  poly->GetPointData()->AddArray(radius);
  poly->GetPointData()->AddArray(strength);

  const int size = 128;
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(size, size);
  renWin->SetMultiSamples(0);
  vtkNew<vtkRenderer> renderer;
  renWin->AddRenderer(renderer);
  vtkNew<HitMapper> mapper;
  mapper->SetInputDataObject(poly);
  mapper->GetField()->SetStrengthArrayName("Strength");
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.5, 0.7, 5.0);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(35);
  camera->SetClippingRange(1.0, 10.0);
  const double minRadius = *std::min_element(radii.begin(), radii.end());

  struct Setting
  {
    double Step;
    int Bisections;
    bool Bounded;
  };
  const Setting settings[] = {
    { 0.4, 4, false }, { 0.1, 0, false }, { 0.1, 10, true }, { 0.02, 20, true }
  };
  const char* names[6] = {
    "Wyvill", "quartic", "Gaussian", "cubic spline", "Wendland C2", "Wendland C4"
  };
  int failures = 0;
  for (int kernel = 0; kernel < 6; ++kernel)
  {
    // The SPH kernels carry N / R^3 in the strengths; the threshold keeps the
    // blobs about the size of the others'.
    const auto type = static_cast<pointsurfaces::MetaballKernel>(kernel);
    const double normalization = pointsurfaces::KernelNormalization(type);
    std::vector<double> weights(strengths);
    for (int i = 0; i < n && normalization > 0.0; ++i)
    {
      weights[i] *= normalization / (radii[i] * radii[i] * radii[i]);
    }
    mapper->GetField()->SetKernel(kernel);
    mapper->GetField()->SetThreshold(
      normalization > 0.0 ? 0.5 * normalization / (0.45 * 0.45 * 0.45) : 0.5);
    pointsurfaces::MetaballSet set;
    set.Centers = centres.data();
    set.Radii = radii.data();
    set.Strengths = weights.data();
    set.Count = n;
    set.Kernel = type;
    set.Threshold = mapper->GetField()->GetThreshold();

    // The reference, once per kernel: a ray through every pixel centre.
    std::vector<pointsurfaces::RayHit> reference(size * size);
    double eye[3];
    camera->GetPosition(eye);
    for (int y = 0; y < size; ++y)
    {
      for (int x = 0; x < size; ++x)
      {
        renderer->SetDisplayPoint(x + 0.5, y + 0.5, 0.0);
        renderer->DisplayToWorld();
        double p[4];
        renderer->GetWorldPoint(p);
        double d[3], len = 0.0;
        for (int c = 0; c < 3; ++c)
        {
          d[c] = p[c] / p[3] - eye[c];
          len += d[c] * d[c];
        }
        len = std::sqrt(len);
        for (int c = 0; c < 3; ++c)
        {
          d[c] /= len;
        }
        reference[y * size + x] =
          pointsurfaces::CastRay(set, eye, d, 0.0, 12.0, minRadius / 400.0, 50);
      }
    }

    for (const int caster : { vtkMetaballMapper::GPU, vtkMetaballMapper::CPU })
    {
      mapper->SetRayCaster(caster);
      const char* casterName = caster == vtkMetaballMapper::GPU ? "GPU" : "CPU";
      for (const Setting& s : settings)
      {
        mapper->SetStepScale(s.Step);
        mapper->SetBisections(s.Bisections);
        renWin->Render();
        vtkOpenGLRenderWindow::SafeDownCast(renWin)->MakeCurrent();
        vtkNew<vtkFloatArray> hits;
        if (!mapper->ReadHitBuffer(hits) || hits->GetNumberOfTuples() != size * size)
        {
          std::cerr << "no hit buffer\n";
          return EXIT_FAILURE;
        }
        if (mapper->GetRayCasterInUse() != caster)
        {
          std::cerr << "the mapper did not use the " << casterName << " ray caster\n";
          return EXIT_FAILURE;
        }
        vtkMatrix4x4* view = camera->GetViewTransformMatrix();
        std::vector<double> depthErrors, normalErrors;
        int mismatched = 0, covered = 0;
        for (int k = 0; k < size * size; ++k)
        {
          const float* h = hits->GetPointer(4 * k);
          const bool gpuHit = h[3] > 0.0f;
          const pointsurfaces::RayHit& r = reference[k];
          covered += (gpuHit || r.Hit) ? 1 : 0;
          if (gpuHit != r.Hit)
          {
            ++mismatched;
            continue;
          }
          if (!gpuHit)
          {
            continue;
          }
          double p[4] = { r.Point[0], r.Point[1], r.Point[2], 1.0 }, v[4];
          view->MultiplyPoint(p, v);
          depthErrors.push_back(std::abs(h[3] + v[2]) / minRadius);
          double nw[3], dot = 0.0, norm = 0.0;
          for (int c = 0; c < 3; ++c)
          {
            nw[c] = view->GetElement(0, c) * h[0] + view->GetElement(1, c) * h[1] +
              view->GetElement(2, c) * h[2];
            norm += nw[c] * nw[c];
          }
          for (int c = 0; c < 3; ++c)
          {
            dot += nw[c] * r.Normal[c];
          }
          dot /= std::sqrt(norm);
          normalErrors.push_back(
            std::acos(std::min(1.0, std::abs(dot))) * 180.0 / 3.14159265358979);
        }
        auto p99 = [](std::vector<double> v)
        {
          if (v.empty())
          {
            return 0.0;
          }
          const size_t k = v.size() * 99 / 100;
          std::nth_element(v.begin(), v.begin() + k, v.end());
          return v[k];
        };
        const double depth99 = p99(depthErrors), normal99 = p99(normalErrors);
        std::cout << casterName << ", " << names[kernel] << ", step " << s.Step << ", "
                  << s.Bisections << " bisections: " << depthErrors.size() << " hits, "
                  << mismatched << " hit/miss disagreements, depth error p99 " << depth99
                  << " of the smallest radius, normal error p99 " << normal99 << " deg, "
                  << mapper->GetRayCastTime() << " ms ray cast, " << mapper->GetGridBuildTime()
                  << " ms grid\n";
        if (depthErrors.size() < 2000 ||
          (s.Bounded && (mismatched > covered / 100 || !(depth99 < 1e-3) || !(normal99 < 0.5))))
        {
          std::cerr << "the metaballs are off the reference\n";
          ++failures;
        }
      }
    }
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
