// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psSampleNoise.h
 * @brief Whether a point sample is noisy: the residual of its local quadrics
 * against the size of the neighbourhood.
 *
 * A quadric fitted to a neighbourhood leaves a residual of two kinds: the
 * points' noise, which does not depend on how many neighbours the fit
 * takes, and relief the quadric cannot follow, which grows quickly with
 * the neighbourhood's width (as its third power for a cubic term). So the
 * robust residual scale (psSplatFit.h NoiseScale) of the 64 nearest points
 * over that of the 16 nearest, at a few hundred probes, tells a noisy scan
 * (a ratio near 1) from a clean one, sparse or dense (2.7 to 6 on the
 * shared meshes' vertices and their noise-free resamples), where the residual at
 * one scale cannot: a sparse mesh's folds at the sampling scale leave as
 * large a residual as noise does (Lucy's vertices, 0.15 spacings). The
 * splat fitter's ToleranceUnit Automatic (psSplatBuilder.h) fits a noisy
 * sample with the noise-aware bound and wide splats, and any other with
 * the bound in spacings.
 */
#ifndef psSampleNoise_h
#define psSampleNoise_h

#include "PointSurfacesFiltersModule.h" // For export macro

namespace pointsurfaces
{
class PointIndex;

/** What MeasureSampleNoise found. */
struct SampleNoise
{
  /** Median over the probes of NoiseScale(64 points) / NoiseScale(16 points). */
  double Growth = 0.0;
  /** Median over the probes of NoiseScale(16 points) / LocalSpacing. */
  double NoiseOverSpacing = 0.0;
  /** Probes that gave both scales (too few points or degenerate ones give none). */
  int Probes = 0;
  /** Growth under NoisyGrowth with NoiseOverSpacing at least MinimumNoise. */
  bool Noisy = false;
};

/**
 * The Growth under which a sample is noisy: 0.98 to 1.46 on the noisy
 * samples measured (spheres and resampled meshes with noise of 0.1 to 1
 * spacing, a Kinect scan, the raw range scan bun000 at 1.46), 2.7 and up
 * on clean ones; noise of 0.03 spacings measures 1.6 to 1.7.
 */
constexpr double NoisyGrowth = 1.5;
/** The NoiseOverSpacing under which a sample is clean whatever its Growth (a flat or finely sampled one). */
constexpr double MinimumNoise = 0.05;
/** Probes MeasureSampleNoise takes by default. */
constexpr int SampleNoiseProbes = 1024;

/**
 * Measure the noise of the `n` points `xyz` (finite; `index` is their
 * index) at `probes` points spread evenly through their order (their 64
 * nearest points each, planes by PCA). Deterministic; parallel over the
 * probes (vtkSMPTools). Fewer than 64 points or no probe with a residual:
 * Probes 0, not Noisy.
 */
POINTSURFACESFILTERS_EXPORT SampleNoise MeasureSampleNoise(const double* xyz,
  long long n,
  const PointIndex& index,
  int probes = SampleNoiseProbes);
} // namespace pointsurfaces

#endif
