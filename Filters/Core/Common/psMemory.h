// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psMemory.h
 * @brief Memory budgets: the limit a job may use, and sizes in words.
 *
 * The splat fitter and the CPU metaball caster stop before they allocate
 * more than a limit (their MemoryLimit, or the physical memory free when
 * they start) and say so in an error: on Linux an allocation beyond the
 * machine succeeds and the kernel's OOM killer ends the process later.
 */
#ifndef psMemory_h
#define psMemory_h

#include "PointSurfacesFiltersModule.h" // For export macro

#include <string> // For FormatBytes

namespace pointsurfaces
{
/** `requested` bytes when positive, else the physical memory free now (0 if unknown). */
POINTSURFACESFILTERS_EXPORT double MemoryLimitBytes(double requested);

/** "12 MiB", or "340 KiB" under a mebibyte (whole units, rounded down). */
POINTSURFACESFILTERS_EXPORT std::string FormatBytes(double bytes);
} // namespace pointsurfaces

#endif
