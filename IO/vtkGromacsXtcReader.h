// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkGromacsXtcReader
 * @brief   Reads GROMACS .xtc compressed trajectories as atoms, one frame per time step, with names and radii from a structure file.
 *
 * .xtc is what `gmx mdrun` writes by default for long runs (the
 * nstxout-compressed positions): only coordinates, at a fixed precision
 * (1000 units per nm unless compressed-x-precision says otherwise). VTK
 * cannot read it. Every frame is a time step (its time in ps), so ParaView
 * animates the run; the frames are indexed from their headers once (again
 * when the file changes), and each update decodes only the frame asked for.
 *
 * An .xtc names no atoms. Set StructureFileName to a .gro of the same atoms
 * (the run's input or `gmx trjconv -dump 0 -o frame.gro`) to get its
 * per-atom arrays, radius among them, as vtkGromacsGroReader makes them.
 *
 * - Points: the atoms' positions in nm (float, as stored), one vertex cell
 *   per atom.
 * - Point arrays: `atomid` (1-based); with a structure file also `resid`,
 *   `resname`, `name`, `element` and `radius` (the element's van der Waals
 *   radius in nm: what vtkMetaballField's RadiusArrayName can name).
 * - Field data: `Time` (ps), `Step`, `Box` (nine numbers in .gro's order:
 *   v1x v2y v3z v1y v1z v2x v2z v3x v3y) and `Precision` (0 for frames of
 *   at most 9 atoms, which are stored uncompressed).
 *
 * The frames are decoded by this project's own checked decoder, not
 * libgromacs: libgromacs 2022 corrupts memory on damaged frames (see
 * psGromacsXtc.h). A missing, damaged or truncated file gives one
 * vtkErrorMacro naming the file and an empty output; frames before the
 * damage stay readable. A structure file whose atom count differs is an
 * error too. In a parallel pipeline piece 0 holds every atom.
 */
#ifndef vtkGromacsXtcReader_h
#define vtkGromacsXtcReader_h

#include "PointSurfacesIOModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // For the frame index
#include <string> // For FileName

class POINTSURFACESIO_EXPORT vtkGromacsXtcReader : public vtkPolyDataAlgorithm
{
public:
  static vtkGromacsXtcReader* New();
  vtkTypeMacro(vtkGromacsXtcReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The .xtc file. Default: none. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /**
   * A .gro file of the same atoms, whose first frame gives the names,
   * elements and radii. Default: none (positions and atomid only).
   */
  vtkSetStdStringFromCharMacro(StructureFileName);
  vtkGetCharFromStdStringMacro(StructureFileName);
  ///@}

  /** Frames found in the file by the last RequestInformation. */
  int GetNumberOfFrames();

  /** True when the file starts with an .xtc frame header (magic 1995). */
  static bool CanReadFile(const char* fileName);

protected:
  vtkGromacsXtcReader();
  ~vtkGromacsXtcReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  std::string StructureFileName;

private:
  vtkGromacsXtcReader(const vtkGromacsXtcReader&) = delete;
  void operator=(const vtkGromacsXtcReader&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
