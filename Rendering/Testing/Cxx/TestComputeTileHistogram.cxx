// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Dispatches a compute kernel inside a VTK render and checks it against a CPU
// computation: points are projected with the camera and counted per 16x16
// screen tile (the counting pass of a screen-tiled grid build).
//
// The dispatch runs at the end of the first renderer (layer 0). A second
// renderer (layer 1) then draws a sphere whose shader program is the very
// program VTK's cache used for the first sphere: if the compute helper left
// the cache believing that program still bound, the second sphere would be
// drawn with the compute program and vanish from the image.
#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkComputeShaderProgram.h"
#include "vtkMatrix4x4.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointTileCountCS.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkShaderStorageBuffer.h"
#include "vtkSphereSource.h"

#include "psOpenGL.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <vector>

namespace
{
constexpr int TileSize = 16;
constexpr unsigned int NumberOfPoints = 50000;

struct Histogram
{
  vtkOpenGLRenderWindow* Window = nullptr;
  vtkRenderer* Renderer = nullptr;
  std::vector<float> Points; // xyzw
  vtkNew<vtkComputeShaderProgram> Program;
  vtkNew<vtkShaderStorageBuffer> PointBuffer;
  vtkNew<vtkShaderStorageBuffer> CountBuffer;
  vtkNew<vtkShaderStorageBuffer> TileBuffer;
  std::vector<unsigned int> Counts;
  std::vector<int> Tiles;
  double WorldToClip[16];
  int Viewport[2] = { 0, 0 };
  int TileCount[2] = { 0, 0 };
  bool Ran = false;
  bool Failed = false;
};

void Dispatch(vtkObject*, unsigned long, void* clientData, void*)
{
  auto* h = static_cast<Histogram*>(clientData);
  if (h->Ran)
  {
    return;
  }
  h->Ran = true;
  h->Program->SetName("vtkPointTileCountCS");
  h->Program->SetSource(vtkPointTileCountCS);
  if (!h->Program->Compile(h->Window))
  {
    h->Failed = true;
    return;
  }
  h->Renderer->GetTiledSize(&h->Viewport[0], &h->Viewport[1]);
  h->TileCount[0] = (h->Viewport[0] + TileSize - 1) / TileSize;
  h->TileCount[1] = (h->Viewport[1] + TileSize - 1) / TileSize;
  const size_t tiles = static_cast<size_t>(h->TileCount[0]) * h->TileCount[1];

  vtkMatrix4x4* m = h->Renderer->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
    h->Renderer->GetTiledAspectRatio(), -1, 1);
  float rowMajor[16];
  for (int i = 0; i < 16; ++i)
  {
    h->WorldToClip[i] = m->GetElement(i / 4, i % 4);
    rowMajor[i] = static_cast<float>(h->WorldToClip[i]);
  }

  h->PointBuffer->Upload(h->Points.data(), h->Points.size() * sizeof(float));
  h->CountBuffer->Allocate(tiles * sizeof(unsigned int));
  h->CountBuffer->Fill(0);
  h->TileBuffer->Allocate(NumberOfPoints * sizeof(int));

  h->Program->Bind(h->Window);
  h->Program->SetUniformMatrix4x4("worldToClip", rowMajor);
  h->Program->SetUniformui("numberOfPoints", NumberOfPoints);
  h->Program->SetUniform2i("viewportSize", h->Viewport[0], h->Viewport[1]);
  h->Program->SetUniformi("tileSize", TileSize);
  h->Program->SetUniform2i("tileCount", h->TileCount[0], h->TileCount[1]);
  h->PointBuffer->BindBase(0);
  h->CountBuffer->BindBase(1);
  h->TileBuffer->BindBase(2);
  h->Failed = !h->Program->Dispatch(vtkComputeShaderProgram::GroupCount(NumberOfPoints, 128));
  h->Program->Unbind();

  h->Counts.resize(tiles);
  h->Tiles.resize(NumberOfPoints);
  h->Failed =
    h->Failed || !h->CountBuffer->Download(h->Counts.data(), tiles * sizeof(unsigned int));
  h->Failed = h->Failed || !h->TileBuffer->Download(h->Tiles.data(), NumberOfPoints * sizeof(int));
  if (glGetError() != GL_NO_ERROR)
  {
    std::cerr << "GL error after the dispatch\n";
    h->Failed = true;
  }
}

// Double-precision reference; `ambiguous` marks points so close to a tile or
// frustum boundary that float rounding on the GPU may legitimately differ.
int ReferenceTile(const Histogram& h, const float* p, bool& ambiguous)
{
  double clip[4];
  for (int r = 0; r < 4; ++r)
  {
    clip[r] = h.WorldToClip[4 * r] * p[0] + h.WorldToClip[4 * r + 1] * p[1] +
      h.WorldToClip[4 * r + 2] * p[2] + h.WorldToClip[4 * r + 3];
  }
  const double eps = 1e-4;
  ambiguous = std::abs(clip[3]) < eps;
  if (clip[3] <= 0.0)
  {
    return -1;
  }
  double ndc[3];
  for (int c = 0; c < 3; ++c)
  {
    ndc[c] = clip[c] / clip[3];
    ambiguous = ambiguous || std::abs(std::abs(ndc[c]) - 1.0) < eps;
  }
  if (ndc[0] < -1 || ndc[1] < -1 || ndc[2] < -1 || ndc[0] >= 1 || ndc[1] >= 1 || ndc[2] >= 1)
  {
    return -1;
  }
  int t[2];
  for (int c = 0; c < 2; ++c)
  {
    const double pixel = (ndc[c] * 0.5 + 0.5) * h.Viewport[c];
    const double inTile = std::fmod(pixel, TileSize);
    ambiguous = ambiguous || inTile < 0.01 || inTile > TileSize - 0.01;
    t[c] = std::min(static_cast<int>(pixel) / TileSize, h.TileCount[c] - 1);
  }
  return t[1] * h.TileCount[0] + t[0];
}
} // namespace

