// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The Robust fit mode through Ceres, kept in its own translation unit so that
// only this file sees Ceres' headers.
#include "psSplatFit.h"

#include <ceres/ceres.h>

#include <cmath>
#include <memory>
#include <vector>

namespace pointsurfaces
{
namespace
{
// Residual sqrt(w) (g(u, v) - height) of one neighbour, linear in the coefficients.
struct HeightResidual : public ceres::CostFunction
{
  HeightResidual(const double* monomials, int m, double sqrtWeight, double height)
    : Monomials(monomials, monomials + m)
    , SqrtWeight(sqrtWeight)
    , Height(height)
  {
    this->set_num_residuals(1);
    this->mutable_parameter_block_sizes()->push_back(m);
  }

  bool Evaluate(double const* const* parameters,
    double* residuals,
    double** jacobians) const override
  {
    const double* c = parameters[0];
    double g = 0.0;
    for (size_t i = 0; i < this->Monomials.size(); ++i)
    {
      g += c[i] * this->Monomials[i];
    }
    residuals[0] = this->SqrtWeight * (g - this->Height);
    if (jacobians && jacobians[0])
    {
      for (size_t i = 0; i < this->Monomials.size(); ++i)
      {
        jacobians[0][i] = this->SqrtWeight * this->Monomials[i];
      }
    }
    return true;
  }

  std::vector<double> Monomials;
  double SqrtWeight;
  double Height;
};
} // namespace

PolynomialFit FitPolynomialRobust(const double* points,
  const double* w,
  int n,
  const LocalFrame& frame,
  const PolynomialFit& initial,
  RobustLoss loss,
  double lossScale,
  int maxIterations,
  int* iterations)
{
  if (initial.Degree < 1 || !(lossScale > 0.0))
  {
    return initial;
  }
  const int degree = initial.Degree;
  const int m = MonomialCount(degree);
  std::vector<double> c(initial.Coefficients, initial.Coefficients + m);
  ceres::Problem::Options options;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(options);
  // The loss acts on the weighted residual: scale it by the typical weight.
  std::unique_ptr<ceres::LossFunction> rho;
  if (loss == RobustLoss::Cauchy)
  {
    rho.reset(new ceres::CauchyLoss(lossScale));
  }
  else
  {
    rho.reset(new ceres::HuberLoss(lossScale));
  }
  double row[MonomialCount(MaximumDegree)];
  int used = 0;
  for (int i = 0; i < n; ++i)
  {
    const double wi = w ? w[i] : 1.0;
    if (!(wi > 0.0))
    {
      continue;
    }
    double uvh[3];
    ToLocal(frame, points + 3 * i, uvh);
    Monomials(uvh[0], uvh[1], degree, row);
    problem.AddResidualBlock(
      new HeightResidual(row, m, std::sqrt(wi), uvh[2]), rho.get(), c.data());
    ++used;
  }
  if (used < m)
  {
    return initial;
  }
  ceres::Solver::Options solverOptions;
  solverOptions.linear_solver_type = ceres::DENSE_QR;
  solverOptions.max_num_iterations = maxIterations;
  solverOptions.num_threads = 1; // the caller parallelises over splats
  solverOptions.logging_type = ceres::SILENT;
  solverOptions.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(solverOptions, &problem, &summary);
  if (iterations)
  {
    *iterations = static_cast<int>(summary.iterations.size());
  }
  PolynomialFit fit = initial;
  bool finite = true;
  for (int i = 0; i < m; ++i)
  {
    finite = finite && std::isfinite(c[i]);
  }
  if (!summary.IsSolutionUsable() || !finite)
  {
    return initial; // keep the least-squares answer rather than garbage
  }
  for (int i = 0; i < m; ++i)
  {
    fit.Coefficients[i] = c[i];
  }
  return fit;
}
} // namespace pointsurfaces
