// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psLocalFit.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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
constexpr int MaximumMonomials = MonomialCount(MaximumDegree);
using NormalMatrix =
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, MaximumMonomials, MaximumMonomials>;
using NormalVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, MaximumMonomials, 1>;

// The weighted least-squares solution of A c = rhs from its normal equations
// (`normal` = A^T W A and `b` = A^T W rhs, accumulated by the caller), with
// the columns scaled to unit norm: a quarter of the QR's work on the tall,
// narrow systems of a splat fit. Refuses (returns false) unless the column
// norms are within 1e4 of each other and the scaled system is well
// conditioned (smallest LDLT pivot over largest above 1e-8, so that
// squaring the condition number costs about 8 of 16 digits): every system
// it accepts is one the rank-revealing QR (threshold 1e-10) accepts too.
// The caller takes that QR otherwise.
bool SolveNormal(NormalMatrix normal, const NormalVector& b, NormalVector& c)
{
  const Eigen::Index m = normal.cols();
  NormalVector scale(m);
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
  const Eigen::LDLT<NormalMatrix> ldlt(normal);
  if (ldlt.info() != Eigen::Success)
  {
    return false;
  }
  const auto d = ldlt.vectorD();
  if (!(d.minCoeff() > 1e-8 * d.maxCoeff()))
  {
    return false;
  }
  c = scale.asDiagonal() * ldlt.solve(NormalVector(scale.asDiagonal() * b));
  return c.allFinite();
}

// The upper triangle of the normal equations sum w_i r_i r_i^T and
// sum w_i r_i h_i of the degree-D monomials r_i of each point (u, v), from the
// local coordinates `uvh`; a fixed D lets the compiler unroll the products.
template<int D>
void Accumulate(const double* uvh,
  const double* w,
  int n,
  double (&normal)[MaximumMonomials][MaximumMonomials],
  double (&b)[MaximumMonomials],
  double& wsum,
  int& active)
{
  for (int i = 0; i < n; ++i)
  {
    const double wi = w ? w[i] : 1.0;
    if (!(wi > 0.0))
    {
      continue;
    }
    ++active;
    wsum += wi;
    const double* local = uvh + 3 * static_cast<size_t>(i);
    double row[MaximumMonomials];
    Monomials(local[0], local[1], D, row);
    constexpr int M = MonomialCount(D);
    for (int j = 0; j < M; ++j)
    {
      const double wr = wi * row[j];
      for (int k = j; k < M; ++k)
      {
        normal[j][k] += wr * row[k];
      }
      b[j] += wr * local[2];
    }
  }
}
// The degree-d fit by the rank-revealing QR of the weighted design matrix,
// for a system too ill-conditioned for the normal equations (uvh: the local
// coordinates of the n points); false when its rank is short.
bool SolveByQR(const double* uvh, const double* w, int n, int d, NormalVector& c)
{
  const int m = MonomialCount(d);
  thread_local Eigen::MatrixXd A;
  thread_local Eigen::VectorXd h;
  thread_local Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr;
  A.resize(n, m);
  h.resize(n);
  double row[MaximumMonomials];
  for (int i = 0; i < n; ++i)
  {
    const double wi = w ? w[i] : 1.0;
    const double sw = wi > 0.0 ? std::sqrt(wi) : 0.0;
    Monomials(uvh[3 * i], uvh[3 * i + 1], d, row);
    for (int j = 0; j < m; ++j)
    {
      A(i, j) = sw * row[j];
    }
    h(i) = sw * uvh[3 * i + 2];
  }
  qr.compute(A);
  qr.setThreshold(1e-10);
  if (qr.rank() < m)
  {
    return false;
  }
  c = qr.solve(h);
  return true;
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

double PatchOffset(const LocalFrame& f,
  const double* c,
  int degree,
  const double p[3],
  double& inPlane2,
  double* height)
{
  const double h = f.Scale;
  double uvh[3];
  ToLocal(f, p, uvh);
  inPlane2 = (uvh[0] * uvh[0] + uvh[1] * uvh[1]) * h * h;
  double gu, gv;
  const double g = EvaluateWithGradient(c, degree, uvh[0], uvh[1], gu, gv);
  if (height)
  {
    *height = (uvh[2] - g) * h;
  }
  return (uvh[2] - g) * h / std::sqrt(1.0 + gu * gu + gv * gv);
}

//------------------------------------------------------------------------------
PolynomialFit FitPolynomial(const double* points,
  const double* w,
  int n,
  const LocalFrame& frame,
  int degree,
  double* residuals)
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
  // Local coordinates, and the normal equations of the highest degree,
  // accumulated point by point (no n-by-m design matrix): a lower degree's
  // monomials are a prefix of a higher one's, so its system is the leading
  // block. The work arrays are kept per thread: a fitter calls this several
  // times per splat with the same sizes.
  thread_local std::vector<double> uvh;
  uvh.resize(3 * static_cast<size_t>(n));
  double normal[MaximumMonomials][MaximumMonomials] = {};
  double b[MaximumMonomials] = {};
  double wsum = 0.0;
  int active = 0;
  for (int i = 0; i < n; ++i)
  {
    ToLocal(frame, points + 3 * i, &uvh[3 * static_cast<size_t>(i)]);
  }
  switch (degree)
  {
    case 1:
      Accumulate<1>(uvh.data(), w, n, normal, b, wsum, active);
      break;
    case 2:
      Accumulate<2>(uvh.data(), w, n, normal, b, wsum, active);
      break;
    case 3:
      Accumulate<3>(uvh.data(), w, n, normal, b, wsum, active);
      break;
    default:
      Accumulate<4>(uvh.data(), w, n, normal, b, wsum, active);
      break;
  }

  for (int d = degree; d >= 1; --d)
  {
    const int m = MonomialCount(d);
    if (active < m)
    {
      continue;
    }
    NormalMatrix system(m, m);
    NormalVector rhs(m), c(m);
    for (int j = 0; j < m; ++j)
    {
      for (int k = j; k < m; ++k)
      {
        system(j, k) = system(k, j) = normal[j][k];
      }
      rhs(j) = b[j];
    }
    if (!SolveNormal(system, rhs, c))
    {
      // Ill-conditioned or rank-deficient: the rank-revealing QR decides.
      if (!SolveByQR(uvh.data(), w, n, d, c))
      {
        continue; // e.g. points on a line in (u, v): no well-posed fit of this degree
      }
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
    // The weighted RMS and, when asked, each point's distance to the patch.
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
    {
      const double* local = &uvh[3 * static_cast<size_t>(i)];
      const double e = local[2] - Evaluate(fit.Coefficients, d, local[0], local[1]);
      const double wi = w ? w[i] : 1.0;
      sum += wi > 0.0 ? wi * e * e : 0.0;
      if (residuals)
      {
        residuals[i] = std::abs(e) * frame.Scale;
      }
    }
    fit.WeightedRMS = wsum > 0.0 ? std::sqrt(sum / wsum) : 0.0;
    fit.Status = d == degree ? FitStatus::Ok : FitStatus::ReducedDegree;
    return fit;
  }
  fit.Status = active < MonomialCount(1) ? FitStatus::TooFewPoints : FitStatus::Degenerate;
  return fit;
}
} // namespace pointsurfaces
