// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The float root solvers of the splat ray caster (glsl/vtkSplatRoots.glsl),
// run in a compute shader and checked against the double-precision reference
// (psRoots.h) on the same float coefficients, at the extremes:
//
// | case          | what                                        |
// |---------------|---------------------------------------------|
// | separated     | 2-4 roots in [-10, 10], at least 0.5 apart   |
// | near-double   | a pair r, r (1 + 1e-3) among separated roots |
// | spread        | roots over 1e6 (degrees 2, 3) or 1e3 (degree 4) |
// | tiny leading  | leading coefficient 1e-9 of the others       |
// | no real root  | complex roots only: none may be reported     |
//
// Bound on each root, relative: 64 float epsilons times its condition number
// sum|c_i t^i| / |t p'(t)| (at least 1e-6), what float evaluation of p near
// the root allows; 1e-2 on a near-double pair, whose error grows like
// sqrt(epsilon). The largest error of each case is printed.
#include "psRoots.h"
#include "psShaderHooks.h"
#include "vtkComputeShaderProgram.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkShaderStorageBuffer.h"
#include "vtkSplatRoots.h"
#include "vtkSplatRootsCS.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace
{
struct Case
{
  std::string Kind;
  int Degree;
  float C[5];
  std::vector<double> Expected; // reference roots that must be found
  std::vector<double> Bounds;   // relative bound per expected root
  double Pair = 0.0;            // near-double: the value of the close pair
};

// Coefficients (ascending) of lead * prod (t - r_i), rounded to float.
Case FromRoots(const std::string& kind, const std::vector<double>& roots, double lead)
{
  Case c;
  c.Kind = kind;
  c.Degree = static_cast<int>(roots.size());
  std::vector<double> p{ lead };
  for (double r : roots)
  {
    std::vector<double> q(p.size() + 1, 0.0);
    for (size_t k = 0; k < p.size(); ++k)
    {
      q[k + 1] += p[k];
      q[k] -= r * p[k];
    }
    p = q;
  }
  for (int k = 0; k < 5; ++k)
  {
    c.C[k] = k < static_cast<int>(p.size()) ? static_cast<float>(p[k]) : 0.0f;
  }
  return c;
}

// The reference roots of the float coefficients themselves.
std::vector<double> Reference(const Case& c)
{
  double coeffs[5], roots[4];
  for (int k = 0; k < 5; ++k)
  {
    coeffs[k] = c.C[k];
  }
  const int n = pointsurfaces::RealRoots(coeffs, c.Degree, roots);
  return std::vector<double>(roots, roots + n);
}
} // namespace

