// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Run by ctest with DISPLAY unset and an EGL vendor path that does not exist:
// neither X nor EGL is usable. Rendering must report a clear error, return,
// and hand back zeroed pixels, never abort the process.
#include "vtkActor.h"
#include "vtkCommand.h"
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPointSurfacesRenderWindowFactory.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkStringOutputWindow.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <cstdlib>
#include <iostream>
#include <string>

int TestNoUsableDisplay(int, char*[])
{
  vtkNew<vtkRenderWindow> renWin;
  // vtkEGLHeadlessRenderWindow up to VTK 9.3; VTK's own vtkEGLRenderWindow,
  // which VTK 9.4 and later fall back to by themselves, after that.
  const std::string eglClass = vtkPointSurfacesRenderWindowFactory::GetEGLWindowClassName();
  const bool ours = eglClass == "vtkEGLHeadlessRenderWindow";
  // Never VTK 9.4+'s own last resort, an OSMesa window that crashes without
  // libOSMesa.
  std::cout << "Window: " << renWin->GetClassName() << "\n";
  if (!renWin->IsA(eglClass.c_str()))
  {
    std::cerr << "Without DISPLAY the factory should give the EGL window, got "
              << renWin->GetClassName() << "\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkTest::ErrorObserver> errors;
  renWin->AddObserver(vtkCommand::ErrorEvent, errors);
  renWin->AddObserver(vtkCommand::WarningEvent, errors);
  // VTK's own windows warn through the output window, often from the probe
  // windows of their fallback chain rather than this one: keep that text too.
  vtkSmartPointer<vtkOutputWindow> console = vtkOutputWindow::GetInstance();
  vtkNew<vtkStringOutputWindow> text;
  vtkOutputWindow::SetInstance(text);

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

  vtkOutputWindow::SetInstance(console);
  const std::string message = std::string(errors->GetError() ? errors->GetErrorMessage() : "") +
    (errors->GetWarning() ? errors->GetWarningMessage() : "") + text->GetOutput();
  if (message.empty())
  {
    std::cerr << "Rendering without X or EGL reported nothing\n";
    return EXIT_FAILURE;
  }
  std::cout << "Reported: " << message << "\n";
  // VTK's own window words it its way ("Failed to initialize OpenGL
  // functions"); ours says what is missing, once.
  const std::string expected =
    ours ? "Neither EGL nor an X display is usable" : "Failed to initialize OpenGL";
  if (message.find(expected) == std::string::npos)
  {
    std::cerr << "The report does not say what is missing\n";
    return EXIT_FAILURE;
  }
  const std::string once = "Cannot render";
  if (ours && message.find(once) != message.rfind(once))
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
