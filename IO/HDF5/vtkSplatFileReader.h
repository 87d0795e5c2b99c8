// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSplatFileReader
 * @brief   Opens a multi-resolution splat file lazily: the pages and levels a view needs, within a memory budget.
 *
 * A splat file (vtkSplatFileWriter, vtkStreamingSplatFitter; layout in
 * psSplatFile.h) holds a splat set of any size in pages of an octree, each
 * page's splats by level, coarsest first. Opening it reads the header and
 * the octree only; each update then loads the prefixes of the pages that
 * pointsurfaces::SelectPages chooses:
 *
 * - with a Camera (and ViewportSize), the pages in its frustum, each down
 *   to the level whose splats are at most PixelError pixels across (all
 *   levels when PixelError is 0), as vtkAlgebraicSplatMapper's LOD would
 *   draw them; without one, every page with all its levels;
 * - within MemoryBudget megabytes of output (the splat data model's
 *   arrays): every page's coarsest level first, nearest pages first, then
 *   finer levels while the budget lasts. The first picture of a file of
 *   any size thus comes from its coarsest levels.
 *
 * The output is a splat set of the splat data model with its own LOD
 * octree (the mapper culls and refines within what was loaded), the
 * file's attributes as point arrays (integer ones in their types, the rest
 * float), and field data saying what was loaded (SplatFilePages,
 * SplatFileLoadedPages, SplatFileSplats, SplatFileLoadedSplats), the file's
 * absolute path and bounds (SplatFileName, SplatFileBounds: ParaView's
 * Streaming Splats representation draws the file itself from them, each
 * view's pages), and the output's own bounds and point array names
 * (SplatFileLoadedBounds, SplatFileArrays: a filter's output that passed
 * the field data on but moved the points or added an array is drawn as
 * data). A camera move re-executes the reader only when
 * a Camera is set (its MTime counts).
 *
 * Each array reports the whole file's value range, not that of the pages
 * loaded, in two ways:
 *
 * - The file stores every column's and attribute's range
 *   (pointsurfaces::SplatFileInfo::Ranges), set here as the array's cached
 *   ranges (vtkDataArray's COMPONENT_RANGE, L2_NORM_RANGE and their finite
 *   forms), so that GetRange and GetFiniteRange fit the whole file whatever
 *   pages a camera loaded. An array changed afterwards computes its own
 *   range again. ParaView 5.11 takes these.
 * - With LoadRangeEnds (on by default), the output also holds the few
 *   splats of the file that hold each range's ends (their rows,
 *   pointsurfaces::SplatFileInfo::RangeRows; at most two per component and
 *   magnitude of each array, a few dozen, beyond MemoryBudget), so that a
 *   range computed from the values is the file's too: vtkFieldData::GetRange
 *   and ParaView 5.13 and later, whose automatic colour range would
 *   otherwise fit the pages read. They are splats of the file like any
 *   other, at their own levels (the LOD draws a fine one only where its
 *   level is drawn), and they go to piece 0.
 *
 * A file without ranges (written before 2026-12-06) gives the pages' own;
 * one without range rows (older) gets no extra splats.
 *
 * Asked for pieces (ParaView's ranks, a vtkPolyData streamed in pieces),
 * piece p of n holds the p-th n-th of the splats chosen within the budget,
 * in the file's order (pointsurfaces::PieceOfSelection): the pieces
 * together are what one piece would load, each splat once, and every piece
 * has the same arrays (empty only when fewer splats are chosen than there
 * are pieces). The loaded counts and bounds in the field data are the
 * piece's; the file's name, bounds and counts are the whole file's.
 *
 * A missing, truncated, damaged, foreign or unfinished file gives one
 * vtkErrorMacro line that starts with the file's name, and an empty
 * output. HDF5 1.10 (Debian 12) can crash on a damaged file's metadata
 * (found by fuzzing), so each file version is first opened and checked in
 * a child process (CheckInChildProcess, on by default on Linux): if HDF5
 * crashes there, the file is reported as damaged and this program goes on. A budget that holds no page's coarsest level gives a warning
 * with the budget that would, and an empty output.
 */
#ifndef vtkSplatFileReader_h
#define vtkSplatFileReader_h

#include "PointSurfacesIOHDF5Module.h" // For export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // For the camera

#include <memory> // For the open file
#include <string> // For FileName

class vtkCamera;

class POINTSURFACESIOHDF5_EXPORT vtkSplatFileReader : public vtkPolyDataAlgorithm
{
public:
  static vtkSplatFileReader* New();
  vtkTypeMacro(vtkSplatFileReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The splat file. Default: none. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /** Most megabytes of output; 0: no limit. Default 1024. */
  vtkSetClampMacro(MemoryBudget, double, 0.0, 1e12);
  vtkGetMacro(MemoryBudget, double);
  ///@}

  ///@{
  /** With a Camera: the largest splat size in pixels a page is loaded down to; 0: all levels. Default 0. */
  vtkSetClampMacro(PixelError, double, 0.0, 1e6);
  vtkGetMacro(PixelError, double);
  ///@}

  ///@{
  /** The view that chooses the pages (null, the default: the whole model). */
  void SetCamera(vtkCamera* camera);
  vtkCamera* GetCamera();
  ///@}

  ///@{
  /** The view's size in pixels (with a Camera). Default 1920 x 1080. */
  vtkSetVector2Macro(ViewportSize, int);
  vtkGetVector2Macro(ViewportSize, int);
  ///@}

  ///@{
  /** After an update: the file's splats, and those loaded. */
  vtkGetMacro(NumberOfSplats, vtkIdType);
  vtkGetMacro(NumberOfLoadedSplats, vtkIdType);
  ///@}

  /**
   * Bytes a loaded splat of the open file takes in the output (the budget's
   * unit: double arrays, the LOD, a vertex cell, the attributes); 0 before
   * a file was opened.
   */
  double GetBytesPerSplat();

  ///@{
  /**
   * Open and check each file version first in a child process (fork), so
   * that a damaged file on which HDF5 crashes cannot take this program with
   * it; once per file version in a process, a few milliseconds. Default:
   * on. Ignored where child processes are not supported (not Linux). Turn
   * it off in a program that must not fork.
   */
  vtkSetMacro(CheckInChildProcess, vtkTypeBool);
  vtkGetMacro(CheckInChildProcess, vtkTypeBool);
  vtkBooleanMacro(CheckInChildProcess, vtkTypeBool);
  ///@}

  ///@{
  /**
   * The output's field arrays with the file's absolute path
   * ("SplatFileName") and its bounds, discs included ("SplatFileBounds",
   * one tuple of 6), whatever was loaded.
   */
  static const char* FileNameArrayName() { return "SplatFileName"; }
  static const char* FileBoundsArrayName() { return "SplatFileBounds"; }
  /** The output's own bounds (6 values) and point array names: what it is. */
  static const char* LoadedBoundsArrayName() { return "SplatFileLoadedBounds"; }
  static const char* ArraysArrayName() { return "SplatFileArrays"; }
  ///@}

  ///@{
  /**
   * Also load the splats that hold the ends of each array's range in the
   * whole file (see the class comment), so that ranges computed from the
   * values are the file's. Default: on. Off: the pages chosen only.
   */
  vtkSetMacro(LoadRangeEnds, vtkTypeBool);
  vtkGetMacro(LoadRangeEnds, vtkTypeBool);
  vtkBooleanMacro(LoadRangeEnds, vtkTypeBool);
  ///@}

  /** True when the file opens as a splat file. */
  static bool CanReadFile(const char* fileName);

  /** The reader's MTime, or its Camera's when later: a moved camera loads again. */
  vtkMTimeType GetMTime() override;

protected:
  vtkSplatFileReader();
  ~vtkSplatFileReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  double MemoryBudget = 1024.0;
  vtkTypeBool CheckInChildProcess = true;
  vtkTypeBool LoadRangeEnds = true;
  double PixelError = 0.0;
  int ViewportSize[2] = { 1920, 1080 };
  vtkSmartPointer<vtkCamera> Camera;
  vtkIdType NumberOfSplats = 0;
  vtkIdType NumberOfLoadedSplats = 0;

private:
  vtkSplatFileReader(const vtkSplatFileReader&) = delete;
  void operator=(const vtkSplatFileReader&) = delete;
  struct Impl;
  std::unique_ptr<Impl> P;
};

#endif
