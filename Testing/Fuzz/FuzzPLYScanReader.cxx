// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkPLYScanReader on arbitrary .ply bytes. See README.md.
#include "psFuzzFile.h"
#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPLYScanReader.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string path = pointsurfaces::FuzzFile(data, size, "ply");
  vtkNew<vtkPLYScanReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  // Touch what was read, so that a bad array or index shows up here.
  vtkPolyData* out = reader->GetOutput();
  double bounds[6];
  out->GetBounds(bounds);
  vtkPointData* pd = out->GetPointData();
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    double range[2];
    pd->GetArray(a)->GetRange(range, -1);
  }
  const vtkIdType n = out->GetNumberOfPoints();
  vtkCellArray* polys = out->GetPolys();
  for (vtkIdType k = 0; k < polys->GetNumberOfConnectivityIds(); ++k)
  {
    const vtkIdType id = polys->GetConnectivityArray()->GetComponent(k, 0);
    if (id < 0 || id >= n)
    {
      __builtin_trap(); // a polygon that names no point
    }
  }
  // Piece by piece (SplitPoints): the record ranges of a binary file.
  vtkIdType pieces = 0;
  for (int piece = 0; piece < 3; ++piece)
  {
    vtkNew<vtkPLYScanReader> split;
    split->SetFileName(path.c_str());
    split->SplitPointsOn();
    split->UpdatePiece(piece, 3, 0);
    vtkPolyData* part = split->GetOutput();
    part->GetBounds(bounds);
    pieces += part->GetNumberOfPoints();
    if (part->GetNumberOfPolys() != 0)
    {
      __builtin_trap(); // a piece with faces
    }
  }
  if (n > 0 && pieces != n)
  {
    __builtin_trap(); // the pieces do not hold the whole file's points
  }
  return 0;
}
