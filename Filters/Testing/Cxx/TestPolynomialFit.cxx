// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the plain numerics in Filters/Core: monomial order, exact
// recovery of polynomials of degree 1-4, invariance under offsets of 1e7 and
// scales of 1e-6 and 1e6, and the degenerate neighbourhoods.
#include "psFiltersTestSupport.h"
#include "psLocalFit.h"
#include "psPolynomial.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <vector>

using namespace pointsurfaces;

namespace
{

// Sample z = g(u, v) (in units of h) in a tilted frame placed at `offset` with scale `h`.
std::vector<double> Sample(const LocalFrame& f, const double* c, int degree, int n, unsigned seed)
{
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> uni(-2.0, 2.0);
  std::vector<double> pts(3 * n);
  for (int i = 0; i < n; ++i)
  {
    const double u = uni(gen), v = uni(gen);
    const double w = Evaluate(c, degree, u, v);
    for (int k = 0; k < 3; ++k)
    {
      pts[3 * i + k] =
        f.Origin[k] + f.Scale * (u * f.Tangent[k] + v * f.Bitangent[k] + w * f.Normal[k]);
    }
  }
  return pts;
}

LocalFrame TiltedFrame(double offset, double scale)
{
  LocalFrame f;
  const double n[3] = { 0.3, -0.4, 0.866 };
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  double t[3] = { 1, 0, 0 };
  for (int k = 0; k < 3; ++k)
  {
    f.Normal[k] = n[k] / len;
  }
  double d = t[0] * f.Normal[0];
  for (int k = 0; k < 3; ++k)
  {
    t[k] -= d * f.Normal[k];
  }
  d = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  for (int k = 0; k < 3; ++k)
  {
    f.Tangent[k] = t[k] / d;
    f.Origin[k] = offset + 0.25 * scale * (k + 1);
  }
  f.Bitangent[0] = f.Normal[1] * f.Tangent[2] - f.Normal[2] * f.Tangent[1];
  f.Bitangent[1] = f.Normal[2] * f.Tangent[0] - f.Normal[0] * f.Tangent[2];
  f.Bitangent[2] = f.Normal[0] * f.Tangent[1] - f.Normal[1] * f.Tangent[0];
  f.Scale = scale;
  return f;
}

double MaxRelativeError(const double* a, const double* b, int m)
{
  double err = 0.0, norm = 0.0;
  for (int i = 0; i < m; ++i)
  {
    err = std::max(err, std::abs(a[i] - b[i]));
    norm = std::max(norm, std::abs(b[i]));
  }
  return err / norm;
}

void TestMonomialOrder()
{
  double m[15];
  Monomials(2.0, 3.0, 4, m);
  const double expected[15] = { 1, 2, 3, 4, 6, 9, 8, 12, 18, 27, 16, 24, 36, 54, 81 };
  bool same = true;
  for (int i = 0; i < 15; ++i)
  {
    same = same && m[i] == expected[i];
  }
  Check(same, "monomials ordered by total degree, then descending power of u");
  for (int d = 1; d <= 4; ++d)
  {
    Check(DegreeFromMonomialCount(MonomialCount(d)) == d, "degree from monomial count");
  }
  Check(DegreeFromMonomialCount(7) == -1, "no degree has 7 monomials");

  // Gradient against central differences.
  const double c[15] = {
    0.1, -0.2, 0.3, 0.5, -0.7, 0.2, 0.05, -0.03, 0.08, 0.01, 0.02, -0.01, 0.03, 0.04, -0.02
  };
  double du, dv;
  EvaluateWithGradient(c, 4, 0.7, -0.4, du, dv);
  const double e = 1e-6;
  const double fdu = (Evaluate(c, 4, 0.7 + e, -0.4) - Evaluate(c, 4, 0.7 - e, -0.4)) / (2 * e);
  const double fdv = (Evaluate(c, 4, 0.7, -0.4 + e) - Evaluate(c, 4, 0.7, -0.4 - e)) / (2 * e);
  Check(std::abs(du - fdu) < 1e-8 && std::abs(dv - fdv) < 1e-8, "analytic gradient");
}

void TestExactRecovery()
{
  const double c[15] = {
    0.02, 0.1, -0.05, 0.3, -0.2, 0.15, 0.04, -0.03, 0.05, 0.02, -0.01, 0.015, 0.01, -0.02, 0.012
  };
  // (offset, scale): translated by 1e7, or scaled by 1e-6 and 1e6.
  const double cases[][2] = { { 0.0, 1.0 }, { 1e7, 1.0 }, { 0.0, 1e-6 }, { 0.0, 1e6 } };
  for (int degree = 1; degree <= 4; ++degree)
  {
    for (const auto& cs : cases)
    {
      const double offset = cs[0], scale = cs[1];
      {
        const LocalFrame f = TiltedFrame(offset, scale);
        const auto pts = Sample(f, c, degree, 60, 7u + degree);
        std::vector<double> w(60);
        for (int i = 0; i < 60; ++i)
        {
          w[i] = 0.2 + 0.8 * ((i * 37) % 11) / 10.0; // arbitrary positive weights
        }
        const PolynomialFit fit = FitPolynomial(pts.data(), w.data(), 60, f, degree);
        // At 1e7 a double keeps ~2e-9 absolute: the bound follows the input's precision.
        const double bound = offset > 0 ? 1e-6 : 1e-9;
        const double err = MaxRelativeError(fit.Coefficients, c, MonomialCount(degree));
        if (!(fit.Status == FitStatus::Ok && fit.Degree == degree && err < bound))
        {
          std::cerr << "degree " << degree << " offset " << offset << " scale " << scale
                    << ": status " << FitStatusName(fit.Status) << ", relative error " << err
                    << "\n";
          Check(false, "exact recovery of the coefficients");
        }
      }
    }
  }
}

void TestPlaneInvariance()
{
  // The reference plane of the same neighbourhood, translated and scaled.
  const double c[3] = { 0.0, 0.0, 0.0 };
  const double cases[][2] = { { 0.0, 1.0 }, { 1e7, 1.0 }, { 0.0, 1e-6 }, { 0.0, 1e6 } };
  for (const auto& cs : cases)
  {
    const double offset = cs[0], scale = cs[1];
    {
      const LocalFrame truth = TiltedFrame(offset, scale);
      const auto pts = Sample(truth, c, 1, 40, 3u);
      LocalFrame f;
      const FitStatus s = FitReferencePlane(pts.data(), nullptr, 40, f, truth.Normal);
      double dot = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        dot += f.Normal[k] * truth.Normal[k];
      }
      if (s != FitStatus::Ok || std::abs(1.0 - dot) > 1e-6)
      {
        std::cerr << "offset " << offset << " scale " << scale << ": 1 - n.n = " << 1.0 - dot
                  << "\n";
        Check(false, "reference plane normal invariant under offset and scale");
      }
    }
  }
}

