// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkGromacsGroReader on a trajectory written by GROMACS itself
// (IO/Testing/Data/gromacs: SPC water, 4 frames with velocities, and the
// inputs that made it): time steps, frame choice, positions, velocities,
// elements and radii against the file's own columns; elements of ions and
// protein atoms; and missing, empty, truncated, damaged and garbage files.
#include "psIOTestSupport.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkGromacsGroReader.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTestErrorObserver.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

using namespace pointsurfaces_test;

namespace
{
std::string StringAt(vtkPolyData* pd, const char* name, vtkIdType k)
{
  auto* a = vtkStringArray::SafeDownCast(pd->GetPointData()->GetAbstractArray(name));
  return a ? a->GetValue(k) : std::string("(none)");
}
} // namespace

int TestGromacsGroReader(int, char*[])
{
  const std::string data = std::string(std::getenv("POINTSURFACES_IO_DATA")) + "/gromacs";
  const std::string temp = std::getenv("POINTSURFACES_TEMP_DIR");
  const std::string traj = data + "/water_traj.gro";
  Check(vtkGromacsGroReader::CanReadFile(traj.c_str()), "CanReadFile on a .gro");

  vtkNew<vtkGromacsGroReader> reader;
  reader->SetFileName(traj.c_str());
  reader->UpdateInformation();
  vtkInformation* info = reader->GetOutputInformation(0);
  const int steps = info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const double* times = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  Check(steps == 4 && reader->GetNumberOfFrames() == 4, "four frames");
  for (int k = 0; k < steps; ++k)
  {
    Check(std::abs(times[k] - 0.02 * k) < 1e-9, "frame " + std::to_string(k) + " at t = 0.02 k ps");
  }

  // t = 0.03 reads the frame at 0.02 (step 10); compare its atoms with the file's columns.
  reader->UpdateTimeStep(0.03);
  vtkPolyData* out = reader->GetOutput();
  Check(out->GetNumberOfPoints() == 327 && out->GetNumberOfVerts() == 327, "327 atoms");
  Check(out->GetFieldData()->GetArray("Step") &&
      out->GetFieldData()->GetArray("Step")->GetTuple1(0) == 10,
    "t = 0.03 reads step 10");
  std::ifstream in(traj);
  std::string line;
  for (int frame = 0; frame < 2; ++frame) // past the first frame and the second's header
  {
    std::getline(in, line);
    std::getline(in, line);
    const int n = std::stoi(line);
    for (int a = 0; a <= n && frame == 0; ++a)
    {
      std::getline(in, line);
    }
  }
  vtkDataArray* v = out->GetPointData()->GetArray("v");
  vtkDataArray* radius = out->GetPointData()->GetArray("radius");
  double worst = 0.0;
  for (vtkIdType k = 0; k < out->GetNumberOfPoints() && v && radius; ++k)
  {
    std::getline(in, line);
    double p[3];
    out->GetPoint(k, p);
    for (int c = 0; c < 3; ++c)
    {
      worst = std::max({ worst,
        std::abs(p[c] - std::stod(line.substr(20 + 8 * c, 8))),
        std::abs(v->GetComponent(k, c) - std::stod(line.substr(44 + 8 * c, 8))) });
    }
    const bool oxygen = line.substr(10, 5).find('O') != std::string::npos;
    Check(StringAt(out, "element", k) == (oxygen ? "O" : "H") &&
        radius->GetTuple1(k) == (oxygen ? 0.152 : 0.120),
      "element and radius of atom " + std::to_string(k));
    Check(StringAt(out, "resname", k) == "SOL", "resname SOL");
  }
  Check(v != nullptr && worst == 0.0, "positions and velocities are the file's numbers");
  vtkDataArray* box = out->GetFieldData()->GetArray("Box");
  Check(box && box->GetNumberOfComponents() == 9 && box->GetComponent(0, 0) == 1.5 &&
      box->GetComponent(0, 3) == 0.0,
    "a rectangular 1.5 nm box");

  // Elements as force fields name atoms: ions, alpha carbons, hydrogens with digits first.
  const std::string mixed = Write(temp + "/mixed.gro",
    "ions and a residue, no velocities\n"
    "    6\n"
    "    1ALA     CA    1   0.100   0.200   0.300\n"
    "    1ALA    1HB    2   0.110   0.210   0.310\n"
    "    2NA      NA    3   1.000   1.000   1.000\n"
    "    3CL      CL    4   1.200   1.000   1.000\n"
    "    4CA      CA    5   1.400   1.000   1.000\n"
    "    5XX      XX    6   1.600   1.000   1.000\n"
    "   2.00000   2.00000   2.00000   0.00000   0.00000   0.50000   0.00000   0.00000   0.00000\n");
  vtkNew<vtkGromacsGroReader> ions;
  vtkNew<vtkTest::ErrorObserver> warnings;
  ions->AddObserver(vtkCommand::WarningEvent, warnings);
  ions->SetFileName(mixed.c_str());
  ions->Update();
  vtkPolyData* m = ions->GetOutput();
  const char* elements[] = { "C", "H", "Na", "Cl", "Ca", "X" };
  for (vtkIdType k = 0; k < 6 && m->GetNumberOfPoints() == 6; ++k)
  {
    Check(StringAt(m, "element", k) == elements[k],
      "atom " + std::to_string(k) + " is " + elements[k] + ", got " + StringAt(m, "element", k));
  }
  Check(m->GetPointData()->GetArray("v") == nullptr, "no velocities, no v");
  Check(
    warnings->GetWarning() && warnings->GetWarningMessage().find("XX (XX)") != std::string::npos,
    "a warning names the atom without a radius");
  Check(m->GetFieldData()->GetArray("Box")->GetComponent(0, 5) == 0.5, "a triclinic box's v2x");
  Check(m->GetFieldData()->GetArray("Time")->GetTuple1(0) == 0.0, "no t= in the title: time 0");

  // Damage.
  const std::string bytes = Slurp(traj);
  const std::string cut = Write(temp + "/cut.gro", bytes.substr(0, bytes.size() * 5 / 8));
  {
    vtkNew<vtkGromacsGroReader> r;
    vtkNew<vtkTest::ErrorObserver> errors;
    r->AddObserver(vtkCommand::ErrorEvent, errors);
    r->SetFileName(cut.c_str());
    r->UpdateInformation();
    Check(errors->GetError() &&
        errors->GetErrorMessage().find("is damaged after 2 frames") != std::string::npos,
      "a truncated trajectory: an error naming what was kept");
    Check(r->GetNumberOfFrames() == 2, "the two whole frames stay readable");
    r->UpdateTimeStep(0.02);
    Check(r->GetOutput()->GetNumberOfPoints() == 327, "a frame before the damage reads");
  }
  ExpectReadError<vtkGromacsGroReader>(temp + "/missing.gro", "cannot be opened");
  ExpectEmptyFileError<vtkGromacsGroReader>(temp + "/empty.gro");
  ExpectReadError<vtkGromacsGroReader>(
    Write(temp + "/garbage.gro", "garbage\nnot a count\n"), "no atom count");
  ExpectReadError<vtkGromacsGroReader>(
    Write(
      temp + "/huge.gro", "title\n999999999999\n    1SOL     OW    1   0.100   0.200   0.300\n"),
    "too short");
  ExpectReadError<vtkGromacsGroReader>(
    Write(temp + "/no-xyz.gro", "title\n1\n    1SOL     OW    1   abc\n1 1 1\n"), "no coordinates");
  ExpectReadError<vtkGromacsGroReader>(
    Write(temp + "/box.gro", "title\n1\n    1SOL     OW    1   0.100   0.200   0.300\n1 1 1 1 1\n"),
    "5 numbers");
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
