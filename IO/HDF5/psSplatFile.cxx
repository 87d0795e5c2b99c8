// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psSplatFile.h"

#include "psChildProcess.h" // For Supported
#include "psHDF5.h"
#include "psLocalFit.h" // For MonomialCount
#include "psOctree.h"

#include "vtkType.h" // For the attribute types

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>

namespace pointsurfaces
{
namespace
{
constexpr int Version = 1;
constexpr hsize_t ChunkRows = 65536;

// The splat columns: name, components (0: the coefficients'), and whether
// stored as float64 / int32 rather than float32.
enum class Kind
{
  Float,
  Double,
  Int
};
struct Column
{
  const char* Name;
  int Components;
  Kind Type;
};
constexpr Column Columns[] = { { "Origin", 3, Kind::Double },
  { "Normal", 3, Kind::Float },
  { "Tangent", 3, Kind::Float },
  { "FeatureSize", 1, Kind::Float },
  { "Coefficients", 0, Kind::Float },
  { "Radius", 1, Kind::Float },
  { "MaxDeviation", 1, Kind::Float },
  { "NominalRadius", 1, Kind::Float },
  { "Tolerance", 1, Kind::Float },
  { "LOD", 1, Kind::Int } };
constexpr int ColumnCount = sizeof(Columns) / sizeof(Columns[0]);

// A column's components: its own, or the coefficients of a splat of `degree`.
int ComponentsOf(const Column& c, int degree)
{
  return c.Components ? c.Components : MonomialCount(degree);
}

// The memory of column k of `c`.
void* ColumnData(SplatColumns& c, int k)
{
  switch (k)
  {
    case 0:
      return c.Origin.data();
    case 1:
      return c.Normal.data();
    case 2:
      return c.Tangent.data();
    case 3:
      return c.FeatureSize.data();
    case 4:
      return c.Coefficients.data();
    case 5:
      return c.Radius.data();
    case 6:
      return c.MaxDeviation.data();
    case 7:
      return c.NominalRadius.data();
    case 8:
      return c.Tolerance.data();
    default:
      return c.LOD.data();
  }
}

hid_t MemoryType(Kind k)
{
  return k == Kind::Double ? H5T_NATIVE_DOUBLE
    : k == Kind::Int       ? H5T_NATIVE_INT32
                           : H5T_NATIVE_FLOAT;
}
hid_t FileType(Kind k)
{
  return k == Kind::Double ? H5T_IEEE_F64LE : k == Kind::Int ? H5T_STD_I32LE : H5T_IEEE_F32LE;
}

// How an attribute of VTK type `type` is stored: integers as the integer
// of their size and sign, everything else as float32.
struct StoredType
{
  int Bytes; // 0: float32
  bool Signed;
};
StoredType StoredTypeOf(int type)
{
  switch (type)
  {
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
      return { 1, true };
    case VTK_UNSIGNED_CHAR:
      return { 1, false };
    case VTK_SHORT:
      return { 2, true };
    case VTK_UNSIGNED_SHORT:
      return { 2, false };
    case VTK_INT:
      return { 4, true };
    case VTK_UNSIGNED_INT:
      return { 4, false };
    case VTK_LONG:
    case VTK_LONG_LONG:
    case VTK_ID_TYPE:
      return { 8, true };
    case VTK_UNSIGNED_LONG:
    case VTK_UNSIGNED_LONG_LONG:
      return { 8, false };
    default:
      return { 0, true };
  }
}
hid_t AttributeFileType(int type)
{
  const StoredType t = StoredTypeOf(type);
  switch (t.Bytes)
  {
    case 1:
      return t.Signed ? H5T_STD_I8LE : H5T_STD_U8LE;
    case 2:
      return t.Signed ? H5T_STD_I16LE : H5T_STD_U16LE;
    case 4:
      return t.Signed ? H5T_STD_I32LE : H5T_STD_U32LE;
    case 8:
      return t.Signed ? H5T_STD_I64LE : H5T_STD_U64LE;
    default:
      return H5T_IEEE_F32LE;
  }
}
// The VTK type a stored attribute dataset reads back as.
int AttributeTypeOf(hid_t dataset)
{
  Handle type(H5Dget_type(dataset), H5Tclose);
  if (type.Id < 0 || H5Tget_class(type.Id) != H5T_INTEGER)
  {
    return VTK_FLOAT;
  }
  const bool isSigned = H5Tget_sign(type.Id) != H5T_SGN_NONE;
  switch (H5Tget_size(type.Id))
  {
    case 1:
      return isSigned ? VTK_SIGNED_CHAR : VTK_UNSIGNED_CHAR;
    case 2:
      return isSigned ? VTK_SHORT : VTK_UNSIGNED_SHORT;
    case 4:
      return isSigned ? VTK_INT : VTK_UNSIGNED_INT;
    default:
      return isSigned ? VTK_LONG_LONG : VTK_UNSIGNED_LONG_LONG;
  }
}
// `values` rounded to the nearest integer of `type`'s stored size and sign,
// clamped to its range (NaN: 0); as they are for a float type.
const float* StoredValues(int type, const std::vector<float>& values, std::vector<float>& rounded)
{
  const StoredType t = StoredTypeOf(type);
  if (t.Bytes == 0)
  {
    return values.data();
  }
  const int bits = 8 * t.Bytes - (t.Signed ? 1 : 0); // of the magnitude
  const double lo = t.Signed ? -std::ldexp(1.0, bits) : 0.0;
  // The type's maximum, or where a float cannot hold it (32 bits and more)
  // the largest float below it.
  const double hi = bits <= 24 ? std::ldexp(1.0, bits) - 1.0
                               : std::nextafter(static_cast<float>(std::ldexp(1.0, bits)), 0.0f);
  rounded.resize(values.size());
  for (size_t k = 0; k < values.size(); ++k)
  {
    const double v = values[k];
    rounded[k] =
      std::isnan(v) ? 0.0f : static_cast<float>(std::round(std::min(hi, std::max(lo, v))));
  }
  return rounded.data();
}

// Whether column k has a Range (the origins, which are the points, have none).
bool Ranged(int k)
{
  return std::strcmp(Columns[k].Name, "Origin") != 0;
}

// Widens `range` (SplatRangeSize(comps) numbers; empty: none yet) by the finite
// values of `rows` rows of `comps` components, the first of them row `first`
// of the file; `where` keeps the row of each minimum and maximum (the first
// row that holds it).
template<typename T>
void GrowRange(std::vector<double>& range,
  std::vector<long long>& where,
  const T* values,
  long long first,
  long long rows,
  int comps)
{
  if (range.empty())
  {
    range.resize(SplatRangeSize(comps));
    where.assign(range.size(), -1);
    for (size_t s = 0; s < range.size(); s += 2)
    {
      range[s] = std::numeric_limits<double>::infinity();
      range[s + 1] = -std::numeric_limits<double>::infinity();
    }
  }
  auto grow = [&](size_t s, double v, long long row)
  {
    if (v < range[s])
    {
      range[s] = v;
      where[s] = row;
    }
    if (v > range[s + 1])
    {
      range[s + 1] = v;
      where[s + 1] = row;
    }
  };
  for (long long r = 0; r < rows; ++r)
  {
    double squares = 0.0;
    bool finite = true;
    for (int c = 0; c < comps; ++c)
    {
      const double v = static_cast<double>(values[r * comps + c]);
      if (!std::isfinite(v))
      {
        finite = false;
        continue;
      }
      grow(2 * static_cast<size_t>(c), v, first + r);
      squares += v * v;
    }
    if (comps > 1 && finite)
    {
      grow(2 * static_cast<size_t>(comps), std::sqrt(squares), first + r);
    }
  }
}

// Whether every [min, max] of `range` holds a finite value.
bool WholeRange(const std::vector<double>& range)
{
  for (size_t s = 0; s + 1 < range.size(); s += 2)
  {
    if (!(std::isfinite(range[s]) && std::isfinite(range[s + 1]) && range[s] <= range[s + 1]))
    {
      return false;
    }
  }
  return !range.empty();
}
} // namespace

int SplatFileInfo::AttributeType(size_t a) const
{
  return a < this->AttributeTypes.size() ? this->AttributeTypes[a] : VTK_FLOAT;
}

namespace
{
// A 2-D dataset of `rows` x `components` (1-D when components is 1), chunked by rows.
hid_t Create(hid_t group, const char* name, hid_t type, hsize_t rows, int components)
{
  const hsize_t dims[2] = { rows, static_cast<hsize_t>(components) };
  const int rank = components == 1 ? 1 : 2;
  Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose);
  Handle plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (rows > 0)
  {
    const hsize_t chunk[2] = { std::min(rows, ChunkRows), static_cast<hsize_t>(components) };
    H5Pset_chunk(plist.Id, rank, chunk);
  }
  return H5Dcreate2(group, name, type, space.Id, H5P_DEFAULT, plist.Id, H5P_DEFAULT);
}

// Rows [first, first + count) of a dataset of `components` columns.
bool Rows(hid_t dataset,
  hsize_t first,
  hsize_t count,
  int components,
  hid_t memType,
  void* data,
  bool write)
{
  if (count == 0)
  {
    return true;
  }
  Handle space(H5Dget_space(dataset), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.Id);
  const hsize_t start[2] = { first, 0 };
  const hsize_t size[2] = { count, static_cast<hsize_t>(components) };
  Handle memory(H5Screate_simple(rank, size, nullptr), H5Sclose);
  if (H5Sselect_hyperslab(space.Id, H5S_SELECT_SET, start, nullptr, size, nullptr) < 0)
  {
    return false;
  }
  return (write ? H5Dwrite(dataset, memType, memory.Id, space.Id, H5P_DEFAULT, data)
                : H5Dread(dataset, memType, memory.Id, space.Id, H5P_DEFAULT, data)) >= 0;
}

// The dimensions of dataset `name` in `group`: {rows, components}; {-1, -1} when absent.
void Shape(hid_t group, const char* name, long long& rows, int& components)
{
  rows = -1;
  components = -1;
  if (H5Lexists(group, name, H5P_DEFAULT) <= 0)
  {
    return;
  }
  Handle dataset(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose);
  if (dataset.Id < 0)
  {
    return;
  }
  Handle space(H5Dget_space(dataset.Id), H5Sclose);
  hsize_t dims[2] = { 0, 1 };
  const int rank = H5Sget_simple_extent_ndims(space.Id);
  if (rank < 1 || rank > 2 || H5Sget_simple_extent_dims(space.Id, dims, nullptr) < 0)
  {
    return;
  }
  if (!SaneDataset(dataset.Id)) // a damaged type or compact layout
  {
    return;
  }
  rows = static_cast<long long>(dims[0]);
  components = rank == 2 ? static_cast<int>(dims[1]) : 1;
}

bool WriteNumbers(hid_t location, const char* name, const double* values, hsize_t n)
{
  Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  Handle attribute(
    H5Acreate2(location, name, H5T_IEEE_F64LE, space.Id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  return attribute.Id >= 0 && H5Awrite(attribute.Id, H5T_NATIVE_DOUBLE, values) >= 0;
}

// A whole small dataset (the octree's tables).
bool WriteTable(hid_t group,
  const char* name,
  hid_t fileType,
  hid_t memType,
  hsize_t rows,
  int components,
  const void* data)
{
  Handle dataset(Create(group, name, fileType, rows, components), H5Dclose);
  return dataset.Id >= 0 &&
    Rows(dataset.Id, 0, rows, components, memType, const_cast<void*>(data), true);
}
bool ReadTable(hid_t group,
  const char* name,
  hid_t memType,
  long long rows,
  int components,
  void* data)
{
  long long r;
  int c;
  Shape(group, name, r, c);
  if (r != rows || c != components)
  {
    return false;
  }
  Handle dataset(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose);
  return dataset.Id >= 0 &&
    Rows(dataset.Id, 0, static_cast<hsize_t>(rows), components, memType, data, false);
}
} // namespace

//------------------------------------------------------------------------------
long long FileModificationStamp(const std::string& path)
{
  struct stat s;
  return stat(path.c_str(), &s) == 0
    ? static_cast<long long>(s.st_mtime) * 1000000000LL + static_cast<long long>(s.st_mtim.tv_nsec)
    : -1;
}

void SplatColumns::Resize(long long count, int degree, const std::vector<int>& components)
{
  const size_t n = static_cast<size_t>(std::max(0LL, count));
  this->Count = static_cast<long long>(n);
  this->Origin.resize(3 * n);
  this->Normal.resize(3 * n);
  this->Tangent.resize(3 * n);
  this->FeatureSize.resize(n);
  this->Coefficients.resize(static_cast<size_t>(MonomialCount(degree)) * n);
  this->Radius.resize(n);
  this->MaxDeviation.resize(n);
  this->NominalRadius.resize(n);
  this->Tolerance.resize(n);
  this->LOD.resize(n);
  this->Attributes.resize(components.size());
  for (size_t a = 0; a < components.size(); ++a)
  {
    this->Attributes[a].resize(static_cast<size_t>(components[a]) * n);
  }
}

void SplatColumns::Append(const SplatColumns& from, long long row)
{
  if (row < 0 || row >= from.Count)
  {
    return;
  }
  auto append = [&](auto& to, const auto& source)
  {
    const auto width = static_cast<std::ptrdiff_t>(source.size() / static_cast<size_t>(from.Count));
    const auto begin = source.begin() + static_cast<std::ptrdiff_t>(row) * width;
    to.insert(to.end(), begin, begin + width);
  };
  append(this->Origin, from.Origin);
  append(this->Normal, from.Normal);
  append(this->Tangent, from.Tangent);
  append(this->FeatureSize, from.FeatureSize);
  append(this->Coefficients, from.Coefficients);
  append(this->Radius, from.Radius);
  append(this->MaxDeviation, from.MaxDeviation);
  append(this->NominalRadius, from.NominalRadius);
  append(this->Tolerance, from.Tolerance);
  append(this->LOD, from.LOD);
  this->Attributes.resize(from.Attributes.size());
  for (size_t a = 0; a < from.Attributes.size(); ++a)
  {
    append(this->Attributes[a], from.Attributes[a]);
  }
  ++this->Count;
}

std::vector<long long> RangeEndRows(const SplatFileInfo& info)
{
  std::vector<long long> rows;
  for (const auto& entry : info.RangeRows)
  {
    rows.insert(rows.end(), entry.second.begin(), entry.second.end());
  }
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  return rows;
}

//------------------------------------------------------------------------------
struct SplatFileWriter::Impl
{
  hid_t File = -1;
  SplatFileInfo Info;
  std::vector<hid_t> Datasets;                   // the columns, then the attributes
  std::vector<std::vector<double>> Ranges;       // of each dataset, as written so far
  std::vector<std::vector<long long>> RangeRows; // the row of each of their ends
  void CloseAll()
  {
    for (hid_t d : this->Datasets)
    {
      H5Dclose(d);
    }
    this->Datasets.clear();
    if (this->File >= 0)
    {
      H5Fclose(this->File);
      this->File = -1;
    }
  }
};

SplatFileWriter::SplatFileWriter()
  : P(new Impl)
{
}

SplatFileWriter::~SplatFileWriter()
{
  QuietHDF5 quiet;
  P->CloseAll();
}

bool SplatFileWriter::Open(const std::string& path, const SplatFileInfo& info, std::string& error)
{
  QuietHDF5 quiet;
  P->CloseAll();
  P->Info = info;
  if (info.Degree < 1 || info.Degree > MaximumDegree || info.Splats < 0 ||
    info.AttributeNames.size() != info.AttributeComponents.size())
  {
    error = "cannot write this splat set (bad degree, count or attributes)";
    return false;
  }
  P->File = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (P->File < 0)
  {
    error = "cannot be created";
    return false;
  }
  Handle splats(H5Gcreate2(P->File, "Splats", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  Handle attributes(
    H5Gcreate2(P->File, "Attributes", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  const hsize_t n = static_cast<hsize_t>(info.Splats);
  for (const Column& c : Columns)
  {
    const int comps = ComponentsOf(c, info.Degree);
    P->Datasets.push_back(Create(splats.Id, c.Name, FileType(c.Type), n, comps));
  }
  for (size_t a = 0; a < info.AttributeNames.size(); ++a)
  {
    const std::string& name = info.AttributeNames[a];
    if (name.empty() || name.find('/') != std::string::npos || name == "." ||
      H5Lexists(attributes.Id, name.c_str(), H5P_DEFAULT) > 0)
    {
      error = "cannot store the attribute '" + name + "' (empty, a '/' in it, or twice)";
      P->CloseAll();
      return false;
    }
    P->Datasets.push_back(Create(attributes.Id,
      name.c_str(),
      AttributeFileType(info.AttributeType(a)),
      n,
      std::max(1, info.AttributeComponents[a])));
  }
  if (std::any_of(P->Datasets.begin(), P->Datasets.end(), [](hid_t d) { return d < 0; }))
  {
    error = "cannot be written (its columns could not be made)";
    P->CloseAll();
    return false;
  }
  P->Ranges.assign(P->Datasets.size(), {});
  P->RangeRows.assign(P->Datasets.size(), {});
  return true;
}

bool SplatFileWriter::Write(long long first, const SplatColumns& block, std::string& error)
{
  QuietHDF5 quiet;
  if (P->File < 0 || first < 0 || first + block.Count > P->Info.Splats)
  {
    error = "rows outside the file";
    return false;
  }
  SplatColumns& rows = const_cast<SplatColumns&>(block);
  const hsize_t f = static_cast<hsize_t>(first), count = static_cast<hsize_t>(block.Count);
  for (int k = 0; k < ColumnCount; ++k)
  {
    const int comps = ComponentsOf(Columns[k], P->Info.Degree);
    if (!Rows(
          P->Datasets[k], f, count, comps, MemoryType(Columns[k].Type), ColumnData(rows, k), true))
    {
      error = "cannot be written (disk full?)";
      return false;
    }
    if (Ranged(k) && Columns[k].Type == Kind::Int)
    {
      GrowRange(P->Ranges[k],
        P->RangeRows[k],
        static_cast<const int*>(ColumnData(rows, k)),
        first,
        block.Count,
        comps);
    }
    else if (Ranged(k))
    {
      GrowRange(P->Ranges[k],
        P->RangeRows[k],
        static_cast<const float*>(ColumnData(rows, k)),
        first,
        block.Count,
        comps);
    }
  }
  std::vector<float> rounded;
  for (size_t a = 0; a < P->Info.AttributeNames.size(); ++a)
  {
    const int comps = std::max(1, P->Info.AttributeComponents[a]);
    const float* stored = rows.Attributes.size() > a
      ? StoredValues(P->Info.AttributeType(a), rows.Attributes[a], rounded)
      : nullptr;
    if (!stored ||
      !Rows(P->Datasets[ColumnCount + a],
        f,
        count,
        comps,
        H5T_NATIVE_FLOAT,
        const_cast<float*>(stored),
        true))
    {
      error = "cannot be written (disk full?)";
      return false;
    }
    GrowRange(
      P->Ranges[ColumnCount + a], P->RangeRows[ColumnCount + a], stored, first, block.Count, comps);
  }
  return true;
}

bool SplatFileWriter::Close(std::string& error)
{
  QuietHDF5 quiet;
  if (P->File < 0)
  {
    error = "not open";
    return false;
  }
  const SplatFileInfo& info = P->Info;
  const Octree& tree = info.Pages.Tree;
  const hsize_t m = tree.Nodes.size();
  const int L = std::max(1, tree.Levels);
  std::vector<double> bounds(6 * m), sphere(4 * m);
  std::vector<std::int32_t> children(2 * m);
  std::vector<std::int64_t> range(2 * m), ends(tree.LevelEnds.begin(), tree.LevelEnds.end());
  for (hsize_t i = 0; i < m; ++i)
  {
    const OctreeNode& node = tree.Nodes[i];
    std::copy(node.Bounds, node.Bounds + 6, &bounds[6 * i]);
    std::copy(node.Sphere, node.Sphere + 4, &sphere[4 * i]);
    children[2 * i] = node.FirstChild;
    children[2 * i + 1] = node.ChildCount;
    range[2 * i] = node.Begin;
    range[2 * i + 1] = node.End;
  }
  Handle group(H5Gcreate2(P->File, "Octree", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  bool ok = group.Id >= 0 && ends.size() == m * L && info.Pages.MeanScale.size() == m &&
    info.Pages.Reach.size() == m &&
    WriteTable(group.Id, "Bounds", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, m, 6, bounds.data()) &&
    WriteTable(group.Id, "Sphere", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, m, 4, sphere.data()) &&
    WriteTable(group.Id, "Children", H5T_STD_I32LE, H5T_NATIVE_INT32, m, 2, children.data()) &&
    WriteTable(group.Id, "Range", H5T_STD_I64LE, H5T_NATIVE_INT64, m, 2, range.data()) &&
    WriteTable(group.Id, "LevelEnds", H5T_STD_I64LE, H5T_NATIVE_INT64, m, L, ends.data()) &&
    WriteTable(group.Id,
      "MeanScale",
      H5T_IEEE_F64LE,
      H5T_NATIVE_DOUBLE,
      m,
      1,
      info.Pages.MeanScale.data()) &&
    WriteTable(group.Id, "Reach", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, m, 1, info.Pages.Reach.data());
  std::vector<double> quality = info.Pages.LevelQuality;
  quality.resize(static_cast<size_t>(L), quality.empty() ? 1.0 : quality.back());
  const double version = Version, degree = info.Degree, levels = L,
               splats = static_cast<double>(info.Splats),
               input = static_cast<double>(info.InputPoints), oriented = info.Oriented ? 1 : 0,
               complete = 1;
  ok = ok && WriteNumbers(P->File, "PointSurfacesSplatFile", &version, 1) &&
    WriteNumbers(P->File, "Degree", &degree, 1) && WriteNumbers(P->File, "Levels", &levels, 1) &&
    WriteNumbers(P->File, "LevelQuality", quality.data(), static_cast<hsize_t>(L)) &&
    WriteNumbers(P->File, "NumberOfSplats", &splats, 1) &&
    WriteNumbers(P->File, "NumberOfInputPoints", &input, 1) &&
    WriteNumbers(P->File, "Oriented", &oriented, 1) &&
    WriteNumbers(P->File, "Bounds", info.Bounds, 6);
  // Each dataset's value ranges and the rows that hold their ends (none
  // where no value was finite).
  for (size_t d = 0; ok && d < P->Datasets.size() && d < P->Ranges.size(); ++d)
  {
    if (WholeRange(P->Ranges[d]))
    {
      const std::vector<double> rows(P->RangeRows[d].begin(), P->RangeRows[d].end());
      ok = WriteNumbers(P->Datasets[d], "Range", P->Ranges[d].data(), P->Ranges[d].size()) &&
        WriteNumbers(P->Datasets[d], "RangeRows", rows.data(), rows.size());
    }
  }
  ok = ok && WriteNumbers(P->File, "Complete", &complete, 1);
  P->CloseAll();
  if (!ok)
  {
    error = "cannot be written (disk full?)";
  }
  return ok;
}

//------------------------------------------------------------------------------
bool WriteSplatFile(const std::string& path,
  SplatFileInfo info,
  const double* origins,
  const double* radii,
  const int* levels,
  long long n,
  const std::vector<double>& levelQuality,
  const SplatFetch& fetch,
  std::string& error,
  int pageSplats)
{
  const int L = std::max<int>(1, static_cast<int>(levelQuality.size()));
  Octree tree = BuildOctree(origins, radii, levels, n, L, std::max(1, pageSplats));
  std::vector<double> sortedRadii(static_cast<size_t>(n));
  std::vector<int> sortedLevels(static_cast<size_t>(n));
  for (long long k = 0; k < n; ++k)
  {
    sortedRadii[k] = radii[tree.Order[k]];
    sortedLevels[k] = levels[tree.Order[k]];
  }
  std::vector<long long> order;
  order.swap(tree.Order);
  std::vector<double> quality = levelQuality;
  quality.resize(static_cast<size_t>(L), quality.empty() ? 1.0 : quality.back());
  info.Pages = MakeLODOctree(std::move(tree), quality, sortedRadii.data(), sortedLevels.data());
  info.Splats = n;
  for (int c = 0; c < 3; ++c)
  {
    info.Bounds[2 * c] = n > 0 ? info.Pages.Tree.Nodes[0].Bounds[2 * c] : 0.0;
    info.Bounds[2 * c + 1] = n > 0 ? info.Pages.Tree.Nodes[0].Bounds[2 * c + 1] : 0.0;
  }
  SplatFileWriter writer;
  if (!writer.Open(path, info, error))
  {
    return false;
  }
  SplatColumns block;
  std::vector<long long> ids;
  for (long long first = 0; first < n; first += static_cast<long long>(ChunkRows))
  {
    const long long count = std::min<long long>(static_cast<long long>(ChunkRows), n - first);
    ids.assign(order.begin() + first, order.begin() + first + count);
    block = SplatColumns();
    block.Resize(count, info.Degree, info.AttributeComponents);
    if (!fetch(ids, block))
    {
      error = "the splats to write could not be read";
      return false;
    }
    if (!writer.Write(first, block, error))
    {
      return false;
    }
  }
  return writer.Close(error);
}

//------------------------------------------------------------------------------
struct SplatFileReader::Impl
{
  hid_t File = -1;
  SplatFileInfo Info;
  std::vector<hid_t> Datasets;
  void CloseAll()
  {
    for (hid_t d : this->Datasets)
    {
      H5Dclose(d);
    }
    this->Datasets.clear();
    if (this->File >= 0)
    {
      H5Fclose(this->File);
      this->File = -1;
    }
  }
  bool Check(std::string& error);
  bool WalkChunks(std::string& error);
  bool CheckInChildProcess = ChildProcess::Supported();
};

// Walks the chunk index (a B-tree) of every dataset that Check opened, so
// that a damaged index shows in the checking child rather than at a read.
bool SplatFileReader::Impl::WalkChunks(std::string& error)
{
  for (hid_t dataset : this->Datasets)
  {
    if (!ChunkIndexReadable(dataset))
    {
      error = "damaged: a column's chunk index cannot be read";
      return false;
    }
  }
  return true;
}

void SplatFileReader::SetCheckInChildProcess(bool check)
{
  P->CheckInChildProcess = check && ChildProcess::Supported();
}

SplatFileReader::SplatFileReader()
  : P(new Impl)
{
}

SplatFileReader::~SplatFileReader()
{
  QuietHDF5 quiet;
  P->CloseAll();
}

const SplatFileInfo& SplatFileReader::Info() const
{
  return P->Info;
}

double SplatFileReader::BytesPerSplat() const
{
  // The splat data model in VTK: double arrays (origin, normal, tangent, h,
  // m coefficients, radius, deviation, nominal radius, tolerance), the
  // int LOD, a vertex cell (offset and connectivity), the attributes in
  // their types.
  double bytes = 8.0 * (3 + 3 + 3 + 1 + MonomialCount(P->Info.Degree) + 4) + 4.0 + 16.0;
  for (size_t a = 0; a < P->Info.AttributeComponents.size(); ++a)
  {
    const int stored = StoredTypeOf(P->Info.AttributeType(a)).Bytes;
    bytes += (stored ? stored : 4.0) * P->Info.AttributeComponents[a];
  }
  return bytes;
}

bool SplatFileReader::Impl::Check(std::string& error)
{
  SplatFileInfo& info = this->Info;
  double version = 0, complete = 0, degree = 0, levels = 0, splats = -1, input = 0, oriented = 0;
  ReadNumbers(this->File, "PointSurfacesSplatFile", &version, 1);
  if (version != Version)
  {
    error = version == 0
      ? "not a PointSurfaces splat file (no PointSurfacesSplatFile attribute)"
      : "a splat file of version " + std::to_string(version) + ", not " + std::to_string(Version);
    return false;
  }
  ReadNumbers(this->File, "Complete", &complete, 1);
  if (complete != 1)
  {
    error = "unfinished: its writer never closed it (stopped while fitting?)";
    return false;
  }
  ReadNumbers(this->File, "Degree", &degree, 1);
  ReadNumbers(this->File, "Levels", &levels, 1);
  ReadNumbers(this->File, "NumberOfSplats", &splats, 1);
  ReadNumbers(this->File, "NumberOfInputPoints", &input, 1);
  ReadNumbers(this->File, "Oriented", &oriented, 1);
  ReadNumbers(this->File, "Bounds", info.Bounds, 6);
  if (!(degree >= 1 && degree <= MaximumDegree && degree == std::floor(degree)) ||
    !(levels >= 1 && levels <= 64 && levels == std::floor(levels)) ||
    !(splats >= 0 && splats < 9e15 && splats == std::floor(splats)))
  {
    error = "damaged: its degree, levels or splat count are not valid";
    return false;
  }
  info.Degree = static_cast<int>(degree);
  info.Splats = static_cast<long long>(splats);
  info.InputPoints = input >= 0 && input < 9e18 ? static_cast<long long>(input) : 0;
  info.Oriented = oriented != 0;
  const int L = static_cast<int>(levels);
  info.Pages.LevelQuality.assign(static_cast<size_t>(L), 1.0);
  if (ReadNumbers(this->File, "LevelQuality", info.Pages.LevelQuality.data(), L) != L)
  {
    error = "damaged: LevelQuality does not hold one s per level";
    return false;
  }

  // Every column has a row per splat.
  Handle splatGroup(H5Lexists(this->File, "Splats", H5P_DEFAULT) > 0
      ? H5Gopen2(this->File, "Splats", H5P_DEFAULT)
      : -1,
    H5Gclose);
  if (splatGroup.Id < 0)
  {
    error = "damaged: no Splats group";
    return false;
  }
  for (const Column& c : Columns)
  {
    long long rows;
    int comps;
    Shape(splatGroup.Id, c.Name, rows, comps);
    const int want = ComponentsOf(c, info.Degree);
    if (rows != info.Splats || comps != want)
    {
      error = std::string("damaged: Splats/") + c.Name + " is not " + std::to_string(info.Splats) +
        " x " + std::to_string(want);
      return false;
    }
    this->Datasets.push_back(H5Dopen2(splatGroup.Id, c.Name, H5P_DEFAULT));
  }
  if (H5Lexists(this->File, "Attributes", H5P_DEFAULT) > 0)
  {
    Handle group(H5Gopen2(this->File, "Attributes", H5P_DEFAULT), H5Gclose);
    H5G_info_t groupInfo;
    if (group.Id < 0 || H5Gget_info(group.Id, &groupInfo) < 0)
    {
      error = "damaged: its Attributes group cannot be read";
      return false;
    }
    for (hsize_t k = 0; k < groupInfo.nlinks; ++k)
    {
      char name[1024] = { 0 };
      if (H5Lget_name_by_idx(
            group.Id, ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof(name), H5P_DEFAULT) < 0)
      {
        error = "damaged: its Attributes group cannot be read";
        return false;
      }
      long long rows;
      int comps;
      Shape(group.Id, name, rows, comps);
      if (rows != info.Splats || comps < 1)
      {
        error = std::string("damaged: Attributes/") + name + " does not hold a row per splat";
        return false;
      }
      info.AttributeNames.push_back(name);
      info.AttributeComponents.push_back(comps);
      this->Datasets.push_back(H5Dopen2(group.Id, name, H5P_DEFAULT));
      info.AttributeTypes.push_back(
        this->Datasets.back() >= 0 ? AttributeTypeOf(this->Datasets.back()) : VTK_FLOAT);
    }
  }
  if (std::any_of(this->Datasets.begin(), this->Datasets.end(), [](hid_t d) { return d < 0; }))
  {
    error = "damaged: a column cannot be opened";
    return false;
  }
  // The value ranges the writer stored; one that does not fit is left out.
  for (size_t d = 0; d < this->Datasets.size(); ++d)
  {
    const bool column = d < static_cast<size_t>(ColumnCount);
    if (column && !Ranged(static_cast<int>(d)))
    {
      continue;
    }
    const int comps =
      column ? ComponentsOf(Columns[d], info.Degree) : info.AttributeComponents[d - ColumnCount];
    std::vector<double> range(SplatRangeSize(comps));
    if (ReadNumbers(this->Datasets[d], "Range", range.data(), static_cast<int>(range.size())) ==
        static_cast<int>(range.size()) &&
      WholeRange(range))
    {
      const std::string key = column ? std::string("Splats/") + Columns[d].Name
                                     : "Attributes/" + info.AttributeNames[d - ColumnCount];
      info.Ranges[key] = range;
      // The rows of the ends: whole numbers within the file, or none.
      std::vector<double> rows(range.size());
      if (ReadNumbers(this->Datasets[d], "RangeRows", rows.data(), static_cast<int>(rows.size())) ==
          static_cast<int>(rows.size()) &&
        std::all_of(rows.begin(),
          rows.end(),
          [&](double r)
          { return r >= 0 && r < static_cast<double>(info.Splats) && r == std::floor(r); }))
      {
        info.RangeRows[key].assign(rows.begin(), rows.end());
      }
    }
  }

  // The octree: every range, child and level end within bounds.
  Handle tree(H5Lexists(this->File, "Octree", H5P_DEFAULT) > 0
      ? H5Gopen2(this->File, "Octree", H5P_DEFAULT)
      : -1,
    H5Gclose);
  long long m = -1;
  int comps = 0;
  if (tree.Id >= 0)
  {
    Shape(tree.Id, "Range", m, comps);
  }
  if (m < 1 || m > 1LL << 31)
  {
    error = "damaged: no octree";
    return false;
  }
  std::vector<double> bounds(6 * m), sphere(4 * m);
  std::vector<std::int32_t> children(2 * m);
  std::vector<std::int64_t> range(2 * m), ends(static_cast<size_t>(m) * L);
  LODOctree& pages = info.Pages;
  pages.MeanScale.resize(m);
  pages.Reach.resize(m);
  if (!ReadTable(tree.Id, "Bounds", H5T_NATIVE_DOUBLE, m, 6, bounds.data()) ||
    !ReadTable(tree.Id, "Sphere", H5T_NATIVE_DOUBLE, m, 4, sphere.data()) ||
    !ReadTable(tree.Id, "Children", H5T_NATIVE_INT32, m, 2, children.data()) ||
    !ReadTable(tree.Id, "Range", H5T_NATIVE_INT64, m, 2, range.data()) ||
    !ReadTable(tree.Id, "LevelEnds", H5T_NATIVE_INT64, m, L, ends.data()) ||
    !ReadTable(tree.Id, "MeanScale", H5T_NATIVE_DOUBLE, m, 1, pages.MeanScale.data()) ||
    !ReadTable(tree.Id, "Reach", H5T_NATIVE_DOUBLE, m, 1, pages.Reach.data()))
  {
    error = "damaged: its octree tables cannot be read or disagree in size";
    return false;
  }
  pages.Tree.Levels = L;
  pages.Tree.Nodes.resize(static_cast<size_t>(m));
  pages.Tree.LevelEnds.assign(ends.begin(), ends.end());
  for (long long i = 0; i < m; ++i)
  {
    OctreeNode& node = pages.Tree.Nodes[i];
    std::copy(&bounds[6 * i], &bounds[6 * i] + 6, node.Bounds);
    std::copy(&sphere[4 * i], &sphere[4 * i] + 4, node.Sphere);
    node.FirstChild = children[2 * i];
    node.ChildCount = children[2 * i + 1];
    node.Begin = range[2 * i];
    node.End = range[2 * i + 1];
    bool ok = node.Begin >= 0 && node.Begin <= node.End && node.End <= info.Splats &&
      std::isfinite(node.Sphere[3]) && std::isfinite(pages.Reach[i]) &&
      std::isfinite(pages.MeanScale[i]);
    if (node.ChildCount != 0)
    {
      ok = ok && node.ChildCount > 0 && node.ChildCount <= 8 && node.FirstChild > i &&
        node.FirstChild + static_cast<long long>(node.ChildCount) <= m;
    }
    long long previous = node.Begin;
    for (int l = 0; ok && l < L; ++l)
    {
      const long long e = ends[static_cast<size_t>(i) * L + l];
      ok = e >= previous && e <= node.End;
      previous = e;
    }
    if (!ok)
    {
      error = "damaged: octree node " + std::to_string(i) + " has ranges outside its splats";
      return false;
    }
  }
  // Children inside their parent's range; depths from the root.
  for (long long i = 0; i < m; ++i)
  {
    const OctreeNode& node = pages.Tree.Nodes[i];
    for (int c = 0; c < node.ChildCount; ++c)
    {
      OctreeNode& child = pages.Tree.Nodes[node.FirstChild + c];
      if (child.Begin < node.Begin || child.End > node.End)
      {
        error = "damaged: octree node " + std::to_string(node.FirstChild + c) +
          " lies outside its parent's range";
        return false;
      }
      child.Depth = node.Depth + 1;
    }
  }
  if (pages.Tree.Nodes[0].Begin != 0 || pages.Tree.Nodes[0].End != info.Splats)
  {
    error = "damaged: the octree's root does not hold every splat";
    return false;
  }
  return true;
}

bool SplatFileReader::Open(const std::string& path, std::string& error)
{
  QuietHDF5 quiet;
  P->CloseAll();
  P->Info = SplatFileInfo();
  if (H5Fis_hdf5(path.c_str()) <= 0)
  {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    const bool empty = f && std::fgetc(f) == EOF;
    error = !f ? "cannot be opened"
      : empty  ? "the file is empty"
               : "not an HDF5 file, or truncated";
    if (f)
    {
      std::fclose(f);
    }
    return false;
  }
  if (P->CheckInChildProcess &&
    !CheckInChild(
      path,
      "splat file",
      [&path]()
      {
        SplatFileReader probe;
        probe.SetCheckInChildProcess(false);
        std::string why;
        probe.Open(path, why); // in the child: also walks the chunk indexes
      },
      error))
  {
    return false;
  }
  P->File = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (P->File < 0)
  {
    error = "cannot be opened as HDF5 (truncated or damaged)";
    return false;
  }
  if (!P->Check(error) || (InCheckingChild() && !P->WalkChunks(error)))
  {
    P->CloseAll();
    return false;
  }
  return true;
}

bool SplatFileReader::Read(long long first, long long count, SplatColumns& out, std::string& error)
{
  QuietHDF5 quiet;
  if (P->File < 0 || first < 0 || count < 0 || first + count > P->Info.Splats)
  {
    error = "rows outside the file";
    return false;
  }
  const long long at = out.Count;
  out.Resize(at + count, P->Info.Degree, P->Info.AttributeComponents);
  const hsize_t f = static_cast<hsize_t>(first), n = static_cast<hsize_t>(count);
  for (int k = 0; k < ColumnCount; ++k)
  {
    const int comps = ComponentsOf(Columns[k], P->Info.Degree);
    const size_t elementBytes = Columns[k].Type == Kind::Double ? 8 : 4;
    unsigned char* base = static_cast<unsigned char*>(ColumnData(out, k)) +
      static_cast<size_t>(at) * comps * elementBytes;
    if (!Rows(P->Datasets[k], f, n, comps, MemoryType(Columns[k].Type), base, false))
    {
      error = std::string("cannot read Splats/") + Columns[k].Name + " (damaged?)";
      return false;
    }
  }
  for (size_t a = 0; a < P->Info.AttributeNames.size(); ++a)
  {
    const int comps = P->Info.AttributeComponents[a];
    if (!Rows(P->Datasets[ColumnCount + a],
          f,
          n,
          comps,
          H5T_NATIVE_FLOAT,
          out.Attributes[a].data() + static_cast<size_t>(at) * comps,
          false))
    {
      error = "cannot read Attributes/" + P->Info.AttributeNames[a] + " (damaged?)";
      return false;
    }
  }
  return true;
}
} // namespace pointsurfaces
