// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMetaballLevelSetWriter.h"

#include "vtkErrorCode.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointSet.h"

#include "psOpenVDBMetaballs.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkMetaballLevelSetWriter);

//------------------------------------------------------------------------------
vtkMetaballLevelSetWriter::vtkMetaballLevelSetWriter()
  : Field(vtkSmartPointer<vtkMetaballField>::New())
{
}

//------------------------------------------------------------------------------
void vtkMetaballLevelSetWriter::SetField(vtkMetaballField* field)
{
  vtkMetaballField::Assign(this->Field, field, this);
}

//------------------------------------------------------------------------------
vtkMTimeType vtkMetaballLevelSetWriter::GetMTime()
{
  return std::max(this->Superclass::GetMTime(), this->Field->GetMTime());
}

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

  vtkMetaballField* field = this->Field;
  const double threshold = field->GetThreshold();
  pointsurfaces::LevelSetBalls prepared = pointsurfaces::PrepareLevelSet(field->ExtractBalls(input),
    field->GetStrengthArrayName(),
    this->VoxelSize,
    this->MaximumVoxels);
  const pointsurfaces::BallSummary& balls = prepared.Summary;
  this->NumberOfInvalidBalls = static_cast<vtkIdType>(balls.Invalid);
  for (const std::string& warning : prepared.Warnings)
  {
    vtkWarningMacro(<< warning);
  }
  if (!std::isfinite(threshold) || threshold <= 0.0)
  {
    vtkErrorMacro(<< "The threshold must be a positive number, not " << threshold << ".");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  if (!prepared.Error.empty())
  {
    vtkErrorMacro(<< "Nothing is written: " << prepared.Error << ".");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  if (balls.Valid.empty())
  {
    vtkWarningMacro(<< "No valid ball in the input: an empty level set is written.");
  }
  const double voxel = prepared.Voxel;
  this->UsedVoxelSize = voxel;

  openvdb::FloatGrid::Ptr levelSet;
  try
  {
    // Sampled and meshed in a frame centred on the data (OpenVDB meshes in
    // float), then the transform moves the level set into place.
    levelSet = pointsurfaces::MetaballLevelSet(prepared.Arrays.Set, balls, voxel, this->HalfWidth);
    openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(voxel);
    xform->postTranslate(balls.Centre);
    levelSet->setTransform(xform);
    levelSet->setName(this->GridName);
    levelSet->setGridClass(openvdb::GRID_LEVEL_SET);
    levelSet->insertMeta("metaball_kernel",
      openvdb::StringMetadata(pointsurfaces::MetaballKernelName(field->GetKernelId())));
    levelSet->insertMeta("metaball_threshold", openvdb::DoubleMetadata(threshold));
    levelSet->insertMeta(
      "metaball_count", openvdb::Int64Metadata(static_cast<int64_t>(balls.Valid.size())));
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
  os << indent << "Field:\n";
  this->Field->PrintSelf(os, indent.GetNextIndent());
  os << indent << "VoxelSize: " << this->VoxelSize << "\n";
  os << indent << "HalfWidth: " << this->HalfWidth << "\n";
  os << indent << "MaximumVoxels: " << this->MaximumVoxels << "\n";
}
