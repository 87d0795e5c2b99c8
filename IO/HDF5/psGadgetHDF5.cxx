// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psGadgetHDF5.h"

#include "psHDF5.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <new>

namespace pointsurfaces
{
namespace
{
bool ReadHeader(hid_t file, SnapshotHeader& header)
{
  if (H5Lexists(file, "Header", H5P_DEFAULT) <= 0)
  {
    return false;
  }
  Handle group(H5Gopen2(file, "Header", H5P_DEFAULT), H5Gclose);
  if (group.Id < 0)
  {
    return false;
  }
  ReadNumbers(group.Id, "Time", &header.Time, 1);
  ReadNumbers(group.Id, "Redshift", &header.Redshift, 1);
  const int box = ReadNumbers(group.Id, "BoxSize", header.BoxSize, 3);
  if (box == 1)
  {
    header.BoxSize[1] = header.BoxSize[2] = header.BoxSize[0];
  }
  ReadNumbers(group.Id, "MassTable", header.MassTable, 6);
  // Counts as the file says them, when they are counts (a damaged header may
  // hold anything: NaN, negative, beyond 2^53).
  auto count = [](double v)
  { return v >= 0.0 && v < 9007199254740992.0 ? static_cast<long long>(v) : 0LL; };
  double counts[6] = { 0, 0, 0, 0, 0, 0 };
  ReadNumbers(group.Id, "NumPart_ThisFile", counts, 6);
  for (int k = 0; k < 6; ++k)
  {
    header.NumPartThisFile[k] = count(counts[k]);
    counts[k] = 0.0;
  }
  ReadNumbers(group.Id, "NumPart_Total", counts, 6);
  double high[6] = { 0, 0, 0, 0, 0, 0 }; // Gadget-2 splits totals over 2^32
  ReadNumbers(group.Id, "NumPart_Total_HighWord", high, 6);
  for (int k = 0; k < 6; ++k)
  {
    const long long low = count(counts[k]), top = count(high[k]);
    header.NumPartTotal[k] = top < (1LL << 21) ? low + top * 4294967296LL : low;
  }
  double files = 1.0;
  ReadNumbers(group.Id, "NumFilesPerSnapshot", &files, 1);
  header.NumFiles = files >= 1.0 && files < 1e6 ? static_cast<int>(files) : 1;
  header.Code = H5Lexists(file, "Code", H5P_DEFAULT) > 0 ? "SWIFT" : "Gadget";
  return true;
}

// The names of a group's members.
herr_t CollectName(hid_t, const char* name, const H5L_info_t*, void* names)
{
  static_cast<std::vector<std::string>*>(names)->emplace_back(name);
  return 0;
}

size_t SizeOf(SnapshotArray::Kind kind)
{
  return kind == SnapshotArray::Float32 || kind == SnapshotArray::Int32 ||
      kind == SnapshotArray::UInt32
    ? 4
    : 8;
}

hid_t MemoryType(SnapshotArray::Kind kind)
{
  switch (kind)
  {
    case SnapshotArray::Float32:
      return H5T_NATIVE_FLOAT;
    case SnapshotArray::Int32:
      return H5T_NATIVE_INT32;
    case SnapshotArray::Int64:
      return H5T_NATIVE_INT64;
    case SnapshotArray::UInt32:
      return H5T_NATIVE_UINT32;
    case SnapshotArray::UInt64:
      return H5T_NATIVE_UINT64;
    case SnapshotArray::Float64:
    default:
      return H5T_NATIVE_DOUBLE;
  }
}

// The most values one dataset may hold (10^11: 800 GB of doubles); a
// dataspace beyond it is damage.
constexpr long long MaximumValues = 100000000000LL;

// The array's type for the HDF5 type `type`; false when it is not numeric.
// (Whether HDF5 can convert it safely is SaneDataset's to say.)
bool NumericType(hid_t type, SnapshotArray& array)
{
  const H5T_class_t kind = type >= 0 ? H5Tget_class(type) : H5T_NO_CLASS;
  const size_t size = type >= 0 ? H5Tget_size(type) : 0;
  if (kind == H5T_FLOAT)
  {
    array.Type = size <= 4 ? SnapshotArray::Float32 : SnapshotArray::Float64;
    return true;
  }
  if (kind == H5T_INTEGER)
  {
    const bool isSigned = H5Tget_sign(type) != H5T_SGN_NONE;
    array.Type = size <= 2 ? SnapshotArray::Int32
      : size <= 4          ? (isSigned ? SnapshotArray::Int32 : SnapshotArray::UInt32)
                           : (isSigned ? SnapshotArray::Int64 : SnapshotArray::UInt64);
    return true;
  }
  return false;
}

// One file's datasets of group `name`: rows in `count`, arrays in `arrays`.
bool ReadPart(hid_t file,
  const std::string& path,
  const std::string& name,
  long long& count,
  std::vector<SnapshotArray>& arrays,
  Snapshot& out)
{
  count = 0;
  arrays.clear();
  if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0)
  {
    return true; // no particles of this type in this file
  }
  Handle group(H5Gopen2(file, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (group.Id < 0)
  {
    out.Error = path + ": /" + name + " is not a readable group.";
    return false;
  }
  std::vector<std::string> names;
  if (H5Literate(group.Id, H5_INDEX_NAME, H5_ITER_INC, nullptr, CollectName, &names) < 0)
  {
    out.Error = path + ": the members of /" + name + " cannot be listed.";
    return false;
  }
  // Coordinates first: they give the particle count.
  const auto coordinates = std::find(names.begin(), names.end(), "Coordinates");
  if (coordinates == names.end())
  {
    out.Error = path + ": /" + name + " has no Coordinates dataset.";
    return false;
  }
  std::rotate(names.begin(), coordinates, coordinates + 1);
  for (const std::string& member : names)
  {
    Handle dataset(H5Dopen2(group.Id, member.c_str(), H5P_DEFAULT), H5Dclose);
    if (dataset.Id < 0)
    {
      if (member == "Coordinates")
      {
        out.Error = path + ": /" + name + "/Coordinates is not a readable dataset.";
        return false;
      }
      Handle subgroup(H5Gopen2(group.Id, member.c_str(), H5P_DEFAULT), H5Gclose);
      if (subgroup.Id < 0)
      {
        // Not a group either: a link to nothing, or a dataset that HDF5 will
        // not open (damaged; HDF5 1.14 refuses numeric types with unused bits).
        out.Warnings.push_back(
          path + ": /" + name + "/" + member + " cannot be opened as a dataset: skipped.");
      }
      continue;
    }
    Handle space(H5Dget_space(dataset.Id), H5Sclose);
    Handle type(H5Dget_type(dataset.Id), H5Tclose);
    hsize_t dims[2] = { 0, 0 };
    const int rank = space.Id >= 0 ? H5Sget_simple_extent_ndims(space.Id) : -1;
    if (rank >= 1 && rank <= 2)
    {
      H5Sget_simple_extent_dims(space.Id, dims, nullptr);
    }
    const bool first = member == "Coordinates";
    if (first)
    {
      if (rank != 2 || dims[1] != 3 || dims[0] > static_cast<hsize_t>(MaximumValues / 3))
      {
        out.Error = path + ": /" + name + "/Coordinates is not a list of 3-D points.";
        return false;
      }
      count = static_cast<long long>(dims[0]);
    }
    const std::string what = "/" + name + "/" + member;
    if (rank < 1 || rank > 2 || dims[0] != static_cast<hsize_t>(count))
    {
      out.Warnings.push_back(path + ": " + what + " does not have one row per particle: skipped.");
      continue;
    }
    const long long components = rank == 2 ? static_cast<long long>(dims[1]) : 1;
    if (components < 1 || components > 16)
    {
      out.Warnings.push_back(
        path + ": " + what + " has " + std::to_string(components) + " columns: skipped.");
      continue;
    }
    SnapshotArray array;
    array.Name = member;
    array.Components = static_cast<int>(components);
    if (!NumericType(type.Id, array) || !SaneDataset(dataset.Id))
    {
      if (first)
      {
        out.Error = path + ": " + what + " is not numeric (or its type or layout is damaged).";
        return false;
      }
      out.Warnings.push_back(
        path + ": " + what + " is not numeric (or its type or layout is damaged): skipped.");
      continue;
    }
    try
    {
      array.Bytes.resize(static_cast<size_t>(count * components) * SizeOf(array.Type));
    }
    catch (const std::bad_alloc&)
    {
      out.Error = path + ": no memory for " + what + ".";
      return false;
    }
    if (count > 0 &&
      H5Dread(
        dataset.Id, MemoryType(array.Type), H5S_ALL, H5S_ALL, H5P_DEFAULT, array.Bytes.data()) < 0)
    {
      if (first)
      {
        out.Error = path + ": " + what + " cannot be read (the file is damaged).";
        return false;
      }
      out.Warnings.push_back(path + ": " + what + " cannot be read: skipped.");
      continue;
    }
    arrays.push_back(std::move(array));
  }
  return true;
}
} // namespace

//------------------------------------------------------------------------------
bool WriteSnapshotFile(const std::string& path,
  const SnapshotHeader& header,
  const std::vector<SnapshotPart>& parts,
  std::string& error)
{
  QuietHDF5 quiet;
  Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (file.Id < 0)
  {
    error = path + ": HDF5 cannot create it.";
    return false;
  }
  bool ok = true;
  auto attribute =
    [&ok](hid_t location, const char* name, hid_t type, const void* values, hsize_t count)
  {
    Handle space(
      count == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr), H5Sclose);
    Handle a(H5Acreate2(location, name, type, space.Id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
    ok = ok && a.Id >= 0 && H5Awrite(a.Id, type, values) >= 0;
  };
  long long thisFile[6] = { 0, 0, 0, 0, 0, 0 };
  for (const SnapshotPart& part : parts)
  {
    for (const SnapshotArray& a : part.Arrays)
    {
      if (a.Name == "Coordinates" && part.Type >= 0 && part.Type < 6)
      {
        thisFile[part.Type] = static_cast<long long>(a.Bytes.size() / (SizeOf(a.Type) * 3));
      }
    }
  }
  {
    Handle group(H5Gcreate2(file.Id, "Header", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    int counts[6];
    unsigned int totals[6], high[6];
    for (int k = 0; k < 6; ++k)
    {
      counts[k] = static_cast<int>(thisFile[k]);
      totals[k] = static_cast<unsigned int>(header.NumPartTotal[k] & 0xffffffffLL);
      high[k] = static_cast<unsigned int>(header.NumPartTotal[k] >> 32);
    }
    attribute(group.Id, "NumPart_ThisFile", H5T_NATIVE_INT32, counts, 6);
    attribute(group.Id, "NumPart_Total", H5T_NATIVE_UINT32, totals, 6);
    attribute(group.Id, "NumPart_Total_HighWord", H5T_NATIVE_UINT32, high, 6);
    attribute(group.Id, "MassTable", H5T_NATIVE_DOUBLE, header.MassTable, 6);
    attribute(group.Id, "Time", H5T_NATIVE_DOUBLE, &header.Time, 1);
    attribute(group.Id, "Redshift", H5T_NATIVE_DOUBLE, &header.Redshift, 1);
    const bool swift = header.Code == "SWIFT";
    attribute(group.Id, "BoxSize", H5T_NATIVE_DOUBLE, header.BoxSize, swift ? 3 : 1);
    attribute(group.Id, "NumFilesPerSnapshot", H5T_NATIVE_INT32, &header.NumFiles, 1);
    if (swift)
    {
      Handle code(H5Gcreate2(file.Id, "Code", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
      ok = ok && code.Id >= 0;
    }
  }
  for (const SnapshotPart& part : parts)
  {
    const std::string name = "PartType" + std::to_string(part.Type);
    Handle group(
      H5Gcreate2(file.Id, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    ok = ok && group.Id >= 0;
    for (const SnapshotArray& a : part.Arrays)
    {
      const hsize_t components = static_cast<hsize_t>(std::max(a.Components, 1));
      const hsize_t dims[2] = { a.Bytes.size() / (SizeOf(a.Type) * components), components };
      Handle space(H5Screate_simple(components > 1 ? 2 : 1, dims, nullptr), H5Sclose);
      Handle d(H5Dcreate2(group.Id,
                 a.Name.c_str(),
                 MemoryType(a.Type),
                 space.Id,
                 H5P_DEFAULT,
                 H5P_DEFAULT,
                 H5P_DEFAULT),
        H5Dclose);
      ok = ok && d.Id >= 0 &&
        (a.Bytes.empty() ||
          H5Dwrite(d.Id, MemoryType(a.Type), H5S_ALL, H5S_ALL, H5P_DEFAULT, a.Bytes.data()) >= 0);
    }
  }
  // What HDF5 still caches goes to the file now, so that a full disk shows.
  ok = ok && H5Fflush(file.Id, H5F_SCOPE_GLOBAL) >= 0;
  if (!ok)
  {
    error = path + ": HDF5 could not write every part of the snapshot.";
  }
  return ok;
}

//------------------------------------------------------------------------------
bool CheckSnapshotFile(const std::string& path, std::string& error)
{
  QuietHDF5 quiet;
  return CheckInChild(
    path,
    "gadget snapshot",
    [&path]()
    {
      if (H5Fis_hdf5(path.c_str()) <= 0)
      {
        return;
      }
      Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
      SnapshotHeader header;
      if (file.Id < 0 || !ReadHeader(file.Id, header))
      {
        return;
      }
      for (int type = 0; type < 6; ++type)
      {
        const std::string name = "PartType" + std::to_string(type);
        if (H5Lexists(file.Id, name.c_str(), H5P_DEFAULT) <= 0)
        {
          continue;
        }
        Handle group(H5Gopen2(file.Id, name.c_str(), H5P_DEFAULT), H5Gclose);
        std::vector<std::string> members;
        if (group.Id < 0 ||
          H5Literate(group.Id, H5_INDEX_NAME, H5_ITER_INC, nullptr, CollectName, &members) < 0)
        {
          continue;
        }
        for (const std::string& member : members)
        {
          Handle dataset(H5Dopen2(group.Id, member.c_str(), H5P_DEFAULT), H5Dclose);
          if (dataset.Id >= 0 && SaneDataset(dataset.Id))
          {
            ChunkIndexReadable(dataset.Id);
          }
        }
      }
    },
    error);
}

//------------------------------------------------------------------------------
bool IsGadgetSnapshot(const std::string& path)
{
  QuietHDF5 quiet;
  std::string error;
  if (H5Fis_hdf5(path.c_str()) <= 0 || !CheckSnapshotFile(path, error))
  {
    return false;
  }
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  return file.Id >= 0 && H5Lexists(file.Id, "Header", H5P_DEFAULT) > 0;
}

//------------------------------------------------------------------------------
std::vector<std::string> SnapshotFiles(const std::string& path, int numFiles)
{
  // base.k.hdf5 (or .h5): the part number is the last number before the extension.
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (numFiles <= 1 || dot == std::string::npos || dot == 0 ||
    (slash != std::string::npos && dot < slash))
  {
    return { path };
  }
  const size_t before = path.find_last_of('.', dot - 1);
  if (before == std::string::npos || (slash != std::string::npos && before < slash) ||
    before + 1 >= dot || path.find_first_not_of("0123456789", before + 1) != dot)
  {
    return { path };
  }
  std::vector<std::string> files;
  for (int k = 0; k < numFiles; ++k)
  {
    files.push_back(path.substr(0, before + 1) + std::to_string(k) + path.substr(dot));
  }
  return files;
}

//------------------------------------------------------------------------------
bool ReadSnapshotHeader(const std::string& path,
  SnapshotHeader& header,
  std::string& error,
  bool check)
{
  QuietHDF5 quiet;
  if (!std::ifstream(path).good())
  {
    error = path + ": the file cannot be opened.";
    return false;
  }
  std::string why;
  if (check && !CheckSnapshotFile(path, why))
  {
    error = path + ": " + why + ".";
    return false;
  }
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (file.Id < 0)
  {
    error = path + ": HDF5 cannot open it (not an HDF5 file, or damaged or truncated).";
    return false;
  }
  if (!ReadHeader(file.Id, header))
  {
    error = path + ": no /Header group: not a Gadget or SWIFT snapshot.";
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
Snapshot ReadSnapshot(const std::string& path, int type, bool check)
{
  Snapshot out;
  QuietHDF5 quiet;
  if (type < 0 || type > 5)
  {
    out.Error = "particle type " + std::to_string(type) + " is not one of 0 to 5.";
    return out;
  }
  const std::string group = "PartType" + std::to_string(type);
  // The snapshot's files, from the header of the one named.
  if (!ReadSnapshotHeader(path, out.Header, out.Error, check))
  {
    return out;
  }
  const std::vector<std::string> files = SnapshotFiles(path, out.Header.NumFiles);
  for (const std::string& name : files)
  {
    std::string why;
    if (check && std::ifstream(name).good() && !CheckSnapshotFile(name, why))
    {
      out.Error = name + ": " + why + ".";
      break;
    }
    Handle file(H5Fopen(name.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    if (file.Id < 0)
    {
      out.Error = name + ": HDF5 cannot open it (not an HDF5 file, or damaged or truncated).";
      break;
    }
    SnapshotHeader header;
    if (!ReadHeader(file.Id, header))
    {
      out.Error = name + ": no /Header group: not a Gadget or SWIFT snapshot.";
      break;
    }
    long long count = 0;
    std::vector<SnapshotArray> arrays;
    if (!ReadPart(file.Id, name, group, count, arrays, out))
    {
      break;
    }
    out.Files.push_back(name);
    if (count != header.NumPartThisFile[type])
    {
      out.Warnings.push_back(name + ": " + std::to_string(count) + " particles of type " +
        std::to_string(type) + ", but NumPart_ThisFile says " +
        std::to_string(header.NumPartThisFile[type]) + ".");
    }
    if (count == 0)
    {
      continue;
    }
    if (out.Count == 0)
    {
      out.Arrays = std::move(arrays);
      out.Count = count;
      continue;
    }
    // Append to what the earlier files gave; drop what a file lacks.
    std::vector<SnapshotArray> kept;
    for (SnapshotArray& a : out.Arrays)
    {
      const auto match = std::find_if(arrays.begin(),
        arrays.end(),
        [&](const SnapshotArray& b)
        { return b.Name == a.Name && b.Type == a.Type && b.Components == a.Components; });
      if (match == arrays.end() && a.Name == "Coordinates")
      {
        out.Error = name + ": its Coordinates differ in type from the snapshot's first file's.";
        break;
      }
      if (match == arrays.end())
      {
        out.Warnings.push_back(
          name + ": no " + a.Name + " as in the snapshot's first file: the array is dropped.");
        continue;
      }
      a.Bytes.insert(a.Bytes.end(), match->Bytes.begin(), match->Bytes.end());
      kept.push_back(std::move(a));
    }
    if (!out.Error.empty())
    {
      break;
    }
    out.Arrays = std::move(kept);
    out.Count += count;
  }
  if (!out.Error.empty())
  {
    out.Count = 0;
    out.Arrays.clear();
    return out;
  }
  // One mass for the whole type: MassTable's, as an array.
  const bool masses = std::any_of(out.Arrays.begin(),
    out.Arrays.end(),
    [](const SnapshotArray& a) { return a.Name == "Masses"; });
  if (!masses && out.Count > 0 && out.Header.MassTable[type] > 0.0)
  {
    SnapshotArray mass;
    mass.Name = "Masses";
    mass.Type = SnapshotArray::Float64;
    mass.Bytes.resize(static_cast<size_t>(out.Count) * sizeof(double));
    const double value = out.Header.MassTable[type];
    for (long long i = 0; i < out.Count; ++i)
    {
      std::memcpy(mass.Bytes.data() + i * sizeof(double), &value, sizeof(double));
    }
    out.Arrays.push_back(std::move(mass));
  }
  const long long total = out.Header.NumPartTotal[type];
  if (total > 0 && total != out.Count)
  {
    out.Warnings.push_back(path + ": " + std::to_string(out.Count) + " particles of type " +
      std::to_string(type) + " read, but NumPart_Total says " + std::to_string(total) + ".");
  }
  return out;
}
} // namespace pointsurfaces
