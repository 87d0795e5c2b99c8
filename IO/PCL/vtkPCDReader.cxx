// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPCDReader.h"

#include "psReadOutcome.h"
#include "vtkSplatDataModel.h"

#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtksys/SystemTools.hxx"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkPCDReader);

namespace
{
int VTKType(std::uint8_t pclType)
{
  switch (pclType)
  {
    case pcl::PCLPointField::INT8:
      return VTK_SIGNED_CHAR;
    case pcl::PCLPointField::UINT8:
      return VTK_UNSIGNED_CHAR;
    case pcl::PCLPointField::INT16:
      return VTK_SHORT;
    case pcl::PCLPointField::UINT16:
      return VTK_UNSIGNED_SHORT;
    case pcl::PCLPointField::INT32:
      return VTK_INT;
    case pcl::PCLPointField::UINT32:
      return VTK_UNSIGNED_INT;
    case pcl::PCLPointField::FLOAT32:
      return VTK_FLOAT;
    case pcl::PCLPointField::FLOAT64:
      return VTK_DOUBLE;
    default:
      return VTK_VOID;
  }
}

int TypeSize(std::uint8_t pclType)
{
  return static_cast<int>(pcl::getFieldSize(pclType));
}

double ReadScalar(const std::uint8_t* p, std::uint8_t type)
{
  switch (type)
  {
    case pcl::PCLPointField::FLOAT32:
    {
      float v;
      std::memcpy(&v, p, sizeof v);
      return v;
    }
    case pcl::PCLPointField::FLOAT64:
    {
      double v;
      std::memcpy(&v, p, sizeof v);
      return v;
    }
    default:
      return std::nan("");
  }
}

// PCL's readHeader already sizes the data for WIDTH x HEIGHT points of
// SIZE x COUNT bytes, so a damaged header makes it allocate gigabytes (found
// by FuzzPCDReader). Read those lines first, as text, and check them
// against the file size: an ASCII point takes at least one byte, a binary
// one its point step, and LZF expands at most about 100-fold.
std::string CheckHeaderCounts(const std::string& fileName)
{
  std::ifstream in(fileName, std::ios::binary | std::ios::ate);
  const double fileSize = static_cast<double>(in.tellg());
  in.seekg(0);
  std::string line, data;
  double width = -1, height = 1, pointsLine = -1, sizeSum = 0, countSum = 0;
  // PCL does not always stop at a damaged DATA line: take the largest counts
  // of any header-like line in the first 10 000 lines.
  for (int lines = 0; lines < 10000 && std::getline(in, line); ++lines)
  {
    std::istringstream words(line);
    std::string key;
    words >> key;
    double value = -1;
    if (key == "WIDTH" && words >> value)
    {
      width = std::max(width, value);
    }
    else if (key == "POINTS" && words >> value)
    {
      pointsLine = std::max(pointsLine, value);
    }
    else if (key == "HEIGHT" && words >> value)
    {
      height = std::max(height, value);
    }
    else if (key == "SIZE" || key == "COUNT")
    {
      // The largest SIZE and COUNT of any field bound a point's step and its
      // number of values from above, whatever lines PCL pairs up.
      double v = 0;
      double sum = 0;
      while (words >> v)
      {
        sum += std::abs(v);
      }
      (key == "SIZE" ? sizeSum : countSum) = std::max(key == "SIZE" ? sizeSum : countSum, sum);
    }
    else if (key == "DATA" && data.empty())
    {
      words >> data;
    }
  }
  const double points = std::max({ width * height, pointsLine, 0.0 });
  // At least one character a value in ASCII; SIZE x COUNT bytes a point in
  // binary (bounded below by the largest of the two sums).
  const double values = points * std::max(countSum, 1.0);
  const double bytes = points * std::max({ sizeSum, countSum, 1.0 });
  const double least = data == "ascii" || data.empty() ? values
    : data == "binary"                                 ? bytes
                                                       : bytes / 100.0;
  if (least > fileSize)
  {
    return "its header announces " + std::to_string(static_cast<long long>(points)) + " points (" +
      std::to_string(static_cast<long long>(countSum)) + " values, " +
      std::to_string(static_cast<long long>(sizeSum)) + " bytes a field), which " +
      std::to_string(static_cast<long long>(fileSize)) + " bytes of " + data + " data cannot hold";
  }
  return std::string();
}

// PCL 1.13 trusts the sizes in a binary file and crashes on a truncated one:
// check them against the file size before the data is read.
std::string CheckDataSize(const std::string& fileName)
{
  pcl::PCLPointCloud2 header;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0, dataType = 0;
  unsigned int dataIndex = 0;
  const std::string counts = CheckHeaderCounts(fileName);
  if (!counts.empty())
  {
    return counts;
  }
  pcl::PCDReader reader;
  if (reader.readHeader(fileName, header, origin, orientation, version, dataType, dataIndex) < 0)
  {
    return "its header cannot be parsed";
  }
  if (header.fields.empty() || header.point_step == 0)
  {
    return "its header declares no FIELDS";
  }
  if (dataType < 0 || dataType > 2)
  {
    return "its DATA line is not ascii, binary or binary_compressed";
  }
  // PCL walks every value of every field (COUNT of them) for each point,
  // whatever its TYPE: a field of no valid type with a count of 2^31 is
  // billions of steps a point (found by scripts/fuzz-campaign.sh). Each
  // field must have a type and fit inside a point.
  for (const pcl::PCLPointField& field : header.fields)
  {
    const std::uint64_t size = pcl::getFieldSize(field.datatype);
    if (size == 0 && field.name != "_")
    {
      return "its field \"" + field.name + "\" has no valid TYPE and SIZE";
    }
    if (static_cast<std::uint64_t>(field.offset) +
        static_cast<std::uint64_t>(field.count) * std::max<std::uint64_t>(size, 1) >
      header.point_step)
    {
      return "its field \"" + field.name + "\" (COUNT " + std::to_string(field.count) +
        ") does not fit in a point of " + std::to_string(header.point_step) + " bytes";
    }
  }
  std::ifstream in(fileName, std::ios::binary | std::ios::ate);
  const std::uint64_t fileSize = static_cast<std::uint64_t>(in.tellg());
  const std::uint64_t expected =
    static_cast<std::uint64_t>(header.width) * header.height * header.point_step;
  // PCL sizes its buffer when it meets the POINTS line, from the fields
  // counted so far, and writes every point of the body into it: a POINTS
  // line before some of the fields would be written past (found by
  // scripts/fuzz-campaign.sh, seen by valgrind in PCL's readBodyASCII).
  if (header.data.size() < expected)
  {
    return "its POINTS line comes before fields it counts (a buffer of " +
      std::to_string(header.data.size()) + " bytes for " + std::to_string(expected) + ")";
  }
  if (dataType == 1 && fileSize < dataIndex + expected)
  {
    return "the binary data holds " +
      std::to_string(fileSize - std::min<std::uint64_t>(fileSize, dataIndex)) + " bytes of the " +
      std::to_string(expected) + " its header announces";
  }
  if (dataType == 2)
  {
    std::uint32_t sizes[2] = { 0, 0 }; // compressed, uncompressed
    in.seekg(dataIndex);
    if (fileSize < dataIndex + 8 || !in.read(reinterpret_cast<char*>(sizes), 8))
    {
      return "the compressed data block is missing";
    }
    if (fileSize < dataIndex + 8 + std::uint64_t(sizes[0]))
    {
      return "the compressed data is cut short (" + std::to_string(fileSize - dataIndex - 8) +
        " of " + std::to_string(sizes[0]) + " bytes)";
    }
    if (sizes[1] != expected)
    {
      return "the compressed data would expand to " + std::to_string(sizes[1]) +
        " bytes instead of " + std::to_string(expected);
    }
  }
  return std::string();
}

const pcl::PCLPointField* Find(const pcl::PCLPointCloud2& cloud, const char* name)
{
  for (const auto& f : cloud.fields)
  {
    if (f.name == name)
    {
      return &f;
    }
  }
  return nullptr;
}
// The PCD file into `cloud`, PCL's own diagnostics silenced; what is wrong
// with it, or empty when it was read whole.
std::string ReadCloud(const std::string& fileName, pcl::PCLPointCloud2& cloud)
{
  // PCL prints its own diagnostics; ours are the ones to act on.
  struct QuietPCL
  {
    pcl::console::VERBOSITY_LEVEL Saved = pcl::console::getVerbosityLevel();
    QuietPCL() { pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS); }
    ~QuietPCL() { pcl::console::setVerbosityLevel(this->Saved); }
  } quiet;
  int status = -1;
  try
  {
    const std::string problem = CheckDataSize(fileName);
    if (!problem.empty())
    {
      return "the file is corrupt or truncated: " + problem + ".";
    }
    pcl::PCDReader reader;
    status = reader.read(fileName, cloud);
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  const size_t n = static_cast<size_t>(cloud.width) * cloud.height;
  if (status < 0 || cloud.point_step == 0 || n > cloud.data.size() / cloud.point_step)
  {
    return "the file is corrupt or truncated (PCL status " + std::to_string(status) + ").";
  }
  return std::string();
}

// Why a field does not fit a point's record (found by FuzzPCDReader: a
// damaged SIZE line put the colour's 4 bytes past the last point); empty
// when every field fits.
std::string FieldProblem(const pcl::PCLPointCloud2& cloud)
{
  for (const auto& f : cloud.fields)
  {
    const size_t bytes = static_cast<size_t>(TypeSize(f.datatype)) * f.count;
    if (static_cast<size_t>(f.offset) + std::max<size_t>(bytes, 1) > cloud.point_step ||
      ((f.name == "rgb" || f.name == "rgba") && bytes < 4))
    {
      std::ostringstream text;
      text << "the field '" << f.name << "' (offset " << f.offset << ", " << bytes
           << " bytes) does not fit a point's " << cloud.point_step
           << " bytes: the header is corrupt.";
      return text.str();
    }
  }
  return std::string();
}

// The indices of the points with finite coordinates.
std::vector<size_t> FinitePoints(const pcl::PCLPointCloud2& cloud,
  const pcl::PCLPointField* fx,
  const pcl::PCLPointField* fy,
  const pcl::PCLPointField* fz)
{
  std::vector<size_t> keep;
  const size_t n = static_cast<size_t>(cloud.width) * cloud.height;
  keep.reserve(n);
  for (size_t i = 0; i < n; ++i)
  {
    const std::uint8_t* p = cloud.data.data() + i * cloud.point_step;
    const double x = ReadScalar(p + fx->offset, fx->datatype);
    const double y = ReadScalar(p + fy->offset, fy->datatype);
    const double z = ReadScalar(p + fz->offset, fz->datatype);
    if (std::isfinite(x) && std::isfinite(y) && std::isfinite(z))
    {
      keep.push_back(i);
    }
  }
  return keep;
}

// The kept points (in double when any coordinate is); the caller adds their vertices.
void SetKeptPoints(const pcl::PCLPointCloud2& cloud,
  const pcl::PCLPointField* fx,
  const pcl::PCLPointField* fy,
  const pcl::PCLPointField* fz,
  const std::vector<size_t>& keep,
  vtkPolyData* output)
{
  const vtkIdType m = static_cast<vtkIdType>(keep.size());
  const bool useDouble = fx->datatype == pcl::PCLPointField::FLOAT64 ||
    fy->datatype == pcl::PCLPointField::FLOAT64 || fz->datatype == pcl::PCLPointField::FLOAT64;
  vtkNew<vtkPoints> points;
  points->SetDataType(useDouble ? VTK_DOUBLE : VTK_FLOAT);
  points->SetNumberOfPoints(m);
  for (vtkIdType j = 0; j < m; ++j)
  {
    const std::uint8_t* p = cloud.data.data() + keep[j] * cloud.point_step;
    points->SetPoint(j,
      ReadScalar(p + fx->offset, fx->datatype),
      ReadScalar(p + fy->offset, fy->datatype),
      ReadScalar(p + fz->offset, fz->datatype));
  }
  output->SetPoints(points);
}

// The normal_x, _y and _z fields, when all three are there, as the normals.
bool AddNormals(const pcl::PCLPointCloud2& cloud,
  const std::vector<size_t>& keep,
  vtkPolyData* output)
{
  const vtkIdType m = static_cast<vtkIdType>(keep.size());
  // Normals: the three normal_* fields together.
  const pcl::PCLPointField* fn[3] = {
    Find(cloud, "normal_x"), Find(cloud, "normal_y"), Find(cloud, "normal_z")
  };
  if (!(fn[0] && fn[1] && fn[2]))
  {
    return false;
  }
  {
    auto normals = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTK_FLOAT));
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(m);
    for (vtkIdType j = 0; j < m; ++j)
    {
      const std::uint8_t* p = cloud.data.data() + keep[j] * cloud.point_step;
      for (int c = 0; c < 3; ++c)
      {
        normals->SetComponent(j, c, ReadScalar(p + fn[c]->offset, fn[c]->datatype));
      }
    }
    output->GetPointData()->SetNormals(normals);
  }

  return true;
}

