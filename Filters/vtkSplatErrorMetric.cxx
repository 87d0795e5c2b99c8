// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSplatErrorMetric.h"

#include "psPolynomial.h"
#include "psSplatError.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSplatDataModel.h"

#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkSplatErrorMetric);

namespace
{
// Copy an array that vtkSplatDataModel::GetSplatDegree() has validated.
void Fetch(vtkPointData* pd,
  const char* name,
  int components,
  vtkIdType n,
  std::vector<double>& out)
{
  vtkDataArray* a = pd->GetArray(name);
  out.resize(static_cast<size_t>(n) * components);
  for (vtkIdType i = 0; i < n; ++i)
  {
    a->GetTuple(i, &out[static_cast<size_t>(i) * components]);
  }
}

void AddValue(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}
} // namespace

//------------------------------------------------------------------------------
vtkSplatErrorMetric::vtkSplatErrorMetric()
{
  this->SetNumberOfInputPorts(2);
}

//------------------------------------------------------------------------------
int vtkSplatErrorMetric::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkPointSet" : "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkSplatErrorMetric::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPointSet* points = vtkPointSet::GetData(inputVector[0]);
  vtkPolyData* splats = vtkPolyData::GetData(inputVector[1]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->RMSDistance = this->MaximumDistance = this->Phi = 0.0;
  this->NumberOfUncoveredPoints = 0;

  // Splat arrays, checked against the data model.
  const int degree = vtkSplatDataModel::GetSplatDegree(splats);
  const vtkIdType m = degree > 0 ? splats->GetNumberOfPoints() : 0;
  std::vector<double> origin, normal, tangent, scale, radius, coeffs;
  if (degree < 0)
  {
    vtkErrorMacro(<< "Input 1 is not a splat set: it needs points, SplatDegree in the field data "
                     "and the SplatNormal, SplatTangent, SplatFeatureSize, SplatRadius and "
                     "SplatCoefficients point arrays.");
    return 1;
  }
  vtkPointData* spd = splats->GetPointData();
  Fetch(spd, vtkSplatDataModel::NormalName(), 3, m, normal);
  Fetch(spd, vtkSplatDataModel::TangentName(), 3, m, tangent);
  Fetch(spd, vtkSplatDataModel::FeatureSizeName(), 1, m, scale);
  Fetch(spd, vtkSplatDataModel::RadiusName(), 1, m, radius);
  Fetch(
    spd, vtkSplatDataModel::CoefficientsName(), pointsurfaces::MonomialCount(degree), m, coeffs);
  origin.resize(3 * m);
  for (vtkIdType j = 0; j < m; ++j)
  {
    splats->GetPoint(j, &origin[3 * j]);
  }

  // Finite input points.
  const vtkIdType n = points->GetNumberOfPoints();
  std::vector<double> xyz;
  std::vector<vtkIdType> kept;
  xyz.reserve(3 * n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
    {
      xyz.insert(xyz.end(), p, p + 3);
      kept.push_back(i);
    }
  }
  if (static_cast<vtkIdType>(kept.size()) < n)
  {
    vtkWarningMacro(<< "Skipped " << n - static_cast<vtkIdType>(kept.size())
                    << " points with NaN or infinite coordinates.");
  }

  pointsurfaces::SplatArrays arrays;
  arrays.Origin = origin.data();
  arrays.Normal = normal.data();
  arrays.Tangent = tangent.data();
  arrays.Scale = scale.data();
  arrays.Radius = radius.data();
  arrays.Coefficients = coeffs.data();
  arrays.Degree = degree;
  arrays.Count = m;
  std::vector<double> delta, distance;
  std::vector<int> covering;
  const pointsurfaces::ErrorSummary summary = pointsurfaces::EvaluateSplatError(
    arrays, xyz.data(), static_cast<long long>(kept.size()), delta, distance, covering);

  // Output: the input's points with the per-point errors (NaN points get NaN).
  vtkNew<vtkPoints> outPoints;
  outPoints->ShallowCopy(points->GetPoints());
  output->SetPoints(outPoints);
  vtkSplatDataModel::AddVertexCells(output);
  output->GetPointData()->PassData(points->GetPointData());
  vtkNew<vtkDoubleArray> deltaArray, distanceArray;
  vtkNew<vtkIntArray> coverArray;
  deltaArray->SetName("SplatError");
  distanceArray->SetName("SurfaceDistance");
  coverArray->SetName("SplatCoverage");
  deltaArray->SetNumberOfValues(n);
  distanceArray->SetNumberOfValues(n);
  coverArray->SetNumberOfValues(n);
  deltaArray->Fill(std::nan(""));
  distanceArray->Fill(std::nan(""));
  coverArray->Fill(0);
  for (size_t k = 0; k < kept.size(); ++k)
  {
    deltaArray->SetValue(kept[k], delta[k]);
    distanceArray->SetValue(kept[k], distance[k]);
    coverArray->SetValue(kept[k], covering[k]);
  }
  output->GetPointData()->AddArray(deltaArray);
  output->GetPointData()->AddArray(distanceArray);
  output->GetPointData()->AddArray(coverArray);
  output->GetPointData()->SetActiveScalars("SurfaceDistance");

  this->RMSDistance = summary.RMS;
  this->MaximumDistance = summary.Maximum;
  this->Phi = summary.Phi;
  this->NumberOfUncoveredPoints = summary.Uncovered;
  vtkFieldData* fd = output->GetFieldData();
  AddValue(fd, "SplatErrorPhi", summary.Phi);
  AddValue(fd, "SurfaceDistanceRMS", summary.RMS);
  AddValue(fd, "SurfaceDistanceMaximum", summary.Maximum);
  AddValue(fd, "UncoveredPoints", static_cast<double>(summary.Uncovered));
  AddValue(fd, "BoundsDiagonal", points->GetLength());
  return 1;
}

//------------------------------------------------------------------------------
void vtkSplatErrorMetric::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RMSDistance: " << this->RMSDistance << "\n";
  os << indent << "MaximumDistance: " << this->MaximumDistance << "\n";
  os << indent << "Phi: " << this->Phi << "\n";
  os << indent << "NumberOfUncoveredPoints: " << this->NumberOfUncoveredPoints << "\n";
}
