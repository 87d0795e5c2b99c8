// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psBallExtraction.h"

#include "psPointIndex.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace pointsurfaces
{
namespace
{
// A point array of `input` by name, or null.
vtkDataArray* PointArray(vtkPointSet* input, const std::string& name)
{
  vtkPointData* pd = input ? input->GetPointData() : nullptr;
  return pd && !name.empty() ? pd->GetArray(name.c_str()) : nullptr;
}

// The positive, finite mean spacing the input's field data carries, or 0.
double FieldDataSpacing(vtkPointSet* input)
{
  vtkFieldData* fd = input ? input->GetFieldData() : nullptr;
  vtkDataArray* a = fd ? fd->GetArray(MeanSpacingArrayName) : nullptr;
  const double s = a && a->GetNumberOfTuples() > 0 ? a->GetComponent(0, 0) : 0.0;
  return std::isfinite(s) && s > 0.0 ? s : 0.0;
}

// A number for messages: six significant digits.
std::string Number(double x)
{
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}
} // namespace

//------------------------------------------------------------------------------
double RadiusSource::SupportRadius(long long i) const
{
  return this->RadiusScale *
    (this->Array ? this->ArrayFactor * this->Array->GetComponent(i, 0) : this->Radius);
}

//------------------------------------------------------------------------------
NearestNeighbours::NearestNeighbours(const double* xyz, long long n)
{
  // Finite points only, then each distinct position once.
  std::vector<double> finite;
  finite.reserve(3 * static_cast<size_t>(n > 0 ? n : 0));
  for (long long i = 0; i < n; ++i)
  {
    const double* p = xyz + 3 * i;
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
    {
      finite.insert(finite.end(), p, p + 3);
    }
  }
  const std::vector<long long> kept =
    UniquePoints(finite.data(), static_cast<long long>(finite.size() / 3), 0.0);
  const long long k = static_cast<long long>(kept.size());
  this->Points.resize(3 * static_cast<size_t>(k));
  for (long long j = 0; j < k; ++j)
  {
    for (int c = 0; c < 3; ++c)
    {
      this->Points[3 * j + c] = finite[3 * kept[j] + c];
    }
  }
  finite = std::vector<double>();
  this->Index.reset(new PointIndex(this->Points.data(), k));
  this->Distances.assign(static_cast<size_t>(k), std::numeric_limits<double>::infinity());
  if (k < 2)
  {
    return;
  }
  vtkSMPTools::For(0,
    k,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType j = begin; j < end; ++j)
      {
        this->Distances[j] = this->NearestTo(this->Point(j));
      }
    });
}

//------------------------------------------------------------------------------
NearestNeighbours::~NearestNeighbours() = default;

//------------------------------------------------------------------------------
double NearestNeighbours::NearestTo(const double q[3]) const
{
  // The points are distinct: at most one is at distance 0 (q itself, or its
  // copy on another process), so the nearest other is among the first two.
  // Near-coincident points may come back in either order from the float
  // tree; PointIndex gives their distances in double.
  thread_local std::vector<int> ids;
  thread_local std::vector<double> d2;
  this->Index->Nearest(q, 2, ids, d2);
  double best = std::numeric_limits<double>::infinity();
  for (double e : d2)
  {
    if (e > 0.0 && e < best)
    {
      best = e;
    }
  }
  return std::sqrt(best);
}

//------------------------------------------------------------------------------
NeighbourSpacing NearestNeighbours::Spacing(const std::vector<double>& distances)
{
  // Summed in point order: the same sum for any number of threads.
  NeighbourSpacing result;
  for (double d : distances)
  {
    if (std::isfinite(d))
    {
      result.Sum += d;
      ++result.Count;
    }
  }
  return result;
}

//------------------------------------------------------------------------------
NeighbourSpacing MeasureSpacing(const double* xyz, long long n)
{
  return NearestNeighbours(xyz, n).Spacing();
}

//------------------------------------------------------------------------------
NeighbourSpacing MeasureSpacing(vtkPointSet* input)
{
  vtkPoints* points = input ? input->GetPoints() : nullptr;
  const vtkIdType n = points ? points->GetNumberOfPoints() : 0;
  std::vector<double> xyz(3 * static_cast<size_t>(n));
  vtkDataArray* data = n ? points->GetData() : nullptr;
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        data->GetTuple(i, &xyz[3 * i]);
      }
    });
  return MeasureSpacing(xyz.data(), n);
}

//------------------------------------------------------------------------------
vtkDataArray* StrengthArray(vtkPointSet* input, const BallRule& rule)
{
  return PointArray(input, rule.StrengthArrayName);
}

//------------------------------------------------------------------------------
vtkDataArray* RadiusArray(vtkPointSet* input, const BallRule& rule)
{
  return ChooseRadii(input, rule).Array;
}

//------------------------------------------------------------------------------
RadiusSource ChooseRadii(vtkPointSet* input, const BallRule& rule)
{
  RadiusSource source;
  source.RadiusScale = rule.RadiusScale;
  if (!rule.RadiusArrayName.empty())
  {
    source.Array = PointArray(input, rule.RadiusArrayName);
    if (source.Array)
    {
      source.Rule = RadiusRule::NamedArray;
      source.ArrayName = rule.RadiusArrayName;
      return source;
    }
    source.MissingArrayName = rule.RadiusArrayName;
  }
  if (std::isfinite(rule.Radius) && rule.Radius > 0.0)
  {
    source.Rule = RadiusRule::Constant;
    source.Radius = rule.Radius;
    return source;
  }
  for (const RadiusArrayCandidate& candidate : AutomaticRadiusArrays)
  {
    source.Array = PointArray(input, candidate.Name);
    if (source.Array)
    {
      source.Rule = RadiusRule::FoundArray;
      source.ArrayName = candidate.Name;
      source.ArrayFactor = candidate.Factor;
      return source;
    }
  }
  source.Rule = RadiusRule::Spacing;
  source.Radius = 0.0;
  const double spacing = FieldDataSpacing(input);
  if (spacing > 0.0)
  {
    ApplySpacing(source, spacing, true);
  }
  return source;
}

