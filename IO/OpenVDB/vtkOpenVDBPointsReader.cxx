// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkOpenVDBPointsReader.h"

#include "psReadOutcome.h"
#include "vtkSplatDataModel.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkType.h"
#include "vtksys/SystemTools.hxx"

#include <oneapi/tbb/task_arena.h>
#include <openvdb/io/Archive.h>
#include <openvdb/io/GridDescriptor.h>
#include <openvdb/io/io.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/AttributeArrayString.h>
#include <openvdb/points/AttributeGroup.h>
#include <openvdb/points/PointDataGrid.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <istream>
#include <map>
#include <set>
#include <streambuf>

vtkStandardNewMacro(vtkOpenVDBPointsReader);

namespace
{
namespace ovp = openvdb::points;
using openvdb::Index;
using pointsurfaces::ReadOutcome;

// Components of one attribute value, and its c-th component as a double.
template<typename T>
struct Components
{
  static constexpr int N = 1;
  static double Get(const T& v, int) { return static_cast<double>(v); }
};
template<typename T>
struct Components<openvdb::math::Vec3<T>>
{
  static constexpr int N = 3;
  static double Get(const openvdb::math::Vec3<T>& v, int c) { return static_cast<double>(v[c]); }
};
template<typename T>
struct Components<openvdb::math::Mat3<T>>
{
  static constexpr int N = 9;
  static double Get(const openvdb::math::Mat3<T>& v, int c) { return v.asPointer()[c]; }
};
template<typename T>
struct Components<openvdb::math::Mat4<T>>
{
  static constexpr int N = 16;
  static double Get(const openvdb::math::Mat4<T>& v, int c) { return v.asPointer()[c]; }
};
template<typename T>
struct Components<openvdb::math::Quat<T>>
{
  static constexpr int N = 4;
  static double Get(const openvdb::math::Quat<T>& v, int c) { return v[c]; }
};

// One output array, created at the first grid that has the attribute.
struct Output
{
  vtkSmartPointer<vtkAbstractArray> Array;
  std::string Type; // the VDB value type (or "string", "group")
};

// The VDB value types this reader converts: the VTK data type of their
// array and their components per point (before an array attribute's stride).
struct ValueType
{
  const char* Name;
  int VTKType;
  int Components;
};
constexpr ValueType ValueTypes[] = { { "bool", VTK_UNSIGNED_CHAR, 1 },
  { "group", VTK_UNSIGNED_CHAR, 1 },
  { "int8", VTK_SIGNED_CHAR, 1 },
  { "int16", VTK_SHORT, 1 },
  { "int32", VTK_INT, 1 },
  { "int64", VTK_TYPE_INT64, 1 },
  { "half", VTK_FLOAT, 1 },
  { "float", VTK_FLOAT, 1 },
  { "double", VTK_DOUBLE, 1 },
  { "vec3i", VTK_INT, 3 },
  { "vec3s", VTK_FLOAT, 3 },
  { "vec3d", VTK_DOUBLE, 3 },
  { "quats", VTK_FLOAT, 4 },
  { "quatd", VTK_DOUBLE, 4 },
  { "mat3s", VTK_FLOAT, 9 },
  { "mat3d", VTK_DOUBLE, 9 },
  { "mat4s", VTK_FLOAT, 16 },
  { "mat4d", VTK_DOUBLE, 16 } };

// The entry for a VDB value type, or null for a type this reader does not convert.
const ValueType* FindValueType(const std::string& name)
{
  for (const ValueType& type : ValueTypes)
  {
    if (name == type.Name)
    {
      return &type;
    }
  }
  return nullptr;
}

// Copies attribute values of the points `indices` into rows first.. of out.
template<typename T>
void CopyValues(const ovp::AttributeArray& array,
  const std::vector<Index>& indices,
  vtkDataArray* out,
  vtkIdType first)
{
  ovp::AttributeHandle<T> handle(array);
  const int n = Components<T>::N;
  const Index stride = handle.stride();
  for (size_t i = 0; i < indices.size(); ++i)
  {
    for (Index m = 0; m < stride; ++m)
    {
      const T value = handle.get(indices[i], m);
      for (int c = 0; c < n; ++c)
      {
        out->SetComponent(first + static_cast<vtkIdType>(i),
          static_cast<int>(m) * n + c,
          Components<T>::Get(value, c));
      }
    }
  }
}

bool CopyTyped(const std::string& type,
  const ovp::AttributeArray& array,
  const std::vector<Index>& indices,
  vtkDataArray* out,
  vtkIdType first)
{
  using namespace openvdb::math;
  if (type == "bool")
  {
    CopyValues<bool>(array, indices, out, first);
  }
  else if (type == "int8")
  {
    CopyValues<int8_t>(array, indices, out, first);
  }
  else if (type == "int16")
  {
    CopyValues<int16_t>(array, indices, out, first);
  }
  else if (type == "int32")
  {
    CopyValues<int32_t>(array, indices, out, first);
  }
  else if (type == "int64")
  {
    CopyValues<int64_t>(array, indices, out, first);
  }
  else if (type == "float")
  {
    CopyValues<float>(array, indices, out, first);
  }
  else if (type == "half")
  {
    CopyValues<openvdb::math::half>(array, indices, out, first);
  }
  else if (type == "double")
  {
    CopyValues<double>(array, indices, out, first);
  }
  else if (type == "vec3i")
  {
    CopyValues<Vec3<int32_t>>(array, indices, out, first);
  }
  else if (type == "vec3s")
  {
    CopyValues<Vec3<float>>(array, indices, out, first);
  }
  else if (type == "vec3d")
  {
    CopyValues<Vec3<double>>(array, indices, out, first);
  }
  else if (type == "mat3s")
  {
    CopyValues<Mat3<float>>(array, indices, out, first);
  }
  else if (type == "mat3d")
  {
    CopyValues<Mat3<double>>(array, indices, out, first);
  }
  else if (type == "mat4s")
  {
    CopyValues<Mat4<float>>(array, indices, out, first);
  }
  else if (type == "mat4d")
  {
    CopyValues<Mat4<double>>(array, indices, out, first);
  }
  else if (type == "quats")
  {
    CopyValues<Quat<float>>(array, indices, out, first);
  }
  else if (type == "quatd")
  {
    CopyValues<Quat<double>>(array, indices, out, first);
  }
  else
  {
    return false;
  }
  return true;
}

// The file's bytes as a stream that refuses, before copying anything, a read
// reaching past the end. OpenVDB 10.0.1 sizes some reads from counts in the
// file and checks them only after reading (see Testing/Fuzz/README.md); a
// damaged count beyond the end of the file then throws here instead of
// writing past OpenVDB's buffer; a negative count is refused too. Counts
// that still fit the file are beyond the reader's reach.
class BoundedBuffer : public std::streambuf
{
public:
  explicit BoundedBuffer(std::vector<char>& bytes)
  {
    this->setg(bytes.data(), bytes.data(), bytes.data() + bytes.size());
  }

protected:
  std::streamsize xsgetn(char* s, std::streamsize n) override
  {
    // A negative count (a damaged size that std::istream::read passes on
    // as it is) would turn into a huge copy.
    if (n < 0 || n > this->egptr() - this->gptr())
    {
      throw std::ios_base::failure(
        "a read of " + std::to_string(n) + " bytes reaches past the end of the file");
    }
    std::memcpy(s, this->gptr(), static_cast<size_t>(n));
    this->setg(this->eback(), this->gptr() + n, this->egptr());
    return n;
  }
  int_type underflow() override { return traits_type::eof(); }
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override
  {
    char* base = dir == std::ios_base::beg ? this->eback()
      : dir == std::ios_base::cur          ? this->gptr()
                                           : this->egptr();
    return this->Seek(base + off);
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode) override
  {
    return this->Seek(this->eback() + static_cast<off_type>(pos));
  }

private:
  pos_type Seek(char* at)
  {
    if (at < this->eback() || at > this->egptr())
    {
      return pos_type(off_type(-1));
    }
    this->setg(this->eback(), at, this->egptr());
    return pos_type(at - this->eback());
  }
};

// A point data tree that checks the start of its topology before OpenVDB
// reads it: Debian's OpenVDB 10.0.1 is built with assertions, and a point
// data leaf created with a nonzero background value (the root's, read from
// the file) aborts the program ("Cannot modify voxel values in a
// PointDataTree"; found by FuzzOpenVDBPointsReader). The topology starts
// with the buffer count (TreeBase) and the root's background value.
class CheckedPointDataTree : public ovp::PointDataTree
{
public:
  void readTopology(std::istream& is, bool saveFloatAsHalf) override
  {
    if (openvdb::io::getFormatVersion(is) < openvdb::OPENVDB_FILE_VERSION_ROOTNODE_MAP)
    {
      OPENVDB_THROW(openvdb::IoError, "a point data grid in a file format older than points");
    }
    const std::streampos start = is.tellg();
    int32_t buffers = 0;
    ValueType background = openvdb::zeroVal<ValueType>();
    is.read(reinterpret_cast<char*>(&buffers), sizeof(buffers));
    is.read(reinterpret_cast<char*>(&background), sizeof(background));
    if (background != openvdb::zeroVal<ValueType>())
    {
      OPENVDB_THROW(openvdb::IoError, "a point data grid whose background value is not zero");
    }
    is.seekg(start);
    ovp::PointDataTree::readTopology(is, saveFloatAsHalf);
  }
};

// Reads every grid of a .vdb stream as io::Stream(is, false) does (the same
// OpenVDB calls, in the same order), but builds each point data grid on a
// CheckedPointDataTree.
class CheckedArchive : public openvdb::io::Archive
{
public:
  openvdb::GridPtrVec Read(std::istream& is)
  {
    this->readHeader(is);
    openvdb::io::StreamMetadata::Ptr streamMetadata(new openvdb::io::StreamMetadata);
    openvdb::io::setStreamMetadataPtr(is, streamMetadata, /*transfer=*/false);
    openvdb::io::setVersion(is, this->libraryVersion(), this->fileVersion());
    openvdb::io::setDataCompression(is, this->compression());
    openvdb::MetaMap fileMetadata;
    fileMetadata.readMeta(is);
    const int32_t count = readGridCount(is);
    openvdb::GridPtrVec grids;
    std::vector<openvdb::io::GridDescriptor> descriptors;
    NamedGridMap named;
    for (int32_t i = 0; i < count; ++i)
    {
      openvdb::io::GridDescriptor gd;
      openvdb::GridBase::Ptr grid = gd.read(is);
      if (gd.gridType() == ovp::PointDataGrid::gridType())
      {
        grid = ovp::PointDataGrid::create(std::make_shared<CheckedPointDataTree>());
      }
      if (!grid)
      {
        OPENVDB_THROW(openvdb::TypeError, "grid type " << gd.gridType() << " is unknown");
      }
      grid->setSaveFloatAsHalf(gd.saveFloatAsHalf());
      readGrid(grid, gd, is);
      descriptors.push_back(gd);
      grids.push_back(grid);
      named[gd.uniqueName()] = grid;
    }
    for (const openvdb::io::GridDescriptor& gd : descriptors)
    {
      this->connectInstance(gd, named);
    }
    return grids;
  }
};

// A leaf whose offsets or arrays disagree would be read out of bounds.
bool LeafConsistent(const ovp::PointDataTree::LeafNodeType& leaf, std::string& why)
{
  Index previous = 0;
  for (Index i = 0; i < ovp::PointDataTree::LeafNodeType::SIZE; ++i)
  {
    const Index offset = leaf.getValue(i);
    if (offset < previous)
    {
      why = "a leaf's point offsets decrease";
      return false;
    }
    previous = offset;
  }
  const ovp::AttributeSet& set = leaf.attributeSet();
  for (size_t a = 0; a < set.size(); ++a)
  {
    const ovp::AttributeArray* array = set.getConst(a);
    if (!array)
    {
      why = "a leaf lacks an attribute array";
      return false;
    }
    if (!array->isUniform() && array->hasConstantStride() && array->size() < previous)
    {
      why = "a leaf's attribute array holds " + std::to_string(array->size()) + " values for " +
        std::to_string(previous) + " points";
      return false;
    }
  }
  return true;
}
// Reads the point grids of `fileName` (those named `gridName`, or all when it
// is empty), whole. OpenVDB's io::File reads from a stream that does not
// report a short read, and loops for a long time over counts that a damaged
// file announces (found by FuzzOpenVDBPointsReader); here the stream throws
// at the first read past the end or failure instead.
std::vector<ovp::PointDataGrid::Ptr> ReadPointGrids(const std::string& fileName,
  const std::string& gridName,
  std::vector<std::string>& names)
{
  std::vector<char> bytes;
  {
    std::ifstream file(fileName, std::ios::binary | std::ios::ate);
    bytes.resize(static_cast<size_t>(file.tellg()));
    file.seekg(0);
    file.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  BoundedBuffer buffer(bytes);
  std::istream in(&buffer);
  in.exceptions(std::ios::failbit | std::ios::badbit | std::ios::eofbit);
  CheckedArchive archive;
  std::vector<ovp::PointDataGrid::Ptr> grids;
  for (const openvdb::GridBase::Ptr& base : archive.Read(in))
  {
    ovp::PointDataGrid::Ptr grid = openvdb::gridPtrCast<ovp::PointDataGrid>(base);
    if (grid && (gridName.empty() || grid->getName() == gridName))
    {
      grids.push_back(grid);
      names.push_back(grid->getName());
    }
  }
  return grids;
}

// The first output point of each grid (active points only), and the total
// as the last entry; false with `error` when a leaf is inconsistent.
bool FirstPointOfGrids(const std::vector<ovp::PointDataGrid::Ptr>& grids,
  const std::vector<std::string>& names,
  std::vector<vtkIdType>& first,
  std::string& error)
{
  first.assign(grids.size() + 1, 0);
  for (size_t g = 0; g < grids.size(); ++g)
  {
    vtkIdType count = 0;
    for (auto leaf = grids[g]->tree().cbeginLeaf(); leaf; ++leaf)
    {
      std::string why;
      if (!LeafConsistent(*leaf, why))
      {
        error = "grid \"" + names[g] + "\" is corrupt: " + why;
        return false;
      }
      count += static_cast<vtkIdType>(leaf->onPointCount());
    }
    first[g + 1] = first[g] + count;
  }
  return true;
}

// The output arrays by attribute name, each made (zero-filled, `total`
// tuples) when first seen; an attribute whose kind differs between grids
// keeps the first grid's, with one warning.
class OutputArrays
{
public:
  OutputArrays(vtkIdType total, std::function<void(const std::string&)> warnOnce)
    : Total(total)
    , WarnOnce(std::move(warnOnce))
  {
  }

  vtkAbstractArray* For(const std::string& name, const std::string& type, int components)
  {
    auto it = this->Arrays.find(name);
    if (it == this->Arrays.end())
    {
      it = this->Arrays.emplace(name, this->Make(name, type, components)).first;
    }
    const bool stringOut = it->second.Type == "string";
    if (stringOut != (type == "string") ||
      (!stringOut && it->second.Array->GetNumberOfComponents() != components))
    {
      this->WarnOnce("attribute \"" + name +
        "\" differs in type or size between grids: only the first grid's kind is read.");
      return nullptr;
    }
    return it->second.Array;
  }

  const std::map<std::string, Output>& All() const { return this->Arrays; }

private:
  Output Make(const std::string& name, const std::string& type, int components) const
  {
    Output o;
    o.Type = type;
    if (type == "string")
    {
      auto strings = vtkSmartPointer<vtkStringArray>::New();
      strings->SetNumberOfValues(this->Total);
      o.Array = strings;
    }
    else
    {
      auto data = vtkSmartPointer<vtkDataArray>::Take(
        vtkDataArray::CreateDataArray(FindValueType(type)->VTKType));
      data->SetNumberOfComponents(components);
      data->SetNumberOfTuples(this->Total);
      data->Fill(0.0);
      o.Array = data;
    }
    o.Array->SetName(name.c_str());
    return o;
  }

  vtkIdType Total;
  std::function<void(const std::string&)> WarnOnce;
  std::map<std::string, Output> Arrays;
};

// Copies the attributes (but P) and the groups of `leaf`'s points `indices`
// into `outputs`, from output point `next` on.
void CopyLeafAttributes(const ovp::PointDataTree::LeafNodeType& leaf,
  size_t positionIndex,
  const std::vector<Index>& indices,
  vtkIdType next,
  OutputArrays& outputs,
  const std::function<void(const std::string&)>& warnOnce)
{
  const ovp::AttributeSet::Descriptor& descriptor = leaf.attributeSet().descriptor();
  for (const auto& entry : descriptor.map())
  {
    if (entry.second == positionIndex)
    {
      continue;
    }
    const ovp::AttributeArray& array = leaf.constAttributeArray(entry.second);
    if (ovp::isGroup(array))
    {
      continue; // groups are read by name below
    }
    if (!array.hasConstantStride())
    {
      warnOnce("attribute \"" + entry.first + "\" has a variable length per point: skipped.");
      continue;
    }
    if (ovp::isString(array))
    {
      auto* out = vtkStringArray::SafeDownCast(outputs.For(entry.first, "string", 1));
      if (out)
      {
        ovp::StringAttributeHandle handle(array, descriptor.getMetadata());
        for (size_t i = 0; i < indices.size(); ++i)
        {
          out->SetValue(next + static_cast<vtkIdType>(i), handle.get(indices[i]));
        }
      }
      continue;
    }
    const std::string type = array.type().first;
    const ValueType* known = FindValueType(type);
    if (!known)
    {
      warnOnce("attribute \"" + entry.first + "\" has the type " + type +
        ", which this reader does not convert: skipped.");
      continue;
    }
    auto* out = vtkDataArray::SafeDownCast(
      outputs.For(entry.first, type, known->Components * static_cast<int>(array.stride())));
    if (out)
    {
      CopyTyped(type, array, indices, out, next);
    }
  }
  // Groups, as 0/1 arrays.
  for (const auto& group : descriptor.groupMap())
  {
    auto* out = vtkDataArray::SafeDownCast(outputs.For("group:" + group.first, "group", 1));
    if (out)
    {
      const ovp::GroupHandle handle = leaf.groupHandle(group.first);
      for (size_t i = 0; i < indices.size(); ++i)
      {
        out->SetComponent(next + static_cast<vtkIdType>(i), 0, handle.get(indices[i]));
      }
    }
  }
}

// Reads every point of `grids` into `points` (world positions),
// `gridIndex` and `outputs`; false with `error` for a grid without P.
bool CopyGrids(const std::vector<ovp::PointDataGrid::Ptr>& grids,
  const std::vector<std::string>& names,
  const std::vector<vtkIdType>& firstOfGrid,
  vtkPoints* points,
  vtkIntArray* gridIndex,
  OutputArrays& outputs,
  const std::function<void(const std::string&)>& warnOnce,
  std::string& error)
{
  std::vector<Index> indices;
  for (size_t g = 0; g < grids.size(); ++g)
  {
    const openvdb::math::Transform& xform = grids[g]->transform();
    vtkIdType next = firstOfGrid[g];
    for (auto leaf = grids[g]->tree().cbeginLeaf(); leaf; ++leaf)
    {
      const size_t positionIndex = leaf->attributeSet().descriptor().find("P");
      if (positionIndex == ovp::AttributeSet::INVALID_POS)
      {
        error = "grid \"" + names[g] + "\" has no position attribute P";
        return false;
      }
      // Positions: voxel centre plus the decoded offset, to world space.
      indices.clear();
      ovp::AttributeHandle<openvdb::Vec3f> position(leaf->constAttributeArray(positionIndex));
      for (auto index = leaf->beginIndexOn(); index; ++index)
      {
        const openvdb::Vec3d xyz =
          index.getCoord().asVec3d() + openvdb::Vec3d(position.get(*index));
        const openvdb::Vec3d world = xform.indexToWorld(xyz);
        points->SetPoint(
          next + static_cast<vtkIdType>(indices.size()), world[0], world[1], world[2]);
        gridIndex->SetValue(next + static_cast<vtkIdType>(indices.size()), static_cast<int>(g));
        indices.push_back(*index);
      }
      CopyLeafAttributes(*leaf, positionIndex, indices, next, outputs, warnOnce);
      next += static_cast<vtkIdType>(indices.size());
    }
  }
  return true;
}

// Reads the point grids of `fileName` into points and arrays. Reports only
// through the outcome (no VTK messages): it may run in a child process.
ReadOutcome ReadFile(const std::string& fileName, const std::string& gridName)
{
  ReadOutcome result;
  std::vector<std::string> names;
  std::vector<ovp::PointDataGrid::Ptr> grids;
  try
  {
    grids = ReadPointGrids(fileName, gridName, names);
  }
  catch (const std::exception& e)
  {
    result.Error = "Cannot read \"" + fileName + "\": " + e.what() +
      (dynamic_cast<const std::ios::failure*>(&e) ? " (the file ends early or is damaged)" : "");
    return result;
  }
  if (grids.empty())
  {
    result.Error = "\"" + fileName + "\" holds no point data grid" +
      (gridName.empty() ? std::string(".") : " named \"" + gridName + "\".");
    return result;
  }

  // Count the points (active voxels only) and check every leaf first.
  std::vector<vtkIdType> firstOfGrid;
  std::string error;
  if (!FirstPointOfGrids(grids, names, firstOfGrid, error))
  {
    result.Error = "\"" + fileName + "\", " + error + ".";
    return result;
  }
  const vtkIdType total = firstOfGrid.back();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(total);
  vtkNew<vtkIntArray> gridIndex;
  gridIndex->SetName("VDBGridIndex");
  gridIndex->SetNumberOfTuples(total);
  std::set<std::string> warned;
  auto warnOnce = [&](const std::string& text)
  {
    if (warned.insert(text).second)
    {
      result.Warnings.push_back(text);
    }
  };
  OutputArrays outputs(total, warnOnce);
  try
  {
    if (!CopyGrids(grids, names, firstOfGrid, points, gridIndex, outputs, warnOnce, error))
    {
      result.Error = "\"" + fileName + "\", " + error + ".";
      return result;
    }
  }
  catch (const std::exception& e)
  {
    result.Error = "Cannot read the points of \"" + fileName + "\": " + e.what();
    return result;
  }

  result.Output = vtkSmartPointer<vtkPolyData>::New();
  result.Output->SetPoints(points);
  result.Output->GetPointData()->AddArray(gridIndex);
  for (const auto& entry : outputs.All())
  {
    result.Output->GetPointData()->AddArray(entry.second.Array);
  }
  vtkNew<vtkStringArray> gridNames;
  gridNames->SetName("VDBGridNames");
  for (const std::string& name : names)
  {
    gridNames->InsertNextValue(name);
  }
  result.Output->GetFieldData()->AddArray(gridNames);
  return result;
}

} // namespace

//------------------------------------------------------------------------------
vtkOpenVDBPointsReader::vtkOpenVDBPointsReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
const char* vtkOpenVDBPointsReader::GetPointGridName(int i) const
{
  return i >= 0 && i < this->GetNumberOfPointGrids() ? this->PointGridNames[i].c_str() : nullptr;
}

//------------------------------------------------------------------------------
bool vtkOpenVDBPointsReader::CanReadFile(const char* fileName)
{
  if (!fileName)
  {
    return false;
  }
  std::ifstream in(fileName, std::ios::binary);
  unsigned char magic[4] = { 0, 0, 0, 0 };
  in.read(reinterpret_cast<char*>(magic), 4);
  // OPENVDB_MAGIC, 0x56444220 ("VDB "), little-endian.
  return in && magic[0] == 0x20 && magic[1] == 0x42 && magic[2] == 0x44 && magic[3] == 0x56;
}

//------------------------------------------------------------------------------
int vtkOpenVDBPointsReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->PointGridNames.clear();
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No FileName set.");
    return 1;
  }
  if (vtksys::SystemTools::FileExists(this->FileName, true) &&
    vtksys::SystemTools::FileLength(this->FileName) == 0)
  {
    vtkErrorMacro(<< "\"" << this->FileName << "\" is empty.");
    return 1;
  }
  if (!vtkOpenVDBPointsReader::CanReadFile(this->FileName.c_str()))
  {
    vtkErrorMacro(<< "\"" << this->FileName
                  << "\" is missing or is not an OpenVDB file (no VDB magic number).");
    return 1;
  }
  openvdb::initialize();

  // In a child process by default: see the class comment. TBB's worker
  // threads are not copied into a forked child, and what they held at the
  // fork stays held there: OpenVDB's parallel loops in the child (Tree::clear,
  // for one) then waited forever now and then (OpenVDB 13). In the child the
  // read runs in an arena of one thread, whose loops never wait for workers.
  const bool inChild = this->ReadInChildProcess;
  const ReadOutcome outcome = pointsurfaces::GuardedRead(
    [&]()
    {
      if (!inChild)
      {
        return ReadFile(this->FileName, this->GridName);
      }
      ReadOutcome read;
      oneapi::tbb::task_arena alone(1, 1);
      alone.execute([&]() { read = ReadFile(this->FileName, this->GridName); });
      return read;
    },
    inChild,
    this->FileName,
    "OpenVDB");
  for (const std::string& warning : outcome.Warnings)
  {
    vtkWarningMacro(<< "\"" << this->FileName << "\": " << warning);
  }
  if (!outcome.Output)
  {
    vtkErrorMacro(<< outcome.Error);
    return 1;
  }
  output->ShallowCopy(outcome.Output);
  vtkSplatDataModel::AddVertexCells(output); // cells do not come back from a child process
  if (auto* names =
        vtkStringArray::SafeDownCast(output->GetFieldData()->GetAbstractArray("VDBGridNames")))
  {
    for (vtkIdType i = 0; i < names->GetNumberOfValues(); ++i)
    {
      this->PointGridNames.push_back(names->GetValue(i));
    }
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkOpenVDBPointsReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "GridName: " << (this->GridName.empty() ? "(all)" : this->GridName) << "\n";
  os << indent << "ReadInChildProcess: " << (this->ReadInChildProcess ? "on" : "off") << "\n";
  os << indent << "PointGrids: " << this->PointGridNames.size() << "\n";
}
