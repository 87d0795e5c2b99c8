// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkLASReader
 * @brief   Reads LAS and LAZ lidar point clouds through LASzip, piece by piece.
 *
 * Airborne and terrestrial lidar surveys come as LAS files (ASPRS LAS 1.0
 * to 1.4) or their LASzip-compressed form, LAZ; a survey of 10^8 points or
 * more is ordinary. This reader uses LASzip's C API (Debian 13 and later:
 * liblaszip-dev; Debian 12 packages no LAS library, and this module is
 * left out there) and honours piece requests: piece k of n holds the
 * points [N k / n, N (k + 1) / n), reached by seeking (LAZ files by their
 * chunk table), so that vtkStreamingSplatFitter reads a survey of any size
 * in bounded memory.
 *
 * Output: the points in double (the file's integers times its scale plus
 * its offset: coordinates near 1e6 keep their millimetres), as vertices
 * only; point arrays Intensity (unsigned short), Classification,
 * ReturnNumber, NumberOfReturns (unsigned char), GPSTime (double, for the
 * point formats that have it) and RGB (unsigned char, for those that have
 * colour: LAS stores 16-bit colours, many writers 8-bit values in them; the
 * file's first 10 000 points decide, for every piece alike). Field data:
 * LASPointCount, LASPointFormat, LASScale, LASOffset.
 *
 * A missing, empty, truncated or damaged file gives one vtkErrorMacro line
 * that starts with the file's name (with LASzip's own message), and an
 * empty output.
 */
#ifndef vtkLASReader_h
#define vtkLASReader_h

#include "PointSurfacesIOLASModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For FileName

class POINTSURFACESIOLAS_EXPORT vtkLASReader : public vtkPolyDataAlgorithm
{
public:
  static vtkLASReader* New();
  vtkTypeMacro(vtkLASReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The .las or .laz file. Default: none. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /** After an update: the file's points (all pieces). */
  vtkGetMacro(NumberOfPointsInFile, vtkIdType);

  /** True when LASzip opens the file. */
  static bool CanReadFile(const char* fileName);

protected:
  vtkLASReader();
  ~vtkLASReader() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  vtkIdType NumberOfPointsInFile = 0;

private:
  vtkLASReader(const vtkLASReader&) = delete;
  void operator=(const vtkLASReader&) = delete;
};

#endif
