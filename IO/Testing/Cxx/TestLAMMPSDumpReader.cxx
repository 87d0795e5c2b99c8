// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkLAMMPSDumpReader on dumps written by LAMMPS itself (IO/Testing/Data/lammps,
// with the inputs that made them): time steps, snapshot choice, points and
// arrays against the file's own numbers, sorting by id, scaled coordinates
// in a triclinic box against the same run's unscaled dump; and missing,
// empty, truncated, damaged and garbage files (one error, empty or partial output,
// no crash).
#include "psIOTestSupport.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkLAMMPSDumpReader.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTestErrorObserver.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace pointsurfaces_test;

namespace
{
// The atoms of the snapshot at `timestep` of `file`, by id: each row's numbers, parsed here.
std::map<long long, std::vector<double>> Rows(const std::string& file, long long timestep)
{
  std::ifstream in(file);
  std::string line;
  std::map<long long, std::vector<double>> rows;
  while (std::getline(in, line))
  {
    if (line != "ITEM: TIMESTEP")
    {
      continue;
    }
    std::getline(in, line);
    const bool mine = std::stoll(line) == timestep;
    long long n = 0;
    while (std::getline(in, line) && line.rfind("ITEM: ATOMS", 0) != 0)
    {
      if (line == "ITEM: NUMBER OF ATOMS")
      {
        std::getline(in, line);
        n = std::stoll(line);
      }
    }
    for (long long a = 0; a < n && std::getline(in, line); ++a)
    {
      std::istringstream ss(line);
      std::vector<double> v;
      double x;
      while (ss >> x)
      {
        v.push_back(x);
      }
      if (mine)
      {
        rows[static_cast<long long>(v[0])] = v;
      }
    }
  }
  return rows;
}

vtkPolyData* ReadAt(vtkLAMMPSDumpReader* reader, double time)
{
  reader->UpdateTimeStep(time);
  return reader->GetOutput();
}
} // namespace

