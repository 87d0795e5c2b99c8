// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psPerspectiveGrid.h"

#include <cmath>
#include <limits>
#include <utility>

namespace pointsurfaces
{
namespace
{
// Beyond this a projection's far distance counts as infinite (as on the GPU).
constexpr double FarthestDistance = 1e30;

// y = M (x, 1) for a row-major 4x4 matrix.
void Project(const double m[16], const double x[3], double y[4])
{
  for (int r = 0; r < 4; ++r)
  {
    y[r] = m[4 * r] * x[0] + m[4 * r + 1] * x[1] + m[4 * r + 2] * x[2] + m[4 * r + 3];
  }
}

// The tile of pixel coordinate p, clamped in double first (a corner just in
// front of the eye projects far out, and a cast beyond int is undefined).
int TileOf(double p, int tileSize, int tiles)
{
  return static_cast<int>(std::min(std::max(std::floor(p / tileSize), 0.0), tiles - 1.0));
}
} // namespace

//------------------------------------------------------------------------------
void ProjectionRange(const double p[16], bool parallel, double& nearD, double& farD)
{
  const double a = p[10], b = p[11];
  if (parallel)
  {
    // z_clip = a z + b with a = -2 / (f - n), b = -(f + n) / (f - n)
    nearD = (b + 1.0) / a;
    farD = (b - 1.0) / a;
  }
  else
  {
    nearD = b / (a - 1.0);
    farD = b / (a + 1.0);
  }
  if (!std::isfinite(nearD) || !std::isfinite(farD))
  {
    nearD = 0.0;
    farD = std::numeric_limits<double>::max();
  }
  if (nearD > farD)
  {
    std::swap(nearD, farD);
  }
}

//------------------------------------------------------------------------------
void FrustumPlanes(const double p[16], double planes[24])
{
  int k = 0;
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int sign = -1; sign <= 1; sign += 2, ++k)
    {
      // Inside: row3 + sign * row_axis >= 0.
      double* e = planes + 4 * k;
      for (int c = 0; c < 4; ++c)
      {
        e[c] = p[12 + c] + sign * p[4 * axis + c];
      }
      const double norm = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
      for (int c = 0; c < 4; ++c)
      {
        e[c] = norm > 0.0 ? e[c] / norm : (c == 3 ? 1.0 : 0.0);
      }
    }
  }
}

//------------------------------------------------------------------------------
PerspectiveGridGeometry::PerspectiveGridGeometry(const double viewToClip[16],
  bool parallel,
  int width,
  int height,
  int tileSize,
  int slabs)
  : Parallel(parallel)
  , Width(std::max(width, 0))
  , Height(std::max(height, 0))
  , TileSize(std::max(tileSize, 1))
  , Slabs(std::max(slabs, 1))
{
  std::copy(viewToClip, viewToClip + 16, this->ViewToClip);
  this->TilesX = (this->Width + this->TileSize - 1) / this->TileSize;
  this->TilesY = (this->Height + this->TileSize - 1) / this->TileSize;
  FrustumPlanes(viewToClip, this->Frustum);
  ProjectionRange(viewToClip, parallel, this->ProjectionNear, this->ProjectionFar);
  this->ProjectionFar = std::min(this->ProjectionFar, FarthestDistance);
  // The projection is linear: a box corner's clip coordinates are the
  // centre's plus r times a signed sum of the matrix's columns.
  for (int k = 0; k < 8; ++k)
  {
    for (int row = 0; row < 4; ++row)
    {
      const double* m = viewToClip + 4 * row;
      this->Corners[k][row] =
        ((k & 1) ? m[0] : -m[0]) + ((k & 2) ? m[1] : -m[1]) + ((k & 4) ? m[2] : -m[2]);
    }
  }
}

//------------------------------------------------------------------------------
bool PerspectiveGridGeometry::Outside(const double c[3], double r) const
{
  for (int k = 0; k < 6; ++k)
  {
    const double* p = this->Frustum + 4 * k;
    if (p[0] * c[0] + p[1] * c[1] + p[2] * c[2] + p[3] < -r)
    {
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
void PerspectiveGridGeometry::Extend(const double c[3], double r, double& nearD, double& farD) const
{
  const double lo = std::min(std::max(-c[2] - r, this->ProjectionNear), this->ProjectionFar);
  const double hi = std::min(std::max(-c[2] + r, this->ProjectionNear), this->ProjectionFar);
  nearD = std::min(nearD, std::max(lo, 0.0));
  farD = std::max(farD, std::max(hi, 0.0));
}

//------------------------------------------------------------------------------
void PerspectiveGridGeometry::SetSlabRange(double nearD, double farD)
{
  if (!(farD > nearD))
  {
    nearD = this->ProjectionNear;
    farD = std::min(this->ProjectionFar, this->ProjectionNear + 1.0);
  }
  this->SlabNear = nearD;
  this->SlabFar = farD;
  this->Planes.resize(this->Slabs + 1);
  for (int k = 0; k <= this->Slabs; ++k)
  {
    this->Planes[k] = nearD + (farD - nearD) * k / this->Slabs;
  }
  this->Planes.back() = farD;
}

//------------------------------------------------------------------------------
int PerspectiveGridGeometry::SlabOf(double d) const
{
  // Clamped in double first: a cast of a value beyond int is undefined.
  const double k =
    std::floor((d - this->SlabNear) / (this->SlabFar - this->SlabNear) * this->Slabs);
  return static_cast<int>(std::min(std::max(k, 0.0), this->Slabs - 1.0));
}

//------------------------------------------------------------------------------
bool PerspectiveGridGeometry::Range(const double c[3], double r, int range[6]) const
{
  const double d = -c[2];
  if (this->Planes.empty() || d + r < this->SlabNear || d - r > this->SlabFar)
  {
    return false;
  }
  double lo[2] = { 1e300, 1e300 }, hi[2] = { -1e300, -1e300 };
  bool everywhere = !this->Parallel && d - r <= 0.0;
  double centre[4];
  Project(this->ViewToClip, c, centre);
  for (int k = 0; k < 8 && !everywhere; ++k)
  {
    const double clip[4] = { centre[0] + r * this->Corners[k][0],
      centre[1] + r * this->Corners[k][1],
      centre[2] + r * this->Corners[k][2],
      centre[3] + r * this->Corners[k][3] };
    if (!(clip[3] > 0.0))
    {
      everywhere = true;
      break;
    }
    const double px = (0.5 * clip[0] / clip[3] + 0.5) * this->Width;
    const double py = (0.5 * clip[1] / clip[3] + 0.5) * this->Height;
    lo[0] = std::min(lo[0], px);
    lo[1] = std::min(lo[1], py);
    hi[0] = std::max(hi[0], px);
    hi[1] = std::max(hi[1], py);
  }
  if (everywhere)
  {
    range[0] = 0;
    range[1] = this->TilesX - 1;
    range[2] = 0;
    range[3] = this->TilesY - 1;
  }
  else
  {
    if (hi[0] < 0.0 || hi[1] < 0.0 || lo[0] >= this->Width || lo[1] >= this->Height)
    {
      return false;
    }
    range[0] = TileOf(lo[0], this->TileSize, this->TilesX);
    range[1] = TileOf(hi[0], this->TileSize, this->TilesX);
    range[2] = TileOf(lo[1], this->TileSize, this->TilesY);
    range[3] = TileOf(hi[1], this->TileSize, this->TilesY);
  }
  range[4] = this->SlabOf(d - r);
  range[5] = this->SlabOf(d + r);
  return true;
}
} // namespace pointsurfaces
