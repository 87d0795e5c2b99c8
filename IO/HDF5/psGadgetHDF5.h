// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psGadgetHDF5.h
 * @brief Gadget-2/4 and SWIFT HDF5 snapshots, read with HDF5's C API: no VTK pipeline here.
 *
 * The layout (Gadget-2 user guide, "Format 3"; SWIFT writes the same):
 * a group /Header whose attributes hold NumPart_ThisFile, NumPart_Total,
 * MassTable, Time, Redshift, BoxSize and NumFilesPerSnapshot, and a group
 * /PartTypeN per particle type (0 gas, 1 dark matter, 4 stars, 5 black holes)
 * with one dataset per quantity, one row per particle: Coordinates (N x 3),
 * Velocities, ParticleIDs, Masses (absent when MassTable gives the type one
 * mass), and for gas SmoothingLength (Gadget; SWIFT: SmoothingLengths),
 * Density (SWIFT: Densities), InternalEnergy and more. A snapshot may be
 * split over NumFilesPerSnapshot files named base.0.hdf5, base.1.hdf5, ...
 *
 * ReadSnapshot reads one particle type, every dataset of its group with one
 * row per particle as an array (float, double or integer, as stored), over
 * all files of the snapshot. What it cannot use (a dataset whose rows do not
 * match, a compound or string type) is skipped with a warning; what makes
 * the snapshot unreadable (no HDF5 file, a truncated file, which HDF5 finds
 * at opening, no Header, no Coordinates of 3 columns) is an error and no
 * particles.
 */
#ifndef psGadgetHDF5_h
#define psGadgetHDF5_h

#include <string>
#include <vector>

namespace pointsurfaces
{
/** A dataset of one particle type, rows = particles, as stored. */
struct SnapshotArray
{
  enum Kind
  {
    Float32,
    Float64,
    Int32,
    Int64,
    UInt32,
    UInt64
  };
  std::string Name;
  Kind Type = Float64;
  int Components = 1;
  std::vector<unsigned char> Bytes; ///< rows x Components values of Type
};

/** /Header's attributes (those missing stay at their defaults). */
struct SnapshotHeader
{
  double Time = 0.0;     ///< the scale factor in cosmological runs
  double Redshift = 0.0; ///< 0 when absent
  double BoxSize[3] = { 0.0, 0.0, 0.0 };
  double MassTable[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  long long NumPartThisFile[6] = { 0, 0, 0, 0, 0, 0 };
  long long NumPartTotal[6] = { 0, 0, 0, 0, 0, 0 };
  int NumFiles = 1;
  std::string Code = "Gadget"; ///< "SWIFT" when the file says so (a /Code group)
};

/** One particle type of a snapshot. */
struct Snapshot
{
  SnapshotHeader Header;
  long long Count = 0;
  std::vector<SnapshotArray> Arrays; ///< Coordinates first
  std::vector<std::string> Files;    ///< the files read
  std::vector<std::string> Warnings;
  std::string Error; ///< empty when readable; then Count may still be 0
};

/** One particle type of one file, for WriteSnapshotFile. */
struct SnapshotPart
{
  int Type = 0;
  std::vector<SnapshotArray> Arrays; ///< rows = Bytes / (value size x Components)
};

/**
 * Writes one snapshot file in the layout ReadSnapshot reads: the header's
 * attributes (NumPart_ThisFile from the parts' Coordinates, BoxSize as one
 * number for Gadget and three for SWIFT, a /Code group for SWIFT) and one
 * group per part. For test data, subsets of real snapshots and fuzzing.
 */
bool WriteSnapshotFile(const std::string& path,
  const SnapshotHeader& header,
  const std::vector<SnapshotPart>& parts,
  std::string& error);

/**
 * Opens `path`, its header and every dataset of its PartType groups (type,
 * layout, chunk index; no values) in a forked child process first, once per
 * file version (CheckInChild, psHDF5.h): false with `error` set when HDF5
 * crashed there. Where HDF5 1.10 crashes on a damaged file, the readers
 * thus report it instead of ending the program.
 */
bool CheckSnapshotFile(const std::string& path, std::string& error);

/** Is `path` an HDF5 file with a /Header group (a Gadget or SWIFT snapshot)? Checked first. */
bool IsGadgetSnapshot(const std::string& path);

/**
 * The files of the snapshot that `path` belongs to: path itself, or, when its
 * Header says NumFilesPerSnapshot = n > 1 and it is named base.k.hdf5,
 * base.0.hdf5 to base.(n-1).hdf5.
 */
std::vector<std::string> SnapshotFiles(const std::string& path, int numFiles);

/**
 * The header of `path` into `header`; false with `error` said when it is no
 * snapshot. With `check`, the file is checked in a child first
 * (CheckSnapshotFile).
 */
bool ReadSnapshotHeader(const std::string& path,
  SnapshotHeader& header,
  std::string& error,
  bool check = true);

/**
 * Reads particle type `type` (0 to 5) of the snapshot of `path` (every file
 * of it). With `check`, each file is checked in a child first.
 */
Snapshot ReadSnapshot(const std::string& path, int type, bool check = true);
} // namespace pointsurfaces

#endif
