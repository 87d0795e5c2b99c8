// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSplatFileReader.h"

#include "psLocalFit.h"
#include "psOctree.h"
#include "psReaderTime.h" // For RequestedPiece
#include "psSplatFile.h"
#include "psSplatPages.h"

#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkInformationInformationVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSplatDataModel.h"
#include "vtkStringArray.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

vtkStandardNewMacro(vtkSplatFileReader);

namespace
{
void AddCount(vtkFieldData* fd, const char* name, vtkIdType value)
{
  vtkNew<vtkIdTypeArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

// The whole file's ranges of dataset `key` as `array`'s cached ranges
// (vtkDataArray's information keys, finite and not): GetRange and
// GetFiniteRange, and so ParaView 5.11's data information, give the file's
// ranges, not those of the pages read (ParaView 5.13 and later compute
// their own from the values: the range ends loaded serve them). Set after
// the values: an array changed later computes its own again (VTK keeps a
// cached range only while it is newer than the array).
void CacheRange(vtkDataArray* array,
  const pointsurfaces::SplatFileInfo& info,
  const std::string& key)
{
  const auto it = info.Ranges.find(key);
  const int comps = array ? array->GetNumberOfComponents() : 0;
  if (it == info.Ranges.end() || comps < 1 ||
    it->second.size() != pointsurfaces::SplatRangeSize(comps))
  {
    return;
  }
  const std::vector<double>& range = it->second;
  vtkInformation* keys = array->GetInformation();
  for (vtkInformationInformationVectorKey* per :
    { vtkAbstractArray::PER_COMPONENT(), vtkAbstractArray::PER_FINITE_COMPONENT() })
  {
    vtkNew<vtkInformationVector> components;
    components->SetNumberOfInformationObjects(comps);
    for (int c = 0; c < comps; ++c)
    {
      components->GetInformationObject(c)->Set(vtkDataArray::COMPONENT_RANGE(), &range[2 * c], 2);
    }
    keys->Set(per, components);
  }
  if (comps > 1)
  {
    keys->Set(vtkDataArray::L2_NORM_RANGE(), &range[2 * comps], 2);
    keys->Set(vtkDataArray::L2_NORM_FINITE_RANGE(), &range[2 * comps], 2);
  }
}

// The loaded rows as the splat data model, in the order of their own LOD octree.
void Assemble(const pointsurfaces::SplatColumns& c,
  const pointsurfaces::SplatFileInfo& info,
  vtkPolyData* output)
{
  const vtkIdType n = static_cast<vtkIdType>(c.Count);
  const int L = std::max(1, info.Pages.Tree.Levels);
  std::vector<double> radii(c.Radius.begin(), c.Radius.end());
  const pointsurfaces::Octree tree =
    pointsurfaces::BuildOctree(c.Origin.data(), radii.data(), c.LOD.data(), n, L, 64);
  const int m = pointsurfaces::MonomialCount(info.Degree);
  auto make = [&](const char* name, int comps)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(comps);
    a->SetNumberOfTuples(n);
    output->GetPointData()->AddArray(a);
    return a.GetPointer();
  };
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkDoubleArray* normal = make(vtkSplatDataModel::NormalName(), 3);
  vtkDoubleArray* tangent = make(vtkSplatDataModel::TangentName(), 3);
  vtkDoubleArray* size = make(vtkSplatDataModel::FeatureSizeName(), 1);
  vtkDoubleArray* coeffs = make(vtkSplatDataModel::CoefficientsName(), m);
  vtkDoubleArray* radius = make(vtkSplatDataModel::RadiusName(), 1);
  vtkDoubleArray* deviation = make(vtkSplatDataModel::MaxDeviationName(), 1);
  vtkDoubleArray* nominal = make(vtkSplatDataModel::NominalRadiusName(), 1);
  vtkDoubleArray* tolerance = make(vtkSplatDataModel::ToleranceName(), 1);
  vtkNew<vtkIntArray> lod;
  lod->SetName(vtkSplatDataModel::LODName());
  lod->SetNumberOfTuples(n);
  output->GetPointData()->AddArray(lod);
  std::vector<vtkDataArray*> attributes; // null: named like a model array, left out
  for (size_t a = 0; a < info.AttributeNames.size(); ++a)
  {
    if (output->GetPointData()->HasArray(info.AttributeNames[a].c_str()))
    {
      attributes.push_back(nullptr);
      continue;
    }
    vtkSmartPointer<vtkDataArray> array;
    array.TakeReference(vtkDataArray::CreateDataArray(info.AttributeType(a)));
    array->SetName(info.AttributeNames[a].c_str());
    array->SetNumberOfComponents(info.AttributeComponents[a]);
    array->SetNumberOfTuples(n);
    output->GetPointData()->AddArray(array);
    attributes.push_back(array);
  }
  for (vtkIdType k = 0; k < n; ++k)
  {
    const long long i = tree.Order[k];
    points->SetPoint(k, &c.Origin[3 * i]);
    for (int j = 0; j < 3; ++j)
    {
      normal->SetTypedComponent(k, j, c.Normal[3 * i + j]);
      tangent->SetTypedComponent(k, j, c.Tangent[3 * i + j]);
    }
    for (int j = 0; j < m; ++j)
    {
      coeffs->SetTypedComponent(k, j, c.Coefficients[static_cast<size_t>(m) * i + j]);
    }
    size->SetValue(k, c.FeatureSize[i]);
    radius->SetValue(k, c.Radius[i]);
    deviation->SetValue(k, c.MaxDeviation[i]);
    nominal->SetValue(k, c.NominalRadius[i]);
    tolerance->SetValue(k, c.Tolerance[i]);
    lod->SetValue(k, c.LOD[i]);
    for (size_t a = 0; a < attributes.size(); ++a)
    {
      const int comps = info.AttributeComponents[a];
      for (int j = 0; attributes[a] && j < comps; ++j)
      {
        attributes[a]->SetComponent(k, j, c.Attributes[a][static_cast<size_t>(comps) * i + j]);
      }
    }
  }
  const std::pair<vtkDataArray*, const char*> columns[] = { { normal, "Normal" },
    { coeffs, "Coefficients" },
    { tangent, "Tangent" },
    { size, "FeatureSize" },
    { radius, "Radius" },
    { deviation, "MaxDeviation" },
    { nominal, "NominalRadius" },
    { tolerance, "Tolerance" },
    { lod.GetPointer(), "LOD" } };
  for (const auto& [array, column] : columns)
  {
    CacheRange(array, info, std::string("Splats/") + column);
  }
  for (size_t a = 0; a < attributes.size(); ++a)
  {
    CacheRange(attributes[a], info, "Attributes/" + info.AttributeNames[a]);
  }
  output->SetPoints(points);
  vtkSplatDataModel::AddVertexCells(output);
  vtkSplatDataModel::AddSetFields(output, info.Degree, info.Pages.LevelQuality, info.Oriented);
  if (n > 0)
  {
    vtkSplatDataModel::AddOctree(output, tree);
  }
}
} // namespace

