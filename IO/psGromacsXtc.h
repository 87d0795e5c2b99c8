// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psGromacsXtc.h
 * @brief GROMACS .xtc compressed trajectories, as plain functions: a frame index and a checked decoder.
 *
 * An .xtc file is a sequence of XDR (big-endian) frames:
 *
 *     magic 1995, natoms, step, time (float), box (9 floats, the box
 *     vectors as rows), natoms again, then either 3 natoms floats (at
 *     most 9 atoms), or the compressed block: precision (float),
 *     minint[3], maxint[3], smallidx, a byte count and that many bytes
 *     (padded to 4) of bit-packed integer coordinates.
 *
 * Positions are integers (nm times the precision, 1000 by default) packed
 * by Frans van Hoesel's scheme: each atom's triple is coded in as many bits
 * as the frame's range needs, and runs of close atoms (a water molecule)
 * as small differences whose bit width adapts from atom to atom.
 *
 * Why not Debian's libgromacs: its reader (read_first_frame and
 * read_next_frame, GROMACS 2022.5) writes past its buffers on a damaged
 * frame. Of 600 random byte changes inside the coded blocks of a valid
 * 4-frame file, 143 crashed it (heap corruption or SIGSEGV), and changing a
 * frame's atom count crashed it too. A reader that ParaView loads must
 * reject such files with an error, so this decoder checks every count, index
 * and bit read against the frame. Its tests compare every frame with what
 * GROMACS itself decodes (`gmx trjconv -o .g96`, 9 decimals).
 *
 * ScanXtc() indexes the frames from their headers without decoding them;
 * ReadXtcFrame() decodes one. Not read: the 64-bit frames (magic 2023) that
 * GROMACS 2023 and later write for systems of hundreds of millions of atoms,
 * and a small-difference size index of 73, past the end of the format's
 * table (GROMACS's encoder can reach it at precisions of 1e7 and finer).
 */
#ifndef psGromacsXtc_h
#define psGromacsXtc_h

#include <cstddef> // For sizes
#include <cstdint> // For offsets
#include <istream> // For the input
#include <string>  // For errors
#include <vector>  // For frames and positions

namespace pointsurfaces
{
/** One frame's header, as ScanXtc() found it. */
struct XtcFrameInfo
{
  std::int64_t Offset = 0; ///< byte offset of the frame's magic number
  std::int64_t Size = 0;   ///< bytes the frame takes, padding included
  long long NumberOfAtoms = 0;
  long long Step = 0;
  double Time = 0.0;   ///< ps
  float Precision = 0; ///< the integer grid's units per nm; 0 for an uncompressed frame
  double Box[9] = { 0, 0, 0, 0, 0, 0, 0, 0, 0 }; ///< v1x v2y v3z v1y v1z v2x v2z v3x v3y, nm
};

/** Every frame of the .xtc in `in`; on damage, the frames before it and `error`. */
std::vector<XtcFrameInfo> ScanXtc(std::istream& in, std::string& error);

/**
 * The positions (3 a atom, nm) of the frame at `where` (from ScanXtc());
 * false and `error` when the frame is damaged.
 */
bool ReadXtcFrame(std::istream& in,
  const XtcFrameInfo& where,
  std::vector<float>& positions,
  std::string& error);

/**
 * Decodes the coded block of a compressed frame (what follows the second
 * atom count: precision, ranges, smallidx, byte count and bytes), given
 * as `size` bytes at `data`, into `natoms` positions. False and `error`
 * when the block is damaged: a count or an index out of range, a run past
 * the last atom, or a read past the block's bytes.
 */
bool DecodeXtcCoordinates(const unsigned char* data,
  std::size_t size,
  long long natoms,
  std::vector<float>& positions,
  std::string& error);
} // namespace pointsurfaces

#endif
