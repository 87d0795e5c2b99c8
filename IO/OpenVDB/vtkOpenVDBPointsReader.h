// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkOpenVDBPointsReader
 * @brief   Reads the point grids (OpenVDB PointDataGrid) of a .vdb file into a vtkPolyData.
 *
 * Houdini, Blender and many simulation codes store particles as OpenVDB
 * point data grids: positions quantised inside voxels, and any number of
 * typed attributes, groups and strings. VTK 9.1 has no reader for them.
 * This one reads the whole file through openvdb::io::Stream from a stream
 * that throws at the first short read (no delayed loading, so a damaged file
 * fails here and not later; OpenVDB's own file reader can loop for minutes
 * over a damaged count), and turns every PointDataGrid, or the one named by
 * GridName, into points with one vertex cell each:
 *
 * - positions in world space, in double (the grid's transform, then the
 *   decoded voxel offset: fixed-point and truncated codecs are undone);
 * - every attribute but P as a point array of the same name: bool, int8,
 *   int16, int32, int64, float, double, half (as float), vec3 of int, float
 *   or double, and matrices and quaternions, with array attributes (stride
 *   > 1) as extra components. String attributes become vtkStringArray;
 * - every group as an unsigned char array "group:<name>" (1 = member);
 * - "VDBGridIndex" (int), the grid each point came from, and the field data
 *   "VDBGridNames" (strings).
 *
 * Grids that lack an attribute another grid has get zeros (empty strings)
 * there. Grids of other types (level sets, fog volumes) are skipped. A
 * missing, truncated or corrupt file, or one with no point grid, gives an
 * error naming the file and an empty output, never a crash.
 *
 * OpenVDB itself cannot be trusted with every damaged file: Debian's 10.0.1
 * (bookworm, trixie) aborts on assertions in its paged attribute streams,
 * 13.0 (forky) reads out of bounds on one of the same inputs, and both leak
 * what they had allocated when a damaged file makes them throw (tens to
 * hundreds of KB a file, without bound over a long session). So the file is read in a child
 * process (ReadInChildProcess, on by default on Linux): an abort there ends
 * only the child and becomes this reader's error, and what OpenVDB leaked
 * goes when the child exits. The output comes back through a memory file:
 * one more copy of it, small beside OpenVDB's decoding.
 */
#ifndef vtkOpenVDBPointsReader_h
#define vtkOpenVDBPointsReader_h

#include "PointSurfacesIOOpenVDBModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For FileName
#include <vector> // For grid names

class POINTSURFACESIOOPENVDB_EXPORT vtkOpenVDBPointsReader : public vtkPolyDataAlgorithm
{
public:
  static vtkOpenVDBPointsReader* New();
  vtkTypeMacro(vtkOpenVDBPointsReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The .vdb file to read. Default: none. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /** Read only the point grid of this name. Default: empty, every point grid. */
  vtkSetStdStringFromCharMacro(GridName);
  vtkGetCharFromStdStringMacro(GridName);
  ///@}

  ///@{
  /** The point grids found by the last update, in file order. */
  int GetNumberOfPointGrids() const { return static_cast<int>(this->PointGridNames.size()); }
  const char* GetPointGridName(int i) const;
  ///@}

  ///@{
  /**
   * Read the file in a child process (fork), so that a damaged file that
   * makes OpenVDB abort or leak cannot take the program or its memory with
   * it. Default: on. Ignored (always in this process) where child processes
   * are not supported (not Linux). Turn it off in a program that must not
   * fork (some MPI launchers warn on fork()), or to debug OpenVDB itself.
   */
  vtkSetMacro(ReadInChildProcess, vtkTypeBool);
  vtkGetMacro(ReadInChildProcess, vtkTypeBool);
  vtkBooleanMacro(ReadInChildProcess, vtkTypeBool);
  ///@}

  /** True when the file starts with OpenVDB's magic number. */
  static bool CanReadFile(const char* fileName);

protected:
  vtkOpenVDBPointsReader();
  ~vtkOpenVDBPointsReader() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  std::string GridName;
  vtkTypeBool ReadInChildProcess = true;
  std::vector<std::string> PointGridNames;

private:
  vtkOpenVDBPointsReader(const vtkOpenVDBPointsReader&) = delete;
  void operator=(const vtkOpenVDBPointsReader&) = delete;
};

#endif