// The other fields as point arrays: packed rgb(a) as colours, the rest as
// they are typed (a field of unknown type skipped, with a warning).
void AddFields(const pcl::PCLPointCloud2& cloud,
  const std::vector<size_t>& keep,
  bool hasNormals,
  vtkPolyData* output,
  std::vector<std::string>& warnings)
{
  const vtkIdType m = static_cast<vtkIdType>(keep.size());
  for (const auto& f : cloud.fields)
  {
    if (f.name == "x" || f.name == "y" || f.name == "z" || f.name == "_" ||
      (hasNormals && f.name.rfind("normal_", 0) == 0))
    {
      continue;
    }
    if (f.name == "rgb" || f.name == "rgba")
    {
      // Packed 0xAARRGGBB in 4 bytes, whatever the declared type.
      const bool alpha = f.name == "rgba";
      vtkNew<vtkUnsignedCharArray> colors;
      colors->SetName(alpha ? "RGBA" : "RGB");
      colors->SetNumberOfComponents(alpha ? 4 : 3);
      colors->SetNumberOfTuples(m);
      for (vtkIdType j = 0; j < m; ++j)
      {
        std::uint32_t packed;
        std::memcpy(&packed, cloud.data.data() + keep[j] * cloud.point_step + f.offset, 4);
        const unsigned char rgba[4] = { static_cast<unsigned char>((packed >> 16) & 0xff),
          static_cast<unsigned char>((packed >> 8) & 0xff),
          static_cast<unsigned char>(packed & 0xff),
          static_cast<unsigned char>((packed >> 24) & 0xff) };
        colors->SetTypedTuple(j, rgba);
      }
      output->GetPointData()->SetScalars(colors);
      continue;
    }
    const int type = VTKType(f.datatype);
    if (type == VTK_VOID || f.count == 0)
    {
      warnings.push_back("Skipping field '" + f.name + "' of unknown type.");
      continue;
    }
    auto array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(type));
    array->SetName(f.name.c_str());
    array->SetNumberOfComponents(static_cast<int>(f.count));
    array->SetNumberOfTuples(m);
    const int size = TypeSize(f.datatype);
    auto* dst = static_cast<std::uint8_t*>(array->GetVoidPointer(0));
    for (vtkIdType j = 0; j < m; ++j)
    {
      std::memcpy(dst + static_cast<size_t>(j) * f.count * size,
        cloud.data.data() + keep[j] * cloud.point_step + f.offset,
        f.count * size);
    }
    output->GetPointData()->AddArray(array);
  }
}

