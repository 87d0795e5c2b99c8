// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkHardwareSelector on ray-cast splats returns splat ids: the middle of
// the Bunny must pick some, and every id picked in the 20x20 pixel area must
// belong to a splat whose disc, projected, can reach that area.
#include "vtkActor.h"
#include "vtkAlgebraicSplatFitter.h"
#include "vtkAlgebraicSplatMapper.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkHardwareSelector.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkSmartPointer.h"
#include "vtkTestUtilities.h"
#include "vtkXMLPolyDataReader.h"

#include <cmath>
#include <cstdlib>
#include <iostream>

int TestAlgebraicSplatMapperPicking(int argc, char* argv[])
{
  char* file = vtkTestUtilities::ExpandDataFileName(argc, argv, "bunny.vtp");
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file);
  delete[] file;
  vtkNew<vtkAlgebraicSplatFitter> fitter;
  fitter->SetInputConnection(reader->GetOutputPort());
  vtkNew<vtkAlgebraicSplatMapper> mapper;
  mapper->SetInputConnection(fitter->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(300, 300);
  renWin->SetMultiSamples(0);
  renWin->AddRenderer(renderer);
  renderer->ResetCamera();
  renWin->Render();

  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(renderer);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  selector->SetArea(140, 140, 159, 159);
  vtkSmartPointer<vtkSelection> selection;
  selection.TakeReference(selector->Select());
  if (!selection || selection->GetNumberOfNodes() != 1)
  {
    std::cerr << "The selector returned no node\n";
    return EXIT_FAILURE;
  }
  vtkDataArray* ids = vtkDataArray::SafeDownCast(selection->GetNode(0)->GetSelectionList());
  vtkPolyData* splats = fitter->GetOutput();
  vtkDataArray* radius = splats->GetPointData()->GetArray("SplatRadius");
  if (!ids || ids->GetNumberOfTuples() == 0)
  {
    std::cerr << "No splat picked in the middle of the Bunny\n";
    return EXIT_FAILURE;
  }
  int bad = 0;
  for (vtkIdType k = 0; k < ids->GetNumberOfTuples(); ++k)
  {
    const vtkIdType id = static_cast<vtkIdType>(ids->GetTuple1(k));
    if (id < 0 || id >= splats->GetNumberOfPoints())
    {
      ++bad;
      continue;
    }
    double o[3], display[3], edge[3];
    splats->GetPoint(id, o);
    renderer->SetWorldPoint(o[0], o[1], o[2], 1.0);
    renderer->WorldToDisplay();
    renderer->GetDisplayPoint(display);
    // The disc radius in pixels, through a point offset by 2 R (the patch
    // may also rise above its disc).
    const double r = 2.0 * radius->GetTuple1(id);
    renderer->SetWorldPoint(o[0] + r, o[1], o[2], 1.0);
    renderer->WorldToDisplay();
    renderer->GetDisplayPoint(edge);
    const double reach = std::hypot(edge[0] - display[0], edge[1] - display[1]) + 2.0;
    const double dx = std::max({ 140.0 - display[0], 0.0, display[0] - 160.0 });
    const double dy = std::max({ 140.0 - display[1], 0.0, display[1] - 160.0 });
    if (std::hypot(dx, dy) > reach)
    {
      std::cerr << "Splat " << id << " at (" << display[0] << ", " << display[1]
                << ") cannot cover the picked area\n";
      ++bad;
    }
  }
  std::cout << ids->GetNumberOfTuples() << " splats picked, " << bad << " wrong\n";
  return bad ? EXIT_FAILURE : EXIT_SUCCESS;
}