void TestDegenerate()
{
  LocalFrame f;
  std::vector<double> same(30, 1.5);
  Check(FitReferencePlane(same.data(), nullptr, 10, f) == FitStatus::Degenerate,
    "coincident points are degenerate");
  std::vector<double> line;
  for (int i = 0; i < 10; ++i)
  {
    line.insert(line.end(), { 1.0 * i, 2.0 * i, -1.0 * i });
  }
  Check(FitReferencePlane(line.data(), nullptr, 10, f) == FitStatus::Degenerate,
    "collinear points are degenerate");
  Check(FitReferencePlane(line.data(), nullptr, 2, f) == FitStatus::TooFewPoints,
    "two points are too few");
  std::vector<double> bad = { 0, 0, 0, 1, 0, 0, 0, 1, 0, NAN, 0, 0 };
  Check(FitReferencePlane(bad.data(), nullptr, 4, f) == FitStatus::NonFinite, "NaN is reported");
  bad[9] = INFINITY;
  Check(FitPolynomial(bad.data(), nullptr, 4, LocalFrame(), 2).Status == FitStatus::NonFinite,
    "Inf is reported by the polynomial fit");

  // Points on a line in (u, v) cannot carry a quadratic: the fit falls back
  // to a lower degree, or reports the degeneracy, with finite coefficients.
  std::vector<double> uvline;
  for (int i = 0; i < 20; ++i)
  {
    uvline.insert(uvline.end(), { 0.1 * i, 0.05 * i, 0.01 * i * i });
  }
  const PolynomialFit fit = FitPolynomial(uvline.data(), nullptr, 20, LocalFrame(), 2);
  bool finite = true;
  for (double v : fit.Coefficients)
  {
    finite = finite && std::isfinite(v);
  }
  Check(finite && fit.Status == FitStatus::Degenerate,
    "points on a line give a reported degeneracy and finite coefficients");

  // A strip 1e-7 wide in v: its v^2 column is 1e-14 of the others, below
  // the rank test's 1e-10, so the quadratic is not well posed there and the
  // fit falls back to degree 1 (however the least squares are solved).
  std::vector<double> strip;
  std::mt19937 stripGen(5u);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int i = 0; i < 40; ++i)
  {
    const double u = uniform(stripGen), v = 1e-7 * uniform(stripGen);
    strip.insert(strip.end(), { u, v, 0.5 * u * u });
  }
  const PolynomialFit thin = FitPolynomial(strip.data(), nullptr, 40, LocalFrame(), 2);
  Check(thin.Status == FitStatus::ReducedDegree && thin.Degree == 1,
    "a strip too thin for a quadratic falls back to degree 1");

  // Five points cannot determine six quadratic coefficients: degree 1 is used.
  const double c[3] = { 0.1, 0.2, -0.3 };
  const auto few = Sample(TiltedFrame(0, 1), c, 1, 5, 9u);
  const PolynomialFit reduced = FitPolynomial(few.data(), nullptr, 5, TiltedFrame(0, 1), 2);
  Check(reduced.Status == FitStatus::ReducedDegree && reduced.Degree == 1,
    "k < unknowns falls back to a lower degree");
  Check(
    FitPolynomial(few.data(), nullptr, 2, TiltedFrame(0, 1), 1).Status == FitStatus::TooFewPoints,
    "N < 3 is too few");
  Check(
    FitPolynomial(few.data(), nullptr, 0, TiltedFrame(0, 1), 1).Status == FitStatus::TooFewPoints,
    "empty input is too few");
  LocalFrame zero = TiltedFrame(0, 1);
  zero.Scale = 0.0;
  Check(FitPolynomial(few.data(), nullptr, 5, zero, 1).Status == FitStatus::Degenerate,
    "a zero feature size is degenerate");
}
} // namespace

