// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psHDF5.h
 * @brief What the HDF5 readers and writers share: a quiet error stack, closing handles, numeric attributes.
 */
#ifndef psHDF5_h
#define psHDF5_h

#include "vtk_hdf5.h"

#include <algorithm>  // For std::copy_n
#include <functional> // For the checking child's probe
#include <mutex>      // For the lock
#include <string>     // For paths and errors
#include <vector>     // For values

namespace pointsurfaces
{
// The lock every HDF5 call of this module holds: a splat file may be read
// on a loading thread (vtkStreamingSplatMapper) beside other HDF5 files, and
// an HDF5 library built without thread safety (Debian's MPI flavours) must
// see one call at a time. Recursive: a reader's method may call another.
inline std::recursive_mutex& HDF5Mutex()
{
  static std::recursive_mutex mutex;
  return mutex;
}

// True in a child process forked to check a file (psSplatFile.cxx): the
// parent forked while holding HDF5Mutex, and the child, alone, must not
// take it again (a recursive mutex locked by the parent's thread is not
// the child's to relock).
inline bool& InCheckingChild()
{
  static bool child = false;
  return child;
}

// HDF5 prints its error stack by default: quiet while we read (our errors
// say what went wrong), restored after. Holds HDF5Mutex meanwhile, so that
// every entry point that quiets the stack is also serialised.
class QuietHDF5
{
public:
  QuietHDF5()
    : Lock(HDF5Mutex(), std::defer_lock)
  {
    if (!InCheckingChild())
    {
      this->Lock.lock();
    }
    H5Eget_auto2(H5E_DEFAULT, &this->Function, &this->Data);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHDF5() { H5Eset_auto2(H5E_DEFAULT, this->Function, this->Data); }
  QuietHDF5(const QuietHDF5&) = delete;
  QuietHDF5& operator=(const QuietHDF5&) = delete;

private:
  std::unique_lock<std::recursive_mutex> Lock;
  H5E_auto2_t Function = nullptr;
  void* Data = nullptr;
};

// An HDF5 identifier, closed when it goes.
class Handle
{
public:
  Handle(hid_t id, herr_t (*close)(hid_t))
    : Id(id)
    , Close(close)
  {
  }
  ~Handle()
  {
    if (this->Id >= 0)
    {
      this->Close(this->Id);
    }
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t Id;

private:
  herr_t (*Close)(hid_t);
};

// Whether `type` is an integer or floating-point type that HDF5 can convert
// safely: an integer of 1, 2, 4 or 8 bytes, or a float of 2, 4 or 8 bytes,
// whose bits (precision, offset, and a float's sign, exponent and mantissa)
// lie within its size. A damaged file can declare, say, a 36-byte float;
// Debian 12's HDF5 1.10 then reads past its conversion buffer (found by
// FuzzSplatFileReader), so such types count as not numeric.
inline bool SaneNumberType(hid_t type)
{
  if (type < 0)
  {
    return false;
  }
  const H5T_class_t kind = H5Tget_class(type);
  const size_t size = H5Tget_size(type);
  const size_t bits = 8 * size;
  const size_t precision = H5Tget_precision(type);
  const int offset = H5Tget_offset(type);
  if (precision == 0 || offset < 0 || precision + static_cast<size_t>(offset) > bits)
  {
    return false;
  }
  if (kind == H5T_INTEGER)
  {
    return size == 1 || size == 2 || size == 4 || size == 8;
  }
  if (kind != H5T_FLOAT || (size != 2 && size != 4 && size != 8))
  {
    return false;
  }
  size_t spos = 0, epos = 0, esize = 0, mpos = 0, msize = 0;
  return H5Tget_fields(type, &spos, &epos, &esize, &mpos, &msize) >= 0 && esize > 0 && msize > 0 &&
    spos < bits && epos + esize <= bits && mpos + msize <= bits;
}

// Whether dataset `dataset` can be read safely: its type passes
// SaneNumberType, and when its layout is compact (values kept in the object
// header) it holds as many bytes as its dataspace says. HDF5 1.10 reads past
// the end of a compact dataset's buffer that a damaged layout message made
// too short.
inline bool SaneDataset(hid_t dataset)
{
  Handle plist(H5Dget_create_plist(dataset), H5Pclose);
  Handle type(H5Dget_type(dataset), H5Tclose);
  Handle space(H5Dget_space(dataset), H5Sclose);
  if (plist.Id < 0 || space.Id < 0 || !SaneNumberType(type.Id))
  {
    return false;
  }
  const hssize_t values = H5Sget_simple_extent_npoints(space.Id);
  return values >= 0 &&
    (H5Pget_layout(plist.Id) != H5D_COMPACT ||
      static_cast<double>(H5Dget_storage_size(dataset)) >=
        static_cast<double>(values) * static_cast<double>(H5Tget_size(type.Id)));
}

// Whether `dataset`'s chunk index (a B-tree) can be walked: true for a
// dataset that is not chunked. The checking children walk it, so that a
// damaged index shows there rather than at a read.
inline bool ChunkIndexReadable(hid_t dataset)
{
  Handle plist(H5Dget_create_plist(dataset), H5Pclose);
  hsize_t chunks = 0;
  return plist.Id >= 0 &&
    (H5Pget_layout(plist.Id) != H5D_CHUNKED || H5Dget_num_chunks(dataset, H5S_ALL, &chunks) >= 0);
}

// Up to `size` numbers of a numeric attribute, as doubles; how many it has
// (0: none, not numeric, or unreadable).
inline int ReadNumbers(hid_t location, const char* name, double* out, int size)
{
  if (H5Aexists(location, name) <= 0)
  {
    return 0;
  }
  Handle attribute(H5Aopen(location, name, H5P_DEFAULT), H5Aclose);
  if (attribute.Id < 0)
  {
    return 0;
  }
  Handle space(H5Aget_space(attribute.Id), H5Sclose);
  Handle type(H5Aget_type(attribute.Id), H5Tclose);
  if (space.Id < 0 || type.Id < 0)
  {
    return 0;
  }
  const hssize_t count = H5Sget_simple_extent_npoints(space.Id);
  if (!SaneNumberType(type.Id) || count < 1 || count > 1024)
  {
    return 0;
  }
  std::vector<double> values(static_cast<size_t>(count));
  if (H5Aread(attribute.Id, H5T_NATIVE_DOUBLE, values.data()) < 0)
  {
    return 0;
  }
  std::copy_n(values.begin(), std::min<hssize_t>(count, size), out);
  return static_cast<int>(count);
}

// Runs `probe()` (which opens and reads `path`'s metadata with HDF5) in a
// forked child process first, once per version of the file (path,
// modification time, size) and kind of probe (`what`) in this process:
// HDF5 1.10 (Debian 12) can crash on a damaged file's metadata (a use
// after free in H5Aexists, found by fuzzing), and then only the child
// ends. False, with `error` set, when the child crashed or ended without
// a verdict; true when the probe ran to its end (whatever it found: the
// caller's own reading then says what is wrong), when no child could be
// made, or when the child did not finish within 60 s (it is killed). The
// caller holds HDF5Mutex (QuietHDF5), so that no other thread of ours is
// inside HDF5 at the fork; the child does not take it (InCheckingChild).
// Where child processes are not supported (not Linux), true at once.
bool CheckInChild(const std::string& path,
  const char* what,
  const std::function<void()>& probe,
  std::string& error);

} // namespace pointsurfaces

#endif
