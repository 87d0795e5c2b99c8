// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSplatDataModel.h"

#include "psPolynomial.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <numeric>

vtkStandardNewMacro(vtkSplatDataModel);

//------------------------------------------------------------------------------
void vtkSplatDataModel::AddVertexCells(vtkPolyData* pd)
{
  const vtkIdType n = pd->GetNumberOfPoints();
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(n);
  std::iota(connectivity->GetPointer(0), connectivity->GetPointer(0) + n, vtkIdType(0));
  vtkNew<vtkCellArray> verts;
  verts->SetData(1, connectivity);
  pd->SetVerts(verts);
}

//------------------------------------------------------------------------------
int vtkSplatDataModel::GetSplatDegree(vtkPolyData* pd)
{
  if (!pd || pd->GetNumberOfPoints() == 0)
  {
    return -1;
  }
  vtkDataArray* degreeArray = pd->GetFieldData()->GetArray(DegreeName());
  const int degree = degreeArray ? static_cast<int>(degreeArray->GetTuple1(0)) : -1;
  if (degree < 1 || degree > pointsurfaces::MaximumDegree)
  {
    return -1;
  }
  const vtkIdType n = pd->GetNumberOfPoints();
  const std::pair<const char*, int> arrays[] = { { NormalName(), 3 },
    { TangentName(), 3 },
    { FeatureSizeName(), 1 },
    { RadiusName(), 1 },
    { CoefficientsName(), pointsurfaces::MonomialCount(degree) } };
  for (const auto& a : arrays)
  {
    vtkDataArray* array = pd->GetPointData()->GetArray(a.first);
    if (!array || array->GetNumberOfComponents() != a.second || array->GetNumberOfTuples() != n)
    {
      return -1;
    }
  }
  return degree;
}
