// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psHDF5.h
 * @brief What the HDF5 readers and writers share: a quiet error stack, closing handles, numeric attributes.
 */
#ifndef psHDF5_h
#define psHDF5_h

#include "vtk_hdf5.h"

#include <algorithm> // For std::copy_n
#include <mutex>     // For the lock
#include <vector>    // For values

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

// HDF5 prints its error stack by default: quiet while we read (our errors
// say what went wrong), restored after. Holds HDF5Mutex meanwhile, so that
// every entry point that quiets the stack is also serialised.
class QuietHDF5
{
public:
  QuietHDF5()
    : Lock(HDF5Mutex())
  {
    H5Eget_auto2(H5E_DEFAULT, &this->Function, &this->Data);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHDF5() { H5Eset_auto2(H5E_DEFAULT, this->Function, this->Data); }
  QuietHDF5(const QuietHDF5&) = delete;
  QuietHDF5& operator=(const QuietHDF5&) = delete;

private:
  std::lock_guard<std::recursive_mutex> Lock;
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
  const H5T_class_t kind = H5Tget_class(type.Id);
  const hssize_t count = H5Sget_simple_extent_npoints(space.Id);
  if ((kind != H5T_INTEGER && kind != H5T_FLOAT) || count < 1 || count > 1024)
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

} // namespace pointsurfaces

#endif
