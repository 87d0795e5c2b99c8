// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSplatFileDelegatingMapper
 * @brief   Draws the splat file that ParaView's data came from, each view's pages, instead of the data.
 *
 * A vtkPointSurfacesDelegatingMapper whose input is the output of
 * vtkSplatFileReader (the pages that reader loaded, and the file's path in
 * the field array vtkSplatFileReader::FileNameArrayName()). When this
 * process can read that file, the mapper draws it through its
 * vtkStreamingSplatMapper (GetStream): the pages and levels this view
 * needs, within the stream's MemoryBudget of GPU buffers, read by a
 * thread, coarsest first; the delivered data is then only what tells it
 * the file. Where the file cannot be read (a client that renders what a
 * remote server read), or the input has no file name, it draws the
 * delivered data as the superclass does.
 *
 * DrawsFile says whether this process draws the file at all: where every
 * rank renders its own piece and the images are composited by depth, one
 * rank draws the whole file and the others nothing. Ids for selection are
 * not those of the reader's output when the file is drawn: selection is
 * then not supported (GetSupportsSelection is false).
 */
#ifndef vtkSplatFileDelegatingMapper_h
#define vtkSplatFileDelegatingMapper_h

#include "PointSurfacesParaViewRepresentationsHDF5Module.h" // For export macro
#include "vtkPointSurfacesDelegatingMapper.h"

class vtkStreamingSplatMapper;

class POINTSURFACESPARAVIEWREPRESENTATIONSHDF5_EXPORT vtkSplatFileDelegatingMapper
  : public vtkPointSurfacesDelegatingMapper
{
public:
  static vtkSplatFileDelegatingMapper* New();
  vtkTypeMacro(vtkSplatFileDelegatingMapper, vtkPointSurfacesDelegatingMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The mapper that draws the file (its budget and loading settings). */
  vtkStreamingSplatMapper* GetStream() { return this->Stream; }

  ///@{
  /** Draw the file when the input names one this process can read (default on). */
  vtkSetMacro(StreamFile, bool);
  vtkGetMacro(StreamFile, bool);
  ///@}

  ///@{
  /** Whether this process draws the file (default on; off: it draws nothing in its place). */
  vtkSetMacro(DrawsFile, bool);
  vtkGetMacro(DrawsFile, bool);
  ///@}

  /** After a render or GetBounds: the file drawn, or empty when the data was. */
  const std::string& GetFileDrawn() { return this->FileDrawn; }

  void Render(vtkRenderer* ren, vtkActor* act) override;
  double* GetBounds() override;
  void GetBounds(double bounds[6]) override { this->vtkMapper::GetBounds(bounds); }
  void ReleaseGraphicsResources(vtkWindow* window) override;
  bool HasOpaqueGeometry() override;
  bool HasTranslucentPolygonalGeometry() override;
  bool GetSupportsSelection() override;

protected:
  vtkSplatFileDelegatingMapper();
  ~vtkSplatFileDelegatingMapper() override;

  /** The readable file the input names, or empty; sets FileDrawn and the stream's FileName. */
  const std::string& ChooseFile();

  vtkStreamingSplatMapper* Stream;
  bool StreamFile = true;
  bool DrawsFile = true;
  std::string FileDrawn;

private:
  vtkSplatFileDelegatingMapper(const vtkSplatFileDelegatingMapper&) = delete;
  void operator=(const vtkSplatFileDelegatingMapper&) = delete;
};

#endif
