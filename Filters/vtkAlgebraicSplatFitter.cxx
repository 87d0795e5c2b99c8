// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAlgebraicSplatFitter.h"

#include "psMemory.h"
#include "psOctree.h"
#include "psPointIndex.h"
#include "psSplatBuilder.h"
#include "psSplatOrientation.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
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
#include "vtkSMPTools.h"
#include "vtkSplatDataModel.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkAlgebraicSplatFitter);

namespace
{
using namespace pointsurfaces;

template<typename T>
vtkNew<T> MakeArray(const char* name, int components, vtkIdType tuples)
{
  vtkNew<T> a;
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(tuples);
  return a;
}

void AddCount(vtkFieldData* fd, const char* name, vtkIdType value)
{
  vtkNew<vtkIdTypeArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

// Splats into the splat data model (see vtkSplatDataModel and the README's Data model section).
void Assemble(const BuildResult& built, int degree, vtkPolyData* output)
{
  const vtkIdType n = static_cast<vtkIdType>(built.Splats.size());
  const int m = MonomialCount(degree);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  auto normal = MakeArray<vtkDoubleArray>(vtkSplatDataModel::NormalName(), 3, n);
  auto tangent = MakeArray<vtkDoubleArray>(vtkSplatDataModel::TangentName(), 3, n);
  auto size = MakeArray<vtkDoubleArray>(vtkSplatDataModel::FeatureSizeName(), 1, n);
  auto coeffs = MakeArray<vtkDoubleArray>(vtkSplatDataModel::CoefficientsName(), m, n);
  auto radius = MakeArray<vtkDoubleArray>(vtkSplatDataModel::RadiusName(), 1, n);
  auto deviation = MakeArray<vtkDoubleArray>(vtkSplatDataModel::MaxDeviationName(), 1, n);
  auto nominal = MakeArray<vtkDoubleArray>(vtkSplatDataModel::NominalRadiusName(), 1, n);
  auto tolerance = MakeArray<vtkDoubleArray>(vtkSplatDataModel::ToleranceName(), 1, n);
  auto lod = MakeArray<vtkIntArray>(vtkSplatDataModel::LODName(), 1, n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const Splat& s = built.Splats[i].Fitted;
    points->SetPoint(i, s.Frame.Origin);
    normal->SetTypedTuple(i, s.Frame.Normal);
    tangent->SetTypedTuple(i, s.Frame.Tangent);
    size->SetValue(i, s.Frame.Scale);
    // Lower-degree fallbacks keep zeros in the higher coefficients.
    for (int c = 0; c < m; ++c)
    {
      coeffs->SetTypedComponent(
        i, c, c < MonomialCount(s.Fit.Degree) ? s.Fit.Coefficients[c] : 0.0);
    }
    radius->SetValue(i, built.Splats[i].Radius);
    deviation->SetValue(i, built.Splats[i].MaxDeviation);
    nominal->SetValue(i, built.Splats[i].NominalRadius);
    tolerance->SetValue(i, built.Splats[i].Tolerance * s.Spacing);
    lod->SetValue(i, built.Splats[i].Level);
  }
  output->SetPoints(points);
  vtkSplatDataModel::AddVertexCells(output);
  vtkPointData* pd = output->GetPointData();
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(normal),
         static_cast<vtkDataArray*>(tangent),
         static_cast<vtkDataArray*>(size),
         static_cast<vtkDataArray*>(coeffs),
         static_cast<vtkDataArray*>(radius),
         static_cast<vtkDataArray*>(deviation),
         static_cast<vtkDataArray*>(nominal),
         static_cast<vtkDataArray*>(tolerance),
         static_cast<vtkDataArray*>(lod) })
  {
    pd->AddArray(a);
  }
  vtkNew<vtkIntArray> deg;
  deg->SetName(vtkSplatDataModel::DegreeName());
  deg->InsertNextValue(degree);
  output->GetFieldData()->AddArray(deg);
  vtkNew<vtkDoubleArray> levels;
  levels->SetName(vtkSplatDataModel::LODQualityName());
  for (double s : built.LevelQuality)
  {
    levels->InsertNextValue(s);
  }
  output->GetFieldData()->AddArray(levels);
}
// The input's point arrays at the splats, MLS-weighted by each splat's fit
// (VTK interpolates each type), into outPD; the input's scalars stay active.
void CarryArrays(vtkPointData* inPD,
  const std::vector<vtkIdType>& kept,
  const BuildResult& built,
  vtkPointData* outPD)
{
  vtkNew<vtkPointData> carried;
  carried->InterpolateAllocate(inPD, static_cast<vtkIdType>(built.Splats.size()));
  vtkNew<vtkIdList> ids;
  std::vector<double> w;
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(built.Splats.size()); ++i)
  {
    const BuiltSplat& b = built.Splats[i];
    ids->SetNumberOfIds(static_cast<vtkIdType>(b.Ids.size()));
    w.resize(b.Weights.size());
    double sum = 0.0;
    for (size_t j = 0; j < b.Weights.size(); ++j)
    {
      sum += b.Weights[j];
    }
    for (size_t j = 0; j < b.Ids.size(); ++j)
    {
      ids->SetId(static_cast<vtkIdType>(j), kept[b.Ids[j]]);
      w[j] = sum > 0.0 ? b.Weights[j] / sum : 1.0 / b.Ids.size();
    }
    carried->InterpolatePoint(inPD, i, ids, w.data());
  }
  for (int a = 0; a < carried->GetNumberOfArrays(); ++a)
  {
    outPD->AddArray(carried->GetAbstractArray(a));
  }
  if (carried->GetScalars())
  {
    outPD->SetActiveScalars(carried->GetScalars()->GetName());
  }
}
} // namespace

