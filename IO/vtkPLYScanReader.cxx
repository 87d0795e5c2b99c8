// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPLYScanReader.h"

#include "psPLY.h"
#include "psReaderTime.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <set>
#include <type_traits>

vtkStandardNewMacro(vtkPLYScanReader);

namespace
{
int VTKType(pointsurfaces::PLYType type)
{
  using pointsurfaces::PLYType;
  switch (type)
  {
    case PLYType::Int8:
      return VTK_TYPE_INT8;
    case PLYType::UInt8:
      return VTK_TYPE_UINT8;
    case PLYType::Int16:
      return VTK_TYPE_INT16;
    case PLYType::UInt16:
      return VTK_TYPE_UINT16;
    case PLYType::Int32:
      return VTK_TYPE_INT32;
    case PLYType::UInt32:
      return VTK_TYPE_UINT32;
    case PLYType::Int64:
      return VTK_TYPE_INT64;
    case PLYType::UInt64:
      return VTK_TYPE_UINT64;
    case PLYType::Float32:
      return VTK_TYPE_FLOAT32;
    default:
      return VTK_TYPE_FLOAT64;
  }
}

// `columns` as the components of `a`'s tuples, one per point.
template<typename T>
void Interleave(const pointsurfaces::PLYMesh& mesh,
  const std::vector<const pointsurfaces::PLYColumn*>& columns,
  vtkAOSDataArrayTemplate<T>* a)
{
  const size_t n = mesh.NumberOfPoints, m = columns.size();
  a->SetNumberOfComponents(static_cast<int>(m));
  a->SetNumberOfTuples(static_cast<vtkIdType>(n));
  T* out = a->GetPointer(0);
  for (size_t c = 0; c < m; ++c)
  {
    for (size_t k = 0; k < n; ++k)
    {
      const double v = columns[c]->Value(k);
      out[k * m + c] = std::is_same<T, float>::value ? pointsurfaces::PLYFloat(v) : v;
    }
  }
}

// The columns of these names, when all of them are there.
std::vector<const pointsurfaces::PLYColumn*> All(const pointsurfaces::PLYMesh& mesh,
  std::initializer_list<std::string> names)
{
  std::vector<const pointsurfaces::PLYColumn*> found;
  for (const std::string& name : names)
  {
    const pointsurfaces::PLYColumn* c = mesh.Find(name);
    if (!c)
    {
      return {};
    }
    found.push_back(c);
  }
  return found;
}
// x, y and z as points: float when all three are float, else double.
vtkSmartPointer<vtkPoints> Points(const pointsurfaces::PLYMesh& mesh)
{
  const auto xyz = All(mesh, { "x", "y", "z" });
  const bool single = std::all_of(xyz.begin(),
    xyz.end(),
    [](const pointsurfaces::PLYColumn* c) { return c->Type == pointsurfaces::PLYType::Float32; });
  auto points = vtkSmartPointer<vtkPoints>::New();
  if (single)
  {
    vtkNew<vtkFloatArray> a;
    Interleave(mesh, xyz, a.Get());
    points->SetData(a);
  }
  else
  {
    vtkNew<vtkDoubleArray> a;
    Interleave(mesh, xyz, a.Get());
    points->SetData(a);
  }
  return points;
}

// Normals and colours from their columns; every other column (but x, y, z) as it is.
void AddPointData(const pointsurfaces::PLYMesh& mesh, vtkPointData* pd)
{
  std::set<std::string> taken = { "x", "y", "z" };
  const auto normals = All(mesh, { "nx", "ny", "nz" });
  if (!normals.empty())
  {
    vtkNew<vtkFloatArray> a;
    a->SetName("Normals");
    Interleave(mesh, normals, a.Get());
    pd->SetNormals(a);
    taken.insert({ "nx", "ny", "nz" });
  }
  for (const std::string prefix : { "", "diffuse_" })
  {
    auto colours = All(mesh, { prefix + "red", prefix + "green", prefix + "blue" });
    if (colours.empty())
    {
      continue;
    }
    if (const pointsurfaces::PLYColumn* alpha = mesh.Find(prefix + "alpha"))
    {
      colours.push_back(alpha);
    }
    const std::vector<unsigned char> bytes =
      pointsurfaces::PLYColours(colours, mesh.NumberOfPoints);
    vtkNew<vtkUnsignedCharArray> a;
    a->SetName("RGB");
    a->SetNumberOfComponents(static_cast<int>(colours.size()));
    a->SetNumberOfTuples(static_cast<vtkIdType>(mesh.NumberOfPoints));
    std::copy(bytes.begin(), bytes.end(), a->GetPointer(0));
    pd->SetScalars(a);
    for (const pointsurfaces::PLYColumn* c : colours)
    {
      taken.insert(c->Name);
    }
    break;
  }
  for (const pointsurfaces::PLYColumn& c : mesh.Columns)
  {
    if (taken.count(c.Name))
    {
      continue;
    }
    vtkSmartPointer<vtkDataArray> a =
      vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTKType(c.Type)));
    a->SetName(c.Name.c_str());
    a->SetNumberOfTuples(static_cast<vtkIdType>(mesh.NumberOfPoints));
    if (!c.Bytes.empty())
    {
      std::memcpy(a->GetVoidPointer(0), c.Bytes.data(), c.Bytes.size());
    }
    pd->AddArray(a);
  }
}

