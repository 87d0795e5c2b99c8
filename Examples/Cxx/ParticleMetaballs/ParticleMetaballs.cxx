// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Particles to metaballs, headless, to a PNG, and the surface to an OpenVDB
// level set for Houdini or Blender:
//
//   ParticleMetaballs input.{vdb,pdb,vtp} output.png [size] [surface.vdb]
//
// .vdb: OpenVDB point grids (vtkOpenVDBPointsReader; "pscale" is the
// radius); .pdb: atoms (vtkPDBReader; van der Waals radii, element colours);
// .vtp: any points with an optional "Radius" array. Without a radius array,
// the radius follows the mean spacing. Prints the ball count and the
// mapper's per-frame grid build and ray cast times.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkMetaballLevelSetWriter.h"
#include "vtkMetaballMapper.h"
#include "vtkNew.h"
#include "vtkOpenVDBPointsReader.h"
#include "vtkPDBReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

int main(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: ParticleMetaballs input.{vdb,pdb,vtp} output.png [size] [surface.vdb]\n";
    return EXIT_FAILURE;
  }
  const std::string input = argv[1];
  const int size = argc > 3 ? std::atoi(argv[3]) : 600;
  std::string ext = input.substr(input.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);

  vtkSmartPointer<vtkPolyData> balls;
  std::string radiusArray = "Radius"; // the point array of radii, when the input has it
  vtkNew<vtkMetaballMapper> mapper;
  vtkNew<vtkMetaballLevelSetWriter> levelSet;
  // One field for both: the level set holds the surface that the window shows.
  levelSet->SetField(mapper->GetField());
  if (ext == "vdb")
  {
    vtkNew<vtkOpenVDBPointsReader> reader;
    reader->SetFileName(input.c_str());
    reader->Update();
    balls = reader->GetOutput();
    radiusArray = "pscale";
  }
  else if (ext == "pdb")
  {
    vtkNew<vtkPDBReader> reader;
    reader->SetFileName(input.c_str());
    reader->Update();
    balls = reader->GetOutput();
    // Wyvill's kernel at T = 0.5 shows a lone atom at half its support: a
    // support of twice the van der Waals radius shows the atom at its radius.
    radiusArray = "radius";
    mapper->GetField()->SetRadiusScale(2.0);
    mapper->SetColorModeToDirectScalars();
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray("rgb_colors");
  }
  else
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(input.c_str());
    reader->Update();
    balls = reader->GetOutput();
  }
  if (!balls || balls->GetNumberOfPoints() == 0)
  {
    std::cerr << "ParticleMetaballs: no points in " << input << "\n";
    return EXIT_FAILURE;
  }
  if (balls->GetPointData()->GetArray(radiusArray.c_str()))
  {
    mapper->GetField()->SetRadiusArrayName(radiusArray.c_str());
  }
  else
  {
    double b[6];
    balls->GetBounds(b);
    const double extent = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
    const double radius =
      1.6 * extent * std::cbrt(8.0 / static_cast<double>(balls->GetNumberOfPoints()));
    mapper->GetField()->SetRadius(radius);
  }
  mapper->SetInputData(balls);

  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetSpecular(0.3);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkNew<vtkRenderWindow> window; // headless EGL when there is no display
  window->SetSize(size, size);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.3);
  window->Render();
  window->Render();

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  vtkNew<vtkPNGWriter> png;
  png->SetInputConnection(grab->GetOutputPort());
  png->SetFileName(argv[2]);
  png->Write();
  std::cout << "balls:   " << balls->GetNumberOfPoints() << "\n"
            << "window:  " << window->GetClassName() << "\n"
            << "frame:   grid " << mapper->GetGridBuildTime() << " ms, rays "
            << mapper->GetRayCastTime() << " ms at " << size << "x" << size << "\n"
            << "image:   " << argv[2] << "\n";
  if (argc > 4)
  {
    levelSet->SetInputData(balls);
    levelSet->SetFileName(argv[4]);
    if (!levelSet->Write())
    {
      return EXIT_FAILURE;
    }
    std::cout << "surface: " << argv[4] << " (OpenVDB level set, voxel "
              << levelSet->GetUsedVoxelSize() << ", " << levelSet->GetNumberOfActiveVoxels()
              << " active voxels)\n";
  }
  return EXIT_SUCCESS;
}
