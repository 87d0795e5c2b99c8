// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkGadgetHDF5Reader on snapshots written here with HDF5 (exact values) and
// on a subset of a real Gadget-4 snapshot (IO/Testing/Data/gadget):
// - Gadget layout: every dataset of the type as a point array of its type
//   (float coordinates stay float, 64-bit IDs stay 64-bit), Masses from the
//   MassTable when the type has none, the header in field data, Time as the
//   time step; datasets of the wrong length, a string type or a damaged
//   number type (a 36-byte float) skipped with a warning; the same read
//   without the child's check; a type with no particles: an empty output,
//   no error;
// - SWIFT layout split over two files: both read in order from either one,
//   Code "SWIFT", BoxSize of three numbers;
// - the real snapshot: 2000 gas particles with SmoothingLength and Density,
//   Masses from its MassTable, redshift 5.04;
// - bad input: a missing file, an empty file, a text file, truncated copies, no Header, no
//   Coordinates, Coordinates of two columns, parts whose Coordinates differ
//   in type, a missing part of a split snapshot: one error each and an empty
//   output.
#include "psGadgetHDF5.h"
#include "psIOTestSupport.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkGadgetHDF5Reader.h"
#include "vtkInformation.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTypeInt64Array.h"
#include "vtkTypeUInt64Array.h"
#include "vtk_hdf5.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>

using namespace pointsurfaces_test;
using pointsurfaces::SnapshotArray;

namespace
{
template<typename T>
SnapshotArray Array(const std::string& name,
  SnapshotArray::Kind kind,
  int components,
  const std::vector<T>& values)
{
  SnapshotArray a;
  a.Name = name;
  a.Type = kind;
  a.Components = components;
  a.Bytes.resize(values.size() * sizeof(T));
  std::memcpy(a.Bytes.data(), values.data(), a.Bytes.size());
  return a;
}

std::string Temp(const std::string& name)
{
  const char* dir = std::getenv("POINTSURFACES_TEMP_DIR");
  return std::string(dir ? dir : "/tmp") + "/" + name;
}

void Write(const std::string& path,
  const pointsurfaces::SnapshotHeader& header,
  const std::vector<pointsurfaces::SnapshotPart>& parts)
{
  std::string error;
  Check(pointsurfaces::WriteSnapshotFile(path, header, parts, error), "writes " + path + error);
}

vtkPolyData* Read(vtkGadgetHDF5Reader* reader,
  const std::string& path,
  int type,
  vtkTest::ErrorObserver* observer)
{
  reader->SetFileName(path.c_str());
  reader->SetParticleType(type);
  observer->Clear();
  reader->Update();
  return reader->GetOutput();
}

double Field(vtkPolyData* poly, const char* name, int component = 0)
{
  vtkAbstractArray* a = poly->GetFieldData()->GetAbstractArray(name);
  auto* d = vtkDataArray::SafeDownCast(a);
  return d && d->GetNumberOfTuples() > 0 ? d->GetComponent(0, component) : -12345.0;
}

// A copy of `path`'s first `bytes` bytes.
std::string Truncated(const std::string& path, size_t bytes)
{
  std::ifstream in(path, std::ios::binary);
  std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string out = Temp("truncated_" + std::to_string(bytes) + ".hdf5");
  std::ofstream(out, std::ios::binary).write(data.data(), std::min(bytes, data.size()));
  return out;
}
} // namespace