int TestLAMMPSDumpReader(int, char*[])
{
  const std::string data = std::string(std::getenv("POINTSURFACES_IO_DATA")) + "/lammps";
  const std::string temp = std::getenv("POINTSURFACES_TEMP_DIR");
  const std::string melt = data + "/melt.lammpstrj";
  Check(vtkLAMMPSDumpReader::CanReadFile(melt.c_str()), "CanReadFile on a dump");

  // Time steps: six snapshots, at ITEM: TIME 0, 0.1, ..., 0.5.
  vtkNew<vtkLAMMPSDumpReader> reader;
  reader->SetFileName(melt.c_str());
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(0);
  const int steps = info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const double* times = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  Check(steps == 6 && reader->GetNumberOfSnapshots() == 6, "six snapshots");
  for (int k = 0; k < steps; ++k)
  {
    Check(std::abs(times[k] - 0.1 * k) < 1e-9, "time step " + std::to_string(k));
  }

  // The last snapshot at or before t = 0.25: timestep 40.
  vtkPolyData* out = ReadAt(reader, 0.25);
  Check(out->GetNumberOfPoints() == 256 && out->GetNumberOfVerts() == 256, "256 atoms");
  vtkDataArray* step = out->GetFieldData()->GetArray("Timestep");
  Check(step && step->GetTuple1(0) == 40, "t = 0.25 reads timestep 40");
  const auto rows = Rows(melt, 40); // id type x y z xu yu zu vx vy vz
  vtkDataArray* id = out->GetPointData()->GetArray("id");
  vtkDataArray* type = out->GetPointData()->GetArray("type");
  vtkDataArray* v = out->GetPointData()->GetArray("v");
  vtkDataArray* wrapped = out->GetPointData()->GetArray("x");
  Check(id && type && v && v->GetNumberOfComponents() == 3 && wrapped &&
      wrapped->GetNumberOfComponents() == 3 && out->GetPointData()->GetNumberOfArrays() == 4,
    "arrays id, type, v (vx vy vz) and x (wrapped x y z)");
  double worst = 0.0;
  bool sorted = true;
  for (vtkIdType k = 0; id && v && wrapped && k < out->GetNumberOfPoints(); ++k)
  {
    sorted = sorted && id->GetTuple1(k) == k + 1;
    const auto it = rows.find(static_cast<long long>(id->GetTuple1(k)));
    if (it == rows.end())
    {
      sorted = false;
      continue;
    }
    const std::vector<double>& r = it->second;
    double p[3];
    out->GetPoint(k, p);
    for (int c = 0; c < 3; ++c)
    {
      worst = std::max({ worst,
        std::abs(p[c] - r[5 + c]),
        std::abs(wrapped->GetComponent(k, c) - r[2 + c]),
        std::abs(v->GetComponent(k, c) - r[8 + c]) });
    }
  }
  Check(sorted, "atoms in id order");
  Check(worst == 0.0, "points are the unwrapped xu yu zu, arrays the file's numbers");
  Check(ReadAt(reader, 1e9)->GetFieldData()->GetArray("Timestep")->GetTuple1(0) == 100,
    "a time past the end reads the last snapshot");

  // Sorting by id (LAMMPS writes atoms in the order its processes hold them).
  const std::string shuffled = Write(temp + "/shuffled.lammpstrj",
    "ITEM: TIMESTEP\n7\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS pp pp pp\n0 3\n0 3\n0 3\n"
    "ITEM: ATOMS id type x y z\n3 1 3 0 0\n1 2 1 0 0\n2 1 2 0 0\n");
  for (bool sort : { true, false })
  {
    vtkNew<vtkLAMMPSDumpReader> r;
    r->SetFileName(shuffled.c_str());
    r->SetSortById(sort);
    r->Update();
    vtkPolyData* o = r->GetOutput();
    bool ok = o->GetNumberOfPoints() == 3;
    const double expected[2][3] = { { 1, 2, 3 }, { 3, 1, 2 } };
    for (vtkIdType k = 0; ok && k < 3; ++k)
    {
      double p[3];
      o->GetPoint(k, p);
      ok = o->GetPointData()->GetArray("id")->GetTuple1(k) == expected[sort ? 0 : 1][k] &&
        p[0] == expected[sort ? 0 : 1][k];
    }
    Check(ok, sort ? "SortById puts the atoms in id order" : "SortById off keeps the file's order");
  }

  // Scaled coordinates in a triclinic box against the same run's x y z.
  vtkNew<vtkLAMMPSDumpReader> scaled, plain;
  scaled->SetFileName((data + "/tri.lammpstrj").c_str());
  plain->SetFileName((data + "/tri_xyz.lammpstrj").c_str());
  vtkPolyData* a = ReadAt(scaled, 50);
  vtkPolyData* b = ReadAt(plain, 50);
  worst =
    a->GetNumberOfPoints() == b->GetNumberOfPoints() && a->GetNumberOfPoints() == 256 ? 0.0 : 1e9;
  for (vtkIdType k = 0; worst < 1e9 && k < a->GetNumberOfPoints(); ++k)
  {
    double p[3], q[3];
    a->GetPoint(k, p);
    b->GetPoint(k, q);
    for (int c = 0; c < 3; ++c)
    {
      worst = std::max(worst, std::abs(p[c] - q[c]));
    }
  }
  std::cout << "triclinic: scaled against unscaled coordinates, largest difference " << worst
            << "\n";
  // dump atom writes 6 significant digits of the fraction; the box is about 7 long.
  Check(worst < 1e-4, "scaled coordinates through the triclinic box");
  vtkDataArray* tilt = a->GetFieldData()->GetArray("BoxTilt");
  Check(tilt && tilt->GetComponent(0, 0) > 1.6 && tilt->GetComponent(0, 1) > 0.8,
    "BoxTilt holds xy xz yz");

  // Damage. Truncated after three and a half snapshots: an error, three snapshots offered.
  const std::string bytes = Slurp(melt);
  const std::string cut = Write(temp + "/cut.lammpstrj", bytes.substr(0, bytes.size() * 7 / 12));
  {
    vtkNew<vtkLAMMPSDumpReader> r;
    vtkNew<vtkTest::ErrorObserver> errors;
    r->AddObserver(vtkCommand::ErrorEvent, errors);
    r->SetFileName(cut.c_str());
    r->UpdateInformation();
    Check(errors->GetError() &&
        errors->GetErrorMessage().find("is damaged after 3") != std::string::npos,
      "a truncated dump: an error naming what was kept");
    Check(r->GetNumberOfSnapshots() == 3, "the three whole snapshots stay readable");
    Check(ReadAt(r, 0.2)->GetNumberOfPoints() == 256, "a snapshot before the damage reads");
  }
  ExpectReadError<vtkLAMMPSDumpReader>(temp + "/missing.lammpstrj", "cannot be opened", 0);
  ExpectEmptyFileError<vtkLAMMPSDumpReader>(temp + "/empty.lammpstrj");
  ExpectReadError<vtkLAMMPSDumpReader>(
    Write(temp + "/garbage.lammpstrj", "solid garbage\n\x01\x02\x03"), "expected an ITEM line", 0);
  ExpectReadError<vtkLAMMPSDumpReader>(
    Write(temp + "/huge.lammpstrj",
      "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n4000000000000\nITEM: BOX BOUNDS pp pp pp\n"
      "0 1\n0 1\n0 1\nITEM: ATOMS id x y z\n1 0 0 0\n"),
    "too short",
    0);
  ExpectReadError<vtkLAMMPSDumpReader>(
    Write(temp + "/short-row.lammpstrj",
      "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n"
      "0 1\n0 1\n0 1\nITEM: ATOMS id x y z\n1 0 0 0\n2 0.5 0.5\n"),
    "has 3 numbers",
    0);
  ExpectReadError<vtkLAMMPSDumpReader>(
    Write(temp + "/no-xyz.lammpstrj",
      "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n"
      "0 1\n0 1\n0 1\nITEM: ATOMS id q\n1 0.5\n"),
    "has no coordinates",
    0);
  ExpectReadError<vtkLAMMPSDumpReader>(
    Write(temp + "/no-box.lammpstrj",
      "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: ATOMS id x y z\n1 0 0 0\n"),
    "no ITEM: BOX BOUNDS",
    0);
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
