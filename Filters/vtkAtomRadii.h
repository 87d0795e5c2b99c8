// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkAtomRadii
 * @brief   Gives atoms without a radius the van der Waals radius of their element, taken from the atom name.
 *
 * vtkPDBReader takes an atom's element from the PDB's element columns or its
 * atom name, and leaves the radius 0 where neither names an element it
 * knows: simulation tools often leave the element columns blank and name
 * water and ion atoms their own way (OH2, OW, HW1, SOD, CLA), and then the
 * metaball mapper skips those atoms as invalid balls. This filter fills a
 * radius for them from the atom name as force fields name atoms (the
 * element of HW1 and CA is H and C; NA in residue NA is sodium; see
 * pointsurfaces::ElementFromAtomName) and the element's van der Waals
 * radius (Bondi 1964, in nm, times LengthUnitsPerNanometer: 10 for the
 * Ångström of PDB files). Massless virtual sites (TIP4P's MW, lone pairs LP
 * and EP) are no atoms: their radius stays 0.
 *
 * The radius array (RadiusArrayName, default vtkPDBReader's "radius", of any
 * component count) is copied with the filled values in every component, or
 * created with one component when the input has none. Counts of filled,
 * virtual-site and unknown atoms are kept (GetNumberOf...) and unknown
 * elements are named in one warning.
 */
#ifndef vtkAtomRadii_h
#define vtkAtomRadii_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "vtkPointSetAlgorithm.h"

#include <string> // For array names

class POINTSURFACESFILTERS_EXPORT vtkAtomRadii : public vtkPointSetAlgorithm
{
public:
  static vtkAtomRadii* New();
  vtkTypeMacro(vtkAtomRadii, vtkPointSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The string array of atom names. Default "atom_types" (vtkPDBReader's). */
  vtkSetStdStringFromCharMacro(AtomNameArrayName);
  vtkGetCharFromStdStringMacro(AtomNameArrayName);
  ///@}

  ///@{
  /** An optional string array of residue names (tells ions apart). Default "resname". */
  vtkSetStdStringFromCharMacro(ResidueNameArrayName);
  vtkGetCharFromStdStringMacro(ResidueNameArrayName);
  ///@}

  ///@{
  /** The radius array to fill (or create). Default "radius". */
  vtkSetStdStringFromCharMacro(RadiusArrayName);
  vtkGetCharFromStdStringMacro(RadiusArrayName);
  ///@}

  ///@{
  /** Length units of the data per nanometre: 10 for Ångström (PDB), 1 for nm (GROMACS). Default 10. */
  vtkSetClampMacro(LengthUnitsPerNanometer, double, 1e-30, 1e30);
  vtkGetMacro(LengthUnitsPerNanometer, double);
  ///@}

  ///@{
  /** Fill only radii that are 0 or less (on), or replace every radius (off). Default on. */
  vtkSetMacro(FillMissingOnly, bool);
  vtkGetMacro(FillMissingOnly, bool);
  vtkBooleanMacro(FillMissingOnly, bool);
  ///@}

  ///@{
  /** Counts of the last run: radii filled, virtual sites left at 0, atoms of unknown element left as they were. */
  vtkGetMacro(NumberOfFilledRadii, vtkIdType);
  vtkGetMacro(NumberOfVirtualSites, vtkIdType);
  vtkGetMacro(NumberOfUnknownElements, vtkIdType);
  ///@}

protected:
  vtkAtomRadii() = default;
  ~vtkAtomRadii() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string AtomNameArrayName = "atom_types";
  std::string ResidueNameArrayName = "resname";
  std::string RadiusArrayName = "radius";
  double LengthUnitsPerNanometer = 10.0;
  bool FillMissingOnly = true;
  vtkIdType NumberOfFilledRadii = 0;
  vtkIdType NumberOfVirtualSites = 0;
  vtkIdType NumberOfUnknownElements = 0;

private:
  vtkAtomRadii(const vtkAtomRadii&) = delete;
  void operator=(const vtkAtomRadii&) = delete;
};

#endif
