// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMetaballField.h"

#include "vtkObjectFactory.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"

#include "psMetaball.h"

#include <cmath>

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
double vtkMetaballField::EvaluateKernel(int kernel, double x)
{
  return pointsurfaces::KernelValue(static_cast<pointsurfaces::MetaballKernel>(kernel), x);
}

//------------------------------------------------------------------------------
double vtkMetaballField::EvaluateKernelDerivative(int kernel, double x)
{
  double derivative = 0.0;
  pointsurfaces::KernelValue(static_cast<pointsurfaces::MetaballKernel>(kernel), x, &derivative);
  return derivative;
}

//------------------------------------------------------------------------------
pointsurfaces::BallRule vtkMetaballField::GetRule() const
{
  pointsurfaces::BallRule rule;
  rule.Kernel = this->GetKernelId();
  rule.Threshold = this->Threshold;
  rule.RadiusArrayName = this->RadiusArrayName;
  rule.Radius = this->Radius;
  rule.RadiusScale = this->RadiusScale;
  rule.StrengthArrayName = this->StrengthArrayName;
  rule.DensityArrayName = this->DensityArrayName;
  return rule;
}

//------------------------------------------------------------------------------
double vtkMetaballField::GetSpacingRadiusFactor()
{
  return pointsurfaces::SpacingRadiusFactor;
}

//------------------------------------------------------------------------------
pointsurfaces::RadiusSource vtkMetaballField::ChooseRadii(vtkPointSet* input)
{
  pointsurfaces::RadiusSource source = pointsurfaces::ChooseRadii(input, this->GetRule());
  if (pointsurfaces::NeedsSpacing(source))
  {
    vtkPoints* points = input ? input->GetPoints() : nullptr;
    const vtkMTimeType time = points ? points->GetMTime() : 0;
    if (!points || points != this->MeasuredPoints || time != this->MeasuredTime)
    {
      this->MeasuredSpacing = pointsurfaces::MeasureSpacing(input).Mean();
      this->MeasuredPoints = points;
      this->MeasuredTime = time;
    }
    pointsurfaces::ApplySpacing(source, this->MeasuredSpacing, false);
  }
  if (input && input->GetNumberOfPoints() > 0)
  {
    this->ReportRadii(source);
  }
  return source;
}

//------------------------------------------------------------------------------
void vtkMetaballField::ReportRadii(const pointsurfaces::RadiusChoice& choice)
{
  using Rule = pointsurfaces::RadiusRule;
  this->RadiusRule = static_cast<int>(choice.Rule);
  this->ChosenRadiusArrayName = choice.ArrayName;
  this->MeanSpacing = choice.Rule == Rule::Spacing ? choice.Spacing : 0.0;
  this->RadiusRuleDescription = pointsurfaces::RadiusRuleDescription(choice);

  // Told once per outcome: the rule, its array and a missing array; an
  // automatic radius again only when it moved by more than 10 % (a time
  // series' spacing changes a little every step).
  const std::string outcome =
    std::to_string(this->RadiusRule) + "|" + choice.ArrayName + "|" + choice.MissingArrayName;
  const bool moved = choice.Rule != Rule::NamedArray && choice.Rule != Rule::FoundArray &&
    !(std::abs(choice.Radius - this->ToldRadius) <= 0.1 * std::abs(this->ToldRadius));
  if (outcome == this->ToldOutcome && !moved)
  {
    return;
  }
  this->ToldOutcome = outcome;
  this->ToldRadius = choice.Radius;
  if (!choice.MissingArrayName.empty())
  {
    vtkWarningMacro(<< this->RadiusRuleDescription);
  }
  else if (choice.Rule != Rule::NamedArray && choice.Rule != Rule::Constant)
  {
    // Automatic: information, not a warning.
    vtkOutputWindowDisplayText((this->RadiusRuleDescription + "\n").c_str());
  }
}

//------------------------------------------------------------------------------
pointsurfaces::BallArrays vtkMetaballField::ExtractBalls(vtkPointSet* input, double scale)
{
  pointsurfaces::BallArrays balls;
  this->ExtractBalls(input, scale, balls);
  return balls;
}

//------------------------------------------------------------------------------
void vtkMetaballField::ExtractBalls(vtkPointSet* input,
  double scale,
  pointsurfaces::BallArrays& out)
{
  const pointsurfaces::RadiusSource source = this->ChooseRadii(input);
  pointsurfaces::ExtractBalls(input, this->GetRule(), source, scale, out);
}

//------------------------------------------------------------------------------
double vtkMetaballField::GetLargestRadius(vtkPointSet* input)
{
  return pointsurfaces::LargestSupportRadius(input, this->ChooseRadii(input));
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
  os << indent << "RadiusRule: " << this->RadiusRule << "\n";
  os << indent << "ChosenRadiusArrayName: " << this->ChosenRadiusArrayName << "\n";
  os << indent << "MeanSpacing: " << this->MeanSpacing << "\n";
  os << indent << "RadiusRuleDescription: " << this->RadiusRuleDescription << "\n";
}
