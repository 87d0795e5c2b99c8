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
//
// The pair buffers' capacity: a build reads nothing back but the first;
// a view that needs more pairs than the capacity is counted as an overflow
// once its count arrives (statistics off) or built again at once
// (statistics on), and the builds after it are whole; pairs beyond the
// storage buffer limit are left out with a warning, not a crash.
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

void Matrices(vtkCamera* camera, double worldToView[16], double viewToClip[16])
{
  vtkMatrix4x4* m = camera->GetViewTransformMatrix();
  vtkMatrix4x4* p = camera->GetProjectionTransformMatrix(1.0, -1, 1);
  for (int k = 0; k < 16; ++k)
  {
    worldToView[k] = m->GetElement(k / 4, k % 4);
    viewToClip[k] = p->GetElement(k / 4, k % 4);
  }
}

// The grid of `builder` (a fresh one when null) against the reference.
int Compare(vtkOpenGLRenderWindow* win,
  vtkCamera* camera,
  vtkShaderStorageBuffer* buffer,
  const std::vector<double>& centres,
  const std::vector<double>& radii,
  int size,
  int tile,
  int slabs,
  vtkMetaballGridBuilder* given = nullptr)
{
  double worldToView[16], viewToClip[16];
  Matrices(camera, worldToView, viewToClip);
  const long long n = static_cast<long long>(radii.size());
  vtkNew<vtkMetaballGridBuilder> fresh;
  vtkMetaballGridBuilder* builder = given ? given : fresh.Get();
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
  if (!given)
  {
    builder->ReleaseGraphicsResources(win);
  }
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
// The capacity of the pair buffers, from a far view (few pairs) to a near
// one (many).
int Capacity(vtkOpenGLRenderWindow* win,
  vtkCamera* camera,
  vtkShaderStorageBuffer* buffer,
  const std::vector<double>& centres,
  const std::vector<double>& radii)
{
  int failures = 0;
  const long long n = static_cast<long long>(radii.size());
  double far[16], farClip[16], near[16], clip[16];
  camera->SetPosition(2.5, 4.0, 30.0);
  camera->SetClippingRange(5.0, 60.0);
  Matrices(camera, far, farClip);
  camera->SetPosition(0.5, 0.8, 6.0);
  camera->SetClippingRange(0.5, 20.0);
  Matrices(camera, near, clip);
  const auto build = [&](vtkMetaballGridBuilder* builder, const double* view)
  { return builder->Build(win, buffer, n, view, view == far ? farClip : clip, false, 256, 256); };

  // Statistics off: one read-back in all, the overflow found later.
  vtkNew<vtkMetaballGridBuilder> quiet;
  bool ok = true;
  for (int frame = 0; frame < 6; ++frame)
  {
    ok = build(quiet, far) && ok;
  }
  const vtkIdType farCapacity = quiet->GetPairCapacity();
  const vtkIdType readBacks = quiet->GetNumberOfReadBacks();
  for (int frame = 0; frame < 6; ++frame)
  {
    ok = build(quiet, near) && ok;
  }
  std::cout << "capacity " << farCapacity << " pairs from the far view, "
            << quiet->GetPairCapacity() << " after the near one (" << quiet->GetNumberOfPairs()
            << " pairs); " << quiet->GetNumberOfOverflows() << " overflow(s), "
            << quiet->GetNumberOfReadBacks() << " read-back(s) in 12 builds\n";
  if (!ok || readBacks != 1 || quiet->GetNumberOfReadBacks() != 1 ||
    quiet->GetNumberOfOverflows() != 1 || quiet->GetPairCapacity() < quiet->GetNumberOfPairs() ||
    farCapacity >= quiet->GetNumberOfPairs())
  {
    std::cerr << "the capacity did not follow the pair counts without read-backs\n";
    ++failures;
  }
  // The builds after the overflow are whole.
  failures += Compare(win, camera, buffer, centres, radii, 256, 16, 16, quiet);

  // Statistics on: the overflowing build is made again at once, whole.
  vtkNew<vtkMetaballGridBuilder> counted;
  counted->CollectStatisticsOn();
  ok = build(counted, far);
  failures += Compare(win, camera, buffer, centres, radii, 256, 16, 16, counted);
  if (!ok || counted->GetNumberOfOverflows() != 1)
  {
    std::cerr << "the near view after the far one did not overflow once with statistics ("
              << counted->GetNumberOfOverflows() << ")\n";
    ++failures;
  }

  // Beyond the storage buffer limit: the grid holds what fits, with a warning.
  vtkShaderStorageBuffer::SetMaximumSizeLimit(64 * 1024 * 1024);
  vtkNew<vtkMetaballGridBuilder> small;
  small->CollectStatisticsOn();
  small->SetTileSize(1);
  small->SetSlabs(64);
  std::cout << "expect a warning: pairs beyond a 64 MiB storage buffer\n";
  ok = small->Build(win, buffer, n, near, clip, false, 256, 256);
  vtkShaderStorageBuffer::SetMaximumSizeLimit(0);
  std::cout << small->GetNumberOfPairs() << " pairs needed, capacity " << small->GetPairCapacity()
            << "\n";
  if (!ok || small->GetNumberOfPairs() <= small->GetPairCapacity())
  {
    std::cerr << "the grid beyond the buffer limit was not partial\n";
    ++failures;
  }
  for (vtkMetaballGridBuilder* b : { quiet.Get(), counted.Get(), small.Get() })
  {
    b->ReleaseGraphicsResources(win);
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
  failures += Capacity(win, camera, buffer, centres, radii);
  buffer->ReleaseGraphicsResources(win);
  few->ReleaseGraphicsResources(win);
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
