// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSplatFileDelegatingMapper
 * @brief   Draws the splat file that ParaView's data came from, each view's pages, instead of the data.
 *
 * A vtkPointSurfacesDelegatingMapper whose input is the output of
 * vtkSplatFileReader (the pages that reader loaded, and the file's path in
 * the field array vtkSplatFileReader::FileNameArrayName()). When the input
 * is that output unfiltered (its splat count is SplatFileLoadedSplats, its
 * bounds SplatFileLoadedBounds and its point arrays among SplatFileArrays:
 * a filter that passed the field data on but changed, moved or added to the
 * splats is drawn as data) and this process can read the file, the mapper draws it through its
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

#include <string> // For the file name

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

  ///@{
  /**
   * The splat file `data` is the unfiltered vtkSplatFileReader output of,
   * or empty; and that file's bounds (false when `data` names none).
   */
  static std::string SplatFileOf(vtkDataObject* data);
  static bool SplatFileBoundsOf(vtkDataObject* data, double bounds[6]);
  ///@}

  ///@{
  /**
   * Outside the GUI (no Qt interactor on the render window, and no GUI
   * polling this process: pvbatch, pvpython, a server of a Python client),
   * where nothing renders again while pages load, the stream's RenderWait:
   * the most seconds a render waits for its view's pages. Default 60. In
   * the GUI renders never wait.
   */
  vtkSetClampMacro(BatchWait, double, 0.0, 1e6);
  vtkGetMacro(BatchWait, double);
  ///@}

  /**
   * ParaView's GUI polls the splat file's reader (a live source:
   * vtkPVSplatFileReader::GetNeedsUpdate) and renders again while this says
   * true: on a server (client-server) no Qt interactor renders the view
   * again while pages load, so this is how its picture sharpens. True when
   * a mapper of this process draws a file whose pages are being read, or
   * arrived after its last render, and no interactor of its own renders it
   * again. The first call also marks this process as driven by a GUI:
   * from then on its renders never wait for pages (BatchWait), so
   * interaction never waits on the disk.
   */
  static bool PollLoading();

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
  double BatchWait = 60.0;
  std::string FileDrawn;
  bool RendersItself = false; // a Qt interactor renders it again while pages load
  vtkMTimeType ChosenFor = 0; // the input's MTime FileDrawn was chosen for
  bool ChosenStreaming = false;

private:
  vtkSplatFileDelegatingMapper(const vtkSplatFileDelegatingMapper&) = delete;
  void operator=(const vtkSplatFileDelegatingMapper&) = delete;
};

#endif
