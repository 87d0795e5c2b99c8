// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psMetaball.h
 * @brief Metaball fields, the perspective grid and a reference ray caster ([Bolla 2010] ch. 5).
 *
 * Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based
 * Surfaces", M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
 *
 * The double-precision CPU reference for the metaball mapper's GPU work:
 *
 * - the field f(x) = sum_i q_i f_i(|x - p_i|) - T with finite-support kernels
 *   of [Bolla 2010] (Wyvill's sixth-order polynomial, eq. 1.4; the quartic
 *   (1 - r^2/R^2)^2, eq. 1.3) and a truncated Gaussian, and its gradient;
 * - the perspective grid of [Bolla 2010] Algorithm 2: the view frustum cut into screen
 *   tiles times depth slabs, each voxel listing the balls whose support
 *   reaches into it (count, exclusive scan, scatter, sort by voxel);
 * - a ray caster: dense sampling along the ray and bisection on the exact
 *   field, with the analytic normal.
 *
 * Plain functions over spans; nothing here knows VTK's pipeline.
 */
#ifndef psMetaball_h
#define psMetaball_h

#include "PointSurfacesFiltersModule.h" // For export macro

#include "psMetaballKernels.h" // For MetaballKernel
#include "psPerspectiveGrid.h" // For the grid geometry

#include <vector> // For grid lists

