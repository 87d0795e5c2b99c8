// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psMetaballCast.h
 * @brief The metaball mapper's native CPU ray caster (float, vtkSMPTools).
 *
 * On a software OpenGL (Mesa's llvmpipe) a compute shader is emulated, and
 * the coherent tile march of [Bolla 2010] Algorithm 3 spends most of its time
 * in barriers and in samples of empty space. This is the same method, native:
 *
 * - the perspective grid (screen tiles times depth slabs, each voxel listing
 *   the balls whose support reaches into it), built in float from the view-
 *   space boxes of the balls, as the grid compute shader does;
 * - one task per tile (vtkSMPTools), which walks the tile's voxels front to
 *   back while any of its rays is still searching, with the voxel's balls
 *   copied into structure-of-arrays scratch (the ray/support tests of a ray
 *   against them are one vectorisable loop);
 * - per ray and voxel, the stretches of the ray inside some ball's support:
 *   the field is -T everywhere else, so nothing else is sampled, and each
 *   sample sums only the balls whose support the ray crosses there, held
 *   as a structure of arrays and summed in SIMD lanes (a branch-free kernel
 *   in every lane, masked to the balls in reach);
 * - stretches, whole voxels included, where the balls in reach cannot lift f
 *   to 0 even at their closest approach to the ray (the sum of
 *   max(q_i, 0) K(d_i^2 / R_i^2) is below T) are skipped: a dense SPH medium
 *   below the threshold costs no samples;
 * - in a crowded voxel (32 balls or more) the field is bounded before any
 *   ray marches: the voxel's depth is cut in 4 parts, and in the box around
 *   each part of an 8 x 8 pixel group, then of each 4 x 4 block, the sum of
 *   max(q_i, 0) K at the box's point nearest each centre bounds f + T. A
 *   block's rays march only from its first part whose bound reaches T to
 *   the end of its last, and skip the voxel when none does: in SPH gas a
 *   ray crosses hundreds of supports, mostly where the density is far
 *   below T, and finding its crossings and closest approaches cost more
 *   than the bounds;
 * - the march of the GPU: steps of max(base step, |f| / L), L a bound on
 *   |df/dt| over the balls in reach, base step StepScale times their smallest
 *   radius, steps cut where another support begins; then bisection of the
 *   first sign change, the analytic normal and the kernel-weighted colour.
 *
 * The outputs are the GPU pass's images: rgba8 colour (alpha 0: no hit),
 * view-space normal with the view distance, and window depth (1: no hit).
 * The double-precision pointsurfaces::CastRay stays the judge of accuracy.
 *
 * Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based
 * Surfaces", M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
 */
#ifndef psMetaballCast_h
#define psMetaballCast_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "psMetaball.h"                   // For MetaballKernel

#include <string> // For the error
#include <vector> // For the images

namespace pointsurfaces
{
/** The balls as the mapper keeps them: spans, not owned. */
struct MetaballCastInput
{
  const float* Balls = nullptr;         ///< x, y, z, R per ball; R <= 0 or NaN: skipped
  const float* Strengths = nullptr;     ///< q per ball; null: all 1
  const unsigned int* Colors = nullptr; ///< rgba8 per ball (r in the low byte); null: white
  long long Count = 0;
  MetaballKernel Kernel = MetaballKernel::Wyvill;
  double Threshold = 0.5; ///< T
};

/** The view and the march's settings. Matrices are row-major, column vectors. */
struct MetaballCastSettings
{
  double WorldToView[16]; ///< ball coordinates to the camera's view
  double ViewToClip[16];  ///< the projection (OpenGL clip space)
  double ClipToView[16];  ///< its inverse
  bool Parallel = false;
  int Width = 0; ///< pixels
  int Height = 0;
  int TileSize = 16;
  int Slabs = 16;
  double StepScale = 0.1; ///< the base step, in units of the smallest radius in reach
  int Bisections = 10;
  /**
   * Bytes the cast may allocate for its balls and grid; 0: the physical
   * memory free when it starts. Beyond it the cast draws nothing and says
   * why in MetaballCastStatistics::Error (never the kernel's OOM killer).
   */
  double MemoryLimit = 0.0;
};

/** The bytes the caster's copy of `balls` balls takes (its grid comes on top: 4 a pair). */
POINTSURFACESRENDERING_EXPORT double MetaballCastBallBytes(long long balls);

/** Per pixel, row by row from the bottom-left, as the GPU pass writes them. */
struct MetaballCastImages
{
  int Width = 0, Height = 0;
  std::vector<unsigned int> Color;   ///< rgba8; alpha 0 where no ray hit
  std::vector<float> NormalDistance; ///< 4 per pixel: view-space normal, view distance
  std::vector<float> Depth;          ///< window depth in [0, 1]; 1 where no ray hit
};

/** Where the time goes: the counters of one frame. */
struct MetaballCastStatistics
{
  long long Pairs = 0;       ///< (voxel, ball) pairs of the grid
  long long MaxPerVoxel = 0; ///< the most balls in one voxel
  long long Culled = 0;      ///< balls outside the view
  long long Invalid = 0;     ///< balls skipped as unusable
  double SlabNear = 0.0, SlabFar = 0.0;
  long long Rays = 0;             ///< rays cast (pixels)
  long long Hits = 0;             ///< rays that found the surface
  long long StartingInside = 0;   ///< rays whose first sample lies inside the surface
  long long VoxelVisits = 0;      ///< (ray, voxel) pairs a searching ray walked through
  long long EmptyVoxelVisits = 0; ///< of those, with no ball's support on the ray
  long long SupportTests = 0;     ///< ray/support intersection tests
  long long Samples = 0;          ///< field evaluations of the march
  long long BisectionSamples = 0; ///< field evaluations of the bisections
  long long KernelTerms = 0;      ///< kernel evaluations in all of those
  std::string Error;              ///< why nothing was cast (too many balls, no memory); else empty
  double GridSeconds = 0.0;       ///< wall time of the grid build
  double CastSeconds = 0.0;       ///< wall time of the march
  long long MergedBalls = 0;      ///< the GPU caster's level of detail: balls made
  long long BallsMerged = 0;      ///< and the balls they stand for
};

/**
 * Casts one frame. The images are resized to the view; on no usable ball or
 * an empty view they hold misses only.
 */
POINTSURFACESRENDERING_EXPORT void CastMetaballs(const MetaballCastInput& input,
  const MetaballCastSettings& settings,
  MetaballCastImages& images,
  MetaballCastStatistics* statistics = nullptr);
} // namespace pointsurfaces

#endif
