// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSplatFileWriter.h"

#include "psLocalFit.h"
#include "psSplatFile.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSplatDataModel.h"

#include <algorithm>
#include <cstring>
#include <vector>

vtkStandardNewMacro(vtkSplatFileWriter);

//------------------------------------------------------------------------------
int vtkSplatFileWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
void vtkSplatFileWriter::WriteData()
{
  this->NumberOfSplats = 0;
  vtkPolyData* input = vtkPolyData::SafeDownCast(this->GetInput());
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No FileName: nothing written.");
    return;
  }
  const int degree = input ? vtkSplatDataModel::GetSplatDegree(input) : 0;
  if (degree < 1)
  {
    vtkErrorMacro(<< this->FileName
                  << ": the input is not a splat set (see vtkSplatDataModel): nothing written.");
    return;
  }
  vtkPointData* pd = input->GetPointData();
  const vtkIdType n = input->GetNumberOfPoints();
  const char* model[] = { vtkSplatDataModel::NormalName(),
    vtkSplatDataModel::TangentName(),
    vtkSplatDataModel::FeatureSizeName(),
    vtkSplatDataModel::CoefficientsName(),
    vtkSplatDataModel::RadiusName(),
    vtkSplatDataModel::MaxDeviationName(),
    vtkSplatDataModel::NominalRadiusName(),
    vtkSplatDataModel::ToleranceName(),
    vtkSplatDataModel::LODName() };
  std::vector<vtkDataArray*> columns;
  for (const char* name : model)
  {
    columns.push_back(pd->GetArray(name)); // the optional ones may be missing
  }
  pointsurfaces::SplatFileInfo info;
  info.Degree = degree;
  info.InputPoints = 0;
  vtkDataArray* oriented =
    input->GetFieldData()->GetArray(vtkSplatDataModel::NormalsOrientedName());
  info.Oriented = oriented && oriented->GetNumberOfTuples() > 0 && oriented->GetTuple1(0) != 0;
  std::vector<vtkDataArray*> attributes;
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pd->GetArray(a);
    const char* name = array ? array->GetName() : nullptr;
    if (!name ||
      std::any_of(std::begin(model),
        std::end(model),
        [&](const char* m) { return std::strcmp(m, name) == 0; }))
    {
      continue;
    }
    attributes.push_back(array);
    info.AttributeNames.emplace_back(name);
    info.AttributeComponents.push_back(array->GetNumberOfComponents());
    info.AttributeTypes.push_back(array->GetDataType());
  }
  std::vector<double> origins(3 * static_cast<size_t>(n)), radii(static_cast<size_t>(n));
  std::vector<int> levels(static_cast<size_t>(n), 0);
  for (vtkIdType i = 0; i < n; ++i)
  {
    input->GetPoint(i, &origins[3 * i]);
    radii[i] = columns[4]->GetTuple1(i); // a splat set has radii (GetSplatDegree)
    levels[i] = columns[8] ? static_cast<int>(columns[8]->GetTuple1(i)) : 0;
  }
  std::vector<double> quality;
  if (vtkDataArray* q = input->GetFieldData()->GetArray(vtkSplatDataModel::LODQualityName()))
  {
    for (vtkIdType l = 0; l < q->GetNumberOfTuples(); ++l)
    {
      quality.push_back(q->GetTuple1(l));
    }
  }
  const int maxLevel = n > 0 ? *std::max_element(levels.begin(), levels.end()) : 0;
  quality.resize(
    static_cast<size_t>(std::max(1, maxLevel + 1)), quality.empty() ? 1.0 : quality.back());
  const int m = pointsurfaces::MonomialCount(degree);
  auto fetch = [&](const std::vector<long long>& ids, pointsurfaces::SplatColumns& out)
  {
    for (size_t k = 0; k < ids.size(); ++k)
    {
      const vtkIdType i = static_cast<vtkIdType>(ids[k]);
      std::copy(&origins[3 * i], &origins[3 * i] + 3, &out.Origin[3 * k]);
      auto floats = [&](vtkDataArray* a, float* to, int comps, double fallback)
      {
        for (int c = 0; c < comps; ++c)
        {
          to[c] = static_cast<float>(
            a && c < a->GetNumberOfComponents() ? a->GetComponent(i, c) : fallback);
        }
      };
      floats(columns[0], &out.Normal[3 * k], 3, 0.0);
      floats(columns[1], &out.Tangent[3 * k], 3, 0.0);
      floats(columns[2], &out.FeatureSize[k], 1, 1.0);
      floats(columns[3], &out.Coefficients[m * k], m, 0.0);
      out.Radius[k] = static_cast<float>(radii[i]);
      floats(columns[5], &out.MaxDeviation[k], 1, 0.0);
      floats(columns[6], &out.NominalRadius[k], 1, radii[i]);
      floats(columns[7], &out.Tolerance[k], 1, 0.0);
      out.LOD[k] = levels[i];
      for (size_t a = 0; a < attributes.size(); ++a)
      {
        const int comps = info.AttributeComponents[a];
        for (int c = 0; c < comps; ++c)
        {
          out.Attributes[a][comps * k + c] = static_cast<float>(attributes[a]->GetComponent(i, c));
        }
      }
    }
    return true;
  };
  std::string error;
  if (!pointsurfaces::WriteSplatFile(this->FileName,
        info,
        origins.data(),
        radii.data(),
        levels.data(),
        n,
        quality,
        fetch,
        error,
        this->PageSize))
  {
    vtkErrorMacro(<< this->FileName << ": " << error);
    return;
  }
  this->NumberOfSplats = n;
}

//------------------------------------------------------------------------------
void vtkSplatFileWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "PageSize: " << this->PageSize << "\n";
  os << indent << "NumberOfSplats: " << this->NumberOfSplats << "\n";
}
