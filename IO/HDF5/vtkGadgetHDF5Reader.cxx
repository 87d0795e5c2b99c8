// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkGadgetHDF5Reader.h"

#include "psGadgetHDF5.h"
#include "psReaderTime.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
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
#include "vtkStringArray.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkTypeUInt32Array.h"
#include "vtkTypeUInt64Array.h"
#include "vtksys/SystemTools.hxx"

#include <cstring>

vtkStandardNewMacro(vtkGadgetHDF5Reader);

namespace
{
vtkSmartPointer<vtkDataArray> MakeArray(const pointsurfaces::SnapshotArray& a, long long rows)
{
  vtkSmartPointer<vtkDataArray> array;
  switch (a.Type)
  {
    case pointsurfaces::SnapshotArray::Float32:
      array = vtkSmartPointer<vtkFloatArray>::New();
      break;
    case pointsurfaces::SnapshotArray::Int32:
      array = vtkSmartPointer<vtkTypeInt32Array>::New();
      break;
    case pointsurfaces::SnapshotArray::Int64:
      array = vtkSmartPointer<vtkTypeInt64Array>::New();
      break;
    case pointsurfaces::SnapshotArray::UInt32:
      array = vtkSmartPointer<vtkTypeUInt32Array>::New();
      break;
    case pointsurfaces::SnapshotArray::UInt64:
      array = vtkSmartPointer<vtkTypeUInt64Array>::New();
      break;
    case pointsurfaces::SnapshotArray::Float64:
    default:
      array = vtkSmartPointer<vtkDoubleArray>::New();
      break;
  }
  array->SetName(a.Name.c_str());
  array->SetNumberOfComponents(a.Components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(rows));
  if (!a.Bytes.empty())
  {
    std::memcpy(array->GetVoidPointer(0), a.Bytes.data(), a.Bytes.size());
  }
  return array;
}
} // namespace

//------------------------------------------------------------------------------
vtkGadgetHDF5Reader::vtkGadgetHDF5Reader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkGadgetHDF5Reader::~vtkGadgetHDF5Reader() = default;

//------------------------------------------------------------------------------
bool vtkGadgetHDF5Reader::CanReadFile(const char* fileName)
{
  return fileName && pointsurfaces::IsGadgetSnapshot(fileName);
}

//------------------------------------------------------------------------------
int vtkGadgetHDF5Reader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector->GetInformationObject(0);
  info->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  info->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No FileName: nothing is read.");
    return 1;
  }
  // The header alone: its time is the one time step.
  pointsurfaces::SnapshotHeader header;
  std::string error;
  if (!pointsurfaces::ReadSnapshotHeader(
        this->FileName, header, error, this->CheckInChildProcess != 0))
  {
    return 1; // RequestData says why
  }
  info->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), &header.Time, 1);
  const double range[2] = { header.Time, header.Time };
  info->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  return 1;
}

//------------------------------------------------------------------------------
int vtkGadgetHDF5Reader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (this->FileName.empty() || pointsurfaces::LaterPiece(info))
  {
    return 1;
  }
  if (vtksys::SystemTools::FileExists(this->FileName, true) &&
    vtksys::SystemTools::FileLength(this->FileName) == 0)
  {
    vtkErrorMacro(<< this->FileName << " is empty.");
    return 1;
  }
  const pointsurfaces::Snapshot snapshot =
    pointsurfaces::ReadSnapshot(this->FileName, this->ParticleType, this->CheckInChildProcess != 0);
  if (!snapshot.Error.empty())
  {
    vtkErrorMacro(<< "Cannot read the snapshot " << this->FileName << ": " << snapshot.Error);
    return 1;
  }
  if (!snapshot.Warnings.empty())
  {
    std::string all;
    for (const std::string& w : snapshot.Warnings)
    {
      all += "\n  " + w;
    }
    vtkWarningMacro(<< "Reading " << this->FileName << ":" << all);
  }
  const long long n = snapshot.Count;
  vtkNew<vtkPoints> points;
  vtkPointData* pd = output->GetPointData();
  for (const pointsurfaces::SnapshotArray& a : snapshot.Arrays)
  {
    vtkSmartPointer<vtkDataArray> array = MakeArray(a, n);
    if (a.Name == "Coordinates")
    {
      points->SetData(array);
    }
    else
    {
      pd->AddArray(array);
    }
  }
  output->SetPoints(points);
  vtkSplatDataModel::AddVertexCells(output);
  const pointsurfaces::SnapshotHeader& h = snapshot.Header;
  vtkFieldData* fd = output->GetFieldData();
  auto addNumbers = [fd](const char* name, const double* values, int count)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(count);
    a->InsertNextTuple(values);
    fd->AddArray(a);
  };
  addNumbers("Time", &h.Time, 1);
  addNumbers("Redshift", &h.Redshift, 1);
  addNumbers("BoxSize", h.BoxSize, 3);
  double totals[6];
  for (int k = 0; k < 6; ++k)
  {
    totals[k] = static_cast<double>(h.NumPartTotal[k]);
  }
  addNumbers("NumPart_Total", totals, 6);
  vtkNew<vtkIntArray> type;
  type->SetName("ParticleType");
  type->InsertNextValue(this->ParticleType);
  fd->AddArray(type);
  vtkNew<vtkStringArray> code;
  code->SetName("Code");
  code->InsertNextValue(h.Code);
  fd->AddArray(code);
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), h.Time);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGadgetHDF5Reader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "ParticleType: " << this->ParticleType << "\n";
  os << indent << "CheckInChildProcess: " << (this->CheckInChildProcess ? "on" : "off") << "\n";
}
