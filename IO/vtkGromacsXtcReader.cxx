// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkGromacsXtcReader.h"

#include "psGromacsXtc.h"
#include "psReaderTime.h"

#include "vtkCallbackCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkGromacsGroReader.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSplatDataModel.h"

#include <algorithm>
#include <fstream>
#include <new>

vtkStandardNewMacro(vtkGromacsXtcReader);

struct vtkGromacsXtcReader::Internals
{
  pointsurfaces::FrameIndex<pointsurfaces::XtcFrameInfo> Index;
  // The structure file's reader; its errors are caught and reported once,
  // as this reader's (its warnings, such as unknown elements, pass).
  vtkNew<vtkGromacsGroReader> Structure;
  vtkNew<vtkCallbackCommand> StructureErrors;
  std::string StructureError;
  pointsurfaces::FileStamp StructureStamp; // the structure file as last read
  std::vector<float> Positions;            // scratch, kept from frame to frame

  Internals()
  {
    this->StructureErrors->SetClientData(&this->StructureError);
    this->StructureErrors->SetCallback(
      [](vtkObject*, unsigned long, void* client, void* call)
      {
        auto* message = static_cast<std::string*>(client);
        if (message->empty() && call)
        {
          *message = static_cast<const char*>(call);
        }
      });
    this->Structure->AddObserver(vtkCommand::ErrorEvent, this->StructureErrors);
  }
};

//------------------------------------------------------------------------------
vtkGromacsXtcReader::vtkGromacsXtcReader()
  : Internal(new Internals)
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
vtkGromacsXtcReader::~vtkGromacsXtcReader() = default;

//------------------------------------------------------------------------------
int vtkGromacsXtcReader::GetNumberOfFrames()
{
  return static_cast<int>(this->Internal->Index.Frames.size());
}

//------------------------------------------------------------------------------
bool vtkGromacsXtcReader::CanReadFile(const char* fileName)
{
  std::ifstream in(fileName ? fileName : "", std::ios::binary);
  unsigned char magic[4] = { 0, 0, 0, 0 };
  return in.read(reinterpret_cast<char*>(magic), 4) && magic[0] == 0 && magic[1] == 0 &&
    magic[2] == 0x07 && magic[3] == 0xcb; // 1995, big-endian
}

//------------------------------------------------------------------------------
int vtkGromacsXtcReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  this->Internal->Index.Update(
    this, this->FileName, pointsurfaces::ScanXtc, "frame", outputVector->GetInformationObject(0));
  return 1;
}

//------------------------------------------------------------------------------
int vtkGromacsXtcReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  Internals& internal = *this->Internal;
  const auto& frames = internal.Index.Frames;
  if (frames.empty() || pointsurfaces::LaterPiece(info))
  {
    return 1; // RequestInformation said why; or another piece than the first
  }
  const pointsurfaces::XtcFrameInfo& where = frames[internal.Index.Pick(info)];
  const vtkIdType n = static_cast<vtkIdType>(where.NumberOfAtoms);

  // The structure first: a mismatch is found before any decoding.
  vtkPolyData* structure = nullptr;
  if (!this->StructureFileName.empty())
  {
    // Read again when the file changed on disk, or failed last time.
    if (internal.StructureStamp.Stale(this->StructureFileName) || !internal.StructureError.empty())
    {
      internal.StructureError.clear();
      internal.StructureStamp.Take(this->StructureFileName);
      internal.Structure->SetFileName(this->StructureFileName.c_str());
      internal.Structure->Modified();
    }
    internal.Structure->Update();
    structure = internal.Structure->GetOutput();
    if (!internal.StructureError.empty() || structure->GetNumberOfPoints() != n)
    {
      vtkErrorMacro(<< this->FileName << " has " << n << " atoms; its structure file "
                    << this->StructureFileName << " "
                    << (internal.StructureError.empty()
                           ? "has " + std::to_string(structure->GetNumberOfPoints())
                           : "cannot be read: " + internal.StructureError)
                    << ".");
      return 1;
    }
  }

  std::ifstream in(this->FileName, std::ios::binary);
  std::string error;
  bool read = false;
  try
  {
    read = in && pointsurfaces::ReadXtcFrame(in, where, internal.Positions, error);
  }
  catch (const std::bad_alloc&)
  {
    error = "not enough memory for " + std::to_string(n) + " atoms";
  }
  if (!read)
  {
    vtkErrorMacro(<< "Cannot read the frame at t = " << where.Time << " ps of " << this->FileName
                  << ": " << (error.empty() ? "cannot open it" : error) << ".");
    return 1;
  }
  vtkNew<vtkFloatArray> xyz;
  xyz->SetNumberOfComponents(3);
  xyz->SetNumberOfTuples(n);
  std::copy(internal.Positions.begin(), internal.Positions.end(), xyz->GetPointer(0));
  vtkNew<vtkPoints> points;
  points->SetData(xyz);
  output->SetPoints(points);
  vtkSplatDataModel::AddVertexCells(output);

  vtkPointData* pd = output->GetPointData();
  if (structure)
  {
    vtkPointData* from = structure->GetPointData();
    for (int a = 0; a < from->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* array = from->GetAbstractArray(a);
      if (std::string(array->GetName() ? array->GetName() : "") != "v")
      {
        pd->AddArray(array); // shared, not copied: the structure does not change per frame
      }
    }
  }
  else
  {
    vtkNew<vtkIntArray> atomid;
    atomid->SetName("atomid");
    atomid->SetNumberOfValues(n);
    for (vtkIdType k = 0; k < n; ++k)
    {
      atomid->SetValue(k, static_cast<int>(k + 1));
    }
    pd->AddArray(atomid);
  }

  pointsurfaces::StampFrame(output, where.Time, where.Step, where.Box);
  vtkNew<vtkDoubleArray> precision;
  precision->SetName("Precision");
  precision->InsertNextValue(where.Precision);
  output->GetFieldData()->AddArray(precision);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGromacsXtcReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "StructureFileName: " << this->StructureFileName << "\n";
  os << indent << "Frames: " << this->Internal->Index.Frames.size() << "\n";
}
