// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The SPH kernels as simulation codes define them, through vtkMetaballField
// (the rule every metaball class reads balls by):
// - a cubic lattice of spacing a and particle mass m, with support radii
//   (Gadget's smoothing lengths) of 2a for the cubic spline (33 neighbours,
//   Gadget's usual count), 3a for Wendland C2 and 4a for C4 (the larger
//   neighbour counts those kernels need: W. Dehnen and H. Aly 2012, MNRAS
//   425, 1068): the field at a lattice point inside is the SPH density
//   m / a^3 within 1 %, and with the densities as DensityArrayName
//   (weights m / rho) it is 1;
// - SWIFT's convention (support = gamma h): RadiusScale = SWIFTSupportFactor
//   gives the same density from SWIFT's smaller h;
// - the surface: a ball of lattice particles of radius 8a, threshold half the
//   density, has its iso-surface within a/2 of that radius (the reference ray
//   caster), and the mapper's CPU ray caster finds it where the reference
//   does, within 1e-3 a;
// - bad input: a zero or negative density makes its ball invalid; a missing
//   density array is warned about and ignored; an actor's scale enlarges the
//   supports but leaves the normalisation (and so the densities) alone.
#include "psFiltersTestSupport.h"
#include "psMetaball.h"
#include "psMetaballCast.h"
#include "vtkDoubleArray.h"
#include "vtkMetaballField.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <vector>

using namespace pointsurfaces;

namespace
{
// Lattice particles of spacing 1 within `radius` of the origin (a cube when
// radius <= 0, of half-width `half`), mass `mass`, smoothing length `h`,
// density `rho`.
vtkNew<vtkPolyData> Lattice(int half, double radius, double mass, double h, double rho)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> masses, lengths, densities;
  masses->SetName("Masses");
  lengths->SetName("SmoothingLength");
  densities->SetName("Density");
  for (int z = -half; z <= half; ++z)
  {
    for (int y = -half; y <= half; ++y)
    {
      for (int x = -half; x <= half; ++x)
      {
        if (radius > 0.0 && x * x + y * y + z * z > radius * radius)
        {
          continue;
        }
        points->InsertNextPoint(x, y, z);
        masses->InsertNextValue(mass);
        lengths->InsertNextValue(h);
        densities->InsertNextValue(rho);
      }
    }
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->GetPointData()->AddArray(masses);
  poly->GetPointData()->AddArray(lengths);
  poly->GetPointData()->AddArray(densities);
  return poly;
}
} // namespace

