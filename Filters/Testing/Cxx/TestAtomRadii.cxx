// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkAtomRadii after vtkPDBReader on a PDB as simulation tools write them
// (blank element columns; CHARMM's TIP3P water OH2 H1 H2 and ions SOD CLA,
// TIP4P's OW HW1 HW2 and its virtual site MW, a protein's CA and 1HB): the
// atoms VTK leaves without a radius get their element's van der Waals
// radius in Ångström, virtual sites stay at 0, and radii VTK gave are kept.
#include "psIOTestSupport.h"
#include "vtkAtomRadii.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPDBReader.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTestErrorObserver.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

using namespace pointsurfaces_test;

namespace
{
std::string Atom(int serial, const char* name, const char* residue, double x)
{
  char line[100];
  std::snprintf(line,
    sizeof(line),
    // Columns as CHARMM writes them: a four-letter residue (TIP3) fills
    // 18-21 and the chain stays in 22. (With the chain pushed into the
    // residue number's columns, VTK 9.6's vtkPDBReader aborts on a failed
    // number parse.)
    "ATOM  %5d %-4s %-4sA%4d    %8.3f%8.3f%8.3f  1.00  0.00\n",
    serial,
    name,
    residue,
    serial,
    x,
    0.0,
    0.0);
  return line;
}
} // namespace

int TestAtomRadii(int, char*[])
{
  const std::string temp = std::getenv("POINTSURFACES_TEMP_DIR");
  const std::string path = temp + "/simulation.pdb";
  struct Expected
  {
    const char* Name;
    const char* Residue;
    double Radius; // Å; -1: whatever vtkPDBReader gave (it knows the element); -2: unknown
  };
  const Expected atoms[] = { { "CA", "ALA", -1 },
    { "1HB", "ALA", 1.20 },
    { "OH2", "TIP3", 1.52 },
    { "H1", "TIP3", -1 },
    { "SOD", "SOD", 2.27 },
    { "CLA", "CLA", 1.75 },
    { "OW", "SOL", -1 },
    { "HW1", "SOL", -1 },
    { "MW", "SOL", 0.0 },
    { "XQ", "UNK", -2 } };
  {
    std::ofstream out(path);
    int serial = 1;
    for (const Expected& a : atoms)
    {
      out << Atom(serial, a.Name, a.Residue, 3.0 * serial);
      ++serial;
    }
    out << "END\n";
  }
  vtkNew<vtkPDBReader> pdb;
  pdb->SetFileName(path.c_str());
  pdb->Update();
  vtkPolyData* in = pdb->GetOutput();
  const int n = static_cast<int>(sizeof(atoms) / sizeof(atoms[0]));
  Check(in->GetNumberOfPoints() == n, "vtkPDBReader reads every atom");
  vtkDataArray* before = in->GetPointData()->GetArray("radius");
  int missing = 0;
  for (vtkIdType i = 0; before && i < in->GetNumberOfPoints(); ++i)
  {
    missing += before->GetComponent(i, 0) <= 0.0 ? 1 : 0;
  }
  std::cout << "vtkPDBReader leaves " << missing << " of " << n << " atoms without a radius\n";

  vtkNew<vtkAtomRadii> radii;
  vtkNew<vtkTest::ErrorObserver> warnings;
  radii->AddObserver(vtkCommand::WarningEvent, warnings);
  radii->SetInputConnection(pdb->GetOutputPort());
  radii->Update();
  vtkPointSet* out = radii->GetOutput();
  vtkDataArray* after = out->GetPointData()->GetArray("radius");
  Check(after && before && after->GetNumberOfComponents() == before->GetNumberOfComponents(),
    "the radius array keeps its components");
  for (vtkIdType i = 0; after && before && i < n; ++i)
  {
    const Expected& a = atoms[i];
    const double got = after->GetComponent(i, 0), had = before->GetComponent(i, 0);
    bool ok;
    if (a.Radius == -1)
    {
      ok = got == had && got > 0.0; // VTK knew it: kept
    }
    else if (a.Radius == -2)
    {
      ok = got == had; // unknown: left as it was
    }
    else
    {
      ok = (had <= 0.0 || a.Radius == 0.0 ? std::abs(got - a.Radius) < 1e-6 : got == had);
    }
    Check(ok,
      std::string("radius of ") + a.Name + " (" + a.Residue + "): " + std::to_string(got) +
        " (vtkPDBReader: " + std::to_string(had) + ")");
  }
  Check(radii->GetNumberOfVirtualSites() <= 1 && radii->GetNumberOfUnknownElements() == 1,
    "one unknown element, at most one virtual site counted");
  Check(warnings->GetWarning() && warnings->GetWarningMessage().find("XQ") != std::string::npos,
    "a warning names the unknown atom name");

  // Replacing every radius, in nm.
  radii->FillMissingOnlyOff();
  radii->SetLengthUnitsPerNanometer(1.0);
  radii->Update();
  after = radii->GetOutput()->GetPointData()->GetArray("radius");
  Check(
    after && std::abs(after->GetComponent(0, 0) - 0.170) < 1e-6 && after->GetComponent(8, 0) == 0.0,
    "FillMissingOnly off: every radius from the element, in nm (CA 0.17, MW 0)");

  // No atom names: an error, the data passed through.
  vtkNew<vtkAtomRadii> none;
  vtkNew<vtkTest::ErrorObserver> errors;
  none->AddObserver(vtkCommand::ErrorEvent, errors);
  none->SetInputConnection(pdb->GetOutputPort());
  none->SetAtomNameArrayName("no such array");
  none->Update();
  Check(errors->GetError() && none->GetOutput()->GetNumberOfPoints() == n,
    "no atom names: one error, the atoms passed through");
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
