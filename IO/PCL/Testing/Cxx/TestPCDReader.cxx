// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkPCDReader on a real binary_compressed Kinect subset, on an ASCII file
// with normals, colours and a NaN point, and on missing, empty, truncated and
// garbage files (clear error, empty output, no crash).
#include "psIOTestSupport.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkPCDReader.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

using namespace pointsurfaces_test;

namespace
{

} // namespace

int TestPCDReader(int, char*[])
{
  const std::string data = std::getenv("POINTSURFACES_IO_DATA");
  const std::string temp = std::getenv("POINTSURFACES_TEMP_DIR");

  vtkNew<vtkPCDReader> milk;
  milk->SetFileName((data + "/milk_subset.pcd").c_str());
  milk->Update();
  vtkPolyData* m = milk->GetOutput();
  Check(m->GetNumberOfPoints() == 686, "686 points in the compressed Kinect subset");
  Check(m->GetNumberOfVerts() == 686, "one vertex cell per point");
  Check(m->GetPointData()->GetNumberOfArrays() == 0, "an xyz-only scan has no point arrays");
  double bounds[6];
  m->GetBounds(bounds);
  Check(bounds[5] > bounds[4] && bounds[5] < 10.0, "Kinect depths in metres");

  vtkNew<vtkPCDReader> ascii;
  vtkNew<vtkTest::ErrorObserver> warnings;
  ascii->AddObserver(vtkCommand::WarningEvent, warnings);
  ascii->SetFileName((data + "/small_ascii.pcd").c_str());
  ascii->Update();
  vtkPolyData* a = ascii->GetOutput();
  Check(a->GetNumberOfPoints() == 4 && ascii->GetNumberOfDroppedPoints() == 1,
    "the NaN point is dropped and counted");
  Check(warnings->GetWarning() &&
      warnings->GetWarningMessage().find("Dropped 1 of 5") != std::string::npos,
    "the dropped point is reported");
  double p[3];
  a->GetPoint(3, p);
  Check(p[0] == 4 && p[1] == 8 && p[2] == -4, "points after the dropped one keep their values");
  vtkDataArray* normals = a->GetPointData()->GetNormals();
  Check(normals && normals->GetComponent(2, 2) == 1.0, "normals");
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetScalars());
  Check(rgb && rgb->GetNumberOfComponents() == 3 && rgb->GetValue(3) == 10 &&
      rgb->GetValue(4) == 21 && rgb->GetValue(5) == 200,
    "packed rgb unpacked to (10, 21, 200) for point 1");
  vtkDataArray* curvature = a->GetPointData()->GetArray("curvature");
  Check(curvature && curvature->GetComponent(3, 0) == 2.0, "extra fields become arrays");

  Check(ascii->GetReadInChildProcess(), "ReadInChildProcess is on by default");

  // In this process: the same points, arrays, active attributes and count.
  vtkNew<vtkPCDReader> here;
  here->SetFileName((data + "/small_ascii.pcd").c_str());
  here->ReadInChildProcessOff();
  here->Update();
  vtkPolyData* h = here->GetOutput();
  bool same = h->GetNumberOfPoints() == a->GetNumberOfPoints() &&
    h->GetNumberOfVerts() == a->GetNumberOfVerts() &&
    h->GetPoints()->GetDataType() == a->GetPoints()->GetDataType() &&
    here->GetNumberOfDroppedPoints() == 1 &&
    h->GetPointData()->GetNumberOfArrays() == a->GetPointData()->GetNumberOfArrays() &&
    h->GetPointData()->GetNormals() && h->GetPointData()->GetScalars();
  for (int k = 0; same && k < h->GetPointData()->GetNumberOfArrays(); ++k)
  {
    vtkDataArray* x = h->GetPointData()->GetArray(k);
    int index = -1;
    vtkDataArray* y = a->GetPointData()->GetArray(x->GetName(), index);
    same = y && x->GetDataType() == y->GetDataType() &&
      x->GetNumberOfComponents() == y->GetNumberOfComponents() &&
      h->GetPointData()->IsArrayAnAttribute(k) == a->GetPointData()->IsArrayAnAttribute(index);
    for (vtkIdType v = 0; same && v < x->GetNumberOfValues(); ++v)
    {
      same = x->GetComponent(v / x->GetNumberOfComponents(), v % x->GetNumberOfComponents()) ==
        y->GetComponent(v / y->GetNumberOfComponents(), v % y->GetNumberOfComponents());
    }
  }
  for (vtkIdType i = 0; same && i < h->GetNumberOfPoints(); ++i)
  {
    double x[3], y[3];
    h->GetPoint(i, x);
    a->GetPoint(i, y);
    same = x[0] == y[0] && x[1] == y[1] && x[2] == y[2];
  }
  Check(same, "the same output read in a child process and in this process");

  ExpectReadError<vtkPCDReader>(data + "/does_not_exist.pcd", "missing or is not a PCD file");

  // Truncate the compressed file in the middle of its data.
  std::ifstream in(data + "/milk_subset.pcd", std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string truncated = temp + "/truncated.pcd";
  std::ofstream(truncated, std::ios::binary).write(bytes.data(), bytes.size() / 2);
  ExpectReadError<vtkPCDReader>(truncated, "corrupt or truncated");

  // A header that promises more ASCII points than the file holds.
  const std::string shortAscii = temp + "/short_ascii.pcd";
  std::ofstream(shortAscii) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                               "WIDTH 10\nHEIGHT 1\nPOINTS 10\nDATA ascii\n1 2 3\n";
  ExpectReadError<vtkPCDReader>(shortAscii, "corrupt or truncated");

  // POINTS before the fields it counts: PCL sizes its buffer for 2 points of
  // one float and writes 2 points of three (past the buffer; valgrind sees
  // it, ASan does not, PCL is not instrumented).
  const std::string lateFields = temp + "/late_fields.pcd";
  std::ofstream(lateFields) << "# .PCD v0.7\nVERSION 0.7\nFIELDS x\nSIZE 4\nTYPE F\nCOUNT 1\n"
                               "WIDTH 2\nHEIGHT 1\nPOINTS 2\nFIELDS x y z\nSIZE 4 4 4\n"
                               "TYPE F F F\nCOUNT 1 1 1\nDATA ascii\n1 2 3\n4 5 6\n";
  ExpectReadError<vtkPCDReader>(lateFields, "POINTS line comes before fields");

  const std::string garbage = temp + "/garbage.pcd";
  std::ofstream(garbage) << "# .PCD v0.7\nthis is not a header\n\x01\x02\x03";
  ExpectReadError<vtkPCDReader>(garbage, "Cannot read");
  ExpectEmptyFileError<vtkPCDReader>(temp + "/empty.pcd");

  if (Failures)
  {
    return EXIT_FAILURE;
  }
  std::cout << "TestPCDReader: passed\n";
  return EXIT_SUCCESS;
}
