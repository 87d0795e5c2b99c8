// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenVDBMetaballs.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <openvdb/tools/Composite.h>
#include <openvdb/tools/GridOperators.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetRebuild.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/ValueTransformer.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pointsurfaces
{
namespace
{
// Adds each ball's kernel to the voxels inside its support, one sparse grid per thread.
struct SplatKernels
{
  const MetaballSet& Set;
  const BallSummary& Balls;
  double Voxel;
  vtkSMPThreadLocal<openvdb::FloatGrid::Ptr> Grids;

  SplatKernels(const MetaballSet& set, const BallSummary& balls, double voxel)
    : Set(set)
    , Balls(balls)
    , Voxel(voxel)
  {
  }

  void Initialize() { this->Grids.Local() = openvdb::FloatGrid::create(0.0f); }

  void operator()(vtkIdType begin, vtkIdType end)
  {
    openvdb::FloatGrid::Accessor acc = this->Grids.Local()->getAccessor();
    for (vtkIdType k = begin; k < end; ++k)
    {
      const long long b = this->Balls.Valid[k];
      const double* c = this->Set.Centers + 3 * b;
      const double q = this->Set.Strengths ? this->Set.Strengths[b] : 1.0;
      double centre[3]; // in voxels, in the centred frame
      for (int a = 0; a < 3; ++a)
      {
        centre[a] = (c[a] - this->Balls.Centre[a]) / this->Voxel;
      }
      const double r = this->Set.Radii[b] / this->Voxel;
      const double inv = 1.0 / (r * r);
      openvdb::Coord lo, hi;
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = static_cast<openvdb::Int32>(std::floor(centre[a] - r));
        hi[a] = static_cast<openvdb::Int32>(std::ceil(centre[a] + r));
      }
      openvdb::Coord ijk;
      for (ijk[0] = lo[0]; ijk[0] <= hi[0]; ++ijk[0])
      {
        const double dx = ijk[0] - centre[0];
        for (ijk[1] = lo[1]; ijk[1] <= hi[1]; ++ijk[1])
        {
          const double dy = ijk[1] - centre[1];
          const double dxy = dx * dx + dy * dy;
          if (dxy * inv >= 1.0)
          {
            continue;
          }
          for (ijk[2] = lo[2]; ijk[2] <= hi[2]; ++ijk[2])
          {
            const double dz = ijk[2] - centre[2];
            const double x = (dxy + dz * dz) * inv;
            if (x < 1.0)
            {
              const double value = q * KernelValue(this->Set.Kernel, x);
              acc.setValue(ijk, acc.getValue(ijk) + static_cast<float>(value));
            }
          }
        }
      }
    }
  }

  void Reduce() {}
};

// The particle list interface of ParticlesToLevelSet, in the centred frame.
struct Particles
{
  using PosType = openvdb::Vec3R;
  const MetaballSet& Set;
  const BallSummary& Balls;
  const std::vector<double>& Radius;
  size_t size() const { return this->Balls.Valid.size(); }
  void getPos(size_t n, openvdb::Vec3R& xyz) const
  {
    const double* c = this->Set.Centers + 3 * this->Balls.Valid[n];
    xyz = openvdb::Vec3R(c[0], c[1], c[2]) - this->Balls.Centre;
  }
  void getPosRad(size_t n, openvdb::Vec3R& xyz, openvdb::Real& radius) const
  {
    this->getPos(n, xyz);
    radius = this->Radius[this->Balls.Valid[n]];
  }
};
} // namespace

//------------------------------------------------------------------------------
std::vector<std::string> BallWarnings(const BallArrays& arrays,
  const BallSummary& balls,
  const std::string& strengthName)
{
  std::vector<std::string> warnings;
  for (std::string warning : { MissingStrengthsWarning(arrays, strengthName),
         InvalidBallsWarning(balls.Invalid, arrays.Set.Count) })
  {
    if (!warning.empty())
    {
      warnings.push_back(std::move(warning));
    }
  }
  return warnings;
}

