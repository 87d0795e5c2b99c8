// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAtomRadii.h"

#include "psElements.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <map>

vtkStandardNewMacro(vtkAtomRadii);

//------------------------------------------------------------------------------
int vtkAtomRadii::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPointSet* output = vtkPointSet::GetData(outputVector);
  this->NumberOfFilledRadii = this->NumberOfVirtualSites = this->NumberOfUnknownElements = 0;
  output->ShallowCopy(input);
  const vtkIdType n = input->GetNumberOfPoints();
  auto* names = vtkStringArray::SafeDownCast(
    input->GetPointData()->GetAbstractArray(this->AtomNameArrayName.c_str()));
  if (n == 0)
  {
    return 1;
  }
  if (!names)
  {
    vtkErrorMacro(<< "No string array of atom names '" << this->AtomNameArrayName
                  << "': the radii are left as they are.");
    return 1;
  }
  auto* residues = vtkStringArray::SafeDownCast(
    input->GetPointData()->GetAbstractArray(this->ResidueNameArrayName.c_str()));
  vtkDataArray* old = input->GetPointData()->GetArray(this->RadiusArrayName.c_str());
  vtkSmartPointer<vtkDataArray> radius;
  if (old)
  {
    radius.TakeReference(old->NewInstance());
    radius->DeepCopy(old);
  }
  else
  {
    radius = vtkSmartPointer<vtkDoubleArray>::New();
    radius->SetName(this->RadiusArrayName.c_str());
    radius->SetNumberOfTuples(n);
    radius->Fill(0.0);
  }
  std::map<std::string, vtkIdType> unknown;
  const int components = radius->GetNumberOfComponents();
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (this->FillMissingOnly && radius->GetComponent(i, 0) > 0.0)
    {
      continue;
    }
    const std::string& name = names->GetValue(i);
    double r = 0.0;
    if (pointsurfaces::IsVirtualSite(name))
    {
      ++this->NumberOfVirtualSites;
    }
    else
    {
      const std::string element =
        pointsurfaces::ElementFromAtomName(name, residues ? residues->GetValue(i) : "");
      r = pointsurfaces::VanDerWaalsRadius(element) * this->LengthUnitsPerNanometer;
      if (r > 0.0)
      {
        ++this->NumberOfFilledRadii;
      }
      else
      {
        ++unknown[name];
        ++this->NumberOfUnknownElements;
        continue; // left as it was
      }
    }
    for (int c = 0; c < components; ++c)
    {
      radius->SetComponent(i, c, r);
    }
  }
  output->GetPointData()->AddArray(radius);
  if (!unknown.empty())
  {
    vtkWarningMacro(<< "No element with a radius for " << this->NumberOfUnknownElements
                    << " atoms, named like '" << unknown.begin()->first << "' (" << unknown.size()
                    << " names in all): their radius is left as it was.");
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkAtomRadii::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "AtomNameArrayName: " << this->AtomNameArrayName << "\n";
  os << indent << "ResidueNameArrayName: " << this->ResidueNameArrayName << "\n";
  os << indent << "RadiusArrayName: " << this->RadiusArrayName << "\n";
  os << indent << "LengthUnitsPerNanometer: " << this->LengthUnitsPerNanometer << "\n";
  os << indent << "FillMissingOnly: " << this->FillMissingOnly << "\n";
}
