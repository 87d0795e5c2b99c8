// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The GPU perspective grid (vtkMetaballGridBuilder) against the CPU reference
// (pointsurfaces::BuildPerspectiveGrid). 20 000 balls with radii from 0.02
// to 0.3, plus balls with NaN centres, NaN and zero radii, and balls behind
// the eye, are built into grids of 16-pixel tiles and 16 automatic slabs, and
// of 1-pixel tiles and 32 slabs (two million voxels: a three-level scan).
// The GPU computes in float, the reference in double, so each GPU voxel list
// must lie between the reference lists of the balls shrunk and grown by
// 1e-4 of their radius. The automatic slab planes, the pair count and the
// culled and invalid counts are compared as well.
#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkMetaballGridBuilder.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkShaderStorageBuffer.h"

#include "psMetaball.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

using namespace pointsurfaces;

namespace
{
struct Lists
{
  std::vector<unsigned> Offsets, Balls;
  bool Has(long long voxel, unsigned ball) const
  {
    return std::binary_search(this->Balls.begin() + this->Offsets[voxel],
      this->Balls.begin() + this->Offsets[voxel + 1],
      ball);
  }
};

int Compare(vtkOpenGLRenderWindow* win,
  vtkCamera* camera,
  vtkShaderStorageBuffer* buffer,
  const std::vector<double>& centres,
  const std::vector<double>& radii,
  int size,
  int tile,
  int slabs)
{
  double worldToView[16], viewToClip[16];
  vtkMatrix4x4* m = camera->GetViewTransformMatrix();
  vtkMatrix4x4* p = camera->GetProjectionTransformMatrix(1.0, -1, 1);
  for (int k = 0; k < 16; ++k)
  {
    worldToView[k] = m->GetElement(k / 4, k % 4);
    viewToClip[k] = p->GetElement(k / 4, k % 4);
  }
  const long long n = static_cast<long long>(radii.size());
  vtkNew<vtkMetaballGridBuilder> builder;
  builder->CollectStatisticsOn(); // the culled and per-voxel counts are checked
  builder->SetTileSize(tile);
  builder->SetSlabs(slabs);
  if (!builder->Build(win, buffer, n, worldToView, viewToClip, false, size, size))
  {
    std::cerr << "the GPU build failed\n";
    return 1;
  }
  const long long voxels =
    static_cast<long long>(builder->GetTilesX()) * builder->GetTilesY() * slabs;
  Lists gpu;
  gpu.Offsets.resize(voxels + 1);
  gpu.Balls.resize(builder->GetNumberOfPairs());
  builder->GetVoxelOffsets()->Download(gpu.Offsets.data(), gpu.Offsets.size() * sizeof(unsigned));
  if (!gpu.Balls.empty())
  {
    builder->GetVoxelBalls()->Download(gpu.Balls.data(), gpu.Balls.size() * sizeof(unsigned));
  }
  for (long long v = 0; v < voxels; ++v)
  {
    std::sort(gpu.Balls.begin() + gpu.Offsets[v], gpu.Balls.begin() + gpu.Offsets[v + 1]);
  }

  // The reference, with the GPU's slab planes, for the balls shrunk and grown.
  GridView view;
  std::copy(worldToView, worldToView + 16, view.WorldToView);
  std::copy(viewToClip, viewToClip + 16, view.ViewToClip);
  view.Width = view.Height = size;
  view.TileSize = tile;
  view.Slabs = slabs;
  MetaballSet set;
  set.Centers = centres.data();
  set.Radii = radii.data();
  set.Count = n;
  const std::vector<double> autoPlanes = SlabPlanes(set, view);
  view.SlabNear = builder->GetSlabPlane(0);
  view.SlabFar = builder->GetSlabPlane(slabs);
  int failures = 0;
  const double planeError = std::max(
    std::abs(view.SlabNear - autoPlanes.front()), std::abs(view.SlabFar - autoPlanes.back()));
  if (!(planeError < 1e-5 * autoPlanes.back()))
  {
    std::cerr << "automatic slab planes differ by " << planeError << "\n";
    ++failures;
  }
  Lists bounds[2];
  PerspectiveGrid grids[2];
  for (int b = 0; b < 2; ++b)
  {
    std::vector<double> scaled(radii);
    for (double& r : scaled)
    {
      r *= b == 0 ? 1.0 - 1e-4 : 1.0 + 1e-4;
    }
    set.Radii = scaled.data();
    grids[b] = BuildPerspectiveGrid(set, view);
    bounds[b].Offsets = grids[b].Offsets;
    bounds[b].Balls = grids[b].Balls;
  }
  long long missing = 0, extra = 0;
  for (long long v = 0; v < voxels; ++v)
  {
    for (unsigned k = bounds[0].Offsets[v]; k < bounds[0].Offsets[v + 1]; ++k)
    {
      missing += gpu.Has(v, bounds[0].Balls[k]) ? 0 : 1;
    }
    for (unsigned k = gpu.Offsets[v]; k < gpu.Offsets[v + 1]; ++k)
    {
      extra += bounds[1].Has(v, gpu.Balls[k]) ? 0 : 1;
    }
  }
  std::cout << tile << "-pixel tiles, " << slabs << " slabs: " << builder->GetNumberOfPairs()
            << " pairs (reference " << grids[0].Pairs << " to " << grids[1].Pairs << "), at most "
            << builder->GetMaximumBallsPerVoxel() << " per voxel, "
            << builder->GetNumberOfCulledBalls() << " culled, "
            << builder->GetNumberOfInvalidBalls() << " invalid, " << builder->GetBuildTime()
            << " ms to build; " << missing << " missing, " << extra << " extra\n";
  builder->ReleaseGraphicsResources(win);
  if (missing || extra || builder->GetNumberOfInvalidBalls() != grids[0].Invalid ||
    builder->GetNumberOfCulledBalls() < grids[1].Culled ||
    builder->GetNumberOfCulledBalls() > grids[0].Culled ||
    builder->GetNumberOfPairs() < grids[0].Pairs || builder->GetNumberOfPairs() > grids[1].Pairs)
  {
    std::cerr << "the GPU grid differs from the reference\n";
    ++failures;
  }
  return failures;
}
} // namespace