int TestGadgetHDF5Reader(int, char*[])
{
  vtkNew<vtkGadgetHDF5Reader> reader;
  vtkNew<vtkTest::ErrorObserver> observer;
  reader->AddObserver(vtkCommand::ErrorEvent, observer);
  reader->AddObserver(vtkCommand::WarningEvent, observer);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);

  // A Gadget-layout file: 5 gas particles, 3 dark matter of one mass.
  pointsurfaces::SnapshotHeader header;
  header.Time = 0.25;
  header.Redshift = 3.0;
  header.BoxSize[0] = header.BoxSize[1] = header.BoxSize[2] = 100.0;
  header.MassTable[1] = 2.5;
  header.NumPartTotal[0] = 5;
  header.NumPartTotal[1] = 3;
  std::vector<float> gasXYZ, gasV;
  for (int i = 0; i < 15; ++i)
  {
    gasXYZ.push_back(0.5f * i);
    gasV.push_back(-1.0f * i);
  }
  pointsurfaces::SnapshotPart gas, dark;
  gas.Type = 0;
  gas.Arrays = { Array("Coordinates", SnapshotArray::Float32, 3, gasXYZ),
    Array("Velocities", SnapshotArray::Float32, 3, gasV),
    Array("ParticleIDs",
      SnapshotArray::UInt64,
      1,
      std::vector<unsigned long long>{ 1ULL << 40, 2, 3, 4, 5 }),
    Array("Masses", SnapshotArray::Float64, 1, std::vector<double>{ 1, 1, 1, 2, 2 }),
    Array("SmoothingLength", SnapshotArray::Float32, 1, std::vector<float>{ 1, 2, 3, 4, 5 }),
    Array("Density", SnapshotArray::Float32, 1, std::vector<float>{ 5, 4, 3, 2, 1 }),
    Array("BadRows", SnapshotArray::Float32, 1, std::vector<float>{ 1, 2, 3, 4 }) };
  dark.Type = 1;
  dark.Arrays = {
    Array(
      "Coordinates", SnapshotArray::Float64, 3, std::vector<double>{ 1, 2, 3, 4, 5, 6, 7, 8, 9 }),
    Array("ParticleIDs", SnapshotArray::Int64, 1, std::vector<long long>{ -1, 7, 9 })
  };
  const std::string gadget = Temp("gadget_snapshot.hdf5");
  Write(gadget, header, { gas, dark });
  {
    // A string dataset, which no point array can hold.
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    // HDF5 1.14.4 and later refuse to write the 36-byte float below unless told to.
    hid_t access = H5Pcreate(H5P_FILE_ACCESS);
#ifdef H5F_RFIC_UNUSUAL_NUM_UNUSED_NUMERIC_BITS
    H5Pset_relax_file_integrity_checks(access, H5F_RFIC_UNUSUAL_NUM_UNUSED_NUMERIC_BITS);
#endif
    hid_t file = H5Fopen(gadget.c_str(), H5F_ACC_RDWR, access);
    H5Pclose(access);
    hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, 8);
    const hsize_t rows = 5;
    hid_t space = H5Screate_simple(1, &rows, nullptr);
    hid_t set =
      H5Dcreate2(file, "PartType0/Names", type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const char names[40] = "aaaaaaabbbbbbbcccccccdddddddeeeeeee";
    H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, names);
    H5Dclose(set);
    // A float type 36 bytes wide: HDF5 1.10 reads past its conversion
    // buffer on such a type, so the reader skips it (SaneNumberType).
    hid_t wide = H5Tcopy(H5T_IEEE_F32LE);
    H5Tset_size(wide, 36);
    set =
      H5Dcreate2(file, "PartType0/WideFloat", wide, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dclose(set);
    H5Tclose(wide);
    H5Sclose(space);
    H5Tclose(type);
    H5Fclose(file);
  }
  Check(vtkGadgetHDF5Reader::CanReadFile(gadget.c_str()), "CanReadFile on a snapshot");
  vtkPolyData* out = Read(reader, gadget, 0, observer);
  Check(!observer->GetError(), "a Gadget snapshot reads without an error");
  Check(observer->GetWarning() &&
      observer->GetWarningMessage().find("BadRows") != std::string::npos &&
      observer->GetWarningMessage().find("Names") != std::string::npos &&
      observer->GetWarningMessage().find("WideFloat") != std::string::npos,
    "a dataset of the wrong length, a string dataset and a 36-byte float (refused by our type "
    "check, or by HDF5 1.14's open) are skipped with a warning");
  Check(!out->GetPointData()->GetArray("WideFloat"), "no array from the 36-byte float");
  {
    // Read without the child's check first: the same particles.
    vtkNew<vtkGadgetHDF5Reader> inProcess;
    inProcess->CheckInChildProcessOff();
    inProcess->SetFileName(gadget.c_str());
    inProcess->Update();
    Check(inProcess->GetOutput()->GetNumberOfPoints() == 5,
      "without the child's check the snapshot reads the same particles");
  }
  Check(out->GetNumberOfPoints() == 5 && out->GetNumberOfVerts() == 5, "5 gas particles");
  Check(vtkFloatArray::SafeDownCast(out->GetPoints()->GetData()) != nullptr,
    "float coordinates stay float");
  double p[3];
  out->GetPoint(4, p);
  Check(p[0] == 6.0 && p[1] == 6.5 && p[2] == 7.0, "coordinates in order");
  vtkPointData* pd = out->GetPointData();
  auto* ids = vtkTypeUInt64Array::SafeDownCast(pd->GetArray("ParticleIDs"));
  Check(ids && ids->GetValue(0) == (1ULL << 40), "64-bit particle IDs stay 64-bit");
  Check(pd->GetArray("Velocities") && pd->GetArray("Velocities")->GetNumberOfComponents() == 3 &&
      pd->GetArray("Velocities")->GetComponent(1, 2) == -5.0,
    "velocities, 3 components");
  Check(pd->GetArray("SmoothingLength") && pd->GetArray("Density") && pd->GetArray("Masses") &&
      pd->GetArray("Masses")->GetComponent(3, 0) == 2.0 && !pd->GetArray("BadRows") &&
      !pd->GetAbstractArray("Names"),
    "smoothing lengths, densities and masses as point arrays");
  Check(Field(out, "Time") == 0.25 && Field(out, "Redshift") == 3.0 &&
      Field(out, "BoxSize", 2) == 100.0 && Field(out, "NumPart_Total", 1) == 3.0 &&
      Field(out, "ParticleType") == 0.0,
    "the header in field data");
  vtkInformation* info = reader->GetOutputInformation(0);
  Check(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()) == 1 &&
      info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[0] == 0.25,
    "Time is the time step");

  out = Read(reader, gadget, 1, observer);
  Check(!observer->GetError() && out->GetNumberOfPoints() == 3, "3 dark matter particles");
  Check(out->GetPointData()->GetArray("Masses") &&
      out->GetPointData()->GetArray("Masses")->GetComponent(2, 0) == 2.5,
    "Masses from the MassTable");
  Check(vtkTypeInt64Array::SafeDownCast(out->GetPointData()->GetArray("ParticleIDs")) != nullptr,
    "signed 64-bit IDs");
  out = Read(reader, gadget, 4, observer);
  Check(!observer->GetError() && out->GetNumberOfPoints() == 0, "no stars: empty, no error");

  // SWIFT, split over two files.
  pointsurfaces::SnapshotHeader swift = header;
  swift.Code = "SWIFT";
  swift.NumFiles = 2;
  swift.BoxSize[1] = 50.0;
  swift.NumPartTotal[0] = 5;
  swift.NumPartTotal[1] = 0;
  swift.MassTable[1] = 0.0;
  pointsurfaces::SnapshotPart first, second;
  first.Arrays = {
    Array(
      "Coordinates", SnapshotArray::Float64, 3, std::vector<double>{ 0, 0, 0, 1, 1, 1, 2, 2, 2 }),
    Array("SmoothingLengths", SnapshotArray::Float32, 1, std::vector<float>{ 1, 1, 1 }),
    Array("OnlyHere", SnapshotArray::Float32, 1, std::vector<float>{ 1, 1, 1 })
  };
  second.Arrays = {
    Array("Coordinates", SnapshotArray::Float64, 3, std::vector<double>{ 3, 3, 3, 4, 4, 4 }),
    Array("SmoothingLengths", SnapshotArray::Float32, 1, std::vector<float>{ 2, 2 })
  };
  const std::string part0 = Temp("swift_snap.0.hdf5"), part1 = Temp("swift_snap.1.hdf5");
  Write(part0, swift, { first });
  Write(part1, swift, { second });
  out = Read(reader, part1, 0, observer);
  Check(!observer->GetError() && out->GetNumberOfPoints() == 5,
    "a split snapshot reads whole from its second file");
  out->GetPoint(3, p);
  Check(p[0] == 3.0 && out->GetPointData()->GetArray("SmoothingLengths") &&
      out->GetPointData()->GetArray("SmoothingLengths")->GetComponent(4, 0) == 2.0,
    "the parts in order");
  Check(!out->GetPointData()->GetArray("OnlyHere") &&
      observer->GetWarningMessage().find("OnlyHere") != std::string::npos,
    "an array one part lacks is dropped with a warning");
  auto* code = vtkStringArray::SafeDownCast(out->GetFieldData()->GetAbstractArray("Code"));
  Check(code && code->GetValue(0) == "SWIFT" && Field(out, "BoxSize", 1) == 50.0,
    "SWIFT's code and box");

  // The real snapshot's subset.
  const char* data = std::getenv("POINTSURFACES_IO_DATA");
  const std::string real = std::string(data ? data : ".") + "/gadget/lcdm_gas_z5_subset.hdf5";
  out = Read(reader, real, 0, observer);
  Check(
    !observer->GetError() && out->GetNumberOfPoints() == 2000, "2000 gas particles of Gadget-4");
  Check(out->GetPointData()->GetArray("SmoothingLength") &&
      out->GetPointData()->GetArray("Density") && out->GetPointData()->GetArray("Masses") &&
      std::abs(out->GetPointData()->GetArray("Masses")->GetComponent(0, 0) - 4.23508) < 1e-4,
    "the Gadget-4 gas has smoothing lengths, densities and its MassTable's mass");
  Check(std::abs(Field(out, "Redshift") - 5.04011) < 1e-4, "the Gadget-4 redshift");
  double range[2] = { 0.0, 0.0 };
  if (vtkDataArray* h = out->GetPointData()->GetArray("SmoothingLength"))
  {
    h->GetRange(range);
  }
  std::cout << "Gadget-4 subset: " << out->GetNumberOfPoints() << " gas particles, smoothing "
            << "lengths " << range[0] << " to " << range[1] << ", redshift "
            << Field(out, "Redshift") << "\n";

  // Bad input.
  ExpectReadError<vtkGadgetHDF5Reader>(Temp("no_such_snapshot.hdf5"), "cannot be opened");
  ExpectEmptyFileError<vtkGadgetHDF5Reader>(Temp("empty.hdf5"));
  const std::string text = Temp("not_a_snapshot.hdf5");
  std::ofstream(text) << "ITEM: TIMESTEP\n0\n";
  ExpectReadError<vtkGadgetHDF5Reader>(text, "HDF5 cannot open it");
  Check(!vtkGadgetHDF5Reader::CanReadFile(text.c_str()), "CanReadFile on text");
  std::ifstream sized(gadget, std::ios::binary | std::ios::ate);
  const size_t bytes = static_cast<size_t>(sized.tellg());
  for (size_t cut : { size_t(0), size_t(100), bytes / 4, bytes / 2, bytes - 1 })
  {
    ExpectReadError<vtkGadgetHDF5Reader>(
      Truncated(gadget, cut), cut == 0 ? "is empty" : "HDF5 cannot open it");
  }
  {
    const std::string empty = Temp("no_header.hdf5");
    H5Fclose(H5Fcreate(empty.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
    ExpectReadError<vtkGadgetHDF5Reader>(empty, "no /Header");
  }
  pointsurfaces::SnapshotPart flat, none;
  flat.Arrays = { Array(
    "Coordinates", SnapshotArray::Float32, 2, std::vector<float>{ 1, 2, 3, 4 }) };
  none.Arrays = { Array("Velocities", SnapshotArray::Float32, 3, std::vector<float>{ 1, 2, 3 }) };
  const std::string flatFile = Temp("flat.hdf5"), noneFile = Temp("nocoordinates.hdf5");
  Write(flatFile, header, { flat });
  Write(noneFile, header, { none });
  ExpectReadError<vtkGadgetHDF5Reader>(flatFile, "not a list of 3-D points");
  ExpectReadError<vtkGadgetHDF5Reader>(noneFile, "no Coordinates");
  // Coordinates of another type in the second file: an error, not points lost.
  pointsurfaces::SnapshotPart doubles = second;
  doubles.Arrays[0] =
    Array("Coordinates", SnapshotArray::Float32, 3, std::vector<float>{ 3, 3, 3, 4, 4, 4 });
  Write(part1, swift, { doubles });
  ExpectReadError<vtkGadgetHDF5Reader>(part1, "Coordinates differ in type");
  std::remove(part0.c_str());
  ExpectReadError<vtkGadgetHDF5Reader>(part1, "swift_snap.0.hdf5");

  if (Failures == 0)
  {
    std::cout << "vtkGadgetHDF5Reader: all checks passed\n";
  }
  return Failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
