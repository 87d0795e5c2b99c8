// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The radius rule of vtkMetaballField (psBallExtraction.h), against exact
// answers:
// - with nothing named, each array the readers write radii in is found
//   ("Radius", "radius", "SmoothingLength", "SmoothingLengths", "pscale",
//   and half of "diameter"), the first of them when there are several;
// - an explicit choice wins: a named array the input has over the constant
//   and over the arrays found; a positive constant Radius over the arrays
//   found; a named array that is missing is warned about once, and the
//   rules after it apply;
// - the spacing rule: 1.5 times the mean nearest-neighbour spacing, which
//   on a lattice of spacing a is a exactly: with every point repeated
//   (duplicates count once), with NaN and infinite points among them
//   (left out), at an offset of 1e7, and the same to the last bit with one
//   thread and with four; a single point, or all points at one place,
//   give radius 1; the spacing of all processes in the field data
//   (vtkMetaballGhostBalls) is taken instead of measuring;
// - split in two, each half's distances completed by the nearest point of
//   the other (NearestNeighbours::NearestTo, as vtkMetaballGhostBalls does
//   between processes) give the whole set's mean spacing;
// - the spacing is measured once for unchanged points (a change of the
//   coordinates that nobody marked Modified is not seen; marked, it is);
// - the message: once per change of the outcome, as text for automatic
//   choices and as a warning for a missing array, none for explicit ones;
//   the getters (rule, array, spacing, description) say what was chosen.
#include "psBallExtraction.h"
#include "psFiltersTestSupport.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkMetaballField.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace pointsurfaces;

namespace
{
// Counts what the output window is given: text, and warnings apart.
class CaptureOutput : public vtkOutputWindow
{
public:
  static CaptureOutput* New();
  vtkTypeMacro(CaptureOutput, vtkOutputWindow);
  void DisplayText(const char* text) override
  {
    ++this->Texts;
    this->Last = text ? text : "";
    std::cout << "[text] " << this->Last;
  }
  void DisplayWarningText(const char* text) override
  {
    ++this->Warnings;
    this->Last = text ? text : "";
    std::cout << "[warning] " << this->Last;
  }
  void DisplayGenericWarningText(const char* text) override { this->DisplayWarningText(text); }
  void DisplayErrorText(const char* text) override
  {
    ++this->Errors;
    std::cout << "[error] " << (text ? text : "");
  }
  void Reset() { this->Texts = this->Warnings = this->Errors = 0; }
  int Texts = 0, Warnings = 0, Errors = 0;
  std::string Last;
};
vtkStandardNewMacro(CaptureOutput);

// A nx x ny x nz lattice of spacing a from `origin`, each point `copies` times.
vtkSmartPointer<vtkPolyData> Lattice(int nx,
  int ny,
  int nz,
  double a,
  const double origin[3],
  int copies = 1)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (int c = 0; c < copies; ++c)
  {
    for (int z = 0; z < nz; ++z)
    {
      for (int y = 0; y < ny; ++y)
      {
        for (int x = 0; x < nx; ++x)
        {
          points->InsertNextPoint(origin[0] + a * x, origin[1] + a * y, origin[2] + a * z);
        }
      }
    }
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  return poly;
}

// A point array `name` of `value` everywhere on `poly`.
void AddArray(vtkPolyData* poly, const char* name, double value)
{
  vtkNew<vtkFloatArray> a;
  a->SetName(name);
  a->SetNumberOfValues(poly->GetNumberOfPoints());
  a->Fill(value);
  poly->GetPointData()->AddArray(a);
}

bool Near(double a, double b, double relative)
{
  return std::abs(a - b) <= relative * std::abs(b);
}

// Every valid ball's radius is r.
bool AllRadii(const BallArrays& balls, double r, double relative = 1e-12)
{
  bool ok = balls.Set.Count > 0;
  for (long long i = 0; i < balls.Set.Count; ++i)
  {
    ok = ok && (!ValidBall(balls.Set, i) || Near(balls.Set.Radii[i], r, relative));
  }
  return ok;
}
} // namespace

