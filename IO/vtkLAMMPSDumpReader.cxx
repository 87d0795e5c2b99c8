// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkLAMMPSDumpReader.h"

#include "psLAMMPSDump.h"
#include "psReaderTime.h"

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

#include <algorithm>
#include <fstream>
#include <numeric>
#include <vector>

vtkStandardNewMacro(vtkLAMMPSDumpReader);

struct vtkLAMMPSDumpReader::Index : pointsurfaces::FrameIndex<pointsurfaces::DumpSnapshotInfo>
{
};

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
  return static_cast<int>(this->Snapshots->Frames.size());
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
  this->Snapshots->Update(this,
    this->FileName,
    pointsurfaces::ScanDump,
    "snapshot",
    outputVector->GetInformationObject(0));
  return 1;
}

namespace
{
// The index of the column `name` of the snapshot, -1 when it has none.
int ColumnOf(const pointsurfaces::DumpSnapshot& snap, const std::string& name)
{
  const auto it = std::find(snap.Columns.begin(), snap.Columns.end(), name);
  return it == snap.Columns.end() ? -1 : static_cast<int>(it - snap.Columns.begin());
}

// The snapshot's columns, other than the three `used` for the positions, as
// point arrays in the atoms' `order`: Ax Ay Az grouped into one vector A,
// id, mol and type as integers, the rest as doubles.
void AddColumnArrays(const pointsurfaces::DumpSnapshot& snap,
  const std::vector<vtkIdType>& order,
  const int used[3],
  vtkPointData* pd)
{
  const vtkIdType n = static_cast<vtkIdType>(order.size());
  const size_t columns = snap.Columns.size();
  auto column = [&](const std::string& name) { return ColumnOf(snap, name); };
  std::vector<bool> taken(columns, false);
  for (int c : { used[0], used[1], used[2] })
  {
    taken[c] = true;
  }
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
}

// The snapshot's timestep, time, box bounds and tilt as field arrays.
void AddSnapshotFields(const pointsurfaces::DumpSnapshot& snap, vtkFieldData* fd)
{
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
}
} // namespace

//------------------------------------------------------------------------------
int vtkLAMMPSDumpReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  const Index& index = *this->Snapshots;
  if (index.Frames.empty() || pointsurfaces::LaterPiece(info))
  {
    return 1; // RequestInformation said why; or another piece than the first
  }
  const size_t pick = index.Pick(info);
  std::ifstream in(this->FileName, std::ios::binary);
  pointsurfaces::DumpSnapshot snap;
  std::string error;
  if (!in || !pointsurfaces::ReadSnapshot(in, index.Frames[pick].Offset, snap, error))
  {
    vtkErrorMacro(<< "Cannot read timestep " << index.Frames[pick].Timestep << " of "
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
  // The order of the atoms: by id when asked and possible.
  std::vector<vtkIdType> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), vtkIdType(0));
  const int idColumn = ColumnOf(snap, "id");
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
  AddColumnArrays(snap, order, used, output->GetPointData());
  AddSnapshotFields(snap, output->GetFieldData());
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), snap.Info.Time);
  return 1;
}

//------------------------------------------------------------------------------
void vtkLAMMPSDumpReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "SortById: " << this->SortById << "\n";
  os << indent << "Snapshots: " << this->Snapshots->Frames.size() << "\n";
}
