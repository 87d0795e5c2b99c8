// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenVDBParticleMesher.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointSet.h"
#include "vtkPolyData.h"

#include "psOpenVDBMetaballs.h"

#include <algorithm>
#include <chrono>
#include <cmath>

vtkStandardNewMacro(vtkOpenVDBParticleMesher);

//------------------------------------------------------------------------------
vtkOpenVDBParticleMesher::vtkOpenVDBParticleMesher()
  : Field(vtkSmartPointer<vtkMetaballField>::New())
{
}

//------------------------------------------------------------------------------
void vtkOpenVDBParticleMesher::SetField(vtkMetaballField* field)
{
  vtkMetaballField::Assign(this->Field, field, this);
}

//------------------------------------------------------------------------------
vtkMTimeType vtkOpenVDBParticleMesher::GetMTime()
{
  return std::max(this->Superclass::GetMTime(), this->Field->GetMTime());
}

//------------------------------------------------------------------------------
int vtkOpenVDBParticleMesher::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

//------------------------------------------------------------------------------
int vtkOpenVDBParticleMesher::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->LevelSetTime = this->MeshTime = this->UsedVoxelSize = 0.0;
  this->NumberOfInvalidBalls = this->NumberOfSkippedParticles = 0;
  if (!input || input->GetNumberOfPoints() == 0)
  {
    vtkWarningMacro(<< "No balls in the input: the mesh is empty.");
    return 1;
  }
  pointsurfaces::BallRule rule = this->Field->GetRule();
  const auto kernel = rule.Kernel;
  const double threshold = rule.Threshold;
  if (!std::isfinite(threshold) || threshold <= 0.0)
  {
    vtkErrorMacro(<< "The threshold must be a positive number, not " << threshold << ".");
    return 1;
  }
  const std::string strengthName = rule.StrengthArrayName;
  if (this->Method != MetaballField)
  {
    rule.StrengthArrayName.clear(); // spheres have no strengths
  }
  pointsurfaces::LevelSetBalls prepared = pointsurfaces::PrepareLevelSet(
    pointsurfaces::ExtractBalls(input, rule), strengthName, this->VoxelSize, this->MaximumVoxels);
  const pointsurfaces::BallArrays& arrays = prepared.Arrays;
  const pointsurfaces::BallSummary& balls = prepared.Summary;
  this->NumberOfInvalidBalls = static_cast<vtkIdType>(balls.Invalid);
  for (const std::string& warning : prepared.Warnings)
  {
    vtkWarningMacro(<< warning);
  }
  if (balls.Valid.empty())
  {
    vtkWarningMacro(<< "No valid ball: the mesh is empty.");
    return 1;
  }
  if (!prepared.Error.empty())
  {
    vtkErrorMacro(<< "No mesh: " << prepared.Error << ".");
    return 1;
  }
  const double voxel = prepared.Voxel;
  this->UsedVoxelSize = voxel;

  const double halfWidth = 3.0;
  try
  {
    const auto start = std::chrono::steady_clock::now();
    openvdb::FloatGrid::Ptr levelSet;
    if (this->Method == MetaballField)
    {
      levelSet = pointsurfaces::MetaballLevelSet(arrays.Set, balls, voxel, halfWidth);
    }
    else
    {
      // Each sphere has the radius at which its lone ball reaches T.
      const double iso = pointsurfaces::LoneBallIsoRadius(kernel, threshold);
      std::vector<double> radius(arrays.Radii);
      for (double& r : radius)
      {
        r *= iso;
      }
      size_t skipped = 0;
      levelSet =
        pointsurfaces::SphereLevelSet(arrays.Set, balls, radius, voxel, halfWidth, skipped);
      this->NumberOfSkippedParticles = static_cast<vtkIdType>(skipped);
      if (skipped > 0)
      {
        vtkWarningMacro(<< skipped
                        << " spheres are under 1.5 voxels, which OpenVDB's ParticlesToLevelSet "
                           "skips: make VoxelSize smaller.");
      }
    }
    const auto meshed = std::chrono::steady_clock::now();
    output->ShallowCopy(pointsurfaces::MeshLevelSet(*levelSet, balls.Centre, this->Adaptivity));
    const auto end = std::chrono::steady_clock::now();
    this->LevelSetTime = std::chrono::duration<double, std::milli>(meshed - start).count();
    this->MeshTime = std::chrono::duration<double, std::milli>(end - meshed).count();
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "OpenVDB failed: " << e.what());
    output->Initialize();
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkOpenVDBParticleMesher::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << (this->Method == Spheres ? "Spheres" : "MetaballField") << "\n";
  os << indent << "Field:\n";
  this->Field->PrintSelf(os, indent.GetNextIndent());
  os << indent << "VoxelSize: " << this->VoxelSize << "\n";
  os << indent << "Adaptivity: " << this->Adaptivity << "\n";
  os << indent << "MaximumVoxels: " << this->MaximumVoxels << "\n";
}