namespace pointsurfaces
{
// The kernels (MetaballKernel) and their formulas: psMetaballKernels.h.
// The functions below dispatch to its double instances at run time.

/** The kernel at x = r^2 / R^2, and its derivative d/dx in `derivative` when given. */
POINTSURFACESFILTERS_EXPORT double KernelValue(MetaballKernel kernel,
  double x,
  double* derivative = nullptr);

/** Is it one of the SPH kernels (normalised by the support radius)? */
POINTSURFACESFILTERS_EXPORT bool IsSPHKernel(MetaballKernel kernel);

/**
 * N with integral over space of N / R^3 K(|x|^2 / R^2) = 1 for an SPH kernel
 * (8/pi, 21/(2 pi), 495/(32 pi)); 0 for the others, which are not normalised.
 */
POINTSURFACESFILTERS_EXPORT double KernelNormalization(MetaballKernel kernel);

/**
 * SWIFT's ratio of support radius to smoothing length for the kernel
 * (kernel_gamma of SWIFT's kernel_hydro.h: 1.825742 for the cubic spline,
 * 1.936492 for Wendland C2, 2.207940 for Wendland C4); 1 for the others.
 * Use it as vtkMetaballField's RadiusScale for SWIFT's SmoothingLengths.
 */
POINTSURFACESFILTERS_EXPORT double SWIFTSupportFactor(MetaballKernel kernel);

/**
 * The largest |dK/dq| over q = r / R in [0, 1]: |grad f| <= sum |q_i| times
 * this over R_i, the bound the ray marchers step by.
 */
POINTSURFACESFILTERS_EXPORT double KernelSlopeBound(MetaballKernel kernel);

/**
 * The radius, in units of R, at which a lone ball of strength 1 reaches
 * `threshold`: sqrt(x) with K(x) = T, by bisection (the kernels decrease).
 * 0 when T >= K(0), where a lone ball has no surface. Scale T by 1/q for a
 * strength q, or by 1/n for n coincident balls.
 */
POINTSURFACESFILTERS_EXPORT double LoneBallIsoRadius(MetaballKernel kernel, double threshold);

/** A set of balls: spans, not owned. */
struct MetaballSet
{
  const double* Centers = nullptr;   ///< 3 per ball
  const double* Radii = nullptr;     ///< R_i, the support radius
  const double* Strengths = nullptr; ///< q_i (with the SPH kernels' N / R_i^3); null: all 1
  long long Count = 0;
  MetaballKernel Kernel = MetaballKernel::Wyvill;
  double Threshold = 0.5; ///< T
};

/** Is ball i usable: finite centre, finite radius > 0, finite strength? */
POINTSURFACESFILTERS_EXPORT bool ValidBall(const MetaballSet& set, long long i);

/**
 * f(x) = sum q_i f_i - T over the balls `ids` (all balls when ids is null),
 * with its gradient in `gradient` when given.
 */
POINTSURFACESFILTERS_EXPORT double FieldValue(const MetaballSet& set,
  const double x[3],
  double gradient[3] = nullptr,
  const unsigned* ids = nullptr,
  long long idCount = 0);

/**
 * The ball that dominates the field at x, for picking: the valid ball of
 * `ids` (all balls when ids is null) whose term q_i K(|x - p_i|^2 / R_i^2)
 * is the largest, negative terms counting as 0. Among equal terms (all 0
 * where x lies outside every support, as a point a rounding error off the
 * surface can), the smallest |x - p_i|^2 / R_i^2 wins, then the earlier
 * ball of the list. -1 when no ball is valid.
 */
POINTSURFACESFILTERS_EXPORT long long DominantBall(const MetaballSet& set,
  const double x[3],
  const unsigned* ids = nullptr,
  long long idCount = 0);

/**
 * The box that the supports of the valid balls cover (centre +- R_i), as
 * xmin, xmax, ymin, ymax, zmin, zmax; min > max on every axis when no ball
 * is valid.
 */
POINTSURFACESFILTERS_EXPORT void SupportBounds(const MetaballSet& set, double bounds[6]);

/**
 * The valid balls whose support, the sphere of radius R_i around the centre,
 * meets the closed box `bounds` (ascending ids; none for an empty box).
 *
 * Ghost balls for a set split into parts (processes): give each part the
 * balls of the other parts that reach the SupportBounds of its own balls.
 * Then at any point inside the support of one of a part's own balls, the
 * part's field (own plus ghosts) equals the whole set's field, because every
 * ball that contributes there reaches that support and so that box. With
 * non-negative strengths a part's field is nowhere above the whole field,
 * so each part's first hit along a ray is never nearer than the true one,
 * and the part owning a ball around the true hit finds it: keeping the
 * nearest hit over the parts (depth compositing) gives the whole surface.
 */
POINTSURFACESFILTERS_EXPORT std::vector<long long> BallsReachingBox(const MetaballSet& set,
  const double bounds[6]);

/** The view for the perspective grid. Matrices are row-major, column vectors. */
struct GridView
{
  double WorldToView[16]; ///< the camera's view transform
  double ViewToClip[16];  ///< its projection (OpenGL clip space)
  bool Parallel = false;  ///< parallel projection
  int Width = 0;          ///< viewport, pixels
  int Height = 0;
  int TileSize = 16;     ///< pixels per tile side
  int Slabs = 16;        ///< depth slabs
  double SlabNear = 0.0; ///< first slab plane (view distance); SlabFar <= SlabNear: automatic
  double SlabFar = 0.0;  ///< last slab plane
};

/** Tiles x slabs, each voxel listing its balls. Voxel id = (slab * tilesY + ty) * tilesX + tx. */
struct PerspectiveGrid
{
  int TilesX = 0, TilesY = 0, Slabs = 0;
  std::vector<double> SlabPlanes; ///< Slabs + 1 view distances, ascending
  std::vector<unsigned>
    Offsets;                   ///< voxels + 1: voxel v's balls are Balls[Offsets[v], Offsets[v+1])
  std::vector<unsigned> Balls; ///< ball ids by voxel, ascending within a voxel
  long long Pairs = 0;         ///< (voxel, ball) pairs
  unsigned MaxPerVoxel = 0;
  long long Culled = 0;  ///< balls outside the frustum
  long long Invalid = 0; ///< NaN or non-positive radii, skipped
};

/**
 * The voxel range a ball's support reaches: tiles [r[0], r[1]] x [r[2], r[3]]
 * and slabs [r[4], r[5]], from its bounding sphere's projection (the sphere's
 * view-space box for the depth; a ball reaching the eye plane covers every
 * tile), by PerspectiveGridGeometry with uniform slabs between the ends of
 * `slabPlanes`. Returns false when the ball lies outside the frustum or the
 * slabs.
 */
POINTSURFACESFILTERS_EXPORT bool BallVoxels(const GridView& view,
  const std::vector<double>& slabPlanes,
  const double centre[3],
  double radius,
  int range[6]);

/**
 * The slab planes for `view`: its SlabNear/SlabFar, or, when automatic, the
 * nearest and farthest view distance that the balls in the frustum reach,
 * each clamped to the projection's range and to d >= 0, split uniformly
 * (PerspectiveGridGeometry::Extend and SetSlabRange).
 */
POINTSURFACESFILTERS_EXPORT std::vector<double> SlabPlanes(const MetaballSet& set,
  const GridView& view);

/** Algorithm 2 on the CPU: count, exclusive scan, scatter, sort by voxel. */
POINTSURFACESFILTERS_EXPORT PerspectiveGrid BuildPerspectiveGrid(const MetaballSet& set,
  const GridView& view);

/** A ray's first crossing of the iso-surface f = 0 (from f < 0 to f >= 0). */
struct RayHit
{
  bool Hit = false;
  double T = 0.0;                 ///< ray parameter of the hit
  double Point[3] = { 0, 0, 0 };  ///< origin + T direction
  double Normal[3] = { 0, 0, 0 }; ///< unit, -grad f (outward)
};

/**
 * Reference ray cast: samples f every `step` along origin + t direction for
 * t in [tMin, tMax], then bisects the first bracket `bisections` times. With
 * a step well below the smallest radius this finds the first crossing.
 */
POINTSURFACESFILTERS_EXPORT RayHit CastRay(const MetaballSet& set,
  const double origin[3],
  const double direction[3],
  double tMin,
  double tMax,
  double step,
  int bisections);
} // namespace pointsurfaces

#endif
