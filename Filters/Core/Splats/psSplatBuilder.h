// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psSplatBuilder.h
 * @brief Selection plus fitting of a whole splat set, on plain arrays.
 *
 * The work of vtkAlgebraicSplatFitter without the pipeline: choose the splat
 * positions (all points, quality-based decimation over one or several nested
 * levels, or LOP/WLOP to a fixed count), then fit every splat against the
 * original points in parallel (vtkSMPTools). Each chosen point is fitted
 * once, at the level where it first appears: finer levels only add splats.
 *
 * With Fit.MaximumDeviation > 0 every splat is error-bounded
 * (psSplatBound.h): in the Quality selection a point is fitted when it is
 * chosen, and it claims only the points its bounded splat covers, so that
 * a point counts as covered only where a splat is within the tolerance
 * there; on every level and in every selection mode the disc is bounded
 * and the largest deviation measured. A disc is bounded growing: first
 * at 4 point spacings, doubling while the bound leaves it whole, up to its
 * nominal radius (the first radius the bound cuts is the disc), so that a
 * coarse level costs what its cut discs need. Without the bound the discs
 * keep their nominal radius and the deviation over them is measured all
 * the same.
 *
 * Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
 * M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
 */
#ifndef psSplatBuilder_h
#define psSplatBuilder_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "psSampleNoise.h"
#include "psSplatFit.h"

#include <atomic>     // For the abort flag
#include <functional> // For progress
#include <vector>     // For results