// The residuals FitPolynomial returns are each point's distance to its patch
// (world units), and its weighted RMS is theirs: checked against the patch
// evaluated here, with points off any quadratic and a zero weight among them.
void TestResiduals()
{
  const double c[10] = { 0.02, 0.1, -0.05, 0.3, -0.2, 0.15, 0.4, -0.3, 0.25, 0.2 };
  const double cases[][2] = { { 0.0, 1.0 }, { 1e7, 1.0 }, { 0.0, 1e-6 } };
  for (const auto& cs : cases)
  {
    const LocalFrame f = TiltedFrame(cs[0], cs[1]);
    const auto pts = Sample(f, c, 3, 50, 11u); // cubic points, fitted by a quadratic
    std::vector<double> w(50), r(50, -1.0);
    for (int i = 0; i < 50; ++i)
    {
      w[i] = i == 7 ? 0.0 : 0.3 + 0.7 * ((i * 13) % 7) / 6.0;
    }
    const PolynomialFit fit = FitPolynomial(pts.data(), w.data(), 50, f, 2, r.data());
    Check(fit.Status == FitStatus::Ok && fit.Degree == 2, "quadratic fit of cubic points");
    double worst = 0.0, largest = 0.0, sum = 0.0, wsum = 0.0;
    for (int i = 0; i < 50; ++i)
    {
      double uvh[3];
      ToLocal(f, pts.data() + 3 * i, uvh);
      const double e = std::abs(uvh[2] - Evaluate(fit.Coefficients, 2, uvh[0], uvh[1])) * f.Scale;
      worst = std::max(worst, std::abs(r[i] - e));
      largest = std::max(largest, e);
      sum += w[i] * (e / f.Scale) * (e / f.Scale);
      wsum += w[i];
    }
    const double precision = cs[0] > 0 ? 1e-8 : 1e-12 * f.Scale;
    Check(largest > 1e3 * precision && worst <= precision, "residuals: distance to the patch");
    Check(std::abs(fit.WeightedRMS - std::sqrt(sum / wsum)) <= 1e-9 * std::sqrt(sum / wsum) + 1e-12,
      "weighted RMS of the residuals");
  }
}

int TestPolynomialFit(int, char*[])
{
  TestMonomialOrder();
  TestExactRecovery();
  TestPlaneInvariance();
  TestDegenerate();
  TestResiduals();
  if (Failures)
  {
    std::cerr << Failures << " checks failed\n";
    return EXIT_FAILURE;
  }
  std::cout << "all numeric checks passed\n";
  return EXIT_SUCCESS;
}
