// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMetaballLevelSetWriter.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include "psMetaball.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/GridOperators.h>
#include <openvdb/tools/LevelSetRebuild.h>
#include <openvdb/tools/ValueTransformer.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkMetaballLevelSetWriter);

namespace
{
// Adds each ball's kernel to the voxels inside its support, one sparse grid
// per thread.
struct SplatKernels
{
  const pointsurfaces::MetaballSet& Set;
  const std::vector<long long>& Balls;
  const openvdb::math::Transform& Transform;
  double Voxel;
  vtkSMPThreadLocal<openvdb::FloatGrid::Ptr> Grids;

  SplatKernels(const pointsurfaces::MetaballSet& set,
    const std::vector<long long>& balls,
    const openvdb::math::Transform& xform,
    double voxel)
    : Set(set)
    , Balls(balls)
    , Transform(xform)
    , Voxel(voxel)
  {
  }

  void Initialize() { this->Grids.Local() = openvdb::FloatGrid::create(0.0f); }

  void operator()(vtkIdType begin, vtkIdType end)
  {
    openvdb::FloatGrid::Accessor acc = this->Grids.Local()->getAccessor();
    for (vtkIdType k = begin; k < end; ++k)
    {
      const long long b = this->Balls[k];
      const double* c = this->Set.Centers + 3 * b;
      const double radius = this->Set.Radii[b];
      const double q = this->Set.Strengths ? this->Set.Strengths[b] : 1.0;
      const openvdb::Vec3d centre = this->Transform.worldToIndex(openvdb::Vec3d(c[0], c[1], c[2]));
      const double r = radius / this->Voxel; // in voxels
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
              const double value = q * pointsurfaces::KernelValue(this->Set.Kernel, x);
              acc.setValue(ijk, acc.getValue(ijk) + static_cast<float>(value));
            }
          }
        }
      }
    }
  }

  void Reduce() {}
};
} // namespace

//------------------------------------------------------------------------------
vtkMetaballLevelSetWriter::vtkMetaballLevelSetWriter() = default;

//------------------------------------------------------------------------------
int vtkMetaballLevelSetWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