//------------------------------------------------------------------------------
bool ChooseVoxel(const BallSummary& balls,
  double requested,
  double maximumVoxels,
  double& voxel,
  std::string& warning,
  std::string& error)
{
  warning.clear();
  error.clear();
  if (balls.Valid.empty())
  {
    voxel = requested > 0.0 ? requested : 1.0;
    return true;
  }
  const double volume = 4.0 / 3.0 * 3.14159265358979323846 * balls.SumCubedRadius;
  const double budget = std::cbrt(volume / maximumVoxels);
  voxel = requested;
  if (voxel <= 0.0)
  {
    voxel = balls.MinRadius / 10.0;
    if (voxel < budget)
    {
      warning = "A voxel of a tenth of the smallest radius (" + std::to_string(voxel) +
        ") would sample more than MaximumVoxels = " + std::to_string(maximumVoxels) + ": using " +
        std::to_string(budget) + "; balls smaller than two voxels fade from the surface";
      voxel = budget;
    }
  }
  else if (voxel < budget)
  {
    error = "VoxelSize " + std::to_string(voxel) + " would sample about " +
      std::to_string(volume / (voxel * voxel * voxel)) +
      " voxels, more than MaximumVoxels = " + std::to_string(maximumVoxels) + "; use at least " +
      std::to_string(budget);
    return false;
  }
  const double extent =
    std::max({ balls.Hi[0] - balls.Lo[0], balls.Hi[1] - balls.Lo[1], balls.Hi[2] - balls.Lo[2] });
  if (extent / voxel > 1e9)
  {
    error = "the balls span " + std::to_string(extent / voxel) +
      " voxels, beyond OpenVDB's 32-bit coordinates";
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
LevelSetBalls PrepareLevelSet(BallArrays arrays,
  const std::string& strengthName,
  double requestedVoxel,
  double maximumVoxels)
{
  LevelSetBalls out;
  out.Arrays = std::move(arrays);
  out.Summary = SummariseBalls(out.Arrays.Set);
  out.Warnings = BallWarnings(out.Arrays, out.Summary, strengthName);
  std::string warning;
  if (!ChooseVoxel(out.Summary, requestedVoxel, maximumVoxels, out.Voxel, warning, out.Error))
  {
    out.Voxel = 0.0;
    return out;
  }
  if (!warning.empty())
  {
    out.Warnings.push_back(warning + ".");
  }
  out.Summary.CentreOn(out.Voxel);
  return out;
}

//------------------------------------------------------------------------------
void BallSummary::CentreOn(double voxel)
{
  for (int a = 0; a < 3; ++a)
  {
    this->Centre[a] =
      this->Valid.empty() ? 0.0 : std::round(0.5 * (this->Lo[a] + this->Hi[a]) / voxel) * voxel;
  }
}

//------------------------------------------------------------------------------
BallSummary SummariseBalls(const MetaballSet& set)
{
  BallSummary s;
  s.Valid.reserve(static_cast<size_t>(set.Count));
  s.MinRadius = std::numeric_limits<double>::max();
  for (int a = 0; a < 3; ++a)
  {
    s.Lo[a] = std::numeric_limits<double>::max();
    s.Hi[a] = -std::numeric_limits<double>::max();
  }
  for (long long i = 0; i < set.Count; ++i)
  {
    if (!ValidBall(set, i))
    {
      ++s.Invalid;
      continue;
    }
    const double r = set.Radii[i];
    s.Valid.push_back(i);
    s.MinRadius = std::min(s.MinRadius, r);
    s.SumCubedRadius += r * r * r;
    for (int a = 0; a < 3; ++a)
    {
      s.Lo[a] = std::min(s.Lo[a], set.Centers[3 * i + a] - r);
      s.Hi[a] = std::max(s.Hi[a], set.Centers[3 * i + a] + r);
    }
  }
  if (s.Valid.empty())
  {
    s.MinRadius = 0.0;
    for (int a = 0; a < 3; ++a)
    {
      s.Lo[a] = s.Hi[a] = 0.0;
    }
  }
  return s;
}

//------------------------------------------------------------------------------
openvdb::FloatGrid::Ptr MetaballLevelSet(const MetaballSet& set,
  const BallSummary& balls,
  double voxel,
  double halfWidth)
{
  openvdb::initialize();
  openvdb::math::Transform::Ptr local = openvdb::math::Transform::createLinearTransform(voxel);
  if (balls.Valid.empty())
  {
    openvdb::FloatGrid::Ptr empty =
      openvdb::FloatGrid::create(static_cast<float>(halfWidth * voxel));
    empty->setTransform(local);
    empty->setGridClass(openvdb::GRID_LEVEL_SET);
    return empty;
  }
  SplatKernels splat(set, balls, voxel);
  vtkSMPTools::For(0, static_cast<vtkIdType>(balls.Valid.size()), 64, splat);
  openvdb::FloatGrid::Ptr sum;
  for (openvdb::FloatGrid::Ptr& grid : splat.Grids)
  {
    if (!sum)
    {
      sum = grid;
    }
    else
    {
      openvdb::tools::compSum(*sum, *grid);
    }
  }
  sum->setTransform(local);
  // (T - sum) / |grad sum|: the first-order distance to the surface,
  // negative inside. Meshing interpolates it linearly between voxels,
  // which is closer to the truth than interpolating the kernel sum.
  openvdb::Vec3fGrid::Ptr gradient = openvdb::tools::gradient(*sum);
  openvdb::Vec3fGrid::ConstAccessor gradientAccess = gradient->getConstAccessor();
  const float threshold = static_cast<float>(set.Threshold);
  const float far = static_cast<float>((halfWidth + 2.0) * voxel);
  for (auto it = sum->beginValueOn(); it; ++it)
  {
    const float g = gradientAccess.getValue(it.getCoord()).length();
    const float excess = threshold - *it;
    const float distance = g > 0.0f ? excess / g : std::copysign(far, excess);
    it.setValue(std::max(-far, std::min(far, distance)));
  }
  openvdb::tools::changeBackground(sum->tree(), far);
  openvdb::FloatGrid::Ptr levelSet =
    openvdb::tools::levelSetRebuild(*sum, 0.0f, static_cast<float>(halfWidth), local.get());
  levelSet->setGridClass(openvdb::GRID_LEVEL_SET);
  return levelSet;
}

//------------------------------------------------------------------------------
openvdb::FloatGrid::Ptr SphereLevelSet(const MetaballSet& set,
  const BallSummary& balls,
  const std::vector<double>& sphereRadius,
  double voxel,
  double halfWidth,
  size_t& tooSmall)
{
  openvdb::initialize();
  openvdb::FloatGrid::Ptr grid = openvdb::createLevelSet<openvdb::FloatGrid>(voxel, halfWidth);
  tooSmall = 0;
  if (!balls.Valid.empty())
  {
    openvdb::tools::ParticlesToLevelSet<openvdb::FloatGrid> raster(*grid);
    // OpenVDB skips spheres under Rmin voxels; its own counter is not
    // reliable across threads, so count them here.
    for (long long b : balls.Valid)
    {
      tooSmall += sphereRadius[b] / voxel < raster.getRmin() ? 1 : 0;
    }
    raster.rasterizeSpheres(Particles{ set, balls, sphereRadius });
    raster.finalize(/*prune=*/true);
  }
  return grid;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> MeshLevelSet(const openvdb::FloatGrid& grid,
  const openvdb::Vec3d& centre,
  double adaptivity)
{
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(grid, points, triangles, quads, 0.0, adaptivity);

  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(static_cast<vtkIdType>(points.size()));
  openvdb::Vec3fGrid::Ptr gradient = openvdb::tools::gradient(grid);
  vtkSMPTools::For(0,
    static_cast<vtkIdType>(points.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      openvdb::tools::GridSampler<openvdb::Vec3fGrid, openvdb::tools::BoxSampler> sampler(
        *gradient);
      for (vtkIdType i = begin; i < end; ++i)
      {
        const openvdb::Vec3s& p = points[i];
        pts->SetPoint(i, p[0] + centre[0], p[1] + centre[1], p[2] + centre[2]);
        openvdb::Vec3f n = sampler.wsSample(openvdb::Vec3d(p));
        const float length = n.length();
        n = length > 0.0f ? n / length : openvdb::Vec3f(0.0f, 0.0f, 1.0f);
        normals->SetTypedTuple(i, n.asPointer());
      }
    });
  // volumeToMesh's polygons face inward for a level set (negative inside): reverse them.
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(triangles.size() + quads.size() + 1));
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(3 * triangles.size() + 4 * quads.size()));
  vtkIdType cell = 0, at = 0;
  for (const openvdb::Vec4I& q : quads)
  {
    offsets->SetValue(cell++, at);
    for (int k = 3; k >= 0; --k)
    {
      connectivity->SetValue(at++, q[k]);
    }
  }
  for (const openvdb::Vec3I& t : triangles)
  {
    offsets->SetValue(cell++, at);
    for (int k = 2; k >= 0; --k)
    {
      connectivity->SetValue(at++, t[k]);
    }
  }
  offsets->SetValue(cell, at);
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  mesh->SetPoints(pts);
  mesh->SetPolys(polys);
  mesh->GetPointData()->SetNormals(normals);
  return mesh;
}

} // namespace pointsurfaces