int TestMetaballGridBuild(int, char*[])
{
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(64, 64);
  vtkNew<vtkRenderer> renderer;
  renWin->AddRenderer(renderer);
  renWin->Render();
  auto* win = vtkOpenGLRenderWindow::SafeDownCast(renWin);
  win->MakeCurrent();

  std::mt19937 gen(5);
  std::uniform_real_distribution<double> uni(-1.0, 1.0), rad(0.02, 0.3);
  std::vector<double> centres, radii;
  for (int i = 0; i < 20000; ++i)
  {
    centres.insert(centres.end(), { 2 * uni(gen), 2 * uni(gen), 2 * uni(gen) });
    radii.push_back(rad(gen));
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  centres.insert(centres.end(), { nan, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 9, 0, 0, 30 });
  radii.insert(radii.end(), { 0.1, nan, 0.0, 0.5, 1.0 }); // the last two: behind the eye
  std::vector<float> packed;
  for (size_t i = 0; i < radii.size(); ++i)
  {
    packed.insert(packed.end(),
      { static_cast<float>(centres[3 * i]),
        static_cast<float>(centres[3 * i + 1]),
        static_cast<float>(centres[3 * i + 2]),
        static_cast<float>(radii[i]) });
  }
  vtkNew<vtkShaderStorageBuffer> buffer;
  buffer->Upload(packed.data(), packed.size() * sizeof(float));

  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.5, 0.8, 6.0);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(40);
  camera->SetClippingRange(0.5, 20.0);

  int failures = Compare(win, camera, buffer, centres, radii, 256, 16, 16);
  // Keep the second case's pairs modest: the first 2 000 balls only.
  std::vector<double> fewCentres(centres.begin(), centres.begin() + 3 * 2000);
  std::vector<double> fewRadii(radii.begin(), radii.begin() + 2000);
  for (double& r : fewRadii)
  {
    r *= 0.2;
  }
  std::vector<float> fewPacked;
  for (size_t i = 0; i < fewRadii.size(); ++i)
  {
    fewPacked.insert(fewPacked.end(),
      { static_cast<float>(fewCentres[3 * i]),
        static_cast<float>(fewCentres[3 * i + 1]),
        static_cast<float>(fewCentres[3 * i + 2]),
        static_cast<float>(fewRadii[i]) });
  }
  vtkNew<vtkShaderStorageBuffer> few;
  few->Upload(fewPacked.data(), fewPacked.size() * sizeof(float));
  failures += Compare(win, camera, few, fewCentres, fewRadii, 256, 1, 32);
  buffer->ReleaseGraphicsResources(win);
  few->ReleaseGraphicsResources(win);
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
