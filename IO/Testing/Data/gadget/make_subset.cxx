// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Writes the first N particles of one type of a Gadget or SWIFT HDF5 snapshot,
// every dataset and the header kept, as a new snapshot: how
// lcdm_gas_z5_subset.hdf5 was made from a Gadget-4 snapshot (see
// ../README.md). Built by hand from the repository root:
//
//   g++ -std=c++17 -O2 -I IO/HDF5 -I /usr/include/vtk-9.1 -I /usr/include/hdf5/serial \
//     IO/Testing/Data/gadget/make_subset.cxx IO/HDF5/psGadgetHDF5.cxx \
//     -L /usr/lib/x86_64-linux-gnu/hdf5/serial -lhdf5 -o make_subset
//   ./make_subset snapshot.hdf5 0 2000 subset.hdf5
#include "psGadgetHDF5.h"

#include <cstdlib>
#include <iostream>

int main(int argc, char* argv[])
{
  if (argc != 5)
  {
    std::cerr << "usage: make_subset snapshot.hdf5 type count out.hdf5\n";
    return 2;
  }
  const int type = std::atoi(argv[2]);
  const long long keep = std::atoll(argv[3]);
  pointsurfaces::Snapshot snapshot = pointsurfaces::ReadSnapshot(argv[1], type);
  if (!snapshot.Error.empty())
  {
    std::cerr << snapshot.Error << "\n";
    return 1;
  }
  const long long count = std::min(keep, snapshot.Count);
  pointsurfaces::SnapshotPart part;
  part.Type = type;
  for (pointsurfaces::SnapshotArray& a : snapshot.Arrays)
  {
    const size_t row = a.Bytes.size() / static_cast<size_t>(snapshot.Count);
    if (a.Name == "Masses" && snapshot.Header.MassTable[type] > 0.0)
    {
      continue; // the MassTable's, as in the original
    }
    a.Bytes.resize(row * static_cast<size_t>(count));
    part.Arrays.push_back(std::move(a));
  }
  pointsurfaces::SnapshotHeader header = snapshot.Header;
  for (long long& total : header.NumPartTotal)
  {
    total = 0;
  }
  header.NumPartTotal[type] = count;
  header.NumFiles = 1;
  std::string error;
  if (!pointsurfaces::WriteSnapshotFile(argv[4], header, { part }, error))
  {
    std::cerr << error << "\n";
    return 1;
  }
  std::cout << count << " particles of type " << type << " written to " << argv[4] << "\n";
  return 0;
}
