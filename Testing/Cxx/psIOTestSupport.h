// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psIOTestSupport.h
 * @brief What the IO tests share: failure and event counters, and balls as poly data.
 *
 * The tests are one executable and each ctest run calls one of them, so the
 * counters are per run.
 */
#ifndef psIOTestSupport_h
#define psIOTestSupport_h

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"

#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

namespace pointsurfaces_test
{
inline int Failures = 0;
inline int Errors = 0;
inline int Warnings = 0;

/** Prints and counts a failed check. */
inline void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++Failures;
  }
}

/** Writes `bytes` to the file `path`; returns `path`. */
inline std::string Write(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

/** The bytes of the file `path` (empty when it cannot be read). */
inline std::string Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/** vtkCallbackCommand callbacks for ErrorEvent and WarningEvent. */
inline void CountError(vtkObject*, unsigned long, void*, void*)
{
  ++Errors;
}
inline void CountWarning(vtkObject*, unsigned long, void*, void*)
{
  ++Warnings;
}

/**
 * Read `file` with a new `Reader`, expecting an error that mentions
 * `expected` and an output of `points` points (empty by default).
 */
template<typename Reader>
void ExpectReadError(const std::string& file, const std::string& expected, vtkIdType points = 0)
{
  vtkNew<Reader> reader;
  vtkNew<vtkTest::ErrorObserver> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName(file.c_str());
  reader->Update();
  Check(errors->GetError() && errors->GetErrorMessage().find(expected) != std::string::npos,
    "an error mentioning '" + expected + "' for " + file + " (got '" + errors->GetErrorMessage() +
      "')");
  Check(reader->GetOutput()->GetNumberOfPoints() == points,
    "an output of " + std::to_string(points) + " points for " + file);
}

/**
 * Read an empty (0-byte) file, written at `path`, with a new `Reader`:
 * exactly one error, naming the file and saying that it is empty, and an
 * output without points.
 */
template<typename Reader>
void ExpectEmptyFileError(const std::string& path)
{
  Write(path, "");
  vtkNew<Reader> reader;
  vtkNew<vtkTest::ErrorObserver> errors;
  vtkNew<vtkCallbackCommand> count;
  count->SetCallback(CountError);
  for (vtkObject* o :
    { static_cast<vtkObject*>(reader), static_cast<vtkObject*>(reader->GetExecutive()) })
  {
    o->AddObserver(vtkCommand::ErrorEvent, errors);
    o->AddObserver(vtkCommand::ErrorEvent, count);
  }
  const int before = Errors;
  reader->SetFileName(path.c_str());
  reader->Update();
  const std::string message = errors->GetErrorMessage();
  Check(Errors - before == 1 && message.find(path) != std::string::npos &&
      message.find("is empty") != std::string::npos,
    "one error naming the empty file " + path + " (got " + std::to_string(Errors - before) + ": '" +
      message + "')");
  Check(reader->GetOutput()->GetNumberOfPoints() == 0, "no points from the empty file " + path);
}

/** Balls at `xyz` with point arrays "Radius" and, when given, "Strength". */
inline vtkSmartPointer<vtkPolyData> Balls(const std::vector<double>& xyz,
  const std::vector<double>& radii,
  const std::vector<double>& strengths = {})
{
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> r, q;
  r->SetName("Radius");
  q->SetName("Strength");
  for (size_t i = 0; i < radii.size(); ++i)
  {
    points->InsertNextPoint(&xyz[3 * i]);
    r->InsertNextValue(radii[i]);
    if (!strengths.empty())
    {
      q->InsertNextValue(strengths[i]);
    }
  }
  poly->SetPoints(points);
  poly->GetPointData()->AddArray(r);
  if (!strengths.empty())
  {
    poly->GetPointData()->AddArray(q);
  }
  return poly;
}
/**
 * `count` balls drawn from `rng`: centres in [-1.5, 1.5]^3, radii in [0.6,
 * 1.2], strengths in [0.6, 1.4].
 */
struct Cluster
{
  std::vector<double> Centers, Radii, Strengths;
  Cluster(std::mt19937& rng, int count)
  {
    std::uniform_real_distribution<double> u(-1.5, 1.5), r(0.6, 1.2), q(0.6, 1.4);
    for (int i = 0; i < count; ++i)
    {
      this->Centers.insert(this->Centers.end(), { u(rng), u(rng), u(rng) });
      this->Radii.push_back(r(rng));
      this->Strengths.push_back(q(rng));
    }
  }
};
} // namespace pointsurfaces_test

#endif
