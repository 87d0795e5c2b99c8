// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Run by ctest with DISPLAY unset and an EGL vendor path that does not exist:
// neither X nor EGL is usable. Rendering must report a clear error, return,
// and hand back zeroed pixels, never abort the process.
#include "vtkActor.h"
#include "vtkCommand.h"
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <cstdlib>
#include <iostream>
#include <string>

int TestNoUsableDisplay(int, char*[])
{
  vtkNew<vtkRenderWindow> renWin;
  if (!renWin->IsA("vtkEGLHeadlessRenderWindow"))
  {
    std::cerr << "Without DISPLAY the factory should give the EGL window, got "
              << renWin->GetClassName() << "\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkTest::ErrorObserver> errors;
  renWin->AddObserver(vtkCommand::ErrorEvent, errors);

  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renWin->AddRenderer(renderer);
  renWin->SetSize(64, 64);
  renWin->Render();
  renWin->Render(); // a second frame must be as harmless as the first

  if (!errors->GetError())
  {
    std::cerr << "Rendering without X or EGL reported no error\n";
    return EXIT_FAILURE;
  }
  const std::string message = errors->GetErrorMessage();
  std::cout << "Reported: " << message << "\n";
  if (message.find("Neither EGL nor an X display is usable") == std::string::npos)
  {
    std::cerr << "The error does not say what is missing\n";
    return EXIT_FAILURE;
  }
  const std::string once = "Cannot render";
  if (message.find(once) != message.rfind(once))
  {
    std::cerr << "The error was repeated at the second frame\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkUnsignedCharArray> pixels;
  renWin->GetPixelData(0, 0, 63, 63, 0, pixels);
  for (vtkIdType i = 0; i < pixels->GetNumberOfValues(); ++i)
  {
    if (pixels->GetValue(i) != 0)
    {
      std::cerr << "Pixels of a failed render are not zero\n";
      return EXIT_FAILURE;
    }
  }
  std::cout << "TestNoUsableDisplay: passed\n";
  return EXIT_SUCCESS;
}
