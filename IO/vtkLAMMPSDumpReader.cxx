// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkLAMMPSDumpReader.h"

#include "psLAMMPSDump.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSplatDataModel.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <fstream>
#include <numeric>
#include <vector>

vtkStandardNewMacro(vtkLAMMPSDumpReader);

struct vtkLAMMPSDumpReader::Index
{
  std::string File;
  long long Modified = -1; ///< the file's modification time when scanned
  std::vector<pointsurfaces::DumpSnapshotInfo> Infos;
};

namespace
{
long long ModifiedTime(const std::string& file)
{
  return static_cast<long long>(vtksys::SystemTools::ModifiedTime(file));
}
} // namespace

//------------------------------------------------------------------------------
vtkLAMMPSDumpReader::vtkLAMMPSDumpReader()
  : Snapshots(new Index)
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkLAMMPSDumpReader::~vtkLAMMPSDumpReader() = default;

//------------------------------------------------------------------------------
int vtkLAMMPSDumpReader::GetNumberOfSnapshots()
{
  return static_cast<int>(this->Snapshots->Infos.size());
}

//------------------------------------------------------------------------------
bool vtkLAMMPSDumpReader::CanReadFile(const char* fileName)
{
  std::ifstream in(fileName ? fileName : "");
  std::string line;
  while (in && std::getline(in, line) && line.find_first_not_of(" \t\r") == std::string::npos)
  {
  }
  return line.compare(0, 5, "ITEM:") == 0;
}

//------------------------------------------------------------------------------
int vtkLAMMPSDumpReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector->GetInformationObject(0);
  info->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  info->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  Index& index = *this->Snapshots;
  if (this->FileName.empty())
  {
    index = Index();
    vtkErrorMacro(<< "No FileName: nothing to read.");
    return 1;
  }
  const long long modified = ModifiedTime(this->FileName);
  if (index.File != this->FileName || index.Modified != modified)
  {
    index = Index();
    std::ifstream in(this->FileName, std::ios::binary);
    if (!in)
    {
      vtkErrorMacro(<< "Cannot open " << this->FileName << ".");
      return 1;
    }
    std::string error;
    index.Infos = pointsurfaces::ScanDump(in, error);
    index.File = this->FileName;
    index.Modified = modified;
    if (!error.empty())
    {
      vtkErrorMacro(<< this->FileName << " is damaged after " << index.Infos.size()
                    << " snapshots: " << error << ".");
    }
    // Time steps must increase: a restarted run can repeat timesteps, and
    // then the later snapshot of a time is the one kept.
    std::stable_sort(index.Infos.begin(),
      index.Infos.end(),
      [](const pointsurfaces::DumpSnapshotInfo& a, const pointsurfaces::DumpSnapshotInfo& b)
      { return a.Time < b.Time; });
    std::vector<pointsurfaces::DumpSnapshotInfo> unique;
    for (const auto& s : index.Infos)
    {
      if (!unique.empty() && unique.back().Time == s.Time)
      {
        unique.back() = s;
      }
      else
      {
        unique.push_back(s);
      }
    }
    if (unique.size() < index.Infos.size())
    {
      vtkWarningMacro(<< this->FileName << " repeats " << index.Infos.size() - unique.size()
                      << " times (a restarted run?): the last snapshot of each is read.");
    }
    index.Infos.swap(unique);
  }
  if (index.Infos.empty())
  {
    return 1;
  }
  std::vector<double> times;
  for (const auto& s : index.Infos)
  {
    times.push_back(s.Time);
  }
  info->Set(
    vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), static_cast<int>(times.size()));
  const double range[2] = { times.front(), times.back() };
  info->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

