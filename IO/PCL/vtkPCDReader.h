// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPCDReader
 * @brief   Reads Point Cloud Library .pcd files (ascii, binary, binary_compressed) into vtkPolyData.
 *
 * VTK has no reader for PCL's format, in which Kinect and lidar scans are
 * commonly stored. Parsing, including the LZF-compressed binary variant, is
 * done by PCL's own pcl::PCDReader; this class only maps its fields to VTK:
 *
 * - `x y z` become the points (float, or double when any of them is double),
 *   with one vertex cell per point;
 * - `normal_x normal_y normal_z` become the active normals, `Normals`;
 * - packed `rgb` / `rgba` become unsigned-char `RGB` / `RGBA` active scalars;
 * - every other field becomes a point-data array of its own type and count.
 *
 * Points with a NaN or infinite coordinate (the holes of organised clouds)
 * are dropped, and their count is reported with a warning and kept in
 * GetNumberOfDroppedPoints(). A missing, corrupt or truncated file gives a
 * vtkErrorMacro and an empty output.
 *
 * PCL 1.13 itself writes past its buffers on some damaged files (found by
 * fuzzing; those known are refused before PCL reads), and such a write
 * corrupts the program's memory silently. So the file is read in a child
 * process (ReadInChildProcess, on by default on Linux), as
 * vtkOpenVDBPointsReader does: a fault there ends only the child and becomes
 * this reader's error, and the output comes back through a memory file.
 */
#ifndef vtkPCDReader_h
#define vtkPCDReader_h

#include "PointSurfacesIOPCLModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For FileName

class POINTSURFACESIOPCL_EXPORT vtkPCDReader : public vtkPolyDataAlgorithm
{
public:
  static vtkPCDReader* New();
  vtkTypeMacro(vtkPCDReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The .pcd file to read. Default: none. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /** Points dropped for non-finite coordinates by the last read. */
  vtkGetMacro(NumberOfDroppedPoints, vtkIdType);

  ///@{
  /**
   * Read the file in a child process (fork), so that a damaged file on which
   * PCL writes out of bounds cannot corrupt this program. Default: on.
   * Ignored where child processes are not supported (not Linux). Turn it
   * off in a program that must not fork.
   */
  vtkSetMacro(ReadInChildProcess, vtkTypeBool);
  vtkGetMacro(ReadInChildProcess, vtkTypeBool);
  vtkBooleanMacro(ReadInChildProcess, vtkTypeBool);
  ///@}

  /** True when the file starts like a PCD file (a header line or VERSION). */
  static bool CanReadFile(const char* fileName);

protected:
  vtkPCDReader();
  ~vtkPCDReader() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  vtkIdType NumberOfDroppedPoints = 0;
  vtkTypeBool ReadInChildProcess = true;

private:
  vtkPCDReader(const vtkPCDReader&) = delete;
  void operator=(const vtkPCDReader&) = delete;
};

#endif
