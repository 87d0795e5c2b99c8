// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkLASReader.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <laszip_api.h>

#include <algorithm>
#include <fstream>
#include <numeric>

vtkStandardNewMacro(vtkLASReader);

namespace
{
// One LASzip reader, destroyed when it goes.
class LASFile
{
public:
  ~LASFile()
  {
    if (this->Reader)
    {
      if (this->Open)
      {
        laszip_close_reader(this->Reader);
      }
      laszip_destroy(this->Reader);
    }
  }
  // False, with `error` set, when the file cannot be opened.
  bool Start(const std::string& path, std::string& error)
  {
    std::ifstream probe(path, std::ios::binary | std::ios::ate);
    if (!probe)
    {
      error = "cannot be opened";
      return false;
    }
    if (probe.tellg() == 0)
    {
      error = "the file is empty";
      return false;
    }
    laszip_BOOL compressed = 0;
    if (laszip_create(&this->Reader) || !this->Reader)
    {
      error = "LASzip cannot start";
      return false;
    }
    if (laszip_open_reader(this->Reader, path.c_str(), &compressed))
    {
      error = this->Message("not a LAS or LAZ file, or damaged");
      return false;
    }
    this->Open = true;
    if (laszip_get_header_pointer(this->Reader, &this->Header) ||
      laszip_get_point_pointer(this->Reader, &this->Point))
    {
      error = this->Message("damaged header");
      return false;
    }
    this->Count = this->Header->number_of_point_records
      ? static_cast<long long>(this->Header->number_of_point_records)
      : static_cast<long long>(this->Header->extended_number_of_point_records);
    return true;
  }
  std::string Message(const char* otherwise)
  {
    laszip_CHAR* text = nullptr;
    if (this->Reader && !laszip_get_error(this->Reader, &text) && text && *text)
    {
      return text;
    }
    return otherwise;
  }
  bool HasTime() const
  {
    const int f = this->Header->point_data_format;
    return f == 1 || f >= 3;
  }
  bool HasColour() const
  {
    const int f = this->Header->point_data_format;
    return f == 2 || f == 3 || f == 5 || f == 7 || f == 8 || f == 10;
  }
  laszip_POINTER Reader = nullptr;
  laszip_header* Header = nullptr;
  laszip_point* Point = nullptr;
  long long Count = 0;
  bool Open = false;
};
} // namespace

//------------------------------------------------------------------------------
vtkLASReader::vtkLASReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
bool vtkLASReader::CanReadFile(const char* fileName)
{
  LASFile file;
  std::string error;
  return fileName && file.Start(fileName, error);
}

