// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Renders a point scan (.ply, .vtp or .pcd) headless to a PNG, through the
// window that vtkRenderWindow::New() gives: PointSurfaces' EGL window when
// there is no X display. Prints the point count and the frame time.
//
// Usage: RenderScan input.{ply,vtp,pcd} output.png [size]
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkPLYScanReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointGaussianMapper.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTimerLog.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLPolyDataReader.h"
#if POINTSURFACES_HAVE_PCD
#include "vtkPCDReader.h" // PointSurfaces::IOPCL, when PCL was found
#endif

#include "vtkPointData.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
bool EndsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() &&
    s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::fprintf(stderr, "Usage: %s input.{ply,vtp,pcd} output.png [size]\n", argv[0]);
    return 2;
  }
  const std::string input = argv[1];
  const int size = argc > 3 ? std::atoi(argv[3]) : 512;

  vtkSmartPointer<vtkAlgorithm> reader;
  if (EndsWith(input, ".ply"))
  {
    // PointSurfaces' PLY reader: any elements, and one clear error for a damaged file.
    auto ply = vtkSmartPointer<vtkPLYScanReader>::New();
    ply->SetFileName(input.c_str());
    reader = ply;
  }
  else if (EndsWith(input, ".pcd"))
  {
#if POINTSURFACES_HAVE_PCD
    auto pcd = vtkSmartPointer<vtkPCDReader>::New();
    pcd->SetFileName(input.c_str());
    reader = pcd;
#else
    std::fprintf(
      stderr, "RenderScan: this PointSurfaces has no PCD reader (PointSurfaces::IOPCL)\n");
    return 1;
#endif
  }
  else
  {
    auto vtp = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    vtp->SetFileName(input.c_str());
    reader = vtp;
  }
  reader->Update();
  vtkPolyData* points = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!points || points->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "RenderScan: no points in %s\n", input.c_str());
    return 1;
  }

  // Disc size from the average spacing: the bounding-box diagonal over sqrt(N).
  const double spacing =
    points->GetLength() / std::sqrt(static_cast<double>(points->GetNumberOfPoints()));
  vtkNew<vtkPointGaussianMapper> mapper;
  mapper->SetInputData(points);
  mapper->SetScaleFactor(1.4 * spacing);
  mapper->EmissiveOff();
  mapper->SetScalarVisibility(points->GetPointData()->GetScalars() != nullptr);
  mapper->SetSplatShaderCode("//VTK::Color::Impl\n"
                             "float dist = dot(offsetVCVSOutput.xy, offsetVCVSOutput.xy);\n"
                             "if (dist > 1.0) { discard; }\n"
                             "float shade = sqrt(1.0 - dist);\n"
                             "ambientColor *= shade;\n"
                             "diffuseColor *= shade;\n");
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.85, 0.75, 0.6);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(size, size);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.3);

  window->Render(); // first frame: context, shaders and buffers
  vtkNew<vtkTimerLog> timer;
  const int frames = 10;
  timer->StartTimer();
  for (int i = 0; i < frames; ++i)
  {
    renderer->GetActiveCamera()->Azimuth(0.5);
    window->Render();
  }
  timer->StopTimer();

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(argv[2]);
  writer->Write();
  std::printf("RenderScan: %lld points, %s, %.2f ms per frame at %dx%d, wrote %s\n",
    static_cast<long long>(points->GetNumberOfPoints()),
    window->GetClassName(),
    1000.0 * timer->GetElapsedTime() / frames,
    size,
    size,
    argv[2]);
  return 0;
}
