// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psRealArrayView.h
 * @brief A vtkDataArray's values read as doubles without a virtual call per value.
 *
 * The splat data model's arrays are float or double (the fitter writes
 * double, splat files and their pages float). The loops that run over every
 * splat whenever the data change (the mapper's vertex buffers, its octree,
 * vtkSplatDataModel::GetOctree's checks) read them through this view: in
 * place for vtkFloatArray and vtkDoubleArray, through one double copy for
 * any other kind. Through vtkDataArray's virtual GetTuple and GetComponent,
 * those loops took most of a rebuild of the mapper's buffers.
 */
#ifndef psRealArrayView_h
#define psRealArrayView_h

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkSmartPointer.h"

#include <cstddef>

namespace pointsurfaces
{
class RealArrayView
{
public:
  /** Absent (Present() false) without the array, or with fewer than `tuples` tuples. */
  RealArrayView(vtkDataArray* array, vtkIdType tuples)
  {
    if (!array || array->GetNumberOfTuples() == 0 || array->GetNumberOfTuples() < tuples)
    {
      return;
    }
    this->Components = array->GetNumberOfComponents();
    if (auto* f = vtkFloatArray::FastDownCast(array))
    {
      this->F = f->GetPointer(0);
    }
    else if (auto* d = vtkDoubleArray::FastDownCast(array))
    {
      this->D = d->GetPointer(0);
    }
    else
    {
      this->Copy = vtkSmartPointer<vtkDoubleArray>::New();
      this->Copy->DeepCopy(array);
      this->D = this->Copy->GetPointer(0);
    }
  }
  bool Present() const { return this->F || this->D; }
  /** Component c of tuple i (no bounds check: Present(), i below the tuples asked for). */
  double operator()(vtkIdType i, int c) const
  {
    const std::size_t k = static_cast<std::size_t>(i) * this->Components + c;
    return this->F ? static_cast<double>(this->F[k]) : this->D[k];
  }

private:
  int Components = 0;
  const float* F = nullptr;
  const double* D = nullptr;
  vtkSmartPointer<vtkDoubleArray> Copy;
};
} // namespace pointsurfaces

#endif