namespace pointsurfaces
{
enum class Selection
{
  All = 0,
  Quality = 1,
  FixedCount = 2
};

enum class Order
{
  Random = 0,  ///< the order of [Bolla 2010] 3.3.1
  Lattice = 1, ///< grid-centre points first
  Front = 2    ///< grow fronts at hexagonal-covering spacing: fewest splats
};

/** The unit of the error bound (SplatFitParameters::MaximumDeviation). */
enum class ToleranceUnit
{
  Spacing = 0,  ///< local point spacings: the bound follows the sampling
  Noise = 1,    ///< spacings, but never under NoiseFactor local noise scales (NoiseScale)
  Absolute = 2, ///< world units: the same bound at any sampling
  /**
   * Noise with wide splats (MaximumFeatureScale AutomaticFeatureScale
   * unless it is 2 or more) and a lower floor (AutomaticNoiseFloor) on a
   * sample that psSampleNoise.h measures noisy,
   * Spacing on any other: BuildSplats decides from the points it is given,
   * and reports what it chose in BuildResult.
   */
  Automatic = 3
};

/** ToleranceUnit::Automatic on a noisy sample: splats widened up to this factor of h (with MaximumFeatureScale under 2). */
constexpr double AutomaticFeatureScale = 16.0;
/**
 * ToleranceUnit::Automatic on a noisy sample: the Noise bound's floor, as a
 * share of MaximumDeviation spacings. The bound is then NoiseFactor noise
 * scales wherever the noise exceeds a sixth of the floor's spacings (at the
 * defaults, 0.083 spacings): the same in world units at any sampling denser
 * than the noise, where a floor of a whole MaximumDeviation let a sparser
 * sample's bound grow with its spacing (Lucy resampled with noise: 1.35
 * times the splats at 10M points as at 1M, 1.22 times with this floor).
 */
constexpr double AutomaticNoiseFloor = 0.5;

struct BuildParameters
{
  SplatFitParameters Fit;
  Selection Select = Selection::Quality;
  double Quality = 1.0;         ///< s, the finest level's when Levels > 1
  double CoarsestQuality = 1.0; ///< s_0 when Levels > 1
  int Levels = 1;               ///< K nested quality levels from s_0 down to s
  Order VisitOrder = Order::Lattice;
  double LatticeSpacing = 1.6; ///< Lattice cell, in units of s times the median h
  double SlabSpacing =
    4.0; ///< parallel selection slabs, in units of s times the median h; 0: one sequential pass
  long long Count = 1000; ///< m of FixedCount
  bool Weighted = true;   ///< FixedCount: WLOP (true) or LOP
  int LOPIterations = 50;
  unsigned int Seed = 1;
  double RadiusScale = 1.0; ///< R_i = RadiusScale s h_i
  bool KeepWeights = false; ///< keep neighbour ids and weights for attributes
  /**
   * Bounded fits: a point within the tolerance whose normal turns from the
   * patch's by more than this many degrees is not covered, and stops the
   * disc (BoundParameters::NormalAngle). The normals are the input's; without
   * them, PCA normals of NormalNeighbors points when EstimateNormals is set,
   * else there is no such test. 90 or more: no test.
   */
  double NormalAngle = 60.0;
  bool EstimateNormals = false;
  /**
   * Bounded Quality selection: a chosen point's fit is tried again on 4, 16,
   * ... times the neighbours (h twice, four times as wide), up to this factor
   * of h, while the bound leaves the wider disc whole: wide splats where the
   * surface is smooth, narrow ones in folds. 1: one scale (h from
   * FeatureSizeNeighbors).
   */
  double MaximumFeatureScale = 1.0;
  /** What Fit.MaximumDeviation is measured in (see ToleranceUnit). */
  ToleranceUnit Tolerance = ToleranceUnit::Spacing;
  /** ToleranceUnit::Noise: the tolerance is at least this many noise scales. */
  double NoiseFactor = 3.0;
  /**
   * With MaximumFeatureScale of 2 or more: each chosen point's first fit is
   * at least this many noise scales wide (its h, up to MaximumFeatureScale
   * times the k-nearest h), the noise being UncorrelatedNoiseScale of its
   * neighbourhood. On a sample denser than its noise the splats then stop
   * following the sampling. 0: the first fit at the k-nearest h.
   */
  double FeatureNoiseFactor = 12.0;
  /**
   * With MaximumFeatureScale of 2 or more (bounded Quality selection): a
   * wide fit's neighbourhood (its plane, h and fit points; the
   * max(NumberOfNeighbors, FeatureSizeNeighbors + 1) m^2 nearest points at
   * scale m) is found in a subsample of the points (every 4th, 16th or 64th,
   * the sparsest that still holds 256 of them), its 16 nearest points
   * whole; the bound still tests every point. False: every point of it.
   */
  bool SubsampleWideFits = true;
};

/** Neighbours of the PCA normals of BuildParameters::EstimateNormals. */
constexpr int NormalNeighbors = 10;

struct BuiltSplat
{
  Splat Fitted;
  double Radius = 0.0;
  int Level = 0;
  long long Source = -1;      ///< input point the splat grew from, -1 for LOP positions
  double MaxDeviation = 0.0;  ///< largest deviation of a point in its disc from its patch (world)
  double NominalRadius = 0.0; ///< the disc's radius before it was bounded (world)
  bool Bounded = false;       ///< Radius and MaxDeviation are final
  double Tolerance = 0.0;     ///< the error bound it was fitted with, in its local spacings
  std::vector<int> Ids;       ///< with KeepWeights: fit neighbours and their weights
  std::vector<float> Weights;
};

/**
 * One chunk of a streaming fit (psSplatStream.h): the points passed to
 * BuildSplats are the chunk's own points and a halo of its neighbours'
 * points around it. Halo points are fitted against and bounded against as
 * usual, but never chosen; the chunk's own points that the splats of chunks
 * fitted before it claimed start claimed, level by level; and the halo
 * points that this chunk's splats claim are reported, so that the chunks
 * after it start with them claimed. With the halo as wide as a fit's
 * neighbours and a disc's reach, each splat is what the in-memory fit
 * gives, and the selection is the in-memory one's, chunk after chunk, as
 * its slabs are (see SelectByQuality).
 */
struct ChunkContext
{
  /** Per point: non-zero for a halo point (another chunk's). */
  const unsigned char* Halo = nullptr;
  /** Per point: bit l set when an earlier chunk claimed it at level l (own points only). */
  const unsigned char* ClaimedBefore = nullptr;
  /** The median h that sizes the Lattice grid and the slabs (> 0: the whole cloud's). */
  double MedianFeatureSize = 0.0;
  /** Out: per level, the halo points that this chunk's splats claim there. */
  std::vector<std::vector<long long>> HaloClaims;
};

struct BuildResult
{
  std::vector<BuiltSplat> Splats;   ///< successful splats, coarsest level first
  long long Degenerate = 0;         ///< chosen positions that gave no splat
  long long Reduced = 0;            ///< splats fitted at a lower degree
  std::vector<double> LevelQuality; ///< s of each level
  /** The unit the bound was measured in (ToleranceUnit::Automatic resolved). */
  ToleranceUnit Tolerance = ToleranceUnit::Spacing;
  /** ToleranceUnit::Automatic: what decided it (else Probes 0). */
  SampleNoise Noise;
};

/**
 * `params` with ToleranceUnit::Automatic resolved for a sample whose noise
 * is `noise`: when it is noisy Noise, MaximumFeatureScale
 * AutomaticFeatureScale unless it is 2 or more, and Fit.MaximumDeviation
 * times AutomaticNoiseFloor; else Spacing. Any other unit is returned as it is.
 */
POINTSURFACESFILTERS_EXPORT BuildParameters ResolveTolerance(const BuildParameters& params,
  const SampleNoise& noise);

/**
 * Build the splats of `n` finite points `xyz` (with optional unit normals
 * that orient the splats). `progress(f)` is called with f in [0, 1];
 * `abort`, when set, stops the work early with what was built. `chunk`,
 * when given, makes this one chunk of a streaming fit (see ChunkContext;
 * Selection All or Quality only).
 */
POINTSURFACESFILTERS_EXPORT BuildResult BuildSplats(const double* xyz,
  long long n,
  const double* normals,
  const BuildParameters& params,
  const std::function<void(double)>& progress = nullptr,
  const std::atomic<bool>* abort = nullptr,
  ChunkContext* chunk = nullptr);

/**
 * LOP (Lipman et al. 2007) or WLOP (Huang et al. 2009): move `x` (m xyz
 * triples, usually a random subset of the input) towards the input points
 * `p` while repelling each other, for at most `iterations` steps or until no
 * point moves by more than 1e-4 h. Support radius h defaults (h <= 0) to
 * 4 sqrt(area / m) estimated from the bounding box. Returns the steps taken.
 */
POINTSURFACESFILTERS_EXPORT int LocallyOptimalProjection(const double* p,
  long long n,
  std::vector<double>& x,
  bool weighted,
  int iterations,
  double h = 0.0,
  double mu = 0.45);
} // namespace pointsurfaces

#endif