// Reads `fileName` into points, vertices and arrays. Reports only through
// the outcome (no VTK messages): it may run in a child process. Counts[0]:
// the points dropped for NaN or infinite coordinates.
pointsurfaces::ReadOutcome ReadFile(const std::string& fileName)
{
  pointsurfaces::ReadOutcome result;
  result.Counts = { 0 };
  pcl::PCLPointCloud2 cloud;
  std::string problem = ReadCloud(fileName, cloud);
  if (problem.empty())
  {
    problem = FieldProblem(cloud);
  }
  if (!problem.empty())
  {
    result.Error = "Cannot read '" + fileName + "': " + problem;
    return result;
  }
  const pcl::PCLPointField* fx = Find(cloud, "x");
  const pcl::PCLPointField* fy = Find(cloud, "y");
  const pcl::PCLPointField* fz = Find(cloud, "z");
  if (!fx || !fy || !fz ||
    VTKType(fx->datatype) != VTK_FLOAT && VTKType(fx->datatype) != VTK_DOUBLE)
  {
    result.Error = "'" + fileName + "' has no floating-point x, y and z fields.";
    return result;
  }

  // Keep the points with finite coordinates.
  const std::vector<size_t> keep = FinitePoints(cloud, fx, fy, fz);
  const size_t n = static_cast<size_t>(cloud.width) * cloud.height;
  result.Counts[0] = static_cast<long long>(n - keep.size());
  if (result.Counts[0] > 0)
  {
    result.Warnings.push_back("Dropped " + std::to_string(result.Counts[0]) + " of " +
      std::to_string(n) + " points of '" + fileName + "' with NaN or infinite coordinates.");
  }
  result.Output = vtkSmartPointer<vtkPolyData>::New();
  SetKeptPoints(cloud, fx, fy, fz, keep, result.Output);
  const bool hasNormals = AddNormals(cloud, keep, result.Output);
  AddFields(cloud, keep, hasNormals, result.Output, result.Warnings);
  return result;
}
} // namespace

