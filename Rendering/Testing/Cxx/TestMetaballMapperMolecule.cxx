// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Chain A of hemoglobin (1 079 atoms, Testing/Data/hemoglobin_chainA.pdb)
// read by vtkPDBReader, as a blobby molecular surface: each atom's support
// radius is twice its van der Waals radius (RadiusScale 2, so that a lone
// atom shows at its van der Waals radius), coloured by element through the
// reader's rgb_colors array as direct scalars.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkMetaballMapper.h"
#include "vtkNew.h"
#include "vtkPDBReader.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTestUtilities.h"

#include <cstdlib>
#include <iostream>

int TestMetaballMapperMolecule(int argc, char* argv[])
{
  char* file = vtkTestUtilities::ExpandDataFileName(argc, argv, "hemoglobin_chainA.pdb");
  vtkNew<vtkPDBReader> reader;
  reader->SetFileName(file);
  delete[] file;
  reader->Update();
  vtkNew<vtkMetaballMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort());
  mapper->GetField()->SetRadiusArrayName("radius");
  mapper->GetField()->SetRadiusScale(2.0);
  mapper->SetColorModeToDirectScalars();
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray("rgb_colors");
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetSpecular(0.3);
  actor->GetProperty()->SetSpecularPower(20);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(300, 300);
  renWin->SetMultiSamples(0);
  renWin->AddRenderer(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.3);
  renWin->Render();
  std::cout << reader->GetOutput()->GetNumberOfPoints() << " atoms, " << mapper->GetNumberOfPairs()
            << " grid pairs, " << mapper->GetGridBuildTime() << " ms grid, "
            << mapper->GetRayCastTime() << " ms ray cast\n";
  if (reader->GetOutput()->GetNumberOfPoints() != 1079 || mapper->GetNumberOfPairs() == 0)
  {
    return EXIT_FAILURE;
  }
  const int retVal = vtkRegressionTestImage(renWin);
  return retVal == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
