// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psLocalFit.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pointsurfaces
{
const char* FitStatusName(FitStatus status)
{
  switch (status)
  {
    case FitStatus::Ok:
      return "ok";
    case FitStatus::ReducedDegree:
      return "fitted at a lower degree";
    case FitStatus::TooFewPoints:
      return "too few neighbours";
    case FitStatus::Degenerate:
      return "coincident or collinear neighbours";
    case FitStatus::NonFinite:
      return "NaN or infinite coordinates";
  }
  return "unknown";
}

namespace
{
bool AllFinite(const double* p, int n)
{
  for (int i = 0; i < 3 * n; ++i)
  {
    if (!std::isfinite(p[i]))
    {
      return false;
    }
  }
  return true;
}
// The least-squares solution of A c = rhs through the normal equations, with
// the columns scaled to unit norm: a quarter of the QR's work on the tall,
// narrow systems of a splat fit. Refuses (returns false) unless the column
// norms are within 1e4 of each other and the scaled system is well
// conditioned (smallest LDLT pivot over largest above 1e-8, so that
// squaring the condition number costs about 8 of 16 digits): every system
// it accepts is one the rank-revealing QR (threshold 1e-10) accepts too.
// The caller takes that QR otherwise.
bool SolveNormal(const Eigen::MatrixXd& A, const Eigen::VectorXd& rhs, Eigen::VectorXd& c)
{
  constexpr int Max = MonomialCount(MaximumDegree);
  using Square = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, Max, Max>;
  using Column = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, Max, 1>;
  const Eigen::Index m = A.cols();
  if (m > Max || A.rows() < m)
  {
    return false;
  }
  Square normal(m, m);
  normal.noalias() = A.transpose() * A;
  Column scale(m);
  double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
  for (Eigen::Index j = 0; j < m; ++j)
  {
    if (!(normal(j, j) > 0.0) || !std::isfinite(normal(j, j)))
    {
      return false;
    }
    smallest = std::min(smallest, normal(j, j));
    largest = std::max(largest, normal(j, j));
    scale(j) = 1.0 / std::sqrt(normal(j, j));
  }
  // Columns of very different norms (a strip of points thin in v, whose v^2
  // column is tiny) are the QR's to judge: the scaling below would hide
  // what its rank test, on the unscaled columns, rejects.
  if (largest > 1e8 * smallest)
  {
    return false;
  }
  normal = scale.asDiagonal() * normal * scale.asDiagonal();
  const Eigen::LDLT<Square> ldlt(normal);
  if (ldlt.info() != Eigen::Success)
  {
    return false;
  }
  const auto d = ldlt.vectorD();
  if (!(d.minCoeff() > 1e-8 * d.maxCoeff()))
  {
    return false;
  }
  Column b(m);
  b.noalias() = A.transpose() * rhs;
  c = scale.asDiagonal() * ldlt.solve(scale.asDiagonal() * b);
  return c.allFinite();
}
} // namespace

FitStatus FitReferencePlane(const double* points,
  const double* w,
  int n,
  LocalFrame& frame,
  const double* orientation)
{
  if (n < 3)
  {
    return FitStatus::TooFewPoints;
  }
  if (!AllFinite(points, n))
  {
    return FitStatus::NonFinite;
  }
  // Two passes: the centroid first, then the covariance of the centred points,
  // so that offsets of 1e7 cost no digits.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double wsum = 0.0;
  for (int i = 0; i < n; ++i)
  {
    const double wi = w ? w[i] : 1.0;
    centroid += wi * Eigen::Vector3d(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
    wsum += wi;
  }
  if (!(wsum > 0.0))
  {
    return FitStatus::TooFewPoints;
  }
  centroid /= wsum;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int i = 0; i < n; ++i)
  {
    const double wi = w ? w[i] : 1.0;
    const Eigen::Vector3d d =
      Eigen::Vector3d(points[3 * i], points[3 * i + 1], points[3 * i + 2]) - centroid;
    cov.noalias() += wi * d * d.transpose();
  }
  cov /= wsum;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d lambda = eig.eigenvalues(); // ascending
  // The middle eigenvalue measures the second direction of spread: when it is
  // negligible next to the largest, the points lie on a line (or a point).
  if (!(lambda(2) > 0.0) || lambda(1) <= 1e-12 * lambda(2))
  {
    return FitStatus::Degenerate;
  }
  Eigen::Vector3d normal = eig.eigenvectors().col(0);
  Eigen::Vector3d tangent = eig.eigenvectors().col(2);
  if (orientation)
  {
    if (normal.dot(Eigen::Vector3d(orientation[0], orientation[1], orientation[2])) < 0.0)
    {
      normal = -normal;
    }
  }
  else
  {
    Eigen::Index k;
    normal.cwiseAbs().maxCoeff(&k);
    if (normal(k) < 0.0)
    {
      normal = -normal;
    }
  }
  Eigen::Index k;
  tangent.cwiseAbs().maxCoeff(&k);
  if (tangent(k) < 0.0)
  {
    tangent = -tangent;
  }
  tangent = (tangent - tangent.dot(normal) * normal).normalized();
  const Eigen::Vector3d bitangent = normal.cross(tangent);
  for (int c = 0; c < 3; ++c)
  {
    frame.Origin[c] = centroid(c);
    frame.Normal[c] = normal(c);
    frame.Tangent[c] = tangent(c);
    frame.Bitangent[c] = bitangent(c);
  }
  return FitStatus::Ok;
}

PolynomialFit FitPolynomial(const double* points,
  const double* w,
  int n,
  const LocalFrame& frame,
  int degree)
{
  PolynomialFit fit;
  if (degree < 1 || degree > MaximumDegree || !(frame.Scale > 0.0) || !std::isfinite(frame.Scale))
  {
    fit.Status = FitStatus::Degenerate;
    return fit;
  }
  if (!AllFinite(points, n))
  {
    fit.Status = FitStatus::NonFinite;
    return fit;
  }
  // Local coordinates and square-root weights, once for all degrees tried.
  // The work arrays are kept per thread: a fitter calls this several times
  // per splat with the same sizes, and reallocating them cost more than the
  // QR itself on small neighbourhoods.
  thread_local Eigen::MatrixXd uvh, A;
  thread_local Eigen::VectorXd sw, rhs, c;
  thread_local Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr;
  uvh.resize(n, 3);
  sw.resize(n);
  int active = 0;
  for (int i = 0; i < n; ++i)
  {
    double local[3];
    ToLocal(frame, points + 3 * i, local);
    uvh(i, 0) = local[0];
    uvh(i, 1) = local[1];
    uvh(i, 2) = local[2];
    const double wi = w ? w[i] : 1.0;
    sw(i) = wi > 0.0 ? std::sqrt(wi) : 0.0;
    active += wi > 0.0 ? 1 : 0;
  }

  for (int d = degree; d >= 1; --d)
  {
    const int m = MonomialCount(d);
    if (active < m)
    {
      continue;
    }
    A.resize(n, m);
    rhs.resize(n);
    double row[MonomialCount(MaximumDegree)];
    for (int i = 0; i < n; ++i)
    {
      Monomials(uvh(i, 0), uvh(i, 1), d, row);
      for (int j = 0; j < m; ++j)
      {
        A(i, j) = sw(i) * row[j];
      }
      rhs(i) = sw(i) * uvh(i, 2);
    }
    if (!SolveNormal(A, rhs, c))
    {
      // Ill-conditioned or rank-deficient: the rank-revealing QR decides.
      qr.compute(A);
      qr.setThreshold(1e-10);
      if (qr.rank() < m)
      {
        continue; // e.g. points on a line in (u, v): no well-posed fit of this degree
      }
      c = qr.solve(rhs);
    }
    if (!c.allFinite())
    {
      continue;
    }
    fit.Degree = d;
    for (int j = 0; j < m; ++j)
    {
      fit.Coefficients[j] = c(j);
    }
    const double wsum = sw.squaredNorm();
    fit.WeightedRMS = wsum > 0.0 ? std::sqrt((A * c - rhs).squaredNorm() / wsum) : 0.0;
    fit.Status = d == degree ? FitStatus::Ok : FitStatus::ReducedDegree;
    return fit;
  }
  fit.Status = active < MonomialCount(1) ? FitStatus::TooFewPoints : FitStatus::Degenerate;
  return fit;
}
} // namespace pointsurfaces