//------------------------------------------------------------------------------
vtkPCDReader::vtkPCDReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
bool vtkPCDReader::CanReadFile(const char* fileName)
{
  std::ifstream in(fileName ? fileName : "");
  std::string line;
  return in && std::getline(in, line) &&
    (line.rfind("# .PCD", 0) == 0 || line.rfind("VERSION", 0) == 0);
}

//------------------------------------------------------------------------------
int vtkPCDReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  vtkPolyData* output = vtkPolyData::GetData(out);
  this->NumberOfDroppedPoints = 0;
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No FileName to read.");
    return 1;
  }
  if (vtksys::SystemTools::FileExists(this->FileName, true) &&
    vtksys::SystemTools::FileLength(this->FileName) == 0)
  {
    vtkErrorMacro(<< "'" << this->FileName << "' is empty.");
    return 1;
  }
  if (!CanReadFile(this->FileName.c_str()))
  {
    vtkErrorMacro(<< "'" << this->FileName << "' is missing or is not a PCD file.");
    return 1;
  }

  // In a child process by default: see the class comment.
  const pointsurfaces::ReadOutcome outcome = pointsurfaces::GuardedRead(
    [&]() { return ReadFile(this->FileName); }, this->ReadInChildProcess, this->FileName, "PCL");
  for (const std::string& warning : outcome.Warnings)
  {
    vtkWarningMacro(<< warning);
  }
  if (!outcome.Output)
  {
    vtkErrorMacro(<< outcome.Error);
    return 1;
  }
  this->NumberOfDroppedPoints = outcome.Counts.empty() ? 0 : outcome.Counts[0];
  output->ShallowCopy(outcome.Output);
  vtkSplatDataModel::AddVertexCells(output); // cells do not come back from a child process
  return 1;
}

//------------------------------------------------------------------------------
void vtkPCDReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "ReadInChildProcess: " << (this->ReadInChildProcess ? "on" : "off") << "\n";
  os << indent << "NumberOfDroppedPoints: " << this->NumberOfDroppedPoints << "\n";
}