//------------------------------------------------------------------------------
vtkAlgebraicSplatFitter::vtkAlgebraicSplatFitter() = default;

//------------------------------------------------------------------------------
int vtkAlgebraicSplatFitter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

//------------------------------------------------------------------------------
pointsurfaces::BuildParameters vtkAlgebraicSplatFitter::MakeParameters(bool keepWeights) const
{
  BuildParameters params;
  params.Fit.Degree = this->Degree;
  params.Fit.NumberOfNeighbors = this->NumberOfNeighbors;
  params.Fit.FeatureSizeNeighbors = this->FeatureSizeNeighbors;
  params.Fit.WeightScale = this->WeightScale;
  params.Fit.Mode = static_cast<pointsurfaces::FitMode>(this->FitMode);
  params.Fit.Loss = static_cast<pointsurfaces::RobustLoss>(this->RobustLoss);
  params.Fit.LossScale = this->RobustLossScale;
  params.Fit.MaximumDeviation = this->MaximumDeviation;
  params.Fit.ReweightingIterations = this->ReweightingIterations;
  params.NormalAngle = this->MaximumNormalAngle;
  params.EstimateNormals = this->EstimateNormals;
  params.Select = static_cast<pointsurfaces::Selection>(this->SelectionMode);
  params.Quality = this->QualityFactor;
  params.VisitOrder = static_cast<pointsurfaces::Order>(this->SelectionOrder);
  params.Count = this->NumberOfSplats;
  params.Weighted = this->LOPVariant == WLOP;
  params.LOPIterations = this->LOPIterations;
  params.Seed = this->RandomSeed;
  params.RadiusScale = this->RadiusScale;
  params.KeepWeights = keepWeights;
  params.Levels = this->SelectionMode == Quality ? this->NumberOfLevels : 1;
  params.CoarsestQuality = this->CoarsestQualityFactor;
  params.Tolerance = static_cast<pointsurfaces::ToleranceUnit>(this->ToleranceUnit);
  params.NoiseFactor = this->NoiseFactor;
  params.FeatureNoiseFactor = this->FeatureNoiseFactor;
  params.MaximumFeatureScale = this->MaximumFeatureScale;
  params.SubsampleWideFits = this->SubsampleWideFits;
  return params;
}

//------------------------------------------------------------------------------
vtkIdType vtkAlgebraicSplatFitter::EstimateMemorySize(vtkIdType numberOfPoints)
{
  return static_cast<vtkIdType>(
    std::ceil(640.0 * static_cast<double>(std::max<vtkIdType>(numberOfPoints, 0)) / 1024.0));
}

