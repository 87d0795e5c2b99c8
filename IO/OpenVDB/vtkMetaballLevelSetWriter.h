// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballLevelSetWriter
 * @brief   Writes the iso-surface of a metaball field as an OpenVDB level set (.vdb).
 *
 * Houdini, Blender and most VFX tools read narrow-band level sets, not our
 * balls. This writer takes the same input and parameters as
 * vtkMetaballMapper (any vtkPointSet; radius array or constant radius,
 * RadiusScale, optional strengths, kernel, threshold T) and writes the
 * surface f = sum q_i K(|x - p_i|^2 / R_i^2) = T as a FloatGrid of class
 * GRID_LEVEL_SET: signed distances in world units, negative inside, within
 * HalfWidth voxels of the surface.
 *
 * How: every ball adds its kernel to the voxels inside its support (in
 * parallel, one sparse grid per thread, summed), the values become the
 * first-order distance (T - sum) / |grad sum| (central differences), and
 * openvdb::tools::levelSetRebuild meshes that iso-surface and turns it into
 * an exact narrow-band distance to the mesh. Sampling and meshing happen in
 * a frame centred on the data (OpenVDB meshes in float), and the grid's
 * transform then moves it into place, so coordinates near 1e7 keep their
 * precision. TestMetaballLevelSetWriter measures the result against the
 * exact iso-surface.
 *
 * VoxelSize 0 (the default) picks a tenth of the smallest radius (a lone
 * Wyvill ball's surface, at half its radius, is then 5 voxels across), coarsened
 * when the sampled voxels would exceed MaximumVoxels (with a warning, since
 * balls below two voxels then fade). An explicit VoxelSize beyond the budget is
 * an error. Balls with a NaN centre, radius or strength, or a radius <= 0, are
 * skipped and counted (GetNumberOfInvalidBalls) with one warning. Input with
 * no valid ball writes an empty level set and warns.
 */
#ifndef vtkMetaballLevelSetWriter_h
#define vtkMetaballLevelSetWriter_h

#include "PointSurfacesIOOpenVDBModule.h" // For export macro
#include "vtkMetaballField.h"             // For the field
#include "vtkSmartPointer.h"              // For the field
#include "vtkWriter.h"

#include <string> // For FileName

class POINTSURFACESIOOPENVDB_EXPORT vtkMetaballLevelSetWriter : public vtkWriter
{
public:
  static vtkMetaballLevelSetWriter* New();
  vtkTypeMacro(vtkMetaballLevelSetWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The .vdb file to write. Default: none. */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /** The name of the level-set grid in the file. Default "surface". */
  vtkSetStdStringFromCharMacro(GridName);
  vtkGetCharFromStdStringMacro(GridName);
  ///@}

  ///@{
  /**
   * The metaball field: kernel, threshold, radius array or constant radius,
   * radius scale and strength array (see vtkMetaballField). Set one to share
   * it, for example with the vtkMetaballMapper that draws the same balls;
   * null restores a field of its own. Default: a field of its own.
   */
  void SetField(vtkMetaballField* field);
  vtkMetaballField* GetField() { return this->Field; }
  ///@}

  /** Also the field's modification time. */
  vtkMTimeType GetMTime() override;

  ///@{
  /** Voxel edge in world units; 0 (the default): automatic, see the class comment. */
  vtkSetClampMacro(VoxelSize, double, 0.0, 1e30);
  vtkGetMacro(VoxelSize, double);
  ///@}

  ///@{
  /** Half the narrow band's width, in voxels. Default 3 (OpenVDB's usual). */
  vtkSetClampMacro(HalfWidth, double, 1.0, 1000.0);
  vtkGetMacro(HalfWidth, double);
  ///@}

  ///@{
  /** The most voxels the field may be sampled at. Default 2e8 (about 1 GB). */
  vtkSetClampMacro(MaximumVoxels, double, 1.0, 1e12);
  vtkGetMacro(MaximumVoxels, double);
  ///@}

  ///@{
  /** What the last write did: balls skipped, voxel size used, active voxels written. */
  vtkGetMacro(NumberOfInvalidBalls, vtkIdType);
  vtkGetMacro(UsedVoxelSize, double);
  vtkGetMacro(NumberOfActiveVoxels, vtkIdType);
  ///@}

protected:
  vtkMetaballLevelSetWriter();
  ~vtkMetaballLevelSetWriter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  std::string FileName;
  std::string GridName = "surface";
  vtkSmartPointer<vtkMetaballField> Field;
  double VoxelSize = 0.0;
  double HalfWidth = 3.0;
  double MaximumVoxels = 2e8;

  vtkIdType NumberOfInvalidBalls = 0;
  double UsedVoxelSize = 0.0;
  vtkIdType NumberOfActiveVoxels = 0;

private:
  vtkMetaballLevelSetWriter(const vtkMetaballLevelSetWriter&) = delete;
  void operator=(const vtkMetaballLevelSetWriter&) = delete;
};

#endif
