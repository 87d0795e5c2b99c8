// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psBallExtraction.h
 * @brief A point set's balls for the metaball field: the one place that owns the radius rule.
 *
 * Every class that reads balls from a vtkPointSet (the metaball mapper, the
 * level-set writer, the particle mesher and the ghost-ball exchange) reads
 * them here, so that they agree ball for ball:
 *
 * - the support radius of ball i is RadiusScale times the first component
 *   of the radius array (vtkPDBReader's radius array has more than one) when
 *   the input has an array of that name, else RadiusScale times the constant
 *   Radius;
 * - the strength is the strength array's first component, or 1 when no
 *   strength array is named, divided by the density array's first component
 *   when one is named (SPH weights m_i / rho_i); a named array that is
 *   missing counts as none (MissingStrengths tells the caller, who warns);
 * - with an SPH kernel the strength is also multiplied by the kernel's
 *   normalisation N / R_i^3 (KernelNormalization), so that the field is the
 *   SPH sum: the density with masses as strengths, in density units;
 * - a ball is usable when its centre, radius and strength are finite and its
 *   radius is positive (ValidBall).
 *
 * Reads data arrays, no pipeline: callers pass their input and their rule.
 */
#ifndef psBallExtraction_h
#define psBallExtraction_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "psMetaball.h"

#include <string> // For array names
#include <vector> // For the arrays

class vtkDataArray;
class vtkPointSet;

namespace pointsurfaces
{
/** The field's settings: kernel and threshold, and how balls are read from point data. */
struct BallRule
{
  MetaballKernel Kernel = MetaballKernel::Wyvill;
  double Threshold = 0.5;
  std::string RadiusArrayName = "Radius";
  double Radius = 1.0;
  double RadiusScale = 1.0;
  std::string StrengthArrayName;
  std::string DensityArrayName; ///< when named, strengths are divided by it (m / rho)
};

/** The radius array of `input` under `rule`, or null (the constant radius applies). */
POINTSURFACESFILTERS_EXPORT vtkDataArray* RadiusArray(vtkPointSet* input, const BallRule& rule);

/** The strength array of `input` under `rule`, or null (all strengths 1). */
POINTSURFACESFILTERS_EXPORT vtkDataArray* StrengthArray(vtkPointSet* input, const BallRule& rule);

/** The radius rule: the support radius of ball `i`, `radii` from RadiusArray. */
POINTSURFACESFILTERS_EXPORT double SupportRadius(vtkDataArray* radii,
  long long i,
  const BallRule& rule);

/**
 * The largest support radius of `input` under `rule` (the radius array's
 * range, or the constant), for padding bounds; 0 when it is not finite.
 */
POINTSURFACESFILTERS_EXPORT double LargestSupportRadius(vtkPointSet* input, const BallRule& rule);

/** A point set's balls as spans for psMetaball, owning their storage. */
struct BallArrays
{
  BallArrays() = default;
  // Set points into the vectors: a move keeps their storage, a copy would not.
  BallArrays(BallArrays&&) = default;
  BallArrays& operator=(BallArrays&&) = default;
  BallArrays(const BallArrays&) = delete;
  BallArrays& operator=(const BallArrays&) = delete;

  std::vector<double> Centres, Radii, Strengths;
  MetaballSet Set;
  bool MissingStrengths = false;  ///< a strength array was named but not found
  std::string MissingDensityName; ///< a density array named but not found
  bool MissingRadii = false;      ///< a radius array was named but not found
};

/**
 * Centres, radii (times `scale` on top of the rule, for example an actor's
 * scale) and strengths of `input` under `rule`, in parallel.
 */
POINTSURFACESFILTERS_EXPORT BallArrays ExtractBalls(vtkPointSet* input,
  const BallRule& rule,
  double scale = 1.0);

/**
 * The same into `out`, whose storage is kept: a caller that extracts every
 * frame (a mapper of a time series) allocates and touches its arrays once,
 * not once a frame (at 10M balls the fresh pages cost more than the copy).
 */
POINTSURFACESFILTERS_EXPORT void ExtractBalls(vtkPointSet* input,
  const BallRule& rule,
  double scale,
  BallArrays& out);

///@{
/**
 * The warnings every reader of balls gives, worded once: a strength array
 * named `strengthName` but missing in `balls`, and `invalid` of `count`
 * balls skipped. Empty when there is nothing to warn about.
 */
POINTSURFACESFILTERS_EXPORT std::string MissingStrengthsWarning(const BallArrays& balls,
  const std::string& strengthName);
POINTSURFACESFILTERS_EXPORT std::string InvalidBallsWarning(long long invalid, long long count);
///@}
} // namespace pointsurfaces

#endif
