// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psSplatArena.h
 * @brief The rows of a fixed set of buffers, handed out and taken back in extents.
 *
 * vtkStreamingSplatMapper keeps the splats of the pages in memory in vertex
 * buffers of a fixed number of rows, and writes each (page, level) block
 * that arrives into free rows, so that an arrival uploads that block alone
 * instead of the whole resident set. The arena says which rows are free:
 *
 * - Allocate(n) takes the smallest free extent that holds n rows whole;
 *   when none does, it takes free extents from the lowest row up, so that
 *   it succeeds whenever n rows are free at all (a block may then lie in
 *   several extents: one more draw range each).
 * - Release() gives rows back and merges them with free neighbours.
 * - Grow() adds rows at the end.
 *
 * Plain C++: no VTK, no GL.
 */
#ifndef psSplatArena_h
#define psSplatArena_h

#include "PointSurfacesRenderingHDF5Module.h" // For export macro

#include <map>    // For the free extents
#include <vector> // For extents

namespace pointsurfaces
{
/** Rows [Begin, End). */
struct RowExtent
{
  long long Begin = 0;
  long long End = 0;
  long long Size() const { return this->End - this->Begin; }
};

class POINTSURFACESRENDERINGHDF5_EXPORT SplatArena
{
public:
  /** `capacity` rows, all free. */
  explicit SplatArena(long long capacity = 0);

  long long Capacity() const { return this->Rows; }
  long long FreeRows() const { return this->Available; }

  /** Rows up to `capacity` (no fewer than now), free. */
  void Grow(long long capacity);

  /**
   * `n` rows, appended to `out` as extents in ascending order; false, with
   * nothing taken, when fewer than n rows are free. n <= 0 takes nothing.
   */
  bool Allocate(long long n, std::vector<RowExtent>& out);

  /** Rows of `extent` free again (they must have been allocated). */
  void Release(const RowExtent& extent);

  /** The free extents, ascending and merged. */
  std::vector<RowExtent> FreeExtents() const;

private:
  /** The first n rows of free `extent` (all of it when it holds no more), taken. */
  RowExtent Take(std::map<long long, long long>::iterator extent, long long n);

  std::map<long long, long long> Free; // first row -> end
  long long Rows = 0;
  long long Available = 0;
};
} // namespace pointsurfaces

#endif