struct vtkSplatFileReader::Impl
{
  pointsurfaces::SplatFileReader File;
  std::string Path;
  long long Stamp = -1;
  bool Open = false;
  // The splats that hold the ends of the file's ranges (RangeEndRows), read
  // once per file version.
  std::vector<long long> EndRows;
  pointsurfaces::SplatColumns Ends;
  bool EndsRead = false;
};

//------------------------------------------------------------------------------
vtkSplatFileReader::vtkSplatFileReader()
  : P(new Impl)
{
  this->SetNumberOfInputPorts(0);
}

vtkSplatFileReader::~vtkSplatFileReader() = default;

//------------------------------------------------------------------------------
void vtkSplatFileReader::SetCamera(vtkCamera* camera)
{
  if (this->Camera != camera)
  {
    this->Camera = camera;
    this->Modified();
  }
}

vtkCamera* vtkSplatFileReader::GetCamera()
{
  return this->Camera;
}

vtkMTimeType vtkSplatFileReader::GetMTime()
{
  const vtkMTimeType own = this->Superclass::GetMTime();
  return this->Camera ? std::max(own, this->Camera->GetMTime()) : own;
}

//------------------------------------------------------------------------------
double vtkSplatFileReader::GetBytesPerSplat()
{
  return P->Open ? P->File.BytesPerSplat() : 0.0;
}

