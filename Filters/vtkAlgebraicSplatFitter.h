// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkAlgebraicSplatFitter
 * @brief   Replaces a point cloud by algebraic splats: MLS polynomial patches bounded to discs.
 *
 * Implements chapter 3 of N. K. R. Bolla, "High Quality Rendering of Large
 * Point-based Surfaces", M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010];
 * after Levin's MLS surfaces and Lipman et al.'s LOP). For each selected
 * point r_i it fits a weighted least-squares reference plane ([Bolla 2010]
 * eq. 3.1), measures the feature size h_i as the mean distance of the
 * FeatureSizeNeighbors nearest neighbours in that plane, and fits a
 * bivariate polynomial g of degree 1 to 4 in the normalised frame
 * (u/h_i, v/h_i, n/h_i) with Gaussian weights exp(-d^2 / (WeightScale h_i)^2)
 * ([Bolla 2010] eq. 3.2). Splats are always fitted against the original
 * points.
 *
 * Selection:
 * - `All`: one splat per input point.
 * - `Quality` ([Bolla 2010] 3.3.1): a chosen point claims the points within
 *   s·h_i of it in its parametric domain; `Random` order is that of [Bolla 2010],
 *   `Front` grows fronts at the spacing of a hexagonal covering and yields
 *   4 to 8 % fewer splats on clean samples (about as many on noisy ones).
 *   The work runs in parallel over slabs of the bounding box; the result is
 *   deterministic for a given RandomSeed and does not depend on the number
 *   of threads.
 * - `FixedCount` ([Bolla 2010] 3.3.2): m points seeded from the input, moved
 *   to convergence by LOP (Lipman et al. 2007) or its density-weighted WLOP
 *   (Huang et al. 2009), then fitted.
 *
 * The output is the splat data model (see vtkSplatDataModel and the README's
 * Data model section): one vertex per splat at its origin o_i, point arrays
 * SplatNormal, SplatTangent, SplatFeatureSize, SplatCoefficients (3/6/10/15
 * components), SplatRadius (R_i = RadiusScale · s · h_i) and SplatLOD, every
 * input point array carried over by MLS-weighted averaging, and SplatDegree
 * in the field data.
 *
 * Error-bounded splats (MaximumDeviation > 0, the default): a splat covers
 * only the points within MaximumDeviation local point spacings of its
 * patch, its disc stops where the surface bends away from the patch and at
 * the borders of the data, and its fit keeps to the sheet of the surface
 * its centre lies on, so that the other side of a thin part or the other
 * face of a sharp edge does not pull it (see psSplatBound.h and
 * psSplatFit.h). The selection counts a point as covered only by a splat
 * within the tolerance there, so the splat budget goes where the surface
 * needs it. SplatMaxDeviation holds each splat's measured largest deviation
 * (world units) over the points it covers.
 *
 * Coincident and near-coincident input points (closer than MergeTolerance
 * times the bounding-box diagonal) are fitted once.
 *
 * Defaults: cubic patches and FeatureSizeNeighbors 24 (h_i about two point
 * spacings), chosen against the meshes of the Bunny, the Horse and Lucy
 * (masked SSIM of the splats against the mesh from six views: 0.962, 0.965
 * and 0.854 at s = 1; with quadratics and 120 neighbours, 0.867, 0.897 and
 * 0.741): a narrower h follows folds a few spacings wide, which the
 * error-bounded discs of a wider one stop short of.
 *
 * Calibration against [Bolla 2010] Table 4.7 (the unbounded fit,
 * MaximumDeviation 0): FeatureSizeNeighbors 120 makes h_i about four point
 * spacings, and at s = 1 in random order reproduces its splat counts for
 * the Bunny (1344 against 1315) and Igea (within 3 %). Its Horse count
 * (6.1 %) implies a smaller h for that model: FeatureSizeNeighbors = 60
 * reproduces it.
 *
 * Bad input never crashes and never produces NaN: points with NaN or infinite
 * coordinates are dropped and counted, degenerate neighbourhoods (duplicates,
 * collinear points) yield no splat and are counted, rank-deficient fits fall
 * back to a lower degree and are counted; each count is reported with a
 * warning and kept in the output's field data.
 */
