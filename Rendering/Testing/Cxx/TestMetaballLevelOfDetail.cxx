// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkMetaballMapper's LevelOfDetailPixels on the GPU ray caster against the
// exact frame. 40 000 balls fill a sphere of radius 1 (radius 1.5 mean
// spacings: one body), drawn at 160x160 from two distances:
// - with a level of 0.5 pixels every ball covers more than that: nothing is
//   merged, and every pixel's hit and view distance are those of the exact
//   frame to the bit;
// - with levels of 4 and 8 pixels balls are merged (fewer kernel terms),
//   and against the exact frame a pixel's hit or miss differs only within a
//   cell (plus one pixel) of the exact silhouette, on at most 6 % of the
//   exact hits' pixels, and where both hit, the view distance differs by at
//   most four cells' depth at that distance (measured: at most 3.2).
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkMetaballMapper.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include "psTestHitMapper.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <vector>

namespace
{

struct Frame
{
  std::vector<float> Distance; // per pixel, 0 on a miss
  vtkIdType Terms = 0, Merged = 0, Represented = 0;
};

Frame Draw(vtkRenderWindow* window, HitMapper* mapper, double pixels, int size)
{
  mapper->SetLevelOfDetailPixels(pixels);
  window->Render();
  Frame frame;
  vtkNew<vtkFloatArray> hits;
  mapper->ReadHitBuffer(hits);
  frame.Distance.resize(static_cast<size_t>(size) * size);
  for (vtkIdType i = 0; i < hits->GetNumberOfTuples() && i < size * size; ++i)
  {
    frame.Distance[i] = hits->GetComponent(i, 3);
  }
  frame.Terms = mapper->GetNumberOfKernelTerms();
  frame.Merged = mapper->GetNumberOfMergedBalls();
  frame.Represented = mapper->GetNumberOfBallsMerged();
  return frame;
}
} // namespace

int TestMetaballLevelOfDetail(int, char*[])
{
  const int n = 40000, size = 160;
  std::mt19937 gen(23);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  vtkNew<vtkPoints> points;
  while (points->GetNumberOfPoints() < n)
  {
    const double p[3] = { uni(gen), uni(gen), uni(gen) };
    if (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] <= 1.0)
    {
      points->InsertNextPoint(p);
    }
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  vtkNew<HitMapper> mapper;
  mapper->SetInputDataObject(poly);
  mapper->SetRayCaster(vtkMetaballMapper::GPU);
  mapper->CollectStatisticsOn(); // this frame's terms and merged balls
  const double spacing = 0.55 * std::cbrt(4.0 / 3.0 * 3.14159265 / n); // of a uniform cloud
  mapper->GetField()->SetRadius(2.5 * spacing);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(size, size);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetViewAngle(30.0);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  const double perUnitAtOne = 0.5 * size / std::tan(15.0 * 3.14159265 / 180.0);

  int failures = 0;
  for (const double distance : { 4.0, 9.0 })
  {
    camera->SetPosition(0.3, 0.4, distance);
    camera->SetClippingRange(distance - 1.5, distance + 1.5);
    const double ballPixels = 2.5 * spacing * perUnitAtOne / distance;
    const Frame exact = Draw(window, mapper, 0.0, size);
    const Frame none = Draw(window, mapper, 0.5, size);
    vtkIdType hits = 0, same = 0;
    for (size_t i = 0; i < exact.Distance.size(); ++i)
    {
      hits += exact.Distance[i] > 0.0f ? 1 : 0;
      same += exact.Distance[i] == none.Distance[i] ? 1 : 0;
    }
    std::cout << "distance " << distance << ": balls cover " << ballPixels << " pixels; exact "
              << hits << " hits, " << exact.Terms << " kernel terms; level 0.5: " << none.Merged
              << " merged, " << exact.Distance.size() - same << " pixels differ\n";
    if (hits < 1000 || none.Merged != 0 || same != static_cast<vtkIdType>(exact.Distance.size()))
    {
      std::cerr << "a level below every ball's size changed the frame\n";
      ++failures;
    }
    // The exact silhouette: hit pixels next to a miss.
    std::vector<char> edge(exact.Distance.size(), 0);
    for (int y = 0; y < size; ++y)
    {
      for (int x = 0; x < size; ++x)
      {
        const bool hit = exact.Distance[y * size + x] > 0.0f;
        for (int k = 0; k < 4 && hit; ++k)
        {
          const int u = x + (k == 0) - (k == 1), v = y + (k == 2) - (k == 3);
          if (u < 0 || v < 0 || u >= size || v >= size || !(exact.Distance[v * size + u] > 0.0f))
          {
            edge[y * size + x] = 1;
          }
        }
      }
    }
    for (const double pixels : { 4.0, 8.0 })
    {
      const Frame lod = Draw(window, mapper, pixels, size);
      const int reach = static_cast<int>(std::ceil(pixels)) + 1;
      vtkIdType differ = 0, stray = 0, common = 0, deep = 0;
      double worst = 0.0;
      for (int y = 0; y < size; ++y)
      {
        for (int x = 0; x < size; ++x)
        {
          const float a = exact.Distance[y * size + x], b = lod.Distance[y * size + x];
          if ((a > 0.0f) != (b > 0.0f))
          {
            ++differ;
            bool near = false;
            for (int v = std::max(0, y - reach); v <= std::min(size - 1, y + reach) && !near; ++v)
            {
              for (int u = std::max(0, x - reach); u <= std::min(size - 1, x + reach); ++u)
              {
                near = near || edge[v * size + u];
              }
            }
            stray += near ? 0 : 1;
          }
          else if (a > 0.0f)
          {
            ++common;
            const double cellDepth = pixels * a / perUnitAtOne;
            const double error = std::abs(a - b) / cellDepth;
            worst = std::max(worst, error);
            deep += error > 4.0 ? 1 : 0;
          }
        }
      }
      std::cout << "  level " << pixels << ": " << lod.Merged << " balls merged from "
                << lod.Represented << ", " << lod.Terms << " kernel terms (exact " << exact.Terms
                << "); " << differ << " pixels hit or miss otherwise (" << stray
                << " beyond a cell of the silhouette), " << common
                << " common hits, worst depth error " << worst << " cell depths\n";
      const bool merges = ballPixels < pixels;
      if ((merges && (lod.Merged == 0 || lod.Terms >= exact.Terms)) || stray > 0 ||
        differ > 0.06 * hits || deep > 0)
      {
        std::cerr << "the level of " << pixels << " pixels at distance " << distance
                  << " is beyond its bound\n";
        ++failures;
      }
    }
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