int TestMetaballRadii(int, char*[])
{
  vtkNew<CaptureOutput> output;
  vtkOutputWindow::SetInstance(output);
  const double zero[3] = { 0.0, 0.0, 0.0 };

  // The defaults: nothing named, no constant.
  {
    vtkNew<vtkMetaballField> field;
    BallRule rule;
    Check(std::string(field->GetRadiusArrayName()).empty() && field->GetRadius() == 0.0 &&
        rule.RadiusArrayName.empty() && rule.Radius == 0.0 && field->GetRadiusRule() == -1,
      "defaults: no radius array named, Radius 0 (automatic)");
    Check(vtkMetaballField::GetSpacingRadiusFactor() == 1.5 && SpacingRadiusFactor == 1.5,
      "the automatic radius is 1.5 spacings");
  }

  // Each array the readers write radii in, found; the first of several.
  for (const RadiusArrayCandidate& candidate : AutomaticRadiusArrays)
  {
    auto balls = Lattice(3, 3, 3, 1.0, zero);
    AddArray(balls, "Velocity", 9.0);
    AddArray(balls, candidate.Name, 0.8);
    vtkNew<vtkMetaballField> field;
    field->SetRadiusScale(1.5);
    output->Reset();
    BallArrays b = field->ExtractBalls(balls);
    const std::string what = std::string("the array \"") + candidate.Name + "\" is found";
    Check(AllRadii(b, 1.5 * 0.8 * candidate.Factor, 1e-6), what.c_str());
    Check(field->GetRadiusRule() == vtkMetaballField::FoundRadiusArray &&
        std::string(field->GetChosenRadiusArrayName()) == candidate.Name &&
        b.RadiiFrom.Rule == RadiusRule::FoundArray && b.RadiiFrom.ArrayName == candidate.Name,
      "the getters name the array found");
    Check(output->Texts == 1 && output->Warnings == 0 &&
        output->Last.find(std::string("\"") + candidate.Name + "\"") != std::string::npos &&
        output->Last.find("chosen automatically") != std::string::npos,
      "an array found is told once, as text");
    Check(Near(field->GetLargestRadius(balls), 1.5 * 0.8 * candidate.Factor, 1e-6),
      "the largest radius of an array found");
    // The plain rule, as the particle mesher reads it, agrees.
    BallArrays plain = ExtractBalls(balls, field->GetRule());
    Check(AllRadii(plain, 1.5 * 0.8 * candidate.Factor, 1e-6), "the plain rule finds it too");
  }
  {
    auto balls = Lattice(2, 2, 2, 1.0, zero);
    AddArray(balls, "SmoothingLength", 0.3);
    AddArray(balls, "radius", 0.2);
    vtkNew<vtkMetaballField> field;
    BallArrays b = field->ExtractBalls(balls);
    Check(AllRadii(b, 0.2, 1e-6) && std::string(field->GetChosenRadiusArrayName()) == "radius",
      "of several arrays, the first of the list");
  }

  // Explicit choices win.
  {
    auto balls = Lattice(2, 2, 2, 1.0, zero);
    AddArray(balls, "Radius", 0.4);
    AddArray(balls, "Size", 0.25);
    vtkNew<vtkMetaballField> field;
    field->SetRadiusArrayName("Size");
    field->SetRadius(3.0);
    output->Reset();
    BallArrays named = field->ExtractBalls(balls);
    Check(AllRadii(named, 0.25, 1e-6) &&
        field->GetRadiusRule() == vtkMetaballField::NamedRadiusArray &&
        std::string(field->GetChosenRadiusArrayName()) == "Size",
      "a named array wins over the constant and the arrays found");
    Check(output->Texts == 0 && output->Warnings == 0, "an explicit choice is not told");
    field->SetRadiusArrayName(nullptr);
    BallArrays constant = field->ExtractBalls(balls);
    Check(AllRadii(constant, 3.0) && field->GetRadiusRule() == vtkMetaballField::ConstantRadius &&
        std::string(field->GetChosenRadiusArrayName()).empty(),
      "a positive Radius wins over the arrays found");
    Check(output->Texts == 0 && output->Warnings == 0, "a constant radius is not told");
    Check(field->GetLargestRadius(balls) == 3.0, "the largest radius of the constant");

    // A named array that is missing: a warning, once; the rules after it.
    field->SetRadius(0.0);
    field->SetRadiusArrayName("rad");
    output->Reset();
    BallArrays missing = field->ExtractBalls(balls);
    field->ExtractBalls(balls);
    field->GetLargestRadius(balls);
    Check(missing.MissingRadii && AllRadii(missing, 0.4, 1e-6) &&
        field->GetRadiusRule() == vtkMetaballField::FoundRadiusArray,
      "a missing named array: the array found instead");
    Check(output->Warnings == 1 && output->Texts == 0 &&
        output->Last.find("\"rad\"") != std::string::npos,
      "a missing named array: one warning that names it");
    field->SetRadius(0.5);
    BallArrays missingConstant = field->ExtractBalls(balls);
    Check(AllRadii(missingConstant, 0.5) && output->Warnings == 2,
      "a missing named array and a constant: the constant, warned once more");
  }

  // The spacing rule on a lattice: exact.
  const double a = 0.37;
  {
    auto lattice = Lattice(6, 5, 4, a, zero);
    const NeighbourSpacing s = MeasureSpacing(lattice);
    Check(s.Count == 120 && Near(s.Mean(), a, 1e-12), "lattice: the mean spacing is a");
    vtkNew<vtkMetaballField> field;
    output->Reset();
    BallArrays b = field->ExtractBalls(lattice);
    Check(AllRadii(b, 1.5 * a) && field->GetRadiusRule() == vtkMetaballField::SpacingRadius &&
        Near(field->GetMeanSpacing(), a, 1e-12) &&
        std::string(field->GetChosenRadiusArrayName()).empty(),
      "lattice: radii of 1.5 spacings, and the getters say so");
    const std::string told = output->Last;
    Check(output->Texts == 1 && output->Warnings == 0 &&
        told.find("mean nearest-neighbour spacing") != std::string::npos &&
        told == std::string(field->GetRadiusRuleDescription()) + "\n",
      "lattice: the spacing rule is told once, as the description says");
    std::cout << "description: " << field->GetRadiusRuleDescription() << "\n";
    // Again, and the bounds: neither measured nor told again.
    field->ExtractBalls(lattice);
    Check(Near(field->GetLargestRadius(lattice), 1.5 * a, 1e-12) && output->Texts == 1,
      "lattice: told once per outcome, not once per read");
    // Coordinates changed without Modified(): the spacing kept (not
    // measured again); marked Modified: measured and told again.
    vtkDataArray* xyz = lattice->GetPoints()->GetData();
    for (vtkIdType i = 0; i < xyz->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        xyz->SetComponent(i, c, 2.0 * xyz->GetComponent(i, c));
      }
    }
    BallArrays kept = field->ExtractBalls(lattice);
    Check(AllRadii(kept, 1.5 * a), "the spacing of unchanged points is not measured again");
    lattice->GetPoints()->Modified();
    BallArrays moved = field->ExtractBalls(lattice);
    Check(AllRadii(moved, SpacingRadiusFactor * 2.0 * a) && output->Texts == 2,
      "modified points: measured again, and the new radius told");
    // The plain rule measures by itself.
    BallArrays plain = ExtractBalls(lattice, BallRule());
    Check(
      AllRadii(plain, SpacingRadiusFactor * 2.0 * a) && plain.RadiiFrom.Rule == RadiusRule::Spacing,
      "the plain rule measures the spacing");
    // The radius scale multiplies the automatic radius.
    field->SetRadiusScale(2.0);
    BallArrays scaled = field->ExtractBalls(lattice);
    Check(AllRadii(scaled, 2.0 * SpacingRadiusFactor * 2.0 * a),
      "RadiusScale multiplies the automatic radius");
  }

  // Duplicates count once; NaN and infinite points are left out.
  {
    auto triple = Lattice(5, 4, 3, a, zero, 3);
    const NeighbourSpacing s = MeasureSpacing(triple);
    Check(s.Count == 60 && Near(s.Mean(), a, 1e-12), "duplicates: counted once, spacing a");
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    triple->GetPoints()->InsertNextPoint(nan, 0.0, 0.0);
    triple->GetPoints()->InsertNextPoint(0.0, inf, 0.0);
    triple->GetPoints()->InsertNextPoint(nan, nan, nan);
    const NeighbourSpacing t = MeasureSpacing(triple);
    Check(t.Count == 60 && Near(t.Mean(), a, 1e-12), "NaN and infinite points: left out");
    vtkNew<vtkMetaballField> field;
    BallArrays b = field->ExtractBalls(triple);
    long long invalid = 0;
    for (long long i = 0; i < b.Set.Count; ++i)
    {
      invalid += ValidBall(b.Set, i) ? 0 : 1;
    }
    Check(AllRadii(b, 1.5 * a) && invalid == 3, "NaN points: invalid balls, the rest 1.5 a");
  }

  // One point, or all at one place: nothing to measure, radius 1.
  {
    auto one = Lattice(1, 1, 1, a, zero);
    auto same = Lattice(1, 1, 1, a, zero, 50);
    Check(MeasureSpacing(one).Count == 0 && MeasureSpacing(same).Count == 0 &&
        MeasureSpacing(nullptr, 0).Count == 0 && MeasureSpacing(nullptr).Mean() == 0.0,
      "one point, one place, none: no spacing");
    vtkNew<vtkMetaballField> field;
    output->Reset();
    BallArrays b = field->ExtractBalls(one);
    Check(AllRadii(b, 1.0) && field->GetRadiusRule() == vtkMetaballField::UnitRadius &&
        output->Texts == 1,
      "one point: radius 1, told");
    BallArrays c = field->ExtractBalls(same);
    Check(AllRadii(c, 1.0) && output->Texts == 1, "one place: radius 1, not told twice");
    // No points: nothing told, nothing read.
    vtkNew<vtkPolyData> empty;
    BallArrays d = field->ExtractBalls(empty);
    Check(d.Set.Count == 0 && output->Texts == 1 && output->Errors == 0, "no points: quiet");
  }

  // Coordinates near 1e7.
  {
    const double far[3] = { 1e7, -1e7, 1e7 };
    const double small = 0.01;
    auto lattice = Lattice(8, 8, 8, small, far);
    const NeighbourSpacing s = MeasureSpacing(lattice);
    std::cout << "at 1e7: mean spacing " << s.Mean() << " (exact " << small << ")\n";
    Check(s.Count == 512 && Near(s.Mean(), small, 1e-6), "at 1e7: the spacing to 1e-6");
  }

  // The same to the last bit with one thread and with four.
  {
    std::mt19937 gen(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> xyz(3 * 20000);
    for (double& v : xyz)
    {
      v = u(gen);
    }
    vtkSMPTools::Initialize(1);
    const NeighbourSpacing one = MeasureSpacing(xyz.data(), 20000);
    vtkSMPTools::Initialize(4);
    const NeighbourSpacing four = MeasureSpacing(xyz.data(), 20000);
    vtkSMPTools::Initialize(0);
    std::cout << "random cloud: mean spacing " << one.Mean() << " (" << one.Count << " points)\n";
    Check(one.Count == 20000 && one.Sum == four.Sum && one.Count == four.Count,
      "the spacing does not depend on the number of threads");
    // A uniform random cloud's mean nearest-neighbour distance is
    // 0.554 rho^(-1/3) (0.0408 here), a little more with the cube's faces.
    Check(one.Mean() > 0.04 && one.Mean() < 0.046, "a random cloud's spacing");
  }

  // Split in two, each half's nearest neighbours completed by asking the
  // other half (as vtkMetaballGhostBalls asks other processes): the mean
  // spacing of the whole.
  {
    std::mt19937 gen(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> left, right, all;
    for (int i = 0; i < 3000; ++i)
    {
      const double p[3] = { u(gen), u(gen), u(gen) };
      std::vector<double>& half = p[0] < 0.5 ? left : right;
      half.insert(half.end(), p, p + 3);
      all.insert(all.end(), p, p + 3);
    }
    const NearestNeighbours whole(all.data(), 3000);
    const NearestNeighbours l(left.data(), static_cast<long long>(left.size() / 3));
    const NearestNeighbours r(right.data(), static_cast<long long>(right.size() / 3));
    std::vector<double> dl = l.Distances, dr = r.Distances;
    for (long long i = 0; i < l.Size(); ++i)
    {
      dl[i] = std::min(dl[i], r.NearestTo(l.Point(i)));
    }
    for (long long i = 0; i < r.Size(); ++i)
    {
      dr[i] = std::min(dr[i], l.NearestTo(r.Point(i)));
    }
    const NeighbourSpacing sl = NearestNeighbours::Spacing(dl), sr = NearestNeighbours::Spacing(dr),
                           s = whole.Spacing();
    const double split = (sl.Sum + sr.Sum) / static_cast<double>(sl.Count + sr.Count);
    const double alone = (l.Spacing().Sum + r.Spacing().Sum) /
      static_cast<double>(l.Spacing().Count + r.Spacing().Count);
    std::cout << "split in two: mean spacing " << split << ", whole " << s.Mean()
              << ", halves alone " << alone << "\n";
    Check(sl.Count + sr.Count == s.Count && Near(split, s.Mean(), 1e-12),
      "split: each half asking the other gives the whole's spacing");
    Check(alone > s.Mean(), "split: the halves alone miss neighbours across the cut");
    const double on[3] = { left[0], left[1], left[2] };
    Check(l.NearestTo(on) == l.Distances[0], "a point's own position is not its neighbour");
  }

  // The spacing of all processes, from the field data: taken, not measured.
  {
    auto lattice = Lattice(4, 4, 4, a, zero);
    vtkNew<vtkDoubleArray> spacing;
    spacing->SetName(MeanSpacingArrayName);
    spacing->InsertNextValue(0.5);
    lattice->GetFieldData()->AddArray(spacing);
    vtkNew<vtkMetaballField> field;
    output->Reset();
    BallArrays b = field->ExtractBalls(lattice);
    Check(AllRadii(b, SpacingRadiusFactor * 0.5) && b.RadiiFrom.SpacingOfAllProcesses &&
        field->GetMeanSpacing() == 0.5 &&
        std::string(field->GetRadiusRuleDescription()).find("all processes") != std::string::npos,
      "the spacing of all processes, from the field data");
    // Not positive: measured here instead.
    spacing->SetValue(0, 0.0);
    BallArrays c = ExtractBalls(lattice, BallRule());
    Check(AllRadii(c, 1.5 * a) && !c.RadiiFrom.SpacingOfAllProcesses,
      "a field-data spacing of 0 is not taken");
    AddArray(lattice, "radius", 0.1);
    BallArrays d = field->ExtractBalls(lattice);
    Check(AllRadii(d, 0.1, 1e-6), "a radius array wins over the field-data spacing");
  }

  Check(output->Errors == 0, "no errors");
  vtkOutputWindow::SetInstance(nullptr);
  if (Failures == 0)
  {
    std::cout << "metaball radii: all checks passed\n";
  }
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