//------------------------------------------------------------------------------
void ApplySpacing(RadiusChoice& choice, double spacing, bool ofAllProcesses)
{
  if (choice.Rule != RadiusRule::Spacing && choice.Rule != RadiusRule::Unit)
  {
    return;
  }
  if (std::isfinite(spacing) && spacing > 0.0 && std::isfinite(SpacingRadiusFactor * spacing))
  {
    choice.Rule = RadiusRule::Spacing;
    choice.Spacing = spacing;
    choice.SpacingOfAllProcesses = ofAllProcesses;
    choice.Radius = SpacingRadiusFactor * spacing;
  }
  else
  {
    choice.Rule = RadiusRule::Unit;
    choice.Spacing = 0.0;
    choice.SpacingOfAllProcesses = ofAllProcesses;
    choice.Radius = 1.0;
  }
}

//------------------------------------------------------------------------------
RadiusSource ResolveRadii(vtkPointSet* input, const BallRule& rule)
{
  RadiusSource source = ChooseRadii(input, rule);
  if (NeedsSpacing(source))
  {
    ApplySpacing(source, MeasureSpacing(input).Mean(), false);
  }
  return source;
}

//------------------------------------------------------------------------------
double LargestSupportRadius(vtkPointSet* input, const RadiusSource& source)
{
  vtkDataArray* radii = input ? source.Array : nullptr;
  if (!radii)
  {
    const double r = source.Radius * source.RadiusScale;
    return std::isfinite(r) ? r : 0.0;
  }
  double range[2];
  radii->GetRange(range, 0);
  const double r = range[1] * source.ArrayFactor * source.RadiusScale;
  return std::isfinite(r) ? r : 0.0;
}

//------------------------------------------------------------------------------
double LargestSupportRadius(vtkPointSet* input, const BallRule& rule)
{
  return LargestSupportRadius(input, ResolveRadii(input, rule));
}

//------------------------------------------------------------------------------
std::string RadiusRuleDescription(const RadiusChoice& choice)
{
  const std::string choose = "set RadiusArrayName or Radius to choose";
  std::string text = "Metaball radii: ";
  if (!choice.MissingArrayName.empty())
  {
    text += "no point array \"" + choice.MissingArrayName + "\" (RadiusArrayName), so ";
  }
  switch (choice.Rule)
  {
    case RadiusRule::NamedArray:
      text += "point array \"" + choice.ArrayName + "\" (RadiusArrayName)";
      break;
    case RadiusRule::Constant:
      text += "the constant Radius " + Number(choice.Radius);
      break;
    case RadiusRule::FoundArray:
    {
      // The candidates as AutomaticRadiusArrays lists them.
      std::string candidates;
      const size_t count = sizeof(AutomaticRadiusArrays) / sizeof(AutomaticRadiusArrays[0]);
      for (size_t k = 0; k < count; ++k)
      {
        const RadiusArrayCandidate& c = AutomaticRadiusArrays[k];
        candidates += (k == 0              ? ""
                          : k + 1 == count ? " and "
                                           : ", ") +
          std::string("\"") + c.Name + "\"" +
          (c.Factor != 1.0 ? " x " + Number(c.Factor) : std::string());
      }
      text += "point array \"" + choice.ArrayName + "\"" +
        (choice.ArrayFactor != 1.0 ? " x " + Number(choice.ArrayFactor) : std::string()) +
        " (chosen automatically, the first of " + candidates + " present; " + choose + ")";
      break;
    }
    case RadiusRule::Spacing:
      text += Number(SpacingRadiusFactor) + " x the mean nearest-neighbour spacing" +
        (choice.SpacingOfAllProcesses ? " of all processes' balls " : " ") +
        Number(choice.Spacing) + " = " + Number(choice.Radius) + " (no radius array; " + choose +
        ")";
      break;
    case RadiusRule::Unit:
      text += "1 (no radius array, and fewer than two distinct finite points to measure a "
              "spacing; " +
        choose + ")";
      break;
  }
  if (choice.RadiusScale != 1.0)
  {
    text += ", times RadiusScale " + Number(choice.RadiusScale);
  }
  return text + ".";
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
  ExtractBalls(input, rule, ResolveRadii(input, rule), scale, b);
}

//------------------------------------------------------------------------------
void ExtractBalls(vtkPointSet* input,
  const BallRule& rule,
  const RadiusSource& source,
  double scale,
  BallArrays& b)
{
  b.MissingStrengths = b.MissingRadii = false;
  b.MissingDensityName.clear();
  b.RadiiFrom = source;
  const vtkIdType n = input && input->GetPoints() ? input->GetNumberOfPoints() : 0;
  vtkDataArray* strengths = StrengthArray(input, rule);
  vtkDataArray* densities = PointArray(input, rule.DensityArrayName);
  if (!rule.DensityArrayName.empty() && !densities && n > 0)
  {
    b.MissingDensityName = rule.DensityArrayName;
  }
  const double normalization = KernelNormalization(rule.Kernel);
  const bool weighted = strengths || densities || normalization > 0.0;
  b.MissingRadii = !source.MissingArrayName.empty() && n > 0;
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
        const double r = source.SupportRadius(i);
        b.Radii[i] = scale * r;
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