//------------------------------------------------------------------------------
void vtkMetaballLevelSetWriter::WriteData()
{
  this->NumberOfInvalidBalls = 0;
  this->UsedVoxelSize = 0.0;
  this->NumberOfActiveVoxels = 0;
  vtkPointSet* input = vtkPointSet::SafeDownCast(this->GetInput());
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No FileName set.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  if (!input)
  {
    vtkErrorMacro(<< "The input is not a vtkPointSet.");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }

  // Balls in double; radii from the array or the constant, times the scale.
  const vtkIdType n = input->GetNumberOfPoints();
  vtkPointData* pd = input->GetPointData();
  vtkDataArray* radiusArray = pd->GetArray(this->RadiusArrayName.c_str());
  vtkDataArray* strengthArray =
    this->StrengthArrayName.empty() ? nullptr : pd->GetArray(this->StrengthArrayName.c_str());
  if (!this->StrengthArrayName.empty() && !strengthArray)
  {
    vtkWarningMacro(<< "No point array \"" << this->StrengthArrayName
                    << "\" for the strengths: all balls have strength 1.");
  }
  std::vector<double> centres(3 * static_cast<size_t>(n)), radii(n), strengths;
  for (vtkIdType i = 0; i < n; ++i)
  {
    input->GetPoint(i, &centres[3 * i]);
    // A multi-component radius array (vtkPDBReader's) holds the radius first.
    radii[i] = this->RadiusScale * (radiusArray ? radiusArray->GetComponent(i, 0) : this->Radius);
  }
  if (strengthArray)
  {
    strengths.resize(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      strengths[i] = strengthArray->GetComponent(i, 0);
    }
  }
  pointsurfaces::MetaballSet set;
  set.Centers = centres.data();
  set.Radii = radii.data();
  set.Strengths = strengthArray ? strengths.data() : nullptr;
  set.Count = n;
  set.Kernel = static_cast<pointsurfaces::MetaballKernel>(this->Kernel);
  set.Threshold = this->Threshold;

  std::vector<long long> balls;
  balls.reserve(n);
  double minRadius = std::numeric_limits<double>::max();
  double volume = 0.0; // sum of R^3
  double lo[3] = { std::numeric_limits<double>::max(),
    std::numeric_limits<double>::max(),
    std::numeric_limits<double>::max() };
  double hi[3] = { -lo[0], -lo[1], -lo[2] };
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (!pointsurfaces::ValidBall(set, i))
    {
      ++this->NumberOfInvalidBalls;
      continue;
    }
    balls.push_back(i);
    minRadius = std::min(minRadius, radii[i]);
    volume += radii[i] * radii[i] * radii[i];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], centres[3 * i + a] - radii[i]);
      hi[a] = std::max(hi[a], centres[3 * i + a] + radii[i]);
    }
  }
  if (this->NumberOfInvalidBalls > 0)
  {
    vtkWarningMacro(<< this->NumberOfInvalidBalls << " of " << n
                    << " balls have a NaN or infinite centre, radius or strength, or a radius "
                       "<= 0: they are skipped.");
  }
  if (!std::isfinite(this->Threshold) || this->Threshold <= 0.0)
  {
    vtkErrorMacro(<< "The threshold must be a positive number, not " << this->Threshold << ".");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }

  // The voxel size: given, or a tenth of the smallest radius within budget.
  const double ballVoxels = 4.0 / 3.0 * vtkMath::Pi() * volume; // sum of ball volumes
  double voxel = this->VoxelSize;
  if (!balls.empty())
  {
    const double budgetVoxel = std::cbrt(ballVoxels / this->MaximumVoxels);
    if (voxel <= 0.0)
    {
      voxel = minRadius / 10.0;
      if (voxel < budgetVoxel)
      {
        vtkWarningMacro(<< "A voxel of a tenth of the smallest radius (" << voxel
                        << ") would sample more than MaximumVoxels = " << this->MaximumVoxels
                        << ": using " << budgetVoxel
                        << "; balls smaller than two voxels fade from the surface.");
        voxel = budgetVoxel;
      }
    }
    else if (voxel < budgetVoxel)
    {
      vtkErrorMacro(<< "VoxelSize " << voxel << " would sample about "
                    << ballVoxels / (voxel * voxel * voxel)
                    << " voxels, more than MaximumVoxels = " << this->MaximumVoxels
                    << ": nothing is written. Use at least " << budgetVoxel << ".");
      this->SetErrorCode(vtkErrorCode::OutOfDiskSpaceError);
      return;
    }
    const double extent = std::max({ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2] });
    if (extent / voxel > 1e9)
    {
      vtkErrorMacro(<< "The balls span " << extent / voxel
                    << " voxels, beyond OpenVDB's 32-bit coordinates: nothing is written.");
      this->SetErrorCode(vtkErrorCode::UnknownError);
      return;
    }
  }
  else
  {
    voxel = this->VoxelSize > 0.0 ? this->VoxelSize : 1.0;
    vtkWarningMacro(<< "No valid ball in the input: an empty level set is written.");
  }
  this->UsedVoxelSize = voxel;

  openvdb::initialize();
  openvdb::FloatGrid::Ptr levelSet;
  try
  {
    // The field is sampled and meshed in a frame centred on the data (OpenVDB
    // meshes in float world coordinates), then the level set is moved there.
    openvdb::math::Transform::Ptr local = openvdb::math::Transform::createLinearTransform(voxel);
    openvdb::math::Transform::Ptr xform = local->copy();
    openvdb::Vec3d centre(0.0);
    if (!balls.empty())
    {
      for (int a = 0; a < 3; ++a)
      {
        centre[a] = std::round(0.5 * (lo[a] + hi[a]) / voxel) * voxel;
      }
      xform->postTranslate(centre);
    }
    if (balls.empty())
    {
      levelSet = openvdb::FloatGrid::create(static_cast<float>(this->HalfWidth * voxel));
    }
    else
    {
      std::vector<double> shifted(centres);
      for (long long b : balls)
      {
        for (int a = 0; a < 3; ++a)
        {
          shifted[3 * b + a] -= centre[a];
        }
      }
      pointsurfaces::MetaballSet localSet = set;
      localSet.Centers = shifted.data();
      SplatKernels splat(localSet, balls, *local, voxel);
      vtkSMPTools::For(0, static_cast<vtkIdType>(balls.size()), 64, splat);
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
      // which is far closer to the truth than interpolating the kernel sum.
      openvdb::Vec3fGrid::Ptr gradient = openvdb::tools::gradient(*sum);
      openvdb::Vec3fGrid::ConstAccessor gradientAccess = gradient->getConstAccessor();
      const float threshold = static_cast<float>(this->Threshold);
      const float far = static_cast<float>((this->HalfWidth + 2.0) * voxel);
      for (auto it = sum->beginValueOn(); it; ++it)
      {
        const float g = gradientAccess.getValue(it.getCoord()).length();
        const float excess = threshold - *it;
        const float distance = g > 0.0f ? excess / g : std::copysign(far, excess);
        it.setValue(std::max(-far, std::min(far, distance)));
      }
      openvdb::tools::changeBackground(sum->tree(), far);
      levelSet = openvdb::tools::levelSetRebuild(
        *sum, 0.0f, static_cast<float>(this->HalfWidth), local.get());
    }
    levelSet->setTransform(xform);
    levelSet->setName(this->GridName);
    levelSet->setGridClass(openvdb::GRID_LEVEL_SET);
    levelSet->insertMeta("metaball_kernel",
      openvdb::StringMetadata(this->Kernel == Quartic ? "quartic"
          : this->Kernel == Gaussian                  ? "gaussian"
                                                      : "wyvill"));
    levelSet->insertMeta("metaball_threshold", openvdb::DoubleMetadata(this->Threshold));
    levelSet->insertMeta("metaball_count", openvdb::Int64Metadata(balls.size()));
    this->NumberOfActiveVoxels = static_cast<vtkIdType>(levelSet->activeVoxelCount());

    openvdb::io::File file(this->FileName);
    openvdb::GridPtrVec grids{ levelSet };
    file.write(grids);
    file.close();
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "Cannot write \"" << this->FileName << "\": " << e.what());
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    return;
  }
}

//------------------------------------------------------------------------------
void vtkMetaballLevelSetWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "GridName: " << this->GridName << "\n";
  os << indent << "Kernel: " << this->Kernel << "\n";
  os << indent << "Threshold: " << this->Threshold << "\n";
  os << indent << "RadiusArrayName: " << this->RadiusArrayName << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "RadiusScale: " << this->RadiusScale << "\n";
  os << indent << "StrengthArrayName: " << this->StrengthArrayName << "\n";
  os << indent << "VoxelSize: " << this->VoxelSize << "\n";
  os << indent << "HalfWidth: " << this->HalfWidth << "\n";
  os << indent << "MaximumVoxels: " << this->MaximumVoxels << "\n";
}