int TestComputeTileHistogram(int argc, char* argv[])
{
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(300, 300);
  renWin->SetMultiSamples(0);
  renWin->SetNumberOfLayers(2);

  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(24);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> left;
  left->SetMapper(mapper);
  left->SetPosition(-0.6, 0, 0);
  vtkNew<vtkActor> right;
  right->SetMapper(mapper);
  right->SetPosition(0.6, 0, 0);

  vtkNew<vtkRenderer> base;
  base->AddActor(left);
  base->SetBackground(0.2, 0.2, 0.2);
  vtkNew<vtkRenderer> overlay;
  overlay->SetLayer(1);
  overlay->AddActor(right);
  renWin->AddRenderer(base);
  renWin->AddRenderer(overlay);
  base->GetActiveCamera()->SetPosition(0, 0, 5);
  base->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  base->GetActiveCamera()->SetViewAngle(40);
  base->GetActiveCamera()->SetClippingRange(0.5, 20);
  overlay->SetActiveCamera(base->GetActiveCamera());

  Histogram h;
  h.Window = vtkOpenGLRenderWindow::SafeDownCast(renWin);
  h.Renderer = base;
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(2024);
  h.Points.resize(4 * NumberOfPoints);
  for (unsigned int i = 0; i < NumberOfPoints; ++i)
  {
    // A box that reaches behind the eye (z > 5) and past the frustum sides.
    for (int c = 0; c < 3; ++c)
    {
      random->Next();
      const double range = c == 2 ? 8.0 : 3.0;
      h.Points[4 * i + c] = static_cast<float>((random->GetValue() - 0.5) * 2.0 * range);
    }
    h.Points[4 * i + 3] = 1.0f;
  }
  vtkNew<vtkCallbackCommand> callback;
  callback->SetCallback(Dispatch);
  callback->SetClientData(&h);
  base->AddObserver(vtkCommand::EndEvent, callback);

  renWin->Render();
  if (!h.Ran || h.Failed)
  {
    std::cerr << "The compute pass did not run\n";
    return EXIT_FAILURE;
  }

  // Compare with the CPU reference.
  std::vector<unsigned int> gpuHistogram(h.Counts.size(), 0);
  std::vector<unsigned int> cpuHistogram(h.Counts.size(), 0);
  unsigned int ambiguousCount = 0, mismatches = 0, visible = 0;
  for (unsigned int i = 0; i < NumberOfPoints; ++i)
  {
    bool ambiguous = false;
    const int expected = ReferenceTile(h, &h.Points[4 * i], ambiguous);
    const int got = h.Tiles[i];
    if (got >= static_cast<int>(h.Counts.size()) || got < -1)
    {
      std::cerr << "Point " << i << " has an invalid tile " << got << "\n";
      return EXIT_FAILURE;
    }
    if (got >= 0)
    {
      ++gpuHistogram[got];
    }
    if (expected >= 0)
    {
      ++cpuHistogram[expected];
      ++visible;
    }
    if (ambiguous)
    {
      ++ambiguousCount;
    }
    else if (expected != got)
    {
      if (++mismatches < 10)
      {
        std::cerr << "Point " << i << ": GPU tile " << got << ", CPU tile " << expected << "\n";
      }
    }
  }
  // The atomic counts must match the per-point tiles exactly...
  if (gpuHistogram != h.Counts)
  {
    std::cerr << "Atomic tile counts disagree with the per-point tiles\n";
    return EXIT_FAILURE;
  }
  // ...and the CPU histogram up to the few points on a boundary.
  unsigned long difference = 0;
  for (size_t t = 0; t < h.Counts.size(); ++t)
  {
    difference += static_cast<unsigned long>(
      std::abs(static_cast<long>(h.Counts[t]) - static_cast<long>(cpuHistogram[t])));
  }
  std::cout << visible << " of " << NumberOfPoints << " points visible in " << h.Counts.size()
            << " tiles; " << ambiguousCount << " on a boundary; histogram L1 difference "
            << difference << "\n";
  if (mismatches > 0 || difference > 2 * ambiguousCount || visible < NumberOfPoints / 20)
  {
    std::cerr << mismatches << " points in the wrong tile\n";
    return EXIT_FAILURE;
  }

  const int retVal = vtkRegressionTestImage(renWin);
  h.Window->MakeCurrent();
  h.Program->ReleaseGraphicsResources(renWin);
  h.PointBuffer->ReleaseGraphicsResources(renWin);
  h.CountBuffer->ReleaseGraphicsResources(renWin);
  h.TileBuffer->ReleaseGraphicsResources(renWin);
  return retVal == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
