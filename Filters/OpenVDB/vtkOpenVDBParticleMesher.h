// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkOpenVDBParticleMesher
 * @brief   Particles to a triangle mesh through an OpenVDB level set.
 *
 * The usual way to turn particles into a surface outside PointSurfaces:
 * rasterise them into a sparse level set, then polygonise it. It is the
 * OpenVDB peer that benchmarks compare vtkMetaballMapper with, and a way to
 * get a mesh of a metaball surface for any VTK filter or writer.
 *
 * Input and ball parameters as vtkMetaballMapper (any vtkPointSet; radius
 * array or constant, RadiusScale, strengths, kernel, threshold). Methods:
 *
 * - Spheres (the default): openvdb::tools::ParticlesToLevelSet, the union of
 *   one sphere per ball, of the radius at which a lone ball of the field
 *   reaches T (half the support radius for Wyvill's kernel at T = 0.5), so a
 *   lone ball matches the metaball exactly; neighbours merge without the
 *   blend. Spheres under 1.5 voxels are skipped by OpenVDB and counted
 *   (GetNumberOfSkippedParticles) with a warning.
 * - MetaballField: the exact metaball field, as vtkMetaballLevelSetWriter
 *   writes it.
 *
 * The level set is then meshed by openvdb::tools::volumeToMesh (quads and
 * triangles, Adaptivity in [0, 1] merges flat regions), with point normals
 * from the level set's gradient. Both steps are timed (GetLevelSetTime,
 * GetMeshTime, milliseconds). VoxelSize 0 picks a tenth of the smallest
 * radius. Work happens in a frame centred on the data, so coordinates near
 * 1e7 mesh as precisely as near the origin.
 */
#ifndef vtkOpenVDBParticleMesher_h
#define vtkOpenVDBParticleMesher_h

#include "PointSurfacesFiltersOpenVDBModule.h" // For export macro
#include "vtkMetaballField.h"                  // For the field
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // For the field

#include <string> // For array names

class POINTSURFACESFILTERSOPENVDB_EXPORT vtkOpenVDBParticleMesher : public vtkPolyDataAlgorithm
{
public:
  static vtkOpenVDBParticleMesher* New();
  vtkTypeMacro(vtkOpenVDBParticleMesher, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** How particles become a level set (SetMethod). */
  enum Methods
  {
    Spheres = 0,
    MetaballField = 1
  };

  ///@{
  /** Spheres (OpenVDB's ParticlesToLevelSet) or MetaballField. Default Spheres. */
  vtkSetClampMacro(Method, int, Spheres, MetaballField);
  vtkGetMacro(Method, int);
  ///@}

  ///@{
  /**
   * The metaball field: kernel, threshold, radius array or constant radius,
   * radius scale and strength array, the strengths for MetaballField only (see vtkMetaballField). Set one to share
   * it, for example with the vtkMetaballMapper that draws the same balls;
   * null restores a field of its own. Default: a field of its own.
   */
  void SetField(vtkMetaballField* field);
  vtkMetaballField* GetField() { return this->Field; }
  ///@}

  /** Also the field's modification time. */
  vtkMTimeType GetMTime() override;

  ///@{
  /** Voxel edge in world units; 0 (the default): a tenth of the smallest radius. */
  vtkSetClampMacro(VoxelSize, double, 0.0, 1e30);
  vtkGetMacro(VoxelSize, double);
  ///@}

  ///@{
  /** volumeToMesh's adaptivity: 0 (the default) keeps every polygon, 1 merges the most. */
  vtkSetClampMacro(Adaptivity, double, 0.0, 1.0);
  vtkGetMacro(Adaptivity, double);
  ///@}

  ///@{
  /** The most voxels the level set may sample. Default 2e8. */
  vtkSetClampMacro(MaximumVoxels, double, 1.0, 1e12);
  vtkGetMacro(MaximumVoxels, double);
  ///@}

  ///@{
  /** What the last update did. Times in milliseconds. */
  vtkGetMacro(LevelSetTime, double);
  vtkGetMacro(MeshTime, double);
  vtkGetMacro(UsedVoxelSize, double);
  vtkGetMacro(NumberOfInvalidBalls, vtkIdType);
  vtkGetMacro(NumberOfSkippedParticles, vtkIdType);
  ///@}

protected:
  vtkOpenVDBParticleMesher();
  ~vtkOpenVDBParticleMesher() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Method = Spheres;
  vtkSmartPointer<vtkMetaballField> Field;
  double VoxelSize = 0.0;
  double Adaptivity = 0.0;
  double MaximumVoxels = 2e8;

  double LevelSetTime = 0.0;
  double MeshTime = 0.0;
  double UsedVoxelSize = 0.0;
  vtkIdType NumberOfInvalidBalls = 0;
  vtkIdType NumberOfSkippedParticles = 0;

private:
  vtkOpenVDBParticleMesher(const vtkOpenVDBParticleMesher&) = delete;
  void operator=(const vtkOpenVDBParticleMesher&) = delete;
};

#endif
