// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psBallExtraction.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"

#include <cmath>
#include <limits>

namespace pointsurfaces
{
//------------------------------------------------------------------------------
vtkDataArray* RadiusArray(vtkPointSet* input, const BallRule& rule)
{
  vtkPointData* pd = input ? input->GetPointData() : nullptr;
  return pd && !rule.RadiusArrayName.empty() ? pd->GetArray(rule.RadiusArrayName.c_str()) : nullptr;
}

//------------------------------------------------------------------------------
vtkDataArray* StrengthArray(vtkPointSet* input, const BallRule& rule)
{
  vtkPointData* pd = input ? input->GetPointData() : nullptr;
  return pd && !rule.StrengthArrayName.empty() ? pd->GetArray(rule.StrengthArrayName.c_str())
                                               : nullptr;
}

//------------------------------------------------------------------------------
double SupportRadius(vtkDataArray* radii, long long i, const BallRule& rule)
{
  return rule.RadiusScale * (radii ? radii->GetComponent(i, 0) : rule.Radius);
}

//------------------------------------------------------------------------------
double LargestSupportRadius(vtkPointSet* input, const BallRule& rule)
{
  vtkDataArray* radii = RadiusArray(input, rule);
  if (!radii)
  {
    return rule.Radius * rule.RadiusScale;
  }
  double range[2];
  radii->GetRange(range, 0);
  return std::isfinite(range[1]) ? range[1] * rule.RadiusScale : 0.0;
}

//------------------------------------------------------------------------------
BallArrays ExtractBalls(vtkPointSet* input, const BallRule& rule, double scale)
{
  BallArrays b;
  ExtractBalls(input, rule, scale, b);
  return b;
}

//------------------------------------------------------------------------------
void ExtractBalls(vtkPointSet* input, const BallRule& rule, double scale, BallArrays& b)
{
  b.MissingStrengths = b.MissingRadii = false;
  b.MissingDensityName.clear();
  const vtkIdType n = input && input->GetPoints() ? input->GetNumberOfPoints() : 0;
  vtkDataArray* radii = RadiusArray(input, rule);
  vtkDataArray* strengths = StrengthArray(input, rule);
  vtkPointData* pd = input ? input->GetPointData() : nullptr;
  vtkDataArray* densities =
    pd && !rule.DensityArrayName.empty() ? pd->GetArray(rule.DensityArrayName.c_str()) : nullptr;
  if (!rule.DensityArrayName.empty() && !densities && n > 0)
  {
    b.MissingDensityName = rule.DensityArrayName;
  }
  const double normalization = KernelNormalization(rule.Kernel);
  const bool weighted = strengths || densities || normalization > 0.0;
  b.MissingRadii = !rule.RadiusArrayName.empty() && !radii && n > 0;
  b.MissingStrengths = !rule.StrengthArrayName.empty() && !strengths;
  b.Centres.resize(3 * static_cast<size_t>(n));
  b.Radii.resize(static_cast<size_t>(n));
  if (weighted)
  {
    b.Strengths.resize(static_cast<size_t>(n));
  }
  vtkDataArray* points = n ? input->GetPoints()->GetData() : nullptr;
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        points->GetTuple(i, &b.Centres[3 * i]);
        b.Radii[i] = scale * SupportRadius(radii, i, rule);
        if (weighted)
        {
          // A zero, negative or NaN density, or a zero radius, gives a
          // non-finite strength or radius: the ball is invalid, skipped and
          // counted.
          double q = strengths ? strengths->GetComponent(i, 0) : 1.0;
          if (densities)
          {
            const double rho = densities->GetComponent(i, 0);
            q = rho > 0.0 ? q / rho : std::numeric_limits<double>::quiet_NaN();
          }
          if (normalization > 0.0)
          {
            // The data's radius, not the actor-scaled one: the field keeps
            // its values (density units) when the actor is scaled.
            const double r = SupportRadius(radii, i, rule);
            q *= normalization / (r * r * r);
          }
          b.Strengths[i] = q;
        }
      }
    });
  b.Set.Centers = b.Centres.data();
  b.Set.Radii = b.Radii.data();
  b.Set.Strengths = weighted ? b.Strengths.data() : nullptr;
  b.Set.Count = n;
  b.Set.Kernel = rule.Kernel;
  b.Set.Threshold = rule.Threshold;
}

//------------------------------------------------------------------------------
std::string MissingStrengthsWarning(const BallArrays& balls, const std::string& strengthName)
{
  std::string warning = balls.MissingStrengths
    ? "No point array \"" + strengthName + "\" for the strengths: all balls have strength 1."
    : std::string();
  if (!balls.MissingDensityName.empty())
  {
    warning += std::string(warning.empty() ? "" : " ") + "No point array \"" +
      balls.MissingDensityName + "\" for the densities: the strengths are not divided by one.";
  }
  return warning;
}

//------------------------------------------------------------------------------
std::string InvalidBallsWarning(long long invalid, long long count)
{
  return invalid > 0 ? std::to_string(invalid) + " of " + std::to_string(count) +
      " balls have a NaN or infinite centre, radius or strength, or a radius <= 0: they are "
      "skipped."
                     : std::string();
}
} // namespace pointsurfaces