//------------------------------------------------------------------------------
bool vtkSplatFileReader::CanReadFile(const char* fileName)
{
  pointsurfaces::SplatFileReader file;
  std::string error;
  return fileName && file.Open(fileName, error);
}

//------------------------------------------------------------------------------
int vtkSplatFileReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  // Every piece gets a share of the chosen splats: under ParaView's ranks
  // none is left without the arrays (pvbatch --symmetric colours by them).
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkSplatFileReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  int piece = 0, pieces = 1;
  pointsurfaces::RequestedPiece(outInfo, piece, pieces);
  this->NumberOfSplats = this->NumberOfLoadedSplats = 0;
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No FileName: nothing to read.");
    return 1;
  }
  const long long stamp = pointsurfaces::FileModificationStamp(this->FileName);
  if (!P->Open || P->Path != this->FileName || P->Stamp != stamp)
  {
    std::string error;
    P->File.SetCheckInChildProcess(this->CheckInChildProcess);
    P->Open = P->File.Open(this->FileName, error);
    P->Path = this->FileName;
    P->Stamp = stamp;
    P->EndsRead = false;
    if (!P->Open)
    {
      vtkErrorMacro(<< this->FileName << ": " << error);
      return 1;
    }
  }
  const pointsurfaces::SplatFileInfo& info = P->File.Info();
  this->NumberOfSplats = static_cast<vtkIdType>(info.Splats);

  pointsurfaces::LODView view;
  if (this->Camera)
  {
    const int w = std::max(1, this->ViewportSize[0]), h = std::max(1, this->ViewportSize[1]);
    this->Camera->GetFrustumPlanes(static_cast<double>(w) / h, view.Planes);
    this->Camera->GetPosition(view.Eye);
    view.ViewportHeight = h;
    view.Parallel = this->Camera->GetParallelProjection() != 0;
    view.ParallelScale = this->Camera->GetParallelScale();
    view.TanHalfAngle = std::tan(0.5 * vtkMath::RadiansFromDegrees(this->Camera->GetViewAngle()));
    view.PixelError = this->PixelError;
  }
  const double perSplat = P->File.BytesPerSplat();
  const pointsurfaces::PageSelection chosen = pointsurfaces::SelectPages(
    info.Pages, perSplat, this->MemoryBudget * 1e6, this->Camera ? &view : nullptr);
  const pointsurfaces::PageSelection selection =
    pointsurfaces::PieceOfSelection(chosen, piece, pieces, perSplat);
  if (chosen.Ranges.empty() && chosen.SmallestPage > 0.0 && piece == 0)
  {
    vtkWarningMacro(<< this->FileName << ": MemoryBudget " << this->MemoryBudget
                    << " MB holds no page's coarsest level (the smallest needs "
                    << selection.SmallestPage / 1e6 << " MB): the output is empty.");
  }
  pointsurfaces::SplatColumns columns;
  columns.Resize(0, info.Degree, info.AttributeComponents);
  // Adjacent pages in one read.
  for (size_t k = 0; k < selection.Ranges.size();)
  {
    long long begin = selection.Ranges[k].Begin, end = selection.Ranges[k].End;
    size_t next = k + 1;
    while (next < selection.Ranges.size() && selection.Ranges[next].Begin == end)
    {
      end = selection.Ranges[next++].End;
    }
    std::string error;
    if (!P->File.Read(begin, end - begin, columns, error))
    {
      vtkErrorMacro(<< this->FileName << ": " << error);
      P->Open = false;
      return 1;
    }
    k = next;
    this->UpdateProgress(static_cast<double>(k) / selection.Ranges.size());
  }
  // The splats that hold the ends of the file's ranges, where the pages
  // chosen (for every piece) do not hold them: to piece 0.
  if (this->LoadRangeEnds && piece == 0 && !chosen.Ranges.empty())
  {
    if (!P->EndsRead)
    {
      P->EndRows = pointsurfaces::RangeEndRows(info);
      P->Ends = pointsurfaces::SplatColumns();
      P->Ends.Resize(0, info.Degree, info.AttributeComponents);
      for (const long long row : P->EndRows)
      {
        std::string error;
        if (!P->File.Read(row, 1, P->Ends, error))
        {
          vtkErrorMacro(<< this->FileName << ": " << error);
          P->Open = false;
          return 1;
        }
      }
      P->EndsRead = true;
    }
    for (size_t e = 0; e < P->EndRows.size(); ++e)
    {
      const long long row = P->EndRows[e];
      const bool loaded = std::any_of(chosen.Ranges.begin(),
        chosen.Ranges.end(),
        [row](const pointsurfaces::PageRange& r) { return row >= r.Begin && row < r.End; });
      if (!loaded)
      {
        columns.Append(P->Ends, static_cast<long long>(e));
      }
    }
  }
  Assemble(columns, info, output);
  this->NumberOfLoadedSplats = static_cast<vtkIdType>(columns.Count);
  vtkFieldData* fd = output->GetFieldData();
  long long pages = 0;
  for (const pointsurfaces::OctreeNode& node : info.Pages.Tree.Nodes)
  {
    pages += node.ChildCount == 0 && node.End > node.Begin ? 1 : 0;
  }
  AddCount(fd, "SplatFilePages", pages);
  AddCount(fd, "SplatFileLoadedPages", static_cast<vtkIdType>(selection.Ranges.size()));
  AddCount(fd, "SplatFileSplats", this->NumberOfSplats);
  AddCount(fd, "SplatFileLoadedSplats", this->NumberOfLoadedSplats);
  AddCount(fd, "SplatInputPoints", info.InputPoints);
  if (!info.Pages.Tree.Nodes.empty())
  {
    vtkNew<vtkDoubleArray> bounds;
    bounds->SetName(FileBoundsArrayName());
    bounds->SetNumberOfComponents(6);
    bounds->InsertNextTuple(info.Pages.Tree.Nodes[0].Bounds);
    fd->AddArray(bounds);
  }
  vtkNew<vtkStringArray> path;
  path->SetName(FileNameArrayName());
  path->InsertNextValue(vtksys::SystemTools::CollapseFullPath(this->FileName));
  fd->AddArray(path);
  // What this output is, for telling it from a filter's output that passed
  // the field data on (a Transform keeps the count, a Calculator the points).
  vtkNew<vtkDoubleArray> loadedBounds;
  loadedBounds->SetName(LoadedBoundsArrayName());
  loadedBounds->SetNumberOfComponents(6);
  loadedBounds->InsertNextTuple(output->GetBounds());
  fd->AddArray(loadedBounds);
  vtkNew<vtkStringArray> arrays;
  arrays->SetName(ArraysArrayName());
  for (int a = 0; a < output->GetPointData()->GetNumberOfArrays(); ++a)
  {
    const char* name = output->GetPointData()->GetArrayName(a);
    arrays->InsertNextValue(name ? name : "");
  }
  fd->AddArray(arrays);
  return 1;
}

//------------------------------------------------------------------------------
void vtkSplatFileReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "MemoryBudget: " << this->MemoryBudget << " MB\n";
  os << indent << "CheckInChildProcess: " << (this->CheckInChildProcess ? "on" : "off") << "\n";
  os << indent << "LoadRangeEnds: " << (this->LoadRangeEnds ? "on" : "off") << "\n";
  os << indent << "PixelError: " << this->PixelError << "\n";
  os << indent << "Camera: " << this->Camera.GetPointer() << "\n";
  os << indent << "ViewportSize: " << this->ViewportSize[0] << " x " << this->ViewportSize[1]
     << "\n";
  os << indent << "NumberOfSplats: " << this->NumberOfSplats << "\n";
  os << indent << "NumberOfLoadedSplats: " << this->NumberOfLoadedSplats << "\n";
}