int TestSplatRootSolvers(int, char*[])
{
  std::mt19937 gen(17);
  std::uniform_real_distribution<double> uni(-10.0, 10.0), lead(0.1, 10.0);
  std::vector<Case> cases;
  auto separated = [&](int n)
  {
    std::vector<double> r;
    while (static_cast<int>(r.size()) < n)
    {
      const double x = uni(gen);
      if (std::all_of(r.begin(), r.end(), [&](double y) { return std::abs(x - y) > 0.5; }))
      {
        r.push_back(x);
      }
    }
    return r;
  };
  for (int t = 0; t < 300; ++t)
  {
    for (int degree = 2; degree <= 4; ++degree)
    {
      const double sign = (gen() & 1) ? 1.0 : -1.0;
      Case c = FromRoots("separated", separated(degree), sign * lead(gen));
      c.Bounds.assign(degree, 1e-5);
      cases.push_back(c);

      std::vector<double> r = separated(degree - 1);
      const double pair = r.back();
      r.push_back(pair * (1.0 + 1e-3));
      Case d = FromRoots("near-double", r, sign * lead(gen));
      d.Pair = pair;
      cases.push_back(d);
    }
  }
  // Quadratics and cubics over a 1e6 range; quartics over 1e3 (Ferrari's
  // known limit, documented in vtkSplatRoots.glsl).
  const std::vector<std::vector<double>> spreads = { { 1e-3, 1e3 },
    { -1e-3, 1e3 },
    { -1e-3, 1.0, 1e3 },
    { 2e-3, -5.0, 999.0 },
    { 0.03, -0.3, 3.0, -30.0 },
    { 0.1, -1.0, 10.0, 100.0 } };
  for (const auto& r : spreads)
  {
    for (double scale : { 1e-3, 1.0, 1e3 })
    {
      Case c = FromRoots("spread", r, scale);
      c.Bounds.assign(r.size(), 1e-4);
      cases.push_back(c);
    }
  }
  // Tiny leading coefficient: the roots of the lower-degree part must survive.
  for (int degree = 2; degree <= 4; ++degree)
  {
    for (int t = 0; t < 50; ++t)
    {
      Case c = FromRoots("tiny leading", separated(degree - 1), lead(gen));
      double largest = 0.0;
      for (int k = 0; k < degree; ++k)
      {
        largest = std::max(largest, std::abs(static_cast<double>(c.C[k])));
      }
      c.C[degree] = static_cast<float>(1e-9 * largest);
      c.Degree = degree;
      c.Bounds.assign(degree - 1, 1e-5);
      cases.push_back(c);
    }
  }
  // No real roots: (t^2 + 1)(t^2 + 4) and t^2 + t + 1.
  Case none4;
  none4.Kind = "no real root";
  none4.Degree = 4;
  const float q4[5] = { 4, 0, 5, 0, 1 };
  std::copy(q4, q4 + 5, none4.C);
  cases.push_back(none4);
  Case none2 = none4;
  none2.Degree = 2;
  const float q2[5] = { 1, 1, 1, 0, 0 };
  std::copy(q2, q2 + 5, none2.C);
  cases.push_back(none2);

  // Expected roots: the reference's, on the float coefficients. For the tiny
  // leading case only the roots of moderate size are required.
  for (Case& c : cases)
  {
    std::vector<double> ref = Reference(c);
    if (c.Kind == "tiny leading")
    {
      ref.erase(std::remove_if(ref.begin(), ref.end(), [](double x) { return std::abs(x) > 1e3; }),
        ref.end());
    }
    c.Expected = ref;
    c.Bounds.resize(ref.size(), c.Bounds.empty() ? 1e-5 : c.Bounds.back());
    for (size_t k = 0; k < ref.size(); ++k)
    {
      // Float rounding of p(t) near a root moves it by about
      // eps sum|c_i t^i| / |p'(t)|: the bound is a multiple of that
      // condition number; the near-double pair gets the sqrt(eps) bound.
      double sum = 0.0, deriv = 0.0;
      for (int i = 0; i <= c.Degree; ++i)
      {
        sum += std::abs(c.C[i]) * std::pow(std::abs(ref[k]), i);
        deriv += i > 0 ? i * c.C[i] * std::pow(ref[k], i - 1) : 0.0;
      }
      const double kappa = sum / std::max(std::abs(ref[k] * deriv), 1e-300);
      c.Bounds[k] = std::max(1e-6, 64.0 * 6e-8 * kappa);
      if (c.Kind == "near-double" && std::abs(ref[k] - c.Pair) < 1e-2 * std::abs(c.Pair))
      {
        c.Bounds[k] = 1e-2;
      }
    }
  }

  // GPU.
  vtkNew<vtkRenderWindow> renWin;
  vtkNew<vtkRenderer> renderer;
  renWin->AddRenderer(renderer);
  renWin->SetSize(16, 16);
  renWin->Render();
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(renWin);
  std::string source = vtkSplatRootsCS;
  if (!pointsurfaces::ReplaceHook(source, "//VTK::SplatRoots::Dec", vtkSplatRoots))
  {
    std::cerr << "vtkSplatRootsCS lacks its //VTK::SplatRoots::Dec hook\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkComputeShaderProgram> program;
  program->SetName("vtkSplatRootsCS");
  program->SetSource(source);
  if (!program->Compile(gl))
  {
    return EXIT_FAILURE;
  }
  const size_t n = cases.size();
  std::vector<float> coeffs(5 * n);
  std::vector<int> degrees(n);
  for (size_t i = 0; i < n; ++i)
  {
    std::copy(cases[i].C, cases[i].C + 5, &coeffs[5 * i]);
    degrees[i] = cases[i].Degree;
  }
  vtkNew<vtkShaderStorageBuffer> cBuf, dBuf, rBuf, nBuf;
  cBuf->Upload(coeffs.data(), coeffs.size() * sizeof(float));
  dBuf->Upload(degrees.data(), degrees.size() * sizeof(int));
  rBuf->Allocate(n * 4 * sizeof(float));
  nBuf->Allocate(n * sizeof(int));
  program->Bind(gl);
  program->SetUniformui("numberOfPolynomials", static_cast<unsigned int>(n));
  cBuf->BindBase(0);
  dBuf->BindBase(1);
  rBuf->BindBase(2);
  nBuf->BindBase(3);
  program->Dispatch(vtkComputeShaderProgram::GroupCount(n, 64));
  program->Unbind();
  std::vector<float> roots(4 * n);
  std::vector<int> counts(n);
  rBuf->Download(roots.data(), roots.size() * sizeof(float));
  nBuf->Download(counts.data(), counts.size() * sizeof(int));
  for (auto* b : { cBuf.Get(), dBuf.Get(), rBuf.Get(), nBuf.Get() })
  {
    b->ReleaseGraphicsResources(renWin);
  }
  program->ReleaseGraphicsResources(renWin);

  // Compare: every expected root must have a GPU root within its bound, and
  // every GPU root must be near a reference root (no invented roots). A
  // near-double pair may be missed as a whole: in float its discriminant is
  // within rounding of zero, a grazing ray; such misses are counted.
  std::map<std::string, double> worst;
  std::map<std::string, int> failures, total, missedPairs;
  for (size_t i = 0; i < n; ++i)
  {
    const Case& c = cases[i];
    ++total[c.Kind];
    if (c.Kind == "no real root" && counts[i] != 0)
    {
      ++failures[c.Kind];
    }
    // Every root, complex ones too: a GPU root on a pair whose imaginary
    // parts are at rounding level is a grazing hit, not an invention.
    double coeffs[5], re[4], im[4];
    for (int k = 0; k < 5; ++k)
    {
      coeffs[k] = c.C[k];
    }
    const int nAll = pointsurfaces::ComplexRoots(coeffs, c.Degree, re, im);
    for (int j = 0; j < counts[i]; ++j)
    {
      double nearest = 1e300;
      for (int k = 0; k < nAll; ++k)
      {
        const double dr = roots[4 * i + j] - re[k];
        nearest = std::min(
          nearest, std::sqrt(dr * dr + im[k] * im[k]) / std::max(std::hypot(re[k], im[k]), 1e-30));
      }
      if (!(nearest < 1e-2))
      {
        if (++failures[c.Kind] <= 6)
        {
          std::cerr << c.Kind << " degree " << c.Degree << ": invented root " << roots[4 * i + j]
                    << "\n";
        }
      }
    }
    bool pairFound = true;
    for (size_t k = 0; k < c.Expected.size(); ++k)
    {
      if (c.Kind == "near-double" && c.Bounds[k] == 1e-2)
      {
        double best = 1e300;
        for (int j = 0; j < counts[i]; ++j)
        {
          best =
            std::min(best, std::abs(roots[4 * i + j] - c.Expected[k]) / std::abs(c.Expected[k]));
        }
        pairFound = pairFound && best <= 1e-2;
      }
    }
    if (!pairFound)
    {
      ++missedPairs[c.Kind];
    }
    for (size_t k = 0; k < c.Expected.size(); ++k)
    {
      if (!pairFound && c.Bounds[k] == 1e-2)
      {
        continue;
      }
      double best = 1e300;
      for (int j = 0; j < counts[i]; ++j)
      {
        best = std::min(best,
          std::abs(roots[4 * i + j] - c.Expected[k]) / std::max(std::abs(c.Expected[k]), 1e-30));
      }
      worst[c.Kind] = std::max(worst[c.Kind], best);
      if (!(best <= c.Bounds[k]))
      {
        if (++failures[c.Kind] <= 6)
        {
          std::cerr << c.Kind << " degree " << c.Degree << ": root " << c.Expected[k]
                    << " found with relative error " << best << " (bound " << c.Bounds[k]
                    << "); GPU found " << counts[i] << ":";
          for (int j = 0; j < counts[i]; ++j)
          {
            std::cerr << " " << roots[4 * i + j];
          }
          std::cerr << "\n";
        }
      }
    }
  }
  int bad = 0;
  for (const auto& t : total)
  {
    std::cout << std::setw(14) << t.first << ": " << t.second
              << " polynomials, largest relative error " << worst[t.first] << ", "
              << failures[t.first] << " over the bound";
    if (t.first == "near-double")
    {
      std::cout << ", " << missedPairs[t.first] << " pairs missed as grazing";
    }
    std::cout << "\n";
    bad += failures[t.first];
  }
  return bad ? EXIT_FAILURE : EXIT_SUCCESS;
}
