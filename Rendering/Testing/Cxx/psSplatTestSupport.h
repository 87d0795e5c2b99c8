// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// What several splat mapper tests share: points spread evenly over the unit
// sphere, the exact surface most of them check against.
#ifndef psSplatTestSupport_h
#define psSplatTestSupport_h

#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cmath>

// n points of the unit sphere on a Fibonacci spiral, in double precision.
inline vtkSmartPointer<vtkPolyData> psFibonacciSphere(int n)
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), t = golden * i;
    pts->InsertNextPoint(r * std::cos(t), r * std::sin(t), z);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(pts);
  return poly;
}

#endif