vtkSmartPointer<vtkCellArray> Polygons(const pointsurfaces::PLYMesh& mesh)
{
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(mesh.FaceOffsets.size()));
  std::copy(mesh.FaceOffsets.begin(), mesh.FaceOffsets.end(), offsets->GetPointer(0));
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(mesh.FaceConnectivity.size()));
  std::copy(
    mesh.FaceConnectivity.begin(), mesh.FaceConnectivity.end(), connectivity->GetPointer(0));
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  polys->SetData(offsets, connectivity);
  return polys;
}
} // namespace

//------------------------------------------------------------------------------
vtkPLYScanReader::vtkPLYScanReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
bool vtkPLYScanReader::CanReadFile(const char* fileName)
{
  std::ifstream in(fileName ? fileName : "", std::ios::binary);
  char magic[4] = { 0, 0, 0, 0 };
  in.read(magic, 4);
  return in && pointsurfaces::HasPLYMagic(magic, 4);
}

//------------------------------------------------------------------------------
int vtkPLYScanReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector->GetInformationObject(0);
  if (this->SplitPoints)
  {
    info->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  }
  else
  {
    info->Remove(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST());
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkPLYScanReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No FileName: nothing to read.");
    return 1;
  }
  vtkInformation* info = outputVector->GetInformationObject(0);
  int piece = 0, pieces = 1;
  pointsurfaces::RequestedPiece(info, piece, pieces);
  const bool split = this->SplitPoints && pieces > 1;
  if (!split && pointsurfaces::LaterPiece(info))
  {
    return 1; // piece 0 reads the whole file
  }
  pointsurfaces::PLYMesh mesh;
  std::string error;
  bool streamed = false;
  if (split ? !pointsurfaces::ReadPLYFilePiece(this->FileName,
                static_cast<size_t>(std::max(0, piece)),
                static_cast<size_t>(pieces),
                mesh,
                streamed,
                error)
            : !pointsurfaces::ReadPLYFile(this->FileName, mesh, error))
  {
    vtkErrorMacro(<< this->FileName << ": " << error);
    return 1;
  }
  if (split && !streamed && piece == 0)
  {
    vtkWarningMacro(<< this->FileName
                    << ": an ASCII file (or one with lists before its vertices) is read whole "
                       "for each piece; convert it to binary PLY to read it piece by piece");
  }
  const size_t read = mesh.NumberOfPoints;
  const size_t dropped = pointsurfaces::DropNonFinitePoints(mesh);
  if (mesh.NumberOfPoints == 0)
  {
    if (!split)
    {
      vtkErrorMacro(<< this->FileName << ": no points");
    }
    return 1;
  }
  for (const std::string& warning : mesh.Warnings)
  {
    vtkWarningMacro(<< this->FileName << ": " << warning);
  }
  if (dropped > 0)
  {
    vtkWarningMacro(<< this->FileName << ": " << dropped << " of " << read
                    << " points with NaN or infinite coordinates left out");
  }

  output->SetPoints(Points(mesh));
  AddPointData(mesh, output->GetPointData());
  if (!mesh.FaceOffsets.empty())
  {
    output->SetPolys(Polygons(mesh));
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkPLYScanReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "SplitPoints: " << (this->SplitPoints ? "on" : "off") << "\n";
}