//------------------------------------------------------------------------------
int vtkLAMMPSDumpReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  const Index& index = *this->Snapshots;
  if (index.Infos.empty())
  {
    return 1; // RequestInformation said why
  }
  // The whole snapshot goes to piece 0 (a dump is one text stream); other
  // pieces of a parallel pipeline stay empty.
  if (info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) &&
    info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) > 0)
  {
    return 1;
  }
  // The last snapshot at or before the requested time (the first one before it all).
  size_t pick = 0;
  if (info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    const double t = info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
    for (size_t k = 0; k < index.Infos.size() && index.Infos[k].Time <= t; ++k)
    {
      pick = k;
    }
  }
  std::ifstream in(this->FileName, std::ios::binary);
  pointsurfaces::DumpSnapshot snap;
  std::string error;
  if (!in || !pointsurfaces::ReadSnapshot(in, index.Infos[pick].Offset, snap, error))
  {
    vtkErrorMacro(<< "Cannot read timestep " << index.Infos[pick].Timestep << " of "
                  << this->FileName << ": " << (error.empty() ? "cannot open it" : error) << ".");
    return 1;
  }
  std::vector<double> xyz;
  int used[3];
  if (!pointsurfaces::SnapshotPositions(snap, xyz, used))
  {
    vtkErrorMacro(<< this->FileName
                  << " has no coordinates (x y z, xu yu zu, xs ys zs or xsu ysu "
                     "zsu) at timestep "
                  << snap.Info.Timestep << ".");
    return 1;
  }
  const vtkIdType n = static_cast<vtkIdType>(snap.Info.NumberOfAtoms);
  const size_t columns = snap.Columns.size();
  auto column = [&](const std::string& name)
  {
    const auto it = std::find(snap.Columns.begin(), snap.Columns.end(), name);
    return it == snap.Columns.end() ? -1 : static_cast<int>(it - snap.Columns.begin());
  };
  // The order of the atoms: by id when asked and possible.
  std::vector<vtkIdType> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), vtkIdType(0));
  const int idColumn = column("id");
  if (this->SortById && idColumn >= 0)
  {
    std::stable_sort(order.begin(),
      order.end(),
      [&](vtkIdType a, vtkIdType b)
      { return snap.Values[a * columns + idColumn] < snap.Values[b * columns + idColumn]; });
  }

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  for (vtkIdType k = 0; k < n; ++k)
  {
    points->SetPoint(k, &xyz[3 * order[k]]);
  }
  output->SetPoints(points);
  vtkSplatDataModel::AddVertexCells(output);

  // Columns to arrays: Ax Ay Az grouped, id/mol/type as integers.
  std::vector<bool> taken(columns, false);
  for (int c : used)
  {
    taken[c] = true;
  }
  vtkPointData* pd = output->GetPointData();
  for (size_t c = 0; c < columns; ++c)
  {
    const std::string& name = snap.Columns[c];
    if (taken[c] || name.empty() || name.back() != 'x')
    {
      continue;
    }
    const std::string base = name.substr(0, name.size() - 1);
    const std::string arrayName = base.empty() ? "x" : base; // x y z (wrapped) beside xu yu zu
    const int cy = column(base + "y"), cz = column(base + "z");
    if (cy < 0 || cz < 0 || taken[cy] || taken[cz])
    {
      continue;
    }
    vtkNew<vtkDoubleArray> a;
    a->SetName(arrayName.c_str());
    a->SetNumberOfComponents(3);
    a->SetNumberOfTuples(n);
    const int parts[3] = { static_cast<int>(c), cy, cz };
    for (vtkIdType k = 0; k < n; ++k)
    {
      for (int j = 0; j < 3; ++j)
      {
        a->SetTypedComponent(k, j, snap.Values[order[k] * columns + parts[j]]);
      }
    }
    pd->AddArray(a);
    for (int part : parts)
    {
      taken[part] = true;
    }
  }
  for (size_t c = 0; c < columns; ++c)
  {
    if (taken[c])
    {
      continue;
    }
    const std::string& name = snap.Columns[c];
    vtkSmartPointer<vtkDataArray> a;
    if (name == "id" || name == "mol")
    {
      a = vtkSmartPointer<vtkIdTypeArray>::New();
    }
    else if (name == "type")
    {
      a = vtkSmartPointer<vtkIntArray>::New();
    }
    else
    {
      a = vtkSmartPointer<vtkDoubleArray>::New();
    }
    a->SetName(name.c_str());
    a->SetNumberOfTuples(n);
    for (vtkIdType k = 0; k < n; ++k)
    {
      a->SetTuple1(k, snap.Values[order[k] * columns + c]);
    }
    pd->AddArray(a);
  }

  vtkFieldData* fd = output->GetFieldData();
  vtkNew<vtkIdTypeArray> step;
  step->SetName("Timestep");
  step->InsertNextValue(static_cast<vtkIdType>(snap.Info.Timestep));
  fd->AddArray(step);
  vtkNew<vtkDoubleArray> time;
  time->SetName("Time");
  time->InsertNextValue(snap.Info.Time);
  fd->AddArray(time);
  vtkNew<vtkDoubleArray> box;
  box->SetName("BoxBounds");
  box->SetNumberOfComponents(6);
  box->InsertNextTypedTuple(snap.Box);
  fd->AddArray(box);
  vtkNew<vtkDoubleArray> tilt;
  tilt->SetName("BoxTilt");
  tilt->SetNumberOfComponents(3);
  tilt->InsertNextTypedTuple(snap.Tilt);
  fd->AddArray(tilt);
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), snap.Info.Time);
  return 1;
}

//------------------------------------------------------------------------------
void vtkLAMMPSDumpReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "SortById: " << this->SortById << "\n";
  os << indent << "Snapshots: " << this->Snapshots->Infos.size() << "\n";
}
