// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: vtkGadgetHDF5Reader on snapshots built from the input. See README.md.
//
// HDF5's own parser of the container is not ours to fuzz (libhdf5 1.10 has
// known crashes on corrupt metadata; truncation, which it detects at opening,
// is in the unit test). The input is read as a recipe for a well-formed HDF5
// file whose contents are anything: header numbers (NaN, infinite, huge
// counts, several files of which only the first exists, SWIFT or Gadget),
// and datasets of any particle type, name, numeric type, column count and
// row count, with the input's bytes as values. Then every particle type is
// read from it, and the output touched.
#include "psFuzzFile.h"
#include "psGadgetHDF5.h"
#include "vtkGadgetHDF5Reader.h"

#include <cstring>

namespace
{
class Bytes
{
public:
  Bytes(const uint8_t* data, size_t size)
    : Data(data)
    , Size(size)
  {
  }
  bool Empty() const { return this->At >= this->Size; }
  uint8_t Next() { return this->At < this->Size ? this->Data[this->At++] : 0; }
  double Number()
  {
    double v = 0.0;
    uint8_t raw[8];
    for (uint8_t& b : raw)
    {
      b = this->Next();
    }
    std::memcpy(&v, raw, sizeof(v));
    return v;
  }

private:
  const uint8_t* Data;
  size_t Size;
  size_t At = 0;
};

const char* const Names[] = { "Coordinates",
  "Velocities",
  "ParticleIDs",
  "Masses",
  "SmoothingLength",
  "SmoothingLengths",
  "Density",
  "Densities",
  "InternalEnergy",
  "Potential",
  "Metallicity",
  "StarFormationRate" };
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  Bytes in(data, size);
  pointsurfaces::SnapshotHeader header;
  const uint8_t flags = in.Next();
  header.Code = (flags & 1) ? "SWIFT" : "Gadget";
  header.NumFiles = 1 + ((flags >> 1) & 3); // parts 1.. do not exist
  header.Time = (flags & 8) ? in.Number() : 0.5;
  if (flags & 16)
  {
    for (int k = 0; k < 6; ++k)
    {
      header.MassTable[k] = in.Number();
      header.NumPartTotal[k] = static_cast<long long>(in.Next()) << (in.Next() % 40);
    }
  }
  std::vector<pointsurfaces::SnapshotPart> parts;
  while (!in.Empty() && parts.size() < 12)
  {
    pointsurfaces::SnapshotPart part;
    part.Type = in.Next() % 6;
    const int arrays = in.Next() % 5;
    for (int a = 0; a < arrays && !in.Empty(); ++a)
    {
      pointsurfaces::SnapshotArray array;
      array.Name = Names[in.Next() % (sizeof(Names) / sizeof(Names[0]))];
      array.Type = static_cast<pointsurfaces::SnapshotArray::Kind>(in.Next() % 6);
      array.Components = 1 + in.Next() % 4;
      const size_t rows = in.Next() % 40;
      const size_t width = array.Type == pointsurfaces::SnapshotArray::Float32 ||
          array.Type == pointsurfaces::SnapshotArray::Int32 ||
          array.Type == pointsurfaces::SnapshotArray::UInt32
        ? 4
        : 8;
      array.Bytes.resize(rows * array.Components * width);
      for (uint8_t& b : array.Bytes)
      {
        b = in.Next();
      }
      part.Arrays.push_back(std::move(array));
    }
    parts.push_back(std::move(part));
  }
  // Two parts of one type in one file cannot be: HDF5 refuses the second group.
  const std::string path = pointsurfaces::FuzzFile(nullptr, 0, "0.hdf5");
  std::string error;
  pointsurfaces::WriteSnapshotFile(path, header, parts, error);
  for (int type = 0; type < 6; ++type)
  {
    vtkNew<vtkGadgetHDF5Reader> reader;
    reader->SetFileName(path.c_str());
    reader->SetParticleType(type);
    // HDF5 wrote the file: there is no damaged metadata for a checking
    // child to meet, and a fork per input would slow the run eightfold.
    reader->CheckInChildProcessOff();
    reader->Update();
    double bounds[6];
    reader->GetOutput()->GetBounds(bounds);
  }
  return 0;
}
