// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMetaballField.h"

#include "vtkObjectFactory.h"
#include "vtkPointSet.h"

vtkStandardNewMacro(vtkMetaballField);

//------------------------------------------------------------------------------
void vtkMetaballField::DeepCopy(vtkMetaballField* other)
{
  if (!other || other == this)
  {
    return;
  }
  this->SetKernel(other->Kernel);
  this->SetThreshold(other->Threshold);
  this->SetRadiusArrayName(other->RadiusArrayName.c_str());
  this->SetRadius(other->Radius);
  this->SetRadiusScale(other->RadiusScale);
  this->SetStrengthArrayName(other->StrengthArrayName.c_str());
  this->SetDensityArrayName(other->DensityArrayName.c_str());
}

//------------------------------------------------------------------------------
void vtkMetaballField::Assign(vtkSmartPointer<vtkMetaballField>& slot,
  vtkMetaballField* field,
  vtkObject* owner)
{
  if (slot && slot == field)
  {
    return;
  }
  slot =
    field ? vtkSmartPointer<vtkMetaballField>(field) : vtkSmartPointer<vtkMetaballField>::New();
  if (owner)
  {
    owner->Modified();
  }
}

//------------------------------------------------------------------------------
pointsurfaces::BallRule vtkMetaballField::GetRule() const
{
  pointsurfaces::BallRule rule;
  rule.Kernel = static_cast<pointsurfaces::MetaballKernel>(this->Kernel);
  rule.Threshold = this->Threshold;
  rule.RadiusArrayName = this->RadiusArrayName;
  rule.Radius = this->Radius;
  rule.RadiusScale = this->RadiusScale;
  rule.StrengthArrayName = this->StrengthArrayName;
  rule.DensityArrayName = this->DensityArrayName;
  return rule;
}

//------------------------------------------------------------------------------
pointsurfaces::BallArrays vtkMetaballField::ExtractBalls(vtkPointSet* input, double scale) const
{
  return pointsurfaces::ExtractBalls(input, this->GetRule(), scale);
}

//------------------------------------------------------------------------------
void vtkMetaballField::ExtractBalls(vtkPointSet* input,
  double scale,
  pointsurfaces::BallArrays& out) const
{
  pointsurfaces::ExtractBalls(input, this->GetRule(), scale, out);
}

//------------------------------------------------------------------------------
double vtkMetaballField::GetLargestRadius(vtkPointSet* input)
{
  return pointsurfaces::LargestSupportRadius(input, this->GetRule());
}

//------------------------------------------------------------------------------
void vtkMetaballField::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Kernel: " << this->Kernel << "\n";
  os << indent << "Threshold: " << this->Threshold << "\n";
  os << indent << "RadiusArrayName: " << this->RadiusArrayName << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "RadiusScale: " << this->RadiusScale << "\n";
  os << indent << "StrengthArrayName: " << this->StrengthArrayName << "\n";
  os << indent << "DensityArrayName: " << this->DensityArrayName << "\n";
}
