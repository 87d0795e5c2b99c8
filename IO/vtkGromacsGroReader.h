// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkGromacsGroReader
 * @brief   Reads GROMACS .gro files (a structure, or a trajectory of frames) as atoms, one frame per time step.
 *
 * GROMACS writes structures and trajectories (`gmx trjconv -o traj.gro`) as
 * fixed-column text, which VTK cannot read. Every frame is a time step
 * (TIME_STEPS: the title's "t=", else the frame's index), so ParaView
 * animates a trajectory; each update reads only the frame asked for.
 *
 * - Points: the atoms' positions in nm, one vertex cell per atom.
 * - Point arrays: `resid` and `atomid` (vtkIntArray), `resname` and `name`
 *   (vtkStringArray), `v` (nm/ps) when the file has velocities, `element`
 *   (vtkStringArray, from the atom name as force fields name atoms: HW1 and
 *   CA are H and C; NA in residue NA is sodium) and `radius`, the element's
 *   van der Waals radius in nm (Bondi 1964; 0.15 nm and a warning for an
 *   element not in the table; 0 for the massless virtual sites of water
 *   models, MW, EP, LP): what vtkMetaballField's RadiusArrayName can name
 *   for a molecular surface.
 * - Field data: `Time`, `Step` (-1 when the title has none) and `Box` (the
 *   nine numbers v1x v2y v3z v1y v1z v2x v2z v3x v3y, zero beyond the first
 *   three for a rectangular box).
 *
 * In a parallel pipeline piece 0 holds every atom, the other pieces none. A
 * missing, damaged or truncated file gives one vtkErrorMacro naming the file
 * and an empty output; frames before the damage stay readable.
 */
#ifndef vtkGromacsGroReader_h
#define vtkGromacsGroReader_h

#include "PointSurfacesIOModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // For the frame index
#include <string> // For FileName

class POINTSURFACESIO_EXPORT vtkGromacsGroReader : public vtkPolyDataAlgorithm
{
public:
  static vtkGromacsGroReader* New();
  vtkTypeMacro(vtkGromacsGroReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The .gro file. Default: none. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /** Frames found in the file by the last RequestInformation. */
  int GetNumberOfFrames();

  /** True when the file's second line is an atom count and its third an atom line. */
  static bool CanReadFile(const char* fileName);

protected:
  vtkGromacsGroReader();
  ~vtkGromacsGroReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;

private:
  vtkGromacsGroReader(const vtkGromacsGroReader&) = delete;
  void operator=(const vtkGromacsGroReader&) = delete;

  struct Index;
  std::unique_ptr<Index> Frames;
};

#endif