//------------------------------------------------------------------------------
bool vtkAlgebraicSplatFitter::FitsInMemory(vtkIdType points)
{
  const double need = 1024.0 * static_cast<double>(EstimateMemorySize(points));
  const double limit = pointsurfaces::MemoryLimitBytes(1024.0 * this->MemoryLimit);
  if (limit <= 0.0 || need <= limit)
  {
    return true;
  }
  vtkErrorMacro(<< "Fitting " << points << " points needs about "
                << pointsurfaces::FormatBytes(need) << ", more than "
                << (this->MemoryLimit > 0 ? "MemoryLimit" : "the free physical memory") << " ("
                << pointsurfaces::FormatBytes(limit)
                << "): thin the input first (vtkMultiResolutionSplatBuilder "
                << "fits levels of it, VTK's vtkMaskPoints or vtkVoxelGrid thin it), fit it in "
                << "pieces, or raise MemoryLimit. The output is empty.");
  return false;
}

//------------------------------------------------------------------------------
int vtkAlgebraicSplatFitter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->NumberOfInvalidPoints = this->NumberOfDegenerateSplats = this->NumberOfMergedPoints = 0;
  this->NumberOfReducedDegreeSplats = 0;
  this->SetResolvedTolerance(static_cast<pointsurfaces::ToleranceUnit>(
                               this->ToleranceUnit == AUTOMATIC ? SPACING : this->ToleranceUnit),
    pointsurfaces::SampleNoise());
  const vtkIdType nIn = input ? input->GetNumberOfPoints() : 0;
  if (!this->FitsInMemory(nIn))
  {
    Assemble(BuildResult(), this->Degree, output);
    return 1;
  }

  // Finite points only, in double; `kept` maps back to input ids.
  std::vector<double> xyz, normals;
  std::vector<vtkIdType> kept;
  xyz.reserve(3 * nIn);
  kept.reserve(nIn);
  vtkDataArray* inNormals = nIn ? input->GetPointData()->GetNormals() : nullptr;
  vtkDataArray* coords = nIn ? input->GetPoints()->GetData() : nullptr;
  for (vtkIdType i = 0; i < nIn; ++i)
  {
    double p[3];
    coords->GetTuple(i, p);
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
    {
      xyz.insert(xyz.end(), p, p + 3);
      kept.push_back(i);
      if (inNormals)
      {
        double nrm[3];
        inNormals->GetTuple(i, nrm);
        normals.insert(normals.end(), nrm, nrm + 3);
      }
    }
  }
  this->NumberOfInvalidPoints = nIn - static_cast<vtkIdType>(kept.size());
  if (this->NumberOfInvalidPoints > 0)
  {
    vtkWarningMacro(<< "Dropped " << this->NumberOfInvalidPoints << " of " << nIn
                    << " input points with NaN or infinite coordinates.");
  }
  this->MergeCoincident(xyz, normals, kept);
  SortSpatially(xyz, normals, kept);
  const vtkIdType n = static_cast<vtkIdType>(kept.size());
  if (n < 3)
  {
    vtkWarningMacro(<< "Need at least 3 finite points to fit splats, got " << n
                    << (this->NumberOfMergedPoints > 0 ? " distinct ones (the others coincide)"
                                                       : "")
                    << ": the output is empty.");
    Assemble(BuildResult(), this->Degree, output);
    return 1;
  }
  if (this->NumberOfNeighbors > n || this->FeatureSizeNeighbors >= n)
  {
    vtkWarningMacro(<< "NumberOfNeighbors " << this->NumberOfNeighbors << " / FeatureSizeNeighbors "
                    << this->FeatureSizeNeighbors << " exceed the " << n
                    << " points: using all points.");
  }

  const BuildParameters params =
    this->MakeParameters(input->GetPointData()->GetNumberOfArrays() > 0);
  std::atomic<bool> abort(false);
  BuildResult built = BuildSplats(
    xyz.data(),
    n,
    inNormals ? normals.data() : nullptr,
    params,
    [&](double f)
    {
      this->UpdateProgress(f);
      abort = this->GetAbortExecute() != 0;
    },
    &abort);
  this->SetResolvedTolerance(built.Tolerance, built.Noise);
  const bool oriented = inNormals != nullptr || (this->OrientNormals && !abort.load());
  if (!inNormals && oriented)
  {
    std::vector<pointsurfaces::Splat*> fitted;
    std::vector<double> radii;
    fitted.reserve(built.Splats.size());
    radii.reserve(built.Splats.size());
    for (BuiltSplat& b : built.Splats)
    {
      fitted.push_back(&b.Fitted);
      radii.push_back(b.Radius);
    }
    pointsurfaces::OrientSplats(fitted, 8, nullptr, &radii);
  }

  if (this->BuildOctree)
  {
    this->SortByOctree(built, output);
  }
  Assemble(built, this->Degree, output);
  // Carry every input array over, MLS-weighted (VTK interpolates each type).
  if (params.KeepWeights)
  {
    CarryArrays(input->GetPointData(), kept, built, output->GetPointData());
  }

  this->NumberOfDegenerateSplats = built.Degenerate;
  this->NumberOfReducedDegreeSplats = built.Reduced;
  if (built.Degenerate > 0)
  {
    vtkWarningMacro(<< built.Degenerate
                    << " positions had degenerate neighbourhoods (duplicates, collinear points) "
                       "and produced no splat.");
  }
  if (built.Reduced > 0)
  {
    vtkWarningMacro(<< built.Reduced << " splats were fitted below degree " << this->Degree
                    << " (rank-deficient neighbourhoods).");
  }
  vtkFieldData* fd = output->GetFieldData();
  AddCount(fd, "SplatInvalidInputPoints", this->NumberOfInvalidPoints);
  AddCount(fd, "SplatMergedInputPoints", this->NumberOfMergedPoints);
  AddCount(fd, "SplatDegeneratePositions", this->NumberOfDegenerateSplats);
  AddCount(fd, "SplatReducedDegree", this->NumberOfReducedDegreeSplats);
  AddCount(fd, vtkSplatDataModel::NormalsOrientedName(), oriented ? 1 : 0);
  AddCount(fd, "SplatToleranceUnit", this->ResolvedToleranceUnit);
  vtkNew<vtkDoubleArray> noise;
  noise->SetName("SplatSampleNoise");
  noise->SetNumberOfComponents(2);
  noise->SetComponentName(0, "Growth");
  noise->SetComponentName(1, "ResidualOverSpacing");
  noise->InsertNextTuple2(this->SampleNoiseGrowth, this->SampleNoiseLevel);
  fd->AddArray(noise);
  return 1;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatFitter::SetResolvedTolerance(pointsurfaces::ToleranceUnit unit,
  const pointsurfaces::SampleNoise& noise)
{
  this->ResolvedToleranceUnit = static_cast<int>(unit);
  this->SampleNoiseGrowth = noise.Growth;
  this->SampleNoiseLevel = noise.NoiseOverSpacing;
  if (noise.Probes > 0)
  {
    vtkDebugMacro(<< "ToleranceUnit AUTOMATIC: residual growth " << noise.Growth << ", "
                  << noise.NoiseOverSpacing << " spacings over " << noise.Probes
                  << " probes: " << (noise.Noisy ? "NOISE with wide splats" : "SPACING"));
  }
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatFitter::SortSpatially(std::vector<double>& xyz,
  std::vector<double>& normals,
  std::vector<vtkIdType>& kept)
{
  const long long n = static_cast<long long>(kept.size());
  const std::vector<long long> order = pointsurfaces::SpatialOrder(xyz.data(), n);
  std::vector<double> sortedXYZ(xyz.size()), sortedNormals(normals.size());
  std::vector<vtkIdType> sortedKept(kept.size());
  vtkSMPTools::For(0,
    n,
    [&](long long begin, long long end)
    {
      for (long long k = begin; k < end; ++k)
      {
        const long long i = order[k];
        std::copy(&xyz[3 * i], &xyz[3 * i] + 3, &sortedXYZ[3 * k]);
        if (!normals.empty())
        {
          std::copy(&normals[3 * i], &normals[3 * i] + 3, &sortedNormals[3 * k]);
        }
        sortedKept[k] = kept[i];
      }
    });
  xyz.swap(sortedXYZ);
  normals.swap(sortedNormals);
  kept.swap(sortedKept);
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatFitter::MergeCoincident(std::vector<double>& xyz,
  std::vector<double>& normals,
  std::vector<vtkIdType>& kept)
{
  const long long n = static_cast<long long>(kept.size());
  if (n < 2)
  {
    return;
  }
  double lo[3] = { xyz[0], xyz[1], xyz[2] }, hi[3] = { xyz[0], xyz[1], xyz[2] };
  for (long long i = 1; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], xyz[3 * i + c]);
      hi[c] = std::max(hi[c], xyz[3 * i + c]);
    }
  }
  const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) +
    (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const std::vector<long long> unique =
    pointsurfaces::UniquePoints(xyz.data(), n, this->MergeTolerance * diagonal);
  this->NumberOfMergedPoints = static_cast<vtkIdType>(n - static_cast<long long>(unique.size()));
  if (this->NumberOfMergedPoints == 0)
  {
    return;
  }
  for (size_t k = 0; k < unique.size(); ++k)
  {
    const long long i = unique[k];
    std::copy(&xyz[3 * i], &xyz[3 * i] + 3, &xyz[3 * k]);
    if (!normals.empty())
    {
      std::copy(&normals[3 * i], &normals[3 * i] + 3, &normals[3 * k]);
    }
    kept[k] = kept[i];
  }
  xyz.resize(3 * unique.size());
  normals.resize(normals.empty() ? 0 : 3 * unique.size());
  kept.resize(unique.size());
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatFitter::SortByOctree(pointsurfaces::BuildResult& built, vtkPolyData* output)
{
  const vtkIdType n = static_cast<vtkIdType>(built.Splats.size());
  std::vector<double> origins(3 * n), radii(n);
  std::vector<int> levels(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    std::copy(built.Splats[i].Fitted.Frame.Origin,
      built.Splats[i].Fitted.Frame.Origin + 3,
      &origins[3 * i]);
    radii[i] = built.Splats[i].Radius;
    levels[i] = built.Splats[i].Level;
  }
  const int L = static_cast<int>(std::max<size_t>(1, built.LevelQuality.size()));
  const Octree tree = pointsurfaces::BuildOctree(
    origins.data(), radii.data(), levels.data(), n, L, this->OctreeBucketSize);
  std::vector<BuiltSplat> sorted(static_cast<size_t>(n));
  for (vtkIdType k = 0; k < n; ++k)
  {
    sorted[k] = std::move(built.Splats[tree.Order[k]]);
  }
  built.Splats.swap(sorted);

  vtkSplatDataModel::AddOctree(output, tree);
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatFitter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Degree: " << this->Degree << "\n";
  os << indent << "NumberOfNeighbors: " << this->NumberOfNeighbors << "\n";
  os << indent << "FeatureSizeNeighbors: " << this->FeatureSizeNeighbors << "\n";
  os << indent << "WeightScale: " << this->WeightScale << "\n";
  os << indent << "FitMode: " << this->FitMode << "\n";
  os << indent << "SelectionMode: " << this->SelectionMode << "\n";
  os << indent << "QualityFactor: " << this->QualityFactor << "\n";
  os << indent << "SelectionOrder: " << this->SelectionOrder << "\n";
  os << indent << "NumberOfSplats: " << this->NumberOfSplats << "\n";
  os << indent << "LOPVariant: " << this->LOPVariant << "\n";
  os << indent << "RadiusScale: " << this->RadiusScale << "\n";
  os << indent << "RandomSeed: " << this->RandomSeed << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " KiB\n";
  const char* units[] = { "SPACING", "NOISE", "ABSOLUTE", "AUTOMATIC" };
  os << indent << "ToleranceUnit: " << units[this->ToleranceUnit] << "\n";
  os << indent << "ResolvedToleranceUnit: " << units[this->ResolvedToleranceUnit] << "\n";
  os << indent << "SampleNoiseGrowth: " << this->SampleNoiseGrowth << "\n";
  os << indent << "SampleNoiseLevel: " << this->SampleNoiseLevel << "\n";
  os << indent << "NoiseFactor: " << this->NoiseFactor << "\n";
  os << indent << "FeatureNoiseFactor: " << this->FeatureNoiseFactor << "\n";
  os << indent << "MaximumFeatureScale: " << this->MaximumFeatureScale << "\n";
  os << indent << "SubsampleWideFits: " << this->SubsampleWideFits << "\n";
  os << indent << "NumberOfLevels: " << this->NumberOfLevels << "\n";
  os << indent << "CoarsestQualityFactor: " << this->CoarsestQualityFactor << "\n";
  os << indent << "BuildOctree: " << this->BuildOctree << "\n";
  os << indent << "OctreeBucketSize: " << this->OctreeBucketSize << "\n";
  os << indent << "OrientNormals: " << this->OrientNormals << "\n";
  os << indent << "MaximumDeviation: " << this->MaximumDeviation << "\n";
  os << indent << "ReweightingIterations: " << this->ReweightingIterations << "\n";
  os << indent << "MaximumNormalAngle: " << this->MaximumNormalAngle << "\n";
  os << indent << "EstimateNormals: " << (this->EstimateNormals ? "on" : "off") << "\n";
  os << indent << "MergeTolerance: " << this->MergeTolerance << "\n";
}