#ifndef vtkAlgebraicSplatFitter_h
#define vtkAlgebraicSplatFitter_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <vector> // For MergeCoincident

namespace pointsurfaces
{
struct BuildParameters;
struct BuildResult;
struct SampleNoise;
enum class ToleranceUnit;
}

class POINTSURFACESFILTERS_EXPORT vtkAlgebraicSplatFitter : public vtkPolyDataAlgorithm
{
public:
  static vtkAlgebraicSplatFitter* New();
  vtkTypeMacro(vtkAlgebraicSplatFitter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** How each splat is fitted (SetFitMode). */
  enum FitModes
  {
    Linear = 0,
    Robust = 1,
    Projected = 2
  };
  /** The loss of the Robust fit (SetRobustLoss). */
  enum RobustLosses
  {
    Huber = 0,
    Cauchy = 1
  };
  /** Which points get a splat (SetSelectionMode). */
  enum SelectionModes
  {
    All = 0,
    Quality = 1,
    FixedCount = 2
  };
  /** The order in which candidate centres are visited (SetSelectionOrder). */
  enum SelectionOrders
  {
    Random = 0,
    Lattice = 1,
    Front = 2
  };
  /** Locally optimal projection: plain or weighted (SetLOPVariant). */
  enum LOPVariants
  {
    LOP = 0,
    WLOP = 1
  };
  /** What MaximumDeviation is measured in (SetToleranceUnit). */
  enum ToleranceUnits
  {
    SPACING = 0,
    NOISE = 1,
    ABSOLUTE = 2,
    AUTOMATIC = 3
  };

  ///@{
  /** Polynomial degree, 1 (flat disc) to 4. Default 3. */
  vtkSetClampMacro(Degree, int, 1, 4);
  vtkGetMacro(Degree, int);
  ///@}

  ///@{
  /** Neighbours in each fit (k). Default 40. */
  vtkSetClampMacro(NumberOfNeighbors, int, 3, 100000);
  vtkGetMacro(NumberOfNeighbors, int);
  ///@}

  ///@{
  /** Neighbours whose mean in-plane distance is h_i. Default 24 (see the class comment). */
  vtkSetClampMacro(FeatureSizeNeighbors, int, 1, 100000);
  vtkGetMacro(FeatureSizeNeighbors, int);
  ///@}

  ///@{
  /** Width of the Gaussian weight, in units of h_i. Default 1. */
  vtkSetClampMacro(WeightScale, double, 1e-3, 1e3);
  vtkGetMacro(WeightScale, double);
  ///@}

  ///@{
  /** Linear (default), Robust (Ceres) or Projected. */
  vtkSetClampMacro(FitMode, int, Linear, Projected);
  vtkGetMacro(FitMode, int);
  ///@}

  ///@{
  /**
   * Loss of the Robust mode: Huber or Cauchy (default). With 15 % gross
   * outliers Cauchy recovers the curvature to 4 %, Huber only to 80 %
   * (TestSplatFit).
   */
  vtkSetClampMacro(RobustLoss, int, Huber, Cauchy);
  vtkGetMacro(RobustLoss, int);
  ///@}

  ///@{
  /** Where the robust loss bends, in units of h_i. Default 0.05. */
  vtkSetClampMacro(RobustLossScale, double, 1e-6, 1e3);
  vtkGetMacro(RobustLossScale, double);
  ///@}

  ///@{
  /** All, Quality (default) or FixedCount. */
  vtkSetClampMacro(SelectionMode, int, All, FixedCount);
  vtkGetMacro(SelectionMode, int);
  ///@}

  ///@{
  /** Inverse quality factor s of the Quality selection. Default 1. */
  vtkSetClampMacro(QualityFactor, double, 1e-3, 1e3);
  vtkGetMacro(QualityFactor, double);
  ///@}

  ///@{
  /**
   * Visiting order of the Quality selection: Random (default, as in [Bolla 2010]),
   * Lattice (grid-centre points first) or Front (fronts grown at the spacing
   * of a hexagonal covering: 4 to 8 % fewer splats at equal error on clean
   * samples, about as many on noisy ones, at 1.0 to 1.05 times the fit time).
   */
  vtkSetClampMacro(SelectionOrder, int, Random, Front);
  vtkGetMacro(SelectionOrder, int);
  ///@}

  ///@{
  /** Number of splats m of the FixedCount selection. Default 1000. */
  vtkSetClampMacro(NumberOfSplats, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(NumberOfSplats, vtkIdType);
  ///@}

  ///@{
  /** LOP or WLOP (default) for FixedCount. */
  vtkSetClampMacro(LOPVariant, int, LOP, WLOP);
  vtkGetMacro(LOPVariant, int);
  ///@}

  ///@{
  /** Maximum LOP iterations. Default 50. */
  vtkSetClampMacro(LOPIterations, int, 0, 10000);
  vtkGetMacro(LOPIterations, int);
  ///@}

  ///@{
  /** Disc radius R_i = RadiusScale · s · h_i (s = 1 for All and FixedCount). Default 1. */
  vtkSetClampMacro(RadiusScale, double, 1e-3, 1e3);
  vtkGetMacro(RadiusScale, double);
  ///@}

  ///@{
  /**
   * Quality levels ([Bolla 2010] 3.4): K nested levels from CoarsestQualityFactor
   * (s_0) down to QualityFactor (s_k), linearly. Each splat is tagged in
   * SplatLOD with the level where it first appears and is fitted once.
   * Default 1 (a single level); vtkMultiResolutionSplatBuilder defaults to
   * 25 levels from s_0 = 4, as [Bolla 2010] uses 25 to 50.
   */
  vtkSetClampMacro(NumberOfLevels, int, 1, 1000);
  vtkGetMacro(NumberOfLevels, int);
  vtkSetClampMacro(CoarsestQualityFactor, double, 1e-3, 1e3);
  vtkGetMacro(CoarsestQualityFactor, double);
  ///@}

  ///@{
  /**
   * Build the bucketed octree ([Bolla 2010] 3.5): the splats are reordered by leaf,
   * then by level, and the nodes are stored in the field data as
   * OctreeNodeBounds (6), OctreeNodeSphere (4), OctreeNodeChildren (first
   * child, child count), OctreeNodeRange (begin, end) and
   * OctreeNodeLevelEnds (one end offset per level), so that a mapper can cull
   * nodes and draw prefixes. Default on, with buckets of 64 splats.
   */
  vtkSetMacro(BuildOctree, bool);
  vtkGetMacro(BuildOctree, bool);
  vtkBooleanMacro(BuildOctree, bool);
  vtkSetClampMacro(OctreeBucketSize, int, 1, 1000000);
  vtkGetMacro(OctreeBucketSize, int);
  ///@}

  ///@{
  /**
   * Without input normals, orient the splats' normals consistently over
   * each connected part of the splats (Hoppe et al.'s minimum spanning tree
   * over their nearest neighbours; see psSplatOrientation.h), pointing up at
   * each part's highest splat: outward on a closed surface. Off keeps the
   * sign that each plane fit happens to give. With input normals the splats
   * follow them either way. The field data's SplatNormalsOriented (1 or 0)
   * tells the mapper whether back-face culling can trust the normals.
   * Default on.
   */
  vtkSetMacro(OrientNormals, bool);
  vtkGetMacro(OrientNormals, bool);
  vtkBooleanMacro(OrientNormals, bool);
  ///@}

  ///@{
  /**
   * Error bound of each splat, in units of the local point spacing (the
   * mean distance of a point's 6 nearest distinct neighbours): a splat
   * covers, and its disc reaches, only as far as its patch stays within
   * this distance of the points there. 0 turns the bound off and fits
   * as [Bolla 2010] does (discs of radius RadiusScale · s · h_i, whatever
   * the data there). With several quality levels, level l's bound is this
   * times s_l / s (coarser levels are drawn where their splats are smaller
   * on screen). Default 0.5.
   */
  vtkSetClampMacro(MaximumDeviation, double, 0.0, 1e30);
  vtkGetMacro(MaximumDeviation, double);
  ///@}
  ///@{
  /**
   * The unit of MaximumDeviation:
   * - AUTOMATIC (default): on a noisy sample, NOISE with wide splats
   *   (MaximumFeatureScale 16, or yours when you set 2 or more) and the
   *   bound's floor at half of MaximumDeviation (so that the noise, not the
   *   spacing, sets it: the same bound at any sampling denser than the
   *   noise); SPACING on any other. The fit measures
   *   the points' residual about their local quadrics at about a thousand
   *   probes, on their 16 and on their 64 nearest points: noise leaves the
   *   same residual at both (a ratio of 0.98 to 1.46 on the noisy scans and
   *   resamples measured), relief the quadrics cannot follow a growing one
   *   (2.7 and up on the clean ones, sparse or dense); a ratio under 1.5
   *   with a residual of at least 0.05 spacings is noise (psSampleNoise.h).
   *   GetResolvedToleranceUnit() and the field data SplatToleranceUnit and
   *   SplatSampleNoise (the ratio, the residual in spacings) tell what was
   *   chosen. Dense or noisy scans then get far fewer splats and a better
   *   picture; clean ones the same splats as SPACING.
   * - SPACING: local point spacings, as above. The bound follows
   *   the sampling: a denser sample of the same surface is held to a
   *   tighter bound, and needs more splats.
   * - NOISE: spacings, but never under NoiseFactor times the neighbourhood's
   *   measured noise (the robust residual scale of its quadric, see
   *   psSplatFit.h NoiseScale): on a noisy scan the splats smooth the noise
   *   instead of chasing it.
   * - ABSOLUTE: world units, the same bound at any sampling.
   * Applies to every selection mode.
   */
  vtkSetClampMacro(ToleranceUnit, int, SPACING, AUTOMATIC);
  vtkGetMacro(ToleranceUnit, int);
  ///@}
  ///@{
  /**
   * After a run: the unit the bound was measured in (ToleranceUnit, with
   * AUTOMATIC resolved to NOISE or SPACING), and with AUTOMATIC the
   * measurement that decided it: the ratio of the points' residual on
   * their 64 nearest to that on their 16 nearest, and that residual in
   * local spacings (medians over the probes; 0 when not measured).
   */
  vtkGetMacro(ResolvedToleranceUnit, int);
  vtkGetMacro(SampleNoiseGrowth, double);
  vtkGetMacro(SampleNoiseLevel, double);
  ///@}
  ///@{
  /** ToleranceUnit NOISE: the bound is at least this many noise scales. Default 3. */
  vtkSetClampMacro(NoiseFactor, double, 0.0, 100.0);
  vtkGetMacro(NoiseFactor, double);
  ///@}
  ///@{
  /**
   * With MaximumFeatureScale of 2 or more: each chosen point's first fit is
   * at least this many noise scales wide (h up to MaximumFeatureScale times
   * the k-nearest h), the noise being the part that differs from a point to
   * its nearest neighbour (psSplatFit.h UncorrelatedNoiseScale), so that
   * relief a sparse sample cannot resolve does not count. A fit narrower than
   * the noise follows it; on a sample denser than its noise the splat count
   * then stops growing with the sampling (Lucy resampled with noise: 1.18
   * times from 1M to 4M points instead of 1.51, docs/results.md). 0: the
   * first fit at the k-nearest h. Default 12.
   */
  vtkSetClampMacro(FeatureNoiseFactor, double, 0.0, 1000.0);
  vtkGetMacro(FeatureNoiseFactor, double);
  ///@}
  ///@{
  /**
   * Error-bounded Quality selection (MaximumDeviation > 0): each chosen
   * point whose disc the bound leaves whole is fitted again on 4, 16, ...
   * times the neighbours (h two, four, ... times as wide), the last try at
   * this factor of h, and the widest fit that draws the same surface as the
   * narrower one (within half the bound and 5 degrees, both widened by the
   * measured noise) is kept: large splats where the surface is smooth, small
   * ones in folds and at thin parts. On dense, noisy scans far fewer splats
   * and a better picture; on sparse, clean ones a lower score (see
   * docs/results.md, "Splat density and noise"). Each doubling searches
   * four times the neighbours for the splats it is tried on (the fit itself
   * takes at most 8 times NumberOfNeighbors of them, evenly by distance;
   * see SubsampleWideFits), and widens the parallel selection's slabs as
   * much. Default 1: one scale, h from FeatureSizeNeighbors.
   */
  vtkSetClampMacro(MaximumFeatureScale, double, 1.0, 64.0);
  vtkGetMacro(MaximumFeatureScale, double);
  ///@}
  ///@{
  /**
   * With MaximumFeatureScale of 2 or more: a wide fit finds its plane, h and
   * fit points in a subsample of the points (every 4th, 16th or 64th, the
   * sparsest that still holds 256 of its neighbours), its 16 nearest points
   * whole; its bound still tests every point. Off: every neighbour, up to
   * max(NumberOfNeighbors, FeatureSizeNeighbors + 1) m^2 points at scale m.
   * With the spatial order of the points, Lucy resampled to 4M and 10M
   * noisy points fits in 0.58 and 0.52 times the time, the splat count
   * within 1 % and masked SSIM within 0.0013 (docs/results.md). Default on.
   */
  vtkSetMacro(SubsampleWideFits, bool);
  vtkGetMacro(SubsampleWideFits, bool);
  vtkBooleanMacro(SubsampleWideFits, bool);
  ///@}
  ///@{
  /**
   * Most reweighting steps of the error-bounded fit (MaximumDeviation >
   * 0): each refits the plane and the patch with the neighbours' weights
   * lowered by their distance to the last patch, so that the fit keeps to
   * the sheet of the surface its point lies on. A fit stops earlier once no
   * weight moves by more than 0.05. Fewer steps cost less fit time, but
   * with 2 the fits of two parallel sheets closer than the neighbourhood
   * no longer keep them apart. Default 4.
   */
  vtkSetClampMacro(ReweightingIterations, int, 1, 100);
  vtkGetMacro(ReweightingIterations, int);
  ///@}
  ///@{
  /**
   * Normal test of the error-bounded fit (MaximumDeviation > 0): a point
   * within the bound whose normal turns from the patch's normal there by
   * more than MaximumNormalAngle degrees lies on another wall of a crease
   * or a fold. The splat does not cover it, and its disc stops there
   * (psSplatBound.h). Close to a fold's crease, the rows of its other wall
   * are within the bound of the patch, and a disc that reaches over them
   * shows a light flake where the fold is dark.
   *
   * The test uses the input's point normals when it has them. Without
   * them, it runs only with EstimateNormals on, on PCA normals of each
   * point's 10 nearest neighbours. The estimate costs about 1.5 times the
   * fit time on smooth scans (the Bunny, the Horse) and 1.2 times on Lucy,
   * and on those scans it changed the picture little once the bound's
   * other rules stopped flakes at creases (see the README). It lowers how
   * far patches stray at a cube's edges. 90 or more turns the test off. Defaults: 60
   * degrees, EstimateNormals off.
   */
  vtkSetClampMacro(MaximumNormalAngle, double, 0.0, 180.0);
  vtkGetMacro(MaximumNormalAngle, double);
  vtkSetMacro(EstimateNormals, bool);
  vtkGetMacro(EstimateNormals, bool);
  vtkBooleanMacro(EstimateNormals, bool);
  ///@}
  ///@{
  /**
   * Input points within this fraction of the bounding-box diagonal of each
   * other are merged before fitting (see pointsurfaces::UniquePoints);
   * exact duplicates always are. Default 1e-6.
   */
  vtkSetClampMacro(MergeTolerance, double, 0.0, 1.0);
  vtkGetMacro(MergeTolerance, double);
  ///@}
  ///@{
  /**
   * The most memory a fit may take, in kibibytes (as
   * vtkDataObject::GetActualMemorySize counts). 0 (the default): the
   * physical memory free when the fit starts. A fit whose estimate
   * (EstimateMemorySize) is larger stops before it allocates, with one error
   * that names both figures and what to change, and an empty output; the
   * filter runs again as usual once the limit or the input changes.
   */
  vtkSetClampMacro(MemoryLimit, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MemoryLimit, vtkIdType);
  ///@}

  /**
   * The memory, in kibibytes, that fitting `numberOfPoints` points takes at
   * the defaults: 640 bytes a point, the peak measured on 0.1M to 10M points
   * (0.5 to 0.6 KB) with a margin. Other settings move it by tens of percent.
   */
  static vtkIdType EstimateMemorySize(vtkIdType numberOfPoints);

  ///@{
  /** Seed of every random choice. Default 1. */
  vtkSetMacro(RandomSeed, unsigned int);
  vtkGetMacro(RandomSeed, unsigned int);
  ///@}

  ///@{
  /**
   * Counts of the last run: dropped input points, merged (coincident) input
   * points, neighbourhoods without a splat, fits at a lower degree.
   */
  vtkGetMacro(NumberOfInvalidPoints, vtkIdType);
  vtkGetMacro(NumberOfMergedPoints, vtkIdType);
  vtkGetMacro(NumberOfDegenerateSplats, vtkIdType);
  vtkGetMacro(NumberOfReducedDegreeSplats, vtkIdType);
  ///@}

protected:
  vtkAlgebraicSplatFitter();
  ~vtkAlgebraicSplatFitter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  void SortByOctree(pointsurfaces::BuildResult& built, vtkPolyData* output);
  /** False, with an error, when fitting `points` points would exceed MemoryLimit. */
  bool FitsInMemory(vtkIdType points);
  /** What the last run's bound was measured in (ToleranceUnit AUTOMATIC resolved), for the getters. */
  void SetResolvedTolerance(pointsurfaces::ToleranceUnit unit,
    const pointsurfaces::SampleNoise& noise);
  /** Merge coincident points (MergeTolerance) in place; `kept` maps them to input ids. */
  void MergeCoincident(std::vector<double>& xyz,
    std::vector<double>& normals,
    std::vector<vtkIdType>& kept);
  /**
   * Put the points in spatial (Morton) order in place, `kept` with them: the
   * fit's neighbour searches then touch fewer cache lines, and its splats
   * do not depend on the input's order.
   */
  static void SortSpatially(std::vector<double>& xyz,
    std::vector<double>& normals,
    std::vector<vtkIdType>& kept);
  /** The build's parameters from the properties; `keepWeights` to carry the arrays over. */
  pointsurfaces::BuildParameters MakeParameters(bool keepWeights) const;

  int Degree = 3;
  int NumberOfNeighbors = 40;
  int ReweightingIterations = 4;
  double MaximumNormalAngle = 60.0;
  bool EstimateNormals = false;
  int FeatureSizeNeighbors = 24;
  double WeightScale = 1.0;
  int FitMode = Linear;
  int RobustLoss = Cauchy;
  double RobustLossScale = 0.05;
  int SelectionMode = Quality;
  double QualityFactor = 1.0;
  int SelectionOrder = Random;
  vtkIdType NumberOfSplats = 1000;
  int LOPVariant = WLOP;
  int LOPIterations = 50;
  double RadiusScale = 1.0;
  vtkIdType MemoryLimit = 0;
  unsigned int RandomSeed = 1;
  int NumberOfLevels = 1;
  double CoarsestQualityFactor = 4.0;
  bool BuildOctree = true;
  int OctreeBucketSize = 64;
  bool OrientNormals = true;
  double MaximumDeviation = 0.5;
  int ToleranceUnit = AUTOMATIC;
  int ResolvedToleranceUnit = SPACING;
  double SampleNoiseGrowth = 0.0;
  double SampleNoiseLevel = 0.0;
  double NoiseFactor = 3.0;
  double FeatureNoiseFactor = 12.0;
  double MaximumFeatureScale = 1.0;
  bool SubsampleWideFits = true;
  double MergeTolerance = 1e-6;
  vtkIdType NumberOfMergedPoints = 0;

  vtkIdType NumberOfInvalidPoints = 0;
  vtkIdType NumberOfDegenerateSplats = 0;
  vtkIdType NumberOfReducedDegreeSplats = 0;

private:
  vtkAlgebraicSplatFitter(const vtkAlgebraicSplatFitter&) = delete;
  void operator=(const vtkAlgebraicSplatFitter&) = delete;
};

#endif