//------------------------------------------------------------------------------
int vtkLASReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  outputVector->GetInformationObject(0)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkLASReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector->GetInformationObject(0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->NumberOfPointsInFile = 0;
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No FileName: nothing to read.");
    return 1;
  }
  LASFile file;
  std::string error;
  if (!file.Start(this->FileName, error))
  {
    vtkErrorMacro(<< this->FileName << ": " << error);
    return 1;
  }
  this->NumberOfPointsInFile = static_cast<vtkIdType>(file.Count);
  const long long piece = info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    ? info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    : 0;
  const long long pieces = info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    ? std::max(1, info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()))
    : 1;
  const long long first = file.Count * piece / pieces, last = file.Count * (piece + 1) / pieces;
  const laszip_header& h = *file.Header;

  // 8-bit colours in 16-bit fields, or true 16-bit ones: the first points decide.
  bool wide = false;
  if (file.HasColour())
  {
    for (long long i = 0; i < std::min<long long>(file.Count, 10000) && !wide; ++i)
    {
      if (laszip_read_point(file.Reader))
      {
        break;
      }
      wide = std::max({ file.Point->rgb[0], file.Point->rgb[1], file.Point->rgb[2] }) > 255;
    }
  }
  if (first > 0 && laszip_seek_point(file.Reader, first))
  {
    vtkErrorMacro(<< this->FileName << ": " << file.Message("cannot seek to the piece's points"));
    return 1;
  }
  if (first == 0 && file.HasColour() && file.Count > 0 && laszip_seek_point(file.Reader, 0))
  {
    vtkErrorMacro(<< this->FileName << ": " << file.Message("cannot seek to the first point"));
    return 1;
  }
  const vtkIdType n = static_cast<vtkIdType>(last - first);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkUnsignedShortArray> intensity;
  intensity->SetName("Intensity");
  intensity->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedCharArray> classification, returnNumber, returns, rgb;
  classification->SetName("Classification");
  returnNumber->SetName("ReturnNumber");
  returns->SetName("NumberOfReturns");
  for (vtkUnsignedCharArray* a :
    { classification.GetPointer(), returnNumber.GetPointer(), returns.GetPointer() })
  {
    a->SetNumberOfTuples(n);
  }
  vtkNew<vtkDoubleArray> time;
  time->SetName("GPSTime");
  time->SetNumberOfTuples(file.HasTime() ? n : 0);
  rgb->SetName("RGB");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(file.HasColour() ? n : 0);
  const bool extended = h.point_data_format >= 6;
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (laszip_read_point(file.Reader))
    {
      vtkErrorMacro(<< this->FileName << ": " << file.Message("truncated: the points end early")
                    << " (point " << first + i << " of " << file.Count << ")");
      output->Initialize();
      return 1;
    }
    const laszip_point& p = *file.Point;
    points->SetPoint(i,
      h.x_offset + h.x_scale_factor * p.X,
      h.y_offset + h.y_scale_factor * p.Y,
      h.z_offset + h.z_scale_factor * p.Z);
    intensity->SetValue(i, p.intensity);
    classification->SetValue(i, extended ? p.extended_classification : p.classification);
    returnNumber->SetValue(i, extended ? p.extended_return_number : p.return_number);
    returns->SetValue(i, extended ? p.extended_number_of_returns : p.number_of_returns);
    if (file.HasTime())
    {
      time->SetValue(i, p.gps_time);
    }
    if (file.HasColour())
    {
      for (int c = 0; c < 3; ++c)
      {
        rgb->SetTypedComponent(i, c, static_cast<unsigned char>(wide ? p.rgb[c] >> 8 : p.rgb[c]));
      }
    }
    if (i % 65536 == 0)
    {
      this->UpdateProgress(static_cast<double>(i) / std::max<vtkIdType>(1, n));
    }
  }
  output->SetPoints(points);
  vtkNew<vtkCellArray> verts;
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfTuples(n + 1);
  connectivity->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i <= n; ++i)
  {
    offsets->SetValue(i, i);
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    connectivity->SetValue(i, i);
  }
  verts->SetData(offsets, connectivity);
  output->SetVerts(verts);
  vtkPointData* pd = output->GetPointData();
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(intensity.GetPointer()),
         static_cast<vtkDataArray*>(classification.GetPointer()),
         static_cast<vtkDataArray*>(returnNumber.GetPointer()),
         static_cast<vtkDataArray*>(returns.GetPointer()) })
  {
    pd->AddArray(a);
  }
  if (file.HasTime())
  {
    pd->AddArray(time);
  }
  if (file.HasColour())
  {
    pd->SetScalars(rgb);
  }
  vtkFieldData* fd = output->GetFieldData();
  vtkNew<vtkIdTypeArray> count;
  count->SetName("LASPointCount");
  count->InsertNextValue(this->NumberOfPointsInFile);
  fd->AddArray(count);
  vtkNew<vtkIdTypeArray> format;
  format->SetName("LASPointFormat");
  format->InsertNextValue(h.point_data_format);
  fd->AddArray(format);
  vtkNew<vtkDoubleArray> scale, offset;
  scale->SetName("LASScale");
  offset->SetName("LASOffset");
  scale->SetNumberOfComponents(3);
  offset->SetNumberOfComponents(3);
  scale->InsertNextTuple3(h.x_scale_factor, h.y_scale_factor, h.z_scale_factor);
  offset->InsertNextTuple3(h.x_offset, h.y_offset, h.z_offset);
  fd->AddArray(scale);
  fd->AddArray(offset);
  return 1;
}

//------------------------------------------------------------------------------
void vtkLASReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "NumberOfPointsInFile: " << this->NumberOfPointsInFile << "\n";
}
