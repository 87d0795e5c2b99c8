// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSplatFileWriter
 * @brief   Writes a splat set as a multi-resolution splat file (HDF5) that opens lazily.
 *
 * The input is a splat set of the splat data model (vtkAlgebraicSplatFitter
 * or vtkSplatFileReader output). It is written page by page in the order of
 * a page octree (at most pointsurfaces::PageSplats splats a leaf, each
 * leaf's splats by level, coarsest first), so that vtkSplatFileReader
 * loads only the pages and levels a view needs (see psSplatFile.h for the
 * layout). Every other numeric point array (colours, intensity, the input
 * arrays the fitter carried over) is stored as float, with its components.
 *
 * vtkStreamingSplatFitter writes the same file straight from a fit of any
 * size. An input that is not a splat set, or a file that cannot be written,
 * gives one vtkErrorMacro line and no file.
 */
#ifndef vtkSplatFileWriter_h
#define vtkSplatFileWriter_h

#include "PointSurfacesIOHDF5Module.h" // For export macro
#include "vtkWriter.h"

#include <string> // For FileName

class vtkPolyData;

class POINTSURFACESIOHDF5_EXPORT vtkSplatFileWriter : public vtkWriter
{
public:
  static vtkSplatFileWriter* New();
  vtkTypeMacro(vtkSplatFileWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The file to write (by convention .psplat). Default: none. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /**
   * Most splats of one page of the file (a leaf of its page octree): the
   * unit the reader loads. Default 16384 (about 1.5 MB of file).
   */
  vtkSetClampMacro(PageSize, int, 16, 1 << 24);
  vtkGetMacro(PageSize, int);
  ///@}

  /** The splats of the last file written. */
  vtkGetMacro(NumberOfSplats, vtkIdType);

protected:
  vtkSplatFileWriter() = default;
  ~vtkSplatFileWriter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  std::string FileName;
  int PageSize = 16384;
  vtkIdType NumberOfSplats = 0;

private:
  vtkSplatFileWriter(const vtkSplatFileWriter&) = delete;
  void operator=(const vtkSplatFileWriter&) = delete;
};

#endif
