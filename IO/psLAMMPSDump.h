// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psLAMMPSDump.h
 * @brief LAMMPS text dump files (`dump atom`, `dump custom`), as plain functions.
 *
 * A dump holds one snapshot after another, each as
 *
 *     ITEM: TIMESTEP            (optionally preceded by ITEM: TIME and ITEM: UNITS)
 *     1000
 *     ITEM: NUMBER OF ATOMS
 *     4000
 *     ITEM: BOX BOUNDS pp pp pp (or "xy xz yz pp pp pp" with a third value per line)
 *     xlo xhi [xy]
 *     ylo yhi [xz]
 *     zlo zhi [yz]
 *     ITEM: ATOMS id type x y z vx ...
 *     one line per atom, the columns named above
 *
 * ScanDump() finds every snapshot (its timestep, time and byte offset)
 * without reading the atoms, so a reader can offer the time steps and read
 * only the one asked for; ReadSnapshot() reads one. Every count is checked
 * against what the file holds: a truncated or damaged file gives an error
 * message, never a crash or an allocation the file cannot back.
 */
#ifndef psLAMMPSDump_h
#define psLAMMPSDump_h

#include <cstdint> // For offsets
#include <istream> // For the input
#include <string>  // For names and errors
#include <vector>  // For snapshots and columns

namespace pointsurfaces
{
struct DumpSnapshotInfo
{
  long long Timestep = 0;
  double Time = 0.0;           ///< ITEM: TIME when the file has it, else the timestep
  bool HasTime = false;        ///< ITEM: TIME was there
  std::int64_t Offset = 0;     ///< byte offset of the snapshot's first ITEM line
  long long NumberOfAtoms = 0; ///< as the header says
};

struct DumpSnapshot
{
  DumpSnapshotInfo Info;
  double Box[6] = { 0, 0, 0, 0, 0, 0 }; ///< xlo xhi ylo yhi zlo zhi of the box itself
  double Tilt[3] = { 0, 0, 0 };         ///< xy xz yz (triclinic boxes), else 0
  bool Triclinic = false;
  std::string Boundary;             ///< the flags after BOX BOUNDS, e.g. "pp pp pp"
  std::vector<std::string> Columns; ///< the names after ITEM: ATOMS
  std::vector<double> Values;       ///< NumberOfAtoms x Columns, row by row
};

/**
 * Every snapshot of the dump in `in`, in file order. On a damaged file,
 * returns the snapshots before the damage and sets `error`.
 */
std::vector<DumpSnapshotInfo> ScanDump(std::istream& in, std::string& error);

/**
 * The snapshot that starts at `offset` (from ScanDump). Returns false and
 * sets `error` when it is damaged or truncated.
 */
bool ReadSnapshot(std::istream& in,
  std::int64_t offset,
  DumpSnapshot& snapshot,
  std::string& error);

/**
 * Positions of the snapshot's atoms (3 per atom), from the first complete
 * set of columns among unwrapped (xu yu zu), plain (x y z), scaled
 * unwrapped (xsu ysu zsu) and scaled (xs ys zs) coordinates, scaled ones
 * mapped through the (possibly triclinic) box. `used` receives the three
 * column indices. Returns false when the snapshot has no coordinates.
 */
bool SnapshotPositions(const DumpSnapshot& snapshot, std::vector<double>& xyz, int used[3]);
} // namespace pointsurfaces

#endif
