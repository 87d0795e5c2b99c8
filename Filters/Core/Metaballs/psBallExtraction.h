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
 * - the support radius of ball i is RadiusScale times a radius found by the
 *   first of these rules that applies (ChooseRadii, RadiusRule):
 *   1. NamedArray: the first component of the point array RadiusArrayName
 *      (vtkPDBReader's radius array has more than one), when it is named
 *      and the input has it;
 *   2. Constant: the constant Radius, when it is positive (explicit);
 *   3. FoundArray: the first of AutomaticRadiusArrays the input has:
 *      "Radius", "radius" (vtkPDBReader, vtkAtomRadii, the GROMACS readers,
 *      a LAMMPS dump's radius column), "SmoothingLength" (Gadget),
 *      "SmoothingLengths" (SWIFT), "pscale" (OpenVDB points), or half of
 *      "diameter" (a LAMMPS dump's diameter column);
 *   4. Spacing: SpacingRadiusFactor (1.5) times the mean nearest-neighbour
 *      spacing of the points (MeasureSpacing), or the spacing that
 *      vtkMetaballGhostBalls measured over all processes and wrote as the
 *      field-data array MeanSpacingArrayName;
 *   5. Unit: 1, when there is no spacing to measure (fewer than two
 *      distinct finite points);
 *   a named array that the input lacks is reported (MissingArrayName) and
 *   the rules 2 to 5 apply;
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
 * The spacing costs a kd-tree over the points and a query per point (not
 * timed yet at scale): vtkMetaballField keeps it for points that have not
 * changed, and vtkMetaballGhostBalls for leaves that have not.
 */
#ifndef psBallExtraction_h
#define psBallExtraction_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "psMetaball.h"

#include <memory> // For the kd-tree
#include <string> // For array names
#include <vector> // For the arrays

class vtkDataArray;
class vtkPointSet;

namespace pointsurfaces
{
class PointIndex;

/** The field's settings: kernel and threshold, and how balls are read from point data. */
struct BallRule
{
  MetaballKernel Kernel = MetaballKernel::Wyvill;
  double Threshold = 0.5;
  std::string RadiusArrayName; ///< empty: the first of AutomaticRadiusArrays the input has
  double Radius = 0.0;         ///< > 0: every ball's radius (explicit); else automatic
  double RadiusScale = 1.0;
  std::string StrengthArrayName;
  std::string DensityArrayName; ///< when named, strengths are divided by it (m / rho)
};

/** A point array the rule takes radii from when none is named, and its radius per value. */
struct RadiusArrayCandidate
{
  const char* Name;
  double Factor;
};

/** The arrays the readers write radii in, in the order the rule looks for them. */
inline constexpr RadiusArrayCandidate AutomaticRadiusArrays[6] = { { "Radius", 1.0 },
  { "radius", 1.0 },
  { "SmoothingLength", 1.0 },
  { "SmoothingLengths", 1.0 },
  { "pscale", 1.0 },
  { "diameter", 0.5 } };

/**
 * The automatic radius in mean nearest-neighbour spacings. With Wyvill's
 * kernel at T = 0.5 a lone ball shows at half its support R, two balls at
 * distance d join when R >= 0.75 d, and deep inside a cloud of density rho
 * the field is about 0.82 rho R^3. On a cubic lattice of spacing a (its mean
 * spacing) 1.5 a gives a field of 2.8 inside: one body whose particles still
 * show as bumps, a lone particle a sphere of 0.75 a. At 2.5 a (field 12.7)
 * a dense liquid (LAMMPS's melt example, 256 atoms) showed as one smooth
 * featureless box: the particles were lost in their sum. A uniform random
 * cloud (mean spacing 0.55 rho^(-1/3)) is the loose case: sampled inside one
 * of 1 500 points, the field was below T at 54 % of the places at 1.5
 * spacings (loose blobs), 15 % at 2 and 0.9 % at 2.5. So 1.5: particles at
 * their typical spacing join their neighbours and stay visible; RadiusScale
 * (or an explicit Radius) makes a smoother, closed surface.
 */
inline constexpr double SpacingRadiusFactor = 1.5;

/**
 * The field-data array (one double) in which vtkMetaballGhostBalls passes the
 * mean spacing of all processes' balls; the Spacing rule reads it before it
 * measures the points.
 */
inline constexpr const char* MeanSpacingArrayName = "MetaballMeanSpacing";

/** The rules, in the order they apply. */
enum class RadiusRule
{
  NamedArray = 0, ///< the point array RadiusArrayName
  Constant = 1,   ///< the constant Radius (> 0)
  FoundArray = 2, ///< the first of AutomaticRadiusArrays the input has
  Spacing = 3,    ///< SpacingRadiusFactor times the mean nearest-neighbour spacing
  Unit = 4        ///< 1: no spacing to measure
};

/** Which rule gives the radii and what it found (no pointers: it can be kept). */
struct RadiusChoice
{
  RadiusRule Rule = RadiusRule::Unit;
  std::string ArrayName;              ///< NamedArray, FoundArray: the array
  double ArrayFactor = 1.0;           ///< radius per array value (0.5 for "diameter")
  double Radius = 1.0;                ///< Constant, Spacing, Unit: every ball's radius
  double Spacing = 0.0;               ///< Spacing: the mean nearest-neighbour spacing
  bool SpacingOfAllProcesses = false; ///< Spacing: from MeanSpacingArrayName
  std::string MissingArrayName;       ///< RadiusArrayName, when the input lacks it
  double RadiusScale = 1.0;           ///< the rule's RadiusScale, on top of all these
};

/** A RadiusChoice with the array it reads, for one input. */
struct POINTSURFACESFILTERS_EXPORT RadiusSource : RadiusChoice
{
  vtkDataArray* Array = nullptr; ///< NamedArray, FoundArray: the input's (not owned)

  /** The support radius of ball `i`: RadiusScale times the array's value or the radius. */
  double SupportRadius(long long i) const;
};

/** The mean nearest-neighbour spacing as a sum and a count, so that processes can add theirs. */
struct NeighbourSpacing
{
  double Sum = 0.0;    ///< of the distances from each distinct point to its nearest other
  long long Count = 0; ///< distinct points with a neighbour
  double Mean() const
  {
    return this->Count > 0 ? this->Sum / static_cast<double>(this->Count) : 0.0;
  }
};

/**
 * The distinct finite points of a set, a kd-tree over them (PointIndex: offsets
 * near 1e7 keep their precision) and each one's distance to its nearest other.
 * NaN and infinite points are left out and exact duplicates count once (a zero
 * distance says nothing of the spacing). The distances are found in parallel,
 * each on its own, so they do not depend on the number of threads.
 */
class POINTSURFACESFILTERS_EXPORT NearestNeighbours
{
public:
  /** Of `n` xyz triples (copied). */
  NearestNeighbours(const double* xyz, long long n);
  ~NearestNeighbours();
  NearestNeighbours(const NearestNeighbours&) = delete;
  NearestNeighbours& operator=(const NearestNeighbours&) = delete;

  /** The distinct finite points. */
  long long Size() const { return static_cast<long long>(this->Distances.size()); }
  const double* Point(long long i) const { return this->Points.data() + 3 * i; }

  /** Each distinct point's distance to its nearest other; infinite when it is alone. */
  std::vector<double> Distances;

  /** The distance from q to the nearest point here at a positive distance; infinite when none. */
  double NearestTo(const double q[3]) const;

  /** `distances`' finite values summed in point order, and counted (Distances by default). */
  NeighbourSpacing Spacing() const { return Spacing(this->Distances); }
  static NeighbourSpacing Spacing(const std::vector<double>& distances);

private:
  std::vector<double> Points;
  std::unique_ptr<PointIndex> Index;
};

/**
 * The mean nearest-neighbour spacing of `n` xyz triples (NearestNeighbours):
 * each distinct finite point's distance to its nearest other, summed in
 * point order; fewer than two distinct points give a count of 0.
 */
POINTSURFACESFILTERS_EXPORT NeighbourSpacing MeasureSpacing(const double* xyz, long long n);

/** The same for the points of `input` (none when it is null). */
POINTSURFACESFILTERS_EXPORT NeighbourSpacing MeasureSpacing(vtkPointSet* input);

/** The strength array of `input` under `rule`, or null (all strengths 1). */
POINTSURFACESFILTERS_EXPORT vtkDataArray* StrengthArray(vtkPointSet* input, const BallRule& rule);

/** The radius array of `input` under `rule` (NamedArray or FoundArray), or null. */
POINTSURFACESFILTERS_EXPORT vtkDataArray* RadiusArray(vtkPointSet* input, const BallRule& rule);

/**
 * Which rule gives `input`'s radii under `rule`, without measuring: the
 * Spacing rule takes the spacing from the field-data array
 * MeanSpacingArrayName when the input has a positive one, else leaves it
 * to the caller (NeedsSpacing, ApplySpacing).
 */
POINTSURFACESFILTERS_EXPORT RadiusSource ChooseRadii(vtkPointSet* input, const BallRule& rule);

/** Does a Spacing choice still lack its spacing? */
inline bool NeedsSpacing(const RadiusChoice& choice)
{
  return choice.Rule == RadiusRule::Spacing && !(choice.Spacing > 0.0);
}

/**
 * A Spacing choice's radius from the mean spacing `spacing`: SpacingRadiusFactor
 * times it, or the Unit rule when it is not a positive finite number. Other
 * choices are left as they are.
 */
POINTSURFACESFILTERS_EXPORT void ApplySpacing(RadiusChoice& choice,
  double spacing,
  bool ofAllProcesses);

/** ChooseRadii, and the input's spacing measured when the Spacing rule needs it. */
POINTSURFACESFILTERS_EXPORT RadiusSource ResolveRadii(vtkPointSet* input, const BallRule& rule);

/**
 * The largest support radius of `input`'s balls under `source` (the
 * array's range, or the radius, times RadiusScale), for padding bounds; 0
 * when it is not finite.
 */
POINTSURFACESFILTERS_EXPORT double LargestSupportRadius(vtkPointSet* input,
  const RadiusSource& source);

/** The same under `rule` (ResolveRadii: it may measure the spacing). */
POINTSURFACESFILTERS_EXPORT double LargestSupportRadius(vtkPointSet* input, const BallRule& rule);

/**
 * What a choice means, in a sentence for the user: "Metaball radii: point
 * array "radius" (chosen automatically; ...)", "Metaball radii: 2.5 x the
 * mean nearest-neighbour spacing 0.004 = 0.01 (...)", and so on.
 */
POINTSURFACESFILTERS_EXPORT std::string RadiusRuleDescription(const RadiusChoice& choice);

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
  RadiusChoice RadiiFrom;         ///< the rule that gave the radii
  bool MissingStrengths = false;  ///< a strength array was named but not found
  std::string MissingDensityName; ///< a density array named but not found
  bool MissingRadii = false;      ///< a radius array was named but not found
};

/**
 * Centres, radii (times `scale` on top of the rule, for example an actor's
 * scale) and strengths of `input` under `rule`, in parallel. The radii come
 * from ResolveRadii (which may measure the spacing).
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

/** The same with the radii from `source` (ChooseRadii on this input, its spacing applied). */
POINTSURFACESFILTERS_EXPORT void ExtractBalls(vtkPointSet* input,
  const BallRule& rule,
  const RadiusSource& source,
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
