// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkGadgetHDF5Reader
 * @brief   Reads one particle type of a Gadget-2/4 or SWIFT HDF5 snapshot as points with every dataset as a point array.
 *
 * Cosmological and SPH codes (Gadget-2, Gadget-4, AREPO, SWIFT) write
 * snapshots in HDF5: a /Header of attributes and a group /PartTypeN per
 * particle type with one dataset per quantity (see psGadgetHDF5.h). VTK has
 * no reader for them. This one reads the type chosen by ParticleType
 * (default 0, the gas) over every file of a snapshot split into parts
 * (base.0.hdf5, base.1.hdf5, ...), with HDF5's C API:
 *
 * - Points: Coordinates, in the code's units, float or double as stored;
 *   one vertex cell per particle.
 * - Point arrays: every other dataset with one row per particle, under its
 *   own name and type (Velocities, ParticleIDs, Density, InternalEnergy,
 *   SmoothingLength or SWIFT's SmoothingLengths, ...), and Masses from the
 *   header's MassTable when the file has no Masses dataset for the type.
 *   For metaballs of the SPH density, give vtkMetaballField the smoothing
 *   length as RadiusArrayName, Masses as StrengthArrayName, an SPH kernel,
 *   and for SWIFT a RadiusScale of pointsurfaces::SWIFTSupportFactor.
 * - Field data: Time (the scale factor in a cosmological run), Redshift,
 *   BoxSize (3), NumPart_Total (6), ParticleType and Code ("Gadget" or
 *   "SWIFT"). TIME_STEPS holds Time, so that ParaView animates a series of
 *   snapshot files by it.
 *
 * A dataset that cannot be used (rows that do not match, a string or
 * compound type) is skipped with a warning. A missing, damaged or truncated
 * file, or one without a Header or Coordinates, gives one vtkErrorMacro and
 * an empty output. HDF5 1.10 (Debian 12) can crash on a damaged file's
 * metadata, so each file is first opened and walked (header, datasets'
 * types and chunk indexes, no values) in a child process
 * (CheckInChildProcess, on by default on Linux): a crash there is reported
 * as a damaged file. In a parallel pipeline piece 0 holds every particle.
 */
#ifndef vtkGadgetHDF5Reader_h
#define vtkGadgetHDF5Reader_h

#include "PointSurfacesIOHDF5Module.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // For FileName

class POINTSURFACESIOHDF5_EXPORT vtkGadgetHDF5Reader : public vtkPolyDataAlgorithm
{
public:
  static vtkGadgetHDF5Reader* New();
  vtkTypeMacro(vtkGadgetHDF5Reader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The snapshot file (any part of a split snapshot). Default: none. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /** The particle type, 0 to 5 (0 gas, 1 dark matter, 4 stars, 5 black holes). Default 0. */
  vtkSetClampMacro(ParticleType, int, 0, 5);
  vtkGetMacro(ParticleType, int);
  ///@}

  ///@{
  /**
   * Check each file version in a child process (fork) before reading it,
   * so that a damaged file on which HDF5 crashes cannot take this program
   * with it; once per file version in a process, a few milliseconds.
   * Default: on. Ignored where child processes are not supported (not
   * Linux). Turn it off in a program that must not fork.
   */
  vtkSetMacro(CheckInChildProcess, vtkTypeBool);
  vtkGetMacro(CheckInChildProcess, vtkTypeBool);
  vtkBooleanMacro(CheckInChildProcess, vtkTypeBool);
  ///@}

  /** True when the file is HDF5 with a /Header group (checked in a child first). */
  static bool CanReadFile(const char* fileName);

protected:
  vtkGadgetHDF5Reader();
  ~vtkGadgetHDF5Reader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  int ParticleType = 0;
  vtkTypeBool CheckInChildProcess = true;

private:
  vtkGadgetHDF5Reader(const vtkGadgetHDF5Reader&) = delete;
  void operator=(const vtkGadgetHDF5Reader&) = delete;
};

#endif
