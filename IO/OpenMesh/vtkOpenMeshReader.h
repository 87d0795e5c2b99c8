// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkOpenMeshReader
 * @brief   Reads OFF, OBJ, OM and STL meshes through OpenMesh, with normals and colours.
 *
 * VTK 9.1 has no OFF reader and no reader for OpenMesh's own OM format; its
 * OBJ and STL readers drop per-vertex colours. This reader hands the file to
 * OpenMesh::IO::read_mesh (the format follows the extension) into a
 * polygonal mesh and builds a vtkPolyData: the vertices as points, the faces
 * as polygons (any size), vertex normals as the point normals ("Normals")
 * and vertex colours as RGB(A) point scalars ("Colors"), face colours as
 * cell scalars ("Colors"), whenever the file has them. Isolated vertices (a
 * point cloud in OFF or OBJ) become vertex cells.
 *
 * A missing, empty, unreadable or truncated file gives an error naming the
 * file and an empty output, never a crash. OpenMesh parses coordinates as
 * float, so the points are float (about seven digits: offsets near 1e7 keep
 * about unit precision).
 */
#ifndef vtkOpenMeshReader_h
#define vtkOpenMeshReader_h

#include "PointSurfacesIOOpenMeshModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For FileName

class POINTSURFACESIOOPENMESH_EXPORT vtkOpenMeshReader : public vtkPolyDataAlgorithm
{
public:
  static vtkOpenMeshReader* New();
  vtkTypeMacro(vtkOpenMeshReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The .off, .obj, .om or .stl file to read. Default: none. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /** True when the extension is one OpenMesh reads (off, obj, om, stl). */
  static bool CanReadFile(const char* fileName);

protected:
  vtkOpenMeshReader();
  ~vtkOpenMeshReader() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;

private:
  vtkOpenMeshReader(const vtkOpenMeshReader&) = delete;
  void operator=(const vtkOpenMeshReader&) = delete;
};

#endif
