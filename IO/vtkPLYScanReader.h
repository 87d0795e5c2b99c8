// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPLYScanReader
 * @brief   Reads PLY scans and meshes (any elements, ASCII or binary) safely, with one clear error for a bad file.
 *
 * VTK 9.1's vtkPLYReader does not step over elements other than `vertex`
 * and `face`: with any element before `vertex` (MeshLab's range maps start
 * with a `camera`) it takes the camera's numbers for vertices, and it
 * crashes (SIGSEGV or SIGABRT) on such a binary file that also has faces,
 * on a truncated file, on face indices out of range and on a vertex
 * without `z`, and hangs on a huge count in a small file. This reader
 * parses the header, walks every element by its declared property types
 * (scalars and lists of char to uint64, float and double; ASCII and binary
 * of either byte order), checks each element's extent against the file's
 * size before it allocates anything, and keeps:
 *
 * - the `vertex` element: x, y, z as the points (float when all three are
 *   float, else double); nx, ny, nz as the normals ("Normals", float);
 *   red, green, blue [, alpha] (or diffuse_red ...) as the scalars ("RGB",
 *   unsigned char; floating-point colours taken as 0..1); every other
 *   scalar property as a point array of its own name and type;
 * - the `face` element's `vertex_indices` (or `vertex_index`) lists as
 *   polygons; faces with fewer than three corners are left out with a
 *   warning. There are no vertex cells: a point cloud is points only.
 *
 * Other elements (camera, range_grid, edge, material ...) are skipped.
 * Points with a NaN or infinite coordinate are left out with the faces
 * that use them, with a warning. A missing, empty, truncated or damaged
 * file, face indices that are not integers or name no vertex, or a file
 * without points give one vtkErrorMacro line that starts with the file's
 * name, and an empty output. In a parallel pipeline piece 0 holds the
 * whole file, the other pieces nothing, unless SplitPoints is on: then
 * each piece holds its share of the points (no faces), and a binary file
 * is read piece by piece, only the piece's records (see ReadPLYFilePiece in
 * psPLY.h), so that a streaming consumer (vtkStreamingSplatFitter) reads a
 * scan of any size in bounded memory.
 *
 * pointsurfaces.scanio.read_scan reads .ply files with this reader.
 */
#ifndef vtkPLYScanReader_h
#define vtkPLYScanReader_h

#include "PointSurfacesIOModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For FileName

class POINTSURFACESIO_EXPORT vtkPLYScanReader : public vtkPolyDataAlgorithm
{
public:
  static vtkPLYScanReader* New();
  vtkTypeMacro(vtkPLYScanReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The .ply file. Default: none. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /**
   * Pieces of the points: piece k of n holds the vertices [N k / n,
   * N (k + 1) / n), without faces. Default off: piece 0 holds the whole file.
   */
  vtkSetMacro(SplitPoints, bool);
  vtkGetMacro(SplitPoints, bool);
  vtkBooleanMacro(SplitPoints, bool);
  ///@}

  /** True when the file starts with the PLY magic ("ply" and a line break). */
  static bool CanReadFile(const char* fileName);

protected:
  vtkPLYScanReader();
  ~vtkPLYScanReader() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  bool SplitPoints = false;

private:
  vtkPLYScanReader(const vtkPLYScanReader&) = delete;
  void operator=(const vtkPLYScanReader&) = delete;
};

#endif
