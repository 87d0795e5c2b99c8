// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psOpenVDBMetaballs.h
 * @brief Metaball and particle level sets through OpenVDB (PointSurfaces::FiltersOpenVDB, not wrapped).
 *
 * Shared by vtkMetaballLevelSetWriter and vtkOpenVDBParticleMesher:
 *
 * - MetaballLevelSet: the metaball field of psMetaball as a narrow-band
 *   level set (kernels splatted into sparse per-thread grids, the
 *   first-order distance (T - sum) / |grad sum|, levelSetRebuild);
 * - SphereLevelSet: OpenVDB's own ParticlesToLevelSet, a union of spheres;
 * - MeshLevelSet: volumeToMesh, with normals from the level set's gradient.
 *
 * Grids live in a frame whose origin is `centre` (scale-only transform):
 * OpenVDB meshes in float world coordinates, so large offsets are removed
 * first and put back in double on the way out.
 */
#ifndef psOpenVDBMetaballs_h
#define psOpenVDBMetaballs_h

#include "PointSurfacesFiltersOpenVDBModule.h" // For export macro
#include "psBallExtraction.h"
#include "psMetaball.h"
#include "vtkSmartPointer.h"

#include <openvdb/openvdb.h>

#include <string>
#include <vector>

class vtkPointSet;
class vtkPolyData;

namespace pointsurfaces
{
/** The balls usable in `set` (ValidBall), their bounds and smallest radius and sum of R^3. */
struct POINTSURFACESFILTERSOPENVDB_EXPORT BallSummary
{
  std::vector<long long> Valid;
  long long Invalid = 0;
  double Lo[3] = { 0, 0, 0 }, Hi[3] = { 0, 0, 0 };
  double MinRadius = 0.0;
  double SumCubedRadius = 0.0;
  openvdb::Vec3d Centre{ 0.0 }; ///< the bounds' centre, rounded to `voxel` by CentreOn
  void CentreOn(double voxel);
};
POINTSURFACESFILTERSOPENVDB_EXPORT BallSummary SummariseBalls(const MetaballSet& set);

/**
 * The warnings a filter should give about `arrays` and `balls`: a strength
 * array named (`strengthName`) but missing, and balls skipped as invalid.
 */
POINTSURFACESFILTERSOPENVDB_EXPORT std::vector<std::string> BallWarnings(const BallArrays& arrays,
  const BallSummary& balls,
  const std::string& strengthName);

/**
 * The voxel size: `requested`, or a tenth of the smallest radius, raised to
 * keep the sampled voxels (sum of ball volumes / voxel^3) under
 * `maximumVoxels`. Returns false (with `error`) when a requested size is
 * beyond the budget or the span beyond 32-bit voxel coordinates; `warning`
 * is set when an automatic size was raised.
 */
POINTSURFACESFILTERSOPENVDB_EXPORT bool ChooseVoxel(const BallSummary& balls,
  double requested,
  double maximumVoxels,
  double& voxel,
  std::string& warning,
  std::string& error);

/** What vtkMetaballLevelSetWriter and vtkOpenVDBParticleMesher sample: PrepareLevelSet. */
struct POINTSURFACESFILTERSOPENVDB_EXPORT LevelSetBalls
{
  BallArrays Arrays;
  BallSummary Summary;               ///< centred on Voxel (CentreOn) once Voxel is chosen
  std::vector<std::string> Warnings; ///< BallWarnings, then ChooseVoxel's, each a sentence
  double Voxel = 0.0;                ///< 0 when Error is set
  std::string Error;                 ///< ChooseVoxel's, empty when Voxel is usable
};

/**
 * The steps both level-set filters take before sampling: summarise the
 * extracted balls, list the warnings to give, choose the voxel size within
 * `maximumVoxels` (ChooseVoxel) and centre the grid's frame on it. The
 * callers extract the balls themselves (their rules differ) and give the
 * warnings and the error in their own words.
 */
POINTSURFACESFILTERSOPENVDB_EXPORT LevelSetBalls PrepareLevelSet(BallArrays arrays,
  const std::string& strengthName,
  double requestedVoxel,
  double maximumVoxels);

/** The metaball surface f = 0 as a level set, `halfWidth` voxels each side. */
POINTSURFACESFILTERSOPENVDB_EXPORT openvdb::FloatGrid::Ptr MetaballLevelSet(const MetaballSet& set,
  const BallSummary& balls,
  double voxel,
  double halfWidth);

/**
 * OpenVDB's ParticlesToLevelSet: the union of spheres of radius
 * `sphereRadius[i]` (world units) around the valid balls. `tooSmall`
 * receives the number of spheres under 1.5 voxels, which OpenVDB skips.
 */
POINTSURFACESFILTERSOPENVDB_EXPORT openvdb::FloatGrid::Ptr SphereLevelSet(const MetaballSet& set,
  const BallSummary& balls,
  const std::vector<double>& sphereRadius,
  double voxel,
  double halfWidth,
  size_t& tooSmall);

/** volumeToMesh at the zero crossing, moved back by `centre`, with point normals. */
POINTSURFACESFILTERSOPENVDB_EXPORT vtkSmartPointer<vtkPolyData> MeshLevelSet(
  const openvdb::FloatGrid& grid,
  const openvdb::Vec3d& centre,
  double adaptivity);
} // namespace pointsurfaces

#endif
