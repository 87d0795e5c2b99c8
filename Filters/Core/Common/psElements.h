// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psElements.h
 * @brief Chemical elements of atoms named as force fields and PDB files name them, and their van der Waals radii.
 *
 * Molecular-dynamics files often name atoms without an element column
 * (GROMACS .gro files never have one; many PDB files written by simulation
 * tools leave it blank): the element has to come from the atom name.
 */
#ifndef psElements_h
#define psElements_h

#include "PointSurfacesFiltersModule.h" // For export macro

#include <string> // For names

namespace pointsurfaces
{
/**
 * The chemical element an atom name stands for, as force fields name
 * atoms: the name's letters without digits; two letters (Cl, Na, Mg, ...)
 * only when the residue is named like the atom (an ion) or the name is a
 * known two-letter element that no common atom name starts with (Cl, Br);
 * CHARMM's ion names (SOD, POT, CLA, CAL, LIT) as their ions; else the
 * first letter (CA is an alpha carbon, HW1 a water hydrogen).
 */
POINTSURFACESFILTERS_EXPORT std::string ElementFromAtomName(const std::string& atomName,
  const std::string& residueName);

/**
 * Whether an atom name is a massless virtual site of a water or lone-pair
 * model (TIP4P's MW, OM; EP and LP): no atom, and no radius.
 */
POINTSURFACESFILTERS_EXPORT bool IsVirtualSite(const std::string& atomName);

/**
 * Van der Waals radius of an element in nm (Bondi 1964; Na, K, Mg, Ca from
 * Mantina et al. 2009), or 0 when the element is not in the table.
 */
POINTSURFACESFILTERS_EXPORT double VanDerWaalsRadius(const std::string& element);
} // namespace pointsurfaces

#endif
