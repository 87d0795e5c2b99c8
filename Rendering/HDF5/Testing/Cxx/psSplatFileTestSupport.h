// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// What the streaming mapper's tests share: a scratch path of this process's
// own, and a fitted sphere written as a splat file.
#ifndef psSplatFileTestSupport_h
#define psSplatFileTestSupport_h

#include "psRenderTestSupport.h"

#include "vtkAlgebraicSplatFitter.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkSplatFileWriter.h"

#include <unistd.h>

#include <cstdlib>
#include <string>

// `name` in $POINTSURFACES_TEMP_DIR, prefixed with the process id: the egl
// and x11 variants of a test run at once.
inline std::string psScratchPath(const std::string& name)
{
  const char* dir = std::getenv("POINTSURFACES_TEMP_DIR");
  return std::string(dir ? dir : "/tmp") + "/" + std::to_string(getpid()) + "-" + name;
}

// The unit sphere's `points` Fibonacci points with a colour array "Colour"
// (x, y, z mapped to 0..`scale`), fitted with three levels and written to
// `path` in pages of `pageSize` splats; the number of splats written.
inline vtkIdType psWriteSphereSplatFile(const std::string& path,
  int points,
  double scale,
  int pageSize)
{
  auto sphere = psFibonacciSphere(points);
  vtkNew<vtkFloatArray> colour;
  colour->SetName("Colour");
  colour->SetNumberOfComponents(3);
  colour->SetNumberOfTuples(sphere->GetNumberOfPoints());
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    double p[3];
    sphere->GetPoint(i, p);
    colour->SetTuple3(
      i, 0.5 * scale * (1 + p[0]), 0.5 * scale * (1 + p[1]), 0.5 * scale * (1 + p[2]));
  }
  sphere->GetPointData()->AddArray(colour);
  vtkNew<vtkAlgebraicSplatFitter> fitter;
  fitter->SetInputData(sphere);
  fitter->SetNumberOfLevels(3);
  vtkNew<vtkSplatFileWriter> writer;
  writer->SetInputConnection(fitter->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->SetPageSize(pageSize);
  writer->Write();
  return writer->GetNumberOfSplats();
}

#endif
