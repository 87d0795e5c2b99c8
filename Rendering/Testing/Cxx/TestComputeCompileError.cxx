// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// A compute shader with an error on a known line must fail to compile with a
// message that names the program and shows that line, numbered; fixing the
// source must then compile in the same object.
#include "vtkCommand.h"
#include "vtkComputeShaderProgram.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTestErrorObserver.h"

#include <cstdlib>
#include <iostream>
#include <string>

int TestComputeCompileError(int, char*[])
{
  vtkNew<vtkRenderWindow> renWin;
  vtkNew<vtkRenderer> renderer;
  renWin->AddRenderer(renderer);
  renWin->SetSize(32, 32);
  renWin->Render();
  auto* glWin = vtkOpenGLRenderWindow::SafeDownCast(renWin);

  const std::string broken = "//VTK::System::Dec\n"            // 1
                             "layout(local_size_x = 64) in;\n" // 2
                             "void main()\n"                   // 3
                             "{\n"                             // 4
                             "  float x = undefinedThing;\n"   // 5
                             "}\n";
  vtkNew<vtkComputeShaderProgram> program;
  program->SetName("BrokenKernel");
  program->SetSource(broken);
  vtkNew<vtkTest::ErrorObserver> errors;
  program->AddObserver(vtkCommand::ErrorEvent, errors);
  if (program->Compile(glWin))
  {
    std::cerr << "A broken shader compiled\n";
    return EXIT_FAILURE;
  }
  const std::string message = errors->GetErrorMessage();
  if (message.find("BrokenKernel") == std::string::npos ||
    message.find(">5:   float x = undefinedThing;") == std::string::npos)
  {
    std::cerr << "The message does not show the failing line with its number:\n"
              << message.substr(message.find("Compute program")) << "\n";
    return EXIT_FAILURE;
  }

  program->SetSource("//VTK::System::Dec\nlayout(local_size_x = 64) in;\nvoid main() {}\n");
  if (!program->Compile(glWin) || !program->IsCompiled())
  {
    std::cerr << "The corrected shader did not compile: " << program->GetLastLog() << "\n";
    return EXIT_FAILURE;
  }
  program->Bind(glWin);
  program->Dispatch(1);
  program->Unbind();
  program->ReleaseGraphicsResources(renWin);
  return EXIT_SUCCESS;
}