int TestSPHDensity(int, char*[])
{
  const int sph[3] = {
    vtkMetaballField::CubicSpline, vtkMetaballField::WendlandC2, vtkMetaballField::WendlandC4
  };
  const char* names[3] = { "cubic spline", "Wendland C2", "Wendland C4" };
  const double mass = 2.5, origin[3] = { 0.0, 0.0, 0.0 };
  const double support[3] = { 2.0, 3.0, 4.0 };
  for (int k = 0; k < 3; ++k)
  {
    vtkNew<vtkMetaballField> field;
    field->SetKernel(sph[k]);
    field->SetRadiusArrayName("SmoothingLength");
    field->SetStrengthArrayName("Masses");
    // Gadget: h is the support radius.
    auto gadget = Lattice(5, 0.0, mass, support[k], mass);
    BallArrays balls = field->ExtractBalls(gadget);
    const double density = FieldValue(balls.Set, origin) + balls.Set.Threshold;
    // m / rho weights: the SPH interpolant of 1.
    field->SetDensityArrayName("Density");
    BallArrays weighted = field->ExtractBalls(gadget);
    const double unity = FieldValue(weighted.Set, origin) + weighted.Set.Threshold;
    field->SetDensityArrayName("");
    // SWIFT: h is smaller by gamma; RadiusScale restores the support.
    const double gamma = SWIFTSupportFactor(static_cast<MetaballKernel>(sph[k]));
    auto swift = Lattice(5, 0.0, mass, support[k] / gamma, mass);
    field->SetRadiusScale(gamma);
    BallArrays swiftBalls = field->ExtractBalls(swift);
    const double swiftDensity = FieldValue(swiftBalls.Set, origin) + swiftBalls.Set.Threshold;
    field->SetRadiusScale(1.0);
    std::cout << names[k] << ": lattice density " << density << " (exact " << mass
              << "), m/rho sum " << unity << ", with SWIFT's h " << swiftDensity << "\n";
    Check(std::abs(density / mass - 1.0) < 0.01, "the SPH density of a lattice");
    Check(std::abs(unity - 1.0) < 0.01, "m / rho weights sum to 1");
    Check(std::abs(swiftDensity - density) < 1e-9 * mass, "SWIFT's h with its gamma");

    // The surface of a ball of particles at half the density: its radius.
    const double radius = 8.0;
    auto sphere = Lattice(10, radius, mass, support[k], mass);
    field->SetThreshold(0.5 * mass);
    BallArrays ball = field->ExtractBalls(sphere);
    double worst = 0.0;
    const double directions[4][3] = {
      { 1, 0, 0 }, { 0, 0.6, 0.8 }, { 0.577350269, 0.577350269, 0.577350269 }, { -0.8, 0.6, 0 }
    };
    for (const auto& d : directions)
    {
      const double start[3] = { -14 * d[0], -14 * d[1], -14 * d[2] };
      const RayHit hit = CastRay(ball.Set, start, d, 0.0, 14.0, 0.01, 40);
      const double r = std::sqrt(
        hit.Point[0] * hit.Point[0] + hit.Point[1] * hit.Point[1] + hit.Point[2] * hit.Point[2]);
      worst = std::max(worst, hit.Hit ? std::abs(r - radius) : 1e9);
    }
    // The mapper's CPU ray caster, through the same balls (float), down the z axis.
    std::vector<float> floats;
    std::vector<float> strengths;
    for (long long i = 0; i < ball.Set.Count; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        floats.push_back(static_cast<float>(ball.Set.Centers[3 * i + c]));
      }
      floats.back() -= 30.0f; // 30 in front of the eye
      floats.push_back(static_cast<float>(ball.Set.Radii[i]));
      strengths.push_back(static_cast<float>(ball.Set.Strengths[i]));
    }
    MetaballCastInput in;
    in.Balls = floats.data();
    in.Strengths = strengths.data();
    in.Count = ball.Set.Count;
    in.Kernel = static_cast<MetaballKernel>(sph[k]);
    in.Threshold = 0.5 * mass;
    MetaballCastSettings s;
    for (int e = 0; e < 16; ++e)
    {
      s.WorldToView[e] = s.ViewToClip[e] = s.ClipToView[e] = (e % 5 == 0) ? 1.0 : 0.0;
    }
    // Parallel projection of a 24 x 24 window, depth 1 to 60.
    s.ViewToClip[0] = s.ViewToClip[5] = 1.0 / 12.0;
    s.ViewToClip[10] = -2.0 / 59.0;
    s.ViewToClip[11] = -61.0 / 59.0;
    s.ClipToView[0] = s.ClipToView[5] = 12.0;
    s.ClipToView[10] = -59.0 / 2.0;
    s.ClipToView[11] = -61.0 / 2.0;
    s.Parallel = true;
    s.Width = s.Height = 16;
    MetaballCastImages images;
    CastMetaballs(in, s, images, nullptr);
    const int centre = 8 * 16 + 8; // the pixel at (0.75, 0.75)
    const float distance = images.NormalDistance[4 * centre + 3];
    const double down[3] = { 0.0, 0.0, -1.0 }, above[3] = { 0.75, 0.75, 14.0 };
    const RayHit reference = CastRay(ball.Set, above, down, 0.0, 14.0, 0.01, 40);
    const double expected = 16.0 + reference.T; // the view distance of the reference's hit
    std::cout << "  surface of a ball of radius 8: largest radial error " << worst
              << " (reference); the CPU caster is off the reference by " << distance - expected
              << "\n";
    Check(worst < 0.5, "the half-density surface of a ball of particles is at its radius");
    Check(
      reference.Hit && (images.Color[centre] >> 24) != 0 && std::abs(distance - expected) < 1e-3,
      "the CPU caster finds the SPH surface");
  }

  // Bad input: a zero density, a missing density array.
  {
    vtkNew<vtkMetaballField> field;
    field->SetKernel(vtkMetaballField::CubicSpline);
    field->SetRadiusArrayName("SmoothingLength");
    field->SetStrengthArrayName("Masses");
    field->SetDensityArrayName("Density");
    auto lattice = Lattice(1, 0.0, 1.0, 2.0, 1.0);
    vtkDoubleArray::SafeDownCast(lattice->GetPointData()->GetArray("Density"))->SetValue(3, 0.0);
    BallArrays balls = field->ExtractBalls(lattice);
    long long valid = 0;
    for (long long i = 0; i < balls.Set.Count; ++i)
    {
      valid += ValidBall(balls.Set, i);
    }
    Check(valid == balls.Set.Count - 1 && !ValidBall(balls.Set, 3), "a zero density: invalid");
    vtkDoubleArray::SafeDownCast(lattice->GetPointData()->GetArray("Density"))->SetValue(5, -2.0);
    BallArrays negative = field->ExtractBalls(lattice);
    Check(!ValidBall(negative.Set, 5), "a negative density: invalid");
    // An actor's scale enlarges the supports, not the field's values.
    field->SetDensityArrayName("");
    BallArrays plain = field->ExtractBalls(lattice), scaled = field->ExtractBalls(lattice, 2.0);
    Check(scaled.Set.Radii[0] == 2.0 * plain.Set.Radii[0] &&
        scaled.Set.Strengths[0] == plain.Set.Strengths[0],
      "the SPH normalisation uses the data's radius, not the actor-scaled one");
    field->SetDensityArrayName("Density");
    field->SetDensityArrayName("rho");
    BallArrays missing = field->ExtractBalls(lattice);
    const std::string warning = MissingStrengthsWarning(missing, "Masses");
    std::cout << "missing density: " << warning << "\n";
    Check(warning.find("\"rho\"") != std::string::npos, "a missing density array is named");
  }

  if (Failures == 0)
  {
    std::cout << "SPH density: all checks passed\n";
  }
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
