// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psSplatPages.h
 * @brief Which parts of a multi-resolution splat file to load within a memory budget.
 *
 * A splat file (vtkSplatFileWriter, vtkStreamingSplatFitter) keeps its
 * splats in the order of an octree whose leaves are pages: each page's
 * splats are sorted by level, coarsest first, so that levels 0..l of a page
 * are one contiguous range (the octree's LevelEnds). SelectPages chooses,
 * for one view or for the whole model, which prefix of each page to load:
 *
 * - with a view, the pages that the frustum culls get nothing, and each
 *   other page asks for the levels that SelectDrawRanges (psSplatLOD.h)
 *   would draw there: down to the first whose splats are at most
 *   PixelError pixels across;
 * - without one, every page asks for all its levels;
 * - then the budget is spent level by level, coarsest first, pages nearest
 *   to the eye first (without a view, in the octree's order): every page's
 *   coarsest level before any page's second, so that the first picture
 *   covers the whole view and detail comes where the budget allows. A
 *   page's prefix stays contiguous: a page whose level l does not fit gets
 *   no finer level either.
 *
 * Plain functions: no file, no VTK. The reader and the mapper's loader
 * use the same choice.
 */
#ifndef psSplatPages_h
#define psSplatPages_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "psSplatLOD.h"                 // For LODOctree and LODView

#include <vector> // For ranges

namespace pointsurfaces
{
/** One page's loaded prefix: splats [Begin, End), its levels 0 .. Levels - 1. */
struct PageRange
{
  int Node = 0;
  long long Begin = 0;
  long long End = 0;
  int Levels = 0;
};

struct PageSelection
{
  std::vector<PageRange> Ranges; ///< in the file's order
  long long Splats = 0;          ///< splats chosen
  double Bytes = 0.0;            ///< their cost
  double Wanted = 0.0;           ///< what the view (or the model) asks for, within no budget
  /** Bytes of the cheapest coarsest level among the pages asked for (0 when none is). */
  double SmallestPage = 0.0;
};

/**
 * The prefixes to load of the pages of `lod` (its leaves) for `view` (null:
 * the whole model, every level), spending at most `budgetBytes` (<= 0: no
 * limit) at `bytesPerSplat`.
 */
POINTSURFACESFILTERS_EXPORT PageSelection SelectPages(const LODOctree& lod,
  double bytesPerSplat,
  double budgetBytes,
  const LODView* view = nullptr);

/**
 * Piece `piece` of `pieces` of `selection`, for a reader asked for pieces (one
 * a rank): a contiguous share of the chosen splats in the file's order, the
 * ranges cut at the share's ends, so that the pieces hold every chosen splat
 * once and differ in size by one splat at most. Bytes are counted at
 * `bytesPerSplat`; Wanted and SmallestPage stay the whole selection's. A
 * piece outside [0, pieces) is empty; pieces < 2 is the whole selection.
 */
POINTSURFACESFILTERS_EXPORT PageSelection PieceOfSelection(const PageSelection& selection,
  int piece,
  int pieces,
  double bytesPerSplat);
} // namespace pointsurfaces

#endif
