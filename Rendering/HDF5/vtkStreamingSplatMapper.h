// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkStreamingSplatMapper
 * @brief   Draws a multi-resolution splat file of any size: only what the view needs, within a GPU budget, loaded by a thread.
 *
 * A vtkAlgebraicSplatMapper whose splats come from a splat file
 * (FileName: vtkStreamingSplatFitter, vtkSplatFileWriter) instead of its
 * input. Each render:
 *
 * 1. chooses the file's pages and levels for this view with
 *    pointsurfaces::SelectPages: the pages in the frustum, each down to the
 *    level whose splats are at most LODPixelError pixels across (all
 *    levels at 0), within MemoryBudget megabytes of GPU buffers, every
 *    page's coarsest level before any page's finer ones, nearest first;
 * 2. hands that choice to a loading thread (psSplatPageCache.h), which reads
 *    the missing levels from the disk, coarsest first, and evicts what the
 *    view no longer needs when the budget is full; the render never waits
 *    for it (Asynchronous, the default);
 * 3. draws what is in memory now: the resident pages are gathered into the
 *    mapper's input (the splat data model, its octree the file's page
 *    octree), and culled and refined per frame by the superclass. A page
 *    whose finer levels are still on the disk draws its finest level
 *    present, with that level's disc size, so the picture has no holes
 *    while it sharpens.
 *
 * The first picture of a file of any size thus comes from its coarsest
 * levels, as soon as they are read; Loading() says that more is coming.
 * With an initialized interactor the mapper renders again by itself while
 * pages load (RenderWhileLoading); a script renders again until Loading()
 * is false, or calls WaitForPages(). Without Asynchronous,
 * each render reads what it needs first (batch pictures, tests).
 *
 * The bounds are the file's, whatever is loaded, so that cameras and
 * cullers see the whole model. The light's view of a shadow map
 * (vtkShadowMapBakerPass) draws the pages the camera's view loaded. Every vtkAlgebraicSplatMapper setting
 * (blending, anti-aliasing, LODPixelError, colouring by the file's
 * attributes) applies. The input is the mapper's own: a connection set
 * by hand is replaced, with a warning.
 *
 * A file that cannot be opened or read gives one vtkErrorMacro line that
 * names it, and nothing is drawn; a budget smaller than the coarsest level
 * of every page in view gives a warning with the budget that would hold
 * one, and nothing is drawn.
 *
 * The loading thread reads through the splat file's reader, whose HDF5
 * calls hold one lock with every other HDF5 call of PointSurfaces::IOHDF5;
 * VTK's own HDF5 readers do not take it, so with an HDF5 library built
 * without thread safety (Debian's serial one is thread-safe) another reader
 * must not run while pages load.
 *
 * Pages arriving cost what they hold, not what is resident
 * (IncrementalUpload, the default): the splat buffers are rows of a fixed
 * size (psSplatArena.h), each (page, level) block that arrives is written
 * into free rows and uploaded alone (glBufferSubData), and the rows of what
 * the cache evicts are freed and drawn as nothing; each page's levels are
 * then drawn from their rows (one glMultiDrawArrays per run of ranges of
 * one level). Only the colours, when the splats are coloured by an array,
 * are mapped and uploaded whole on each arrival (4 bytes a row). The
 * buffers are made anew (every row uploaded) only when the resident set
 * outgrows them, the budget drops below them, or the file changes; their
 * rows are sized for what the view wants plus a quarter, within the budget.
 * Off, each arrival gathers the resident set and uploads it whole (the
 * former method, kept to compare against); its cost then grows with the
 * budget.
 *
 * GPU memory holds at most MemoryBudget MB of splat buffers
 * (GetNumberOfAllocatedSplats() rows of GetBytesPerSplat() bytes); host
 * memory holds the resident pages twice (the page cache and the mapper's
 * rows), in float, about 2 x 94 bytes a cubic splat.
 */
#ifndef vtkStreamingSplatMapper_h
#define vtkStreamingSplatMapper_h

#include "PointSurfacesRenderingHDF5Module.h" // For export macro
#include "vtkAlgebraicSplatMapper.h"

#include <memory> // For the cache
#include <string> // For FileName

class POINTSURFACESRENDERINGHDF5_EXPORT vtkStreamingSplatMapper : public vtkAlgebraicSplatMapper
{
public:
  static vtkStreamingSplatMapper* New();
  vtkTypeMacro(vtkStreamingSplatMapper, vtkAlgebraicSplatMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The splat file to draw. Default: none. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /** Most megabytes of splat buffers on the GPU; 0: no limit. Default 512. */
  vtkSetClampMacro(MemoryBudget, double, 0.0, 1e12);
  vtkGetMacro(MemoryBudget, double);
  ///@}

  ///@{
  /**
   * Load pages on a thread while rendering goes on (default), or read what
   * a view needs before drawing it (each render then waits on the disk).
   */
  vtkSetMacro(Asynchronous, bool);
  vtkGetMacro(Asynchronous, bool);
  vtkBooleanMacro(Asynchronous, bool);
  ///@}

  ///@{
  /**
   * Upload only the pages that arrive, into free rows of the buffers
   * (default), or gather and upload every resident page on each arrival
   * (off: the method before, kept to compare against).
   */
  vtkSetMacro(IncrementalUpload, bool);
  vtkGetMacro(IncrementalUpload, bool);
  vtkBooleanMacro(IncrementalUpload, bool);
  ///@}

  ///@{
  /**
   * While pages load (Asynchronous), render again by itself through the
   * render window's interactor, when it has one that is initialized: a
   * one-shot timer of LoadingRenderInterval milliseconds after each render
   * that left pages loading, whose TimerEvent calls the interactor's
   * Render(). An application with an event loop (Start(), a Qt widget)
   * thus sees the picture sharpen without a timer of its own. Default: on,
   * every 100 ms. Off, or without an interactor (scripts, offscreen
   * pictures), render again until GetLoading() is false, or WaitForPages().
   */
  vtkSetMacro(RenderWhileLoading, bool);
  vtkGetMacro(RenderWhileLoading, bool);
  vtkBooleanMacro(RenderWhileLoading, bool);
  vtkSetClampMacro(LoadingRenderInterval, int, 1, 60000);
  vtkGetMacro(LoadingRenderInterval, int);
  ///@}

  ///@{
  /**
   * With Asynchronous, the most seconds each render waits for the pages its
   * view wants before it draws. Default 0: a render never waits. Set it
   * where nothing will render again while pages load (a batch job, a
   * server), so that each picture is whole; ParaView's Streaming Splats do
   * so outside the GUI.
   */
  vtkSetClampMacro(RenderWait, double, 0.0, 1e6);
  vtkGetMacro(RenderWait, double);
  ///@}

  /**
   * True while pages the last rendered view wants are still being read, or
   * were read after that render: render again for them.
   */
  bool GetLoading();

  /**
   * Wait until the pages the last rendered view wants are in memory, or
   * `seconds` have passed (< 0: no limit); the next render draws them.
   * False on a timeout or a read error.
   */
  bool WaitForPages(double seconds = -1.0);

  ///@{
  /** After a render: the file's splats; those in memory; those the view wants within the budget. */
  vtkGetMacro(NumberOfSplats, vtkIdType);
  vtkGetMacro(NumberOfResidentSplats, vtkIdType);
  vtkGetMacro(NumberOfWantedSplats, vtkIdType);
  ///@}

  /** Bytes of GPU buffers a splat of the open file takes (the budget's unit). */
  double GetBytesPerSplat();

  /** Rows of splat buffers on the GPU (resident splats and free rows). */
  vtkIdType GetNumberOfAllocatedSplats();

  ///@{
  /**
   * After a render: the seconds it spent bringing the pages that arrived
   * into the buffers (writing or gathering them, converting and uploading,
   * on the render's thread), and the splats whose rows it converted and
   * uploaded; 0 when nothing arrived.
   */
  double GetUploadSeconds();
  vtkIdType GetNumberOfUploadedSplats();
  ///@}

  /** The file's bounds (discs included), whatever is loaded. */
  double* GetBounds() override;
  using vtkAlgebraicSplatMapper::GetBounds;

  void Render(vtkRenderer* ren, vtkActor* act) override;

protected:
  vtkStreamingSplatMapper();
  ~vtkStreamingSplatMapper() override;

  void ComputeBounds() override;
  /**
   * The superclass's nodes, with each node's mean splat scale (MeanScale,
   * which picks the level to draw) as the file states it, over all its
   * levels, instead of over the levels resident: so that the level drawn
   * is the level SelectPages wanted for the view, not a finer one that an
   * earlier, closer view left in memory.
   */
  void ReadOctree(vtkPolyData* poly) override;
  /** With IncrementalUpload: a page's range of file rows becomes the rows its levels hold. */
  void TranslateDrawRanges(std::vector<pointsurfaces::DrawRange>& ranges) override;
  /** With IncrementalUpload: the file's centre (free rows hold no position). */
  void ComputePositionShift(vtkPolyData* poly, double shift[3]) override;
  /** The superclass's, timed (GetUploadSeconds). */
  void BuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  /** Open FileName when it is new or changed (one error when it cannot be); false when not open. */
  bool OpenFile();
  /** Render's work: choose, request and draw the pages of this view. */
  void RenderPages(vtkRenderer* ren, vtkActor* act);
  /** With RenderWhileLoading: a one-shot timer on `ren`'s interactor, unless one is pending. */
  void ScheduleRender(vtkRenderer* ren);

  std::string FileName;
  double MemoryBudget = 512.0;
  bool Asynchronous = true;
  bool IncrementalUpload = true;
  bool RenderWhileLoading = true;
  int LoadingRenderInterval = 100;
  double RenderWait = 0.0;
  vtkIdType NumberOfSplats = 0;
  vtkIdType NumberOfResidentSplats = 0;
  vtkIdType NumberOfWantedSplats = 0;

private:
  vtkStreamingSplatMapper(const vtkStreamingSplatMapper&) = delete;
  void operator=(const vtkStreamingSplatMapper&) = delete;
  struct Impl;
  std::unique_ptr<Impl> P;
};

#endif
