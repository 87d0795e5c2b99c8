// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkStreamingSplatFitter
 * @brief   Fits splats to a point set larger than memory, piece by piece, into a multi-resolution splat file.
 *
 * vtkAlgebraicSplatFitter holds every point and its fits at once (about
 * 330 bytes a point at the defaults). This filter takes the same
 * parameters (it is one), but asks its input for NumberOfPieces pieces, one
 * after another, and never holds more than one chunk of the points:
 * pointsurfaces::SplatStream (psSplatStream.h) spills the pieces to
 * scratch files in ScratchDirectory, cuts the bounds into k-d chunks of
 * at most ChunkPoints points, fits each chunk with a halo of its
 * neighbours' points by exactly the in-memory fit's rules (a splat at a
 * border is the in-memory one; a border is neither covered twice nor left
 * open), orients the normals across chunks, and carries every input point
 * array over (MLS-weighted, as float). The splats are written to FileName
 * as a multi-resolution splat file (vtkSplatFileWriter's format), which
 * vtkSplatFileReader opens lazily.
 *
 * The output is that file read back within OutputMemoryBudget megabytes
 * (coarsest levels first, see vtkSplatFileReader): a picture of a fit of
 * any size. Set NumberOfLevels above 1 for levels of detail in the file.
 *
 * Inputs that stream: vtkPLYScanReader with SplitPoints on (binary PLY,
 * read record range by record range), and any source or filter that
 * honours piece requests; any other input arrives whole in piece 0 (and
 * is then fitted chunk by chunk all the same). Selection FixedCount is not
 * streamed (LOP moves points across the whole set): use Quality.
 *
 * Over MPI ranks (ParaView's pvserver and pvbatch: the Controller, by
 * default the global controller), rank 0 alone fits and writes rank 0's
 * FileName; two ranks writing one file raced before (HDF5 refused the
 * second, or the file was damaged). Every rank asks its input for the same
 * pieces in step (a parallel filter upstream executes on all ranks
 * together; the ranks go on or stop together), and each rank whose piece
 * holds points of its own sends them to rank 0: data spread over the
 * ranks (after RedistributeDataSet, a partitioned reader) is fitted whole,
 * while a piece that equals rank 0's or an earlier rank's (a reader or
 * source that every rank runs alike; told by its count and coordinate
 * sums) is not sent twice. Each rank's output is then its piece of the
 * file read back (vtkSplatFileReader's pieces). A rank that cannot see
 * rank 0's file warns and outputs nothing. A program whose ranks each fit
 * their own file sets the Controller to null.
 *
 * Errors (no FileName, a scratch directory or file that cannot be written,
 * FixedCount) give one vtkErrorMacro line and an empty output.
 */
#ifndef vtkStreamingSplatFitter_h
#define vtkStreamingSplatFitter_h

#include "PointSurfacesIOHDF5Module.h" // For export macro
#include "vtkAlgebraicSplatFitter.h"

#include "vtkSmartPointer.h" // For the gathered pieces

#include <memory> // For the stream

class vtkMultiProcessController;
class vtkPointSet;
#include <string> // For names
#include <vector> // For the arrays

class POINTSURFACESIOHDF5_EXPORT vtkStreamingSplatFitter : public vtkAlgebraicSplatFitter
{
public:
  static vtkStreamingSplatFitter* New();
  vtkTypeMacro(vtkStreamingSplatFitter, vtkAlgebraicSplatFitter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The splat file to write. Default: none (an error). */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /** Pieces asked of the input, one after another. Default 16. */
  vtkSetClampMacro(NumberOfPieces, int, 1, 1 << 20);
  vtkGetMacro(NumberOfPieces, int);
  ///@}

  ///@{
  /** Most points of one chunk (its halo excluded). Default 2 000 000 (about 1.5 GB at the defaults). */
  vtkSetClampMacro(ChunkPoints, vtkIdType, 1000, VTK_ID_MAX);
  vtkGetMacro(ChunkPoints, vtkIdType);
  ///@}

  ///@{
  /** Where the scratch files go (about 60 bytes a point). Default: the system's temporary directory. */
  vtkSetStdStringFromCharMacro(ScratchDirectory);
  vtkGetCharFromStdStringMacro(ScratchDirectory);
  ///@}

  ///@{
  /** Megabytes of the file read back as the output; 0: the whole file. Default 256. */
  vtkSetClampMacro(OutputMemoryBudget, double, 0.0, 1e12);
  vtkGetMacro(OutputMemoryBudget, double);
  ///@}

  ///@{
  /**
   * Most splats of one page of the file (a leaf of its page octree): the
   * unit the reader loads. Default 16384 (about 1.5 MB of file).
   */
  vtkSetClampMacro(PageSize, int, 16, 1 << 24);
  vtkGetMacro(PageSize, int);
  ///@}

  ///@{
  /**
   * The ranks that share the fit (see the class comment); null or one
   * process: this process fits and writes on its own, whatever the others
   * do. Default: the global controller (VTK's parallel filters' rule).
   */
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /**
   * After an update: splats written, chunks fitted, halo points loaded in
   * all, and the most points of one chunk with its halo.
   */
  vtkGetMacro(NumberOfSplatsWritten, vtkIdType);
  vtkGetMacro(NumberOfChunks, vtkIdType);
  vtkGetMacro(NumberOfHaloPoints, vtkIdType);
  vtkGetMacro(LargestChunk, vtkIdType);
  ///@}

protected:
  vtkStreamingSplatFitter();
  ~vtkStreamingSplatFitter() override;

  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  int PageSize = 16384;
  int NumberOfPieces = 16;
  vtkIdType ChunkPoints = 2000000;
  std::string ScratchDirectory;
  double OutputMemoryBudget = 256.0;
  vtkIdType NumberOfSplatsWritten = 0;
  vtkIdType NumberOfChunks = 0;
  vtkIdType NumberOfHaloPoints = 0;
  vtkIdType LargestChunk = 0;
  vtkMultiProcessController* Controller = nullptr;

private:
  vtkStreamingSplatFitter(const vtkStreamingSplatFitter&) = delete;
  void operator=(const vtkStreamingSplatFitter&) = delete;
  // One piece's points into the stream (rank 0; the first piece with points
  // starts it and fixes the carried arrays).
  void AddPiece(vtkPointSet* input);
  // Collective over the Controller's ranks: on rank 0, the pieces to add
  // (its own, then those of the ranks whose points differ).
  void GatherPiece(vtkPointSet* input, std::vector<vtkSmartPointer<vtkPointSet>>& parts);
  // The file written; then read back into `output` when not null.
  bool Finish(vtkPolyData* output);
  void FinishOverRanks(vtkPolyData* output, bool everyPiece);
  void ReadBack(const std::string& path, vtkPolyData* output, int piece, int pieces);
  struct Impl;
  std::unique_ptr<Impl> P;
};

#endif
