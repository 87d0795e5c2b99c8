// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkLAMMPSDumpReader
 * @brief   Reads LAMMPS text dumps (`dump atom`, `dump custom`) as particles, one snapshot per time step.
 *
 * Molecular-dynamics runs in LAMMPS write their particles as text dumps,
 * which VTK cannot read. This reader finds every snapshot of the file once
 * and offers them as time steps (TIME_STEPS: the `ITEM: TIME` values when
 * the dump has them, else the timesteps), so ParaView animates them; each
 * update reads only the snapshot asked for (the last one at or before the
 * requested time).
 *
 * - Points: the first complete set of unwrapped (`xu yu zu`), plain
 *   (`x y z`), scaled unwrapped (`xsu ysu zsu`) or scaled (`xs ys zs`)
 *   coordinates, scaled ones mapped through the box (triclinic boxes
 *   included); one vertex cell per atom.
 * - Point arrays: every other column by its name; columns `Ax Ay Az` become
 *   one 3-component array `A` (`v` from `vx vy vz`, `f`, `mu`, ...; `x`
 *   from wrapped `x y z` when the points are unwrapped ones); `id`
 *   and `mol` as vtkIdTypeArray, `type` as vtkIntArray. A `radius` column is
 *   what vtkMetaballField's RadiusArrayName can name.
 * - Field data: `Timestep`, `Time`, `BoxBounds` (xlo xhi ylo yhi zlo zhi)
 *   and `BoxTilt` (xy xz yz).
 * - With SortById (default on) the atoms are put in `id` order, so that an
 *   atom keeps its point id from one snapshot to the next (LAMMPS writes
 *   them in the order its processes hold them).
 *
 * In a parallel pipeline piece 0 holds every atom (a dump is one text
 * stream), the other pieces none: redistribute them downstream. A missing,
 * damaged or truncated file gives one vtkErrorMacro naming the file and an
 * empty output; snapshots before the damage stay readable.
 */
#ifndef vtkLAMMPSDumpReader_h
#define vtkLAMMPSDumpReader_h

#include "PointSurfacesIOModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // For the snapshot index
#include <string> // For FileName

class POINTSURFACESIO_EXPORT vtkLAMMPSDumpReader : public vtkPolyDataAlgorithm
{
public:
  static vtkLAMMPSDumpReader* New();
  vtkTypeMacro(vtkLAMMPSDumpReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The dump file. Default: none. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /** Put the atoms of each snapshot in `id` order. Default on. */
  vtkSetMacro(SortById, bool);
  vtkGetMacro(SortById, bool);
  vtkBooleanMacro(SortById, bool);
  ///@}

  /** Snapshots found in the file by the last RequestInformation. */
  int GetNumberOfSnapshots();

  /** True when the file starts with a LAMMPS dump item. */
  static bool CanReadFile(const char* fileName);

protected:
  vtkLAMMPSDumpReader();
  ~vtkLAMMPSDumpReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  bool SortById = true;

private:
  vtkLAMMPSDumpReader(const vtkLAMMPSDumpReader&) = delete;
  void operator=(const vtkLAMMPSDumpReader&) = delete;

  struct Index;
  std::unique_ptr<Index> Snapshots;
};

#endif
