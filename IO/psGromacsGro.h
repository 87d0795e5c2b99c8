// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psGromacsGro.h
 * @brief GROMACS .gro coordinate files (one frame or a trajectory of frames), as plain functions.
 *
 * A frame is a title line (GROMACS writes "t= 10.00000 step= 5000" in it for
 * trajectory frames), the atom count, one fixed-column line per atom
 *
 *     residue number (5) residue name (5) atom name (5) atom number (5)
 *     x y z (nm, each as wide as the distance between two decimal points:
 *            8 for the usual %8.3f)  [vx vy vz (nm/ps, as wide, one more decimal)]
 *
 * and the box line (v1x v2y v3z, or nine numbers for a triclinic box: then
 * v1y v1z v2x v2z v3x v3y). ScanGro() finds the frames without reading the
 * atoms; ReadGroFrame() reads one. Counts are checked against the file.
 */
#ifndef psGromacsGro_h
#define psGromacsGro_h

#include "psElements.h" // For atoms' elements and radii

#include <cstdint> // For offsets
#include <istream> // For the input
#include <string>  // For names and errors
#include <vector>  // For frames and atoms

namespace pointsurfaces
{
struct GroFrameInfo
{
  std::int64_t Offset = 0; ///< byte offset of the title line
  long long NumberOfAtoms = 0;
  double Time = 0.0; ///< "t=" of the title, else the frame's index
  bool HasTime = false;
  long long Step = -1; ///< "step=" of the title, else -1
};

struct GroFrame
{
  GroFrameInfo Info;
  std::string Title;
  std::vector<int> ResidueNumbers;
  std::vector<std::string> ResidueNames;
  std::vector<std::string> AtomNames;
  std::vector<int> AtomNumbers;
  std::vector<double> Positions;  ///< 3 per atom, nm
  std::vector<double> Velocities; ///< 3 per atom (nm/ps) when the file has them, else empty
  double Box[9] = { 0, 0, 0, 0, 0, 0, 0, 0, 0 }; ///< v1x v2y v3z v1y v1z v2x v2z v3x v3y
};

/** Every frame of the .gro in `in`; on damage, those before it and `error`. */
std::vector<GroFrameInfo> ScanGro(std::istream& in, std::string& error);

/** The frame at `offset` (from ScanGro); false and `error` when it is damaged. */
bool ReadGroFrame(std::istream& in, const GroFrameInfo& where, GroFrame& frame, std::string& error);

} // namespace pointsurfaces

#endif
