// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkStreamingSplatRepresentation
 * @brief   ParaView's "Streaming Splats" representation: a splat file drawn as each view needs it, within a GPU budget.
 *
 * The Algebraic Splats representation for the Splat File Reader's output,
 * whose main mapper (vtkSplatFileDelegatingMapper) draws the file the data
 * came from through vtkStreamingSplatMapper instead of the data: the
 * pages in the view, each down to the level its pixels need (Splat LOD
 * Pixel Error; 0 wants all levels), within Splat Streaming Budget MB of GPU
 * buffers, read by a thread while the view goes on rendering what is in
 * memory, coarsest levels first. What the reader loaded (within its own
 * Memory Budget) is what other filters see, and what is drawn where this
 * process cannot read the file.
 *
 * With Splat Streaming Asynchronous on (the default), the GUI's view
 * (an interactor with timers) never waits for the disk and renders again
 * by itself while pages load; where nothing would render again (pvbatch,
 * pvpython without a GUI, a render server), each render waits up to Splat
 * Streaming Batch Wait seconds for its view's pages, so pictures are
 * whole. Off, each render reads what its view needs first. The view
 * frames the file's bounds, and renders where the file is read (remote
 * rendering in client-server). Where each rank renders its
 * own piece and images are composited by depth (pvbatch or pvserver over
 * MPI), rank 0 draws the file and the other ranks nothing; on a tile or
 * CAVE display every rank draws it.
 */
#ifndef vtkStreamingSplatRepresentation_h
#define vtkStreamingSplatRepresentation_h

#include "PointSurfacesParaViewRepresentationsHDF5Module.h" // For export macro
#include "vtkAlgebraicSplatRepresentation.h"

class vtkSplatFileDelegatingMapper;

class POINTSURFACESPARAVIEWREPRESENTATIONSHDF5_EXPORT vtkStreamingSplatRepresentation
  : public vtkAlgebraicSplatRepresentation
{
public:
  static vtkStreamingSplatRepresentation* New();
  vtkTypeMacro(vtkStreamingSplatRepresentation, vtkAlgebraicSplatRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The stream's MemoryBudget (MB of GPU buffers; 0: no limit) and Asynchronous; see vtkStreamingSplatMapper. */
  void SetSplatStreamingBudget(double megabytes);
  void SetSplatStreamingAsynchronous(bool on);
  /** Outside the GUI, the most seconds a render waits for its pages (default 60): see vtkSplatFileDelegatingMapper::SetBatchWait. */
  void SetSplatStreamingBatchWait(double seconds);
  ///@}

  ///@{
  /**
   * After a render on this process: the file's splats, those in memory,
   * those the view wants within the budget, and whether pages it wants are
   * still loading (all 0 where the data was drawn instead of a file, and on
   * a rank that leaves the file to rank 0).
   */
  vtkIdType GetSplatStreamingFileSplats();
  vtkIdType GetSplatStreamingResidentSplats();
  vtkIdType GetSplatStreamingWantedSplats();
  int GetSplatStreamingLoading();
  ///@}

  int ProcessViewRequest(vtkInformationRequestKey* request_type,
    vtkInformation* inInfo,
    vtkInformation* outInfo) override;

protected:
  vtkStreamingSplatRepresentation();
  ~vtkStreamingSplatRepresentation() override;

  vtkSplatFileDelegatingMapper* FileMapper;

  /** Whether this process draws a file (not the data, and not left to rank 0). */
  bool DrawsFile();

private:
  vtkStreamingSplatRepresentation(const vtkStreamingSplatRepresentation&) = delete;
  void operator=(const vtkStreamingSplatRepresentation&) = delete;
};

#endif
