// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSplatDataModel
 * @brief   Names and helpers of the splat data model (DESIGN.md section 3), shared by its producers and consumers.
 *
 * Splats are a vtkPolyData with one vertex per splat and the point arrays
 * named here. The fitter writes them, the error metric and the mappers read
 * them; keeping the names and the checks in one place keeps them in step.
 */
#ifndef vtkSplatDataModel_h
#define vtkSplatDataModel_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "vtkObject.h"

class vtkPolyData;

class POINTSURFACESFILTERS_EXPORT vtkSplatDataModel : public vtkObject
{
public:
  static vtkSplatDataModel* New();
  vtkTypeMacro(vtkSplatDataModel, vtkObject);

  ///@{
  /** Array names of the data model. */
  static const char* NormalName() { return "SplatNormal"; }
  static const char* TangentName() { return "SplatTangent"; }
  static const char* FeatureSizeName() { return "SplatFeatureSize"; }
  static const char* CoefficientsName() { return "SplatCoefficients"; }
  static const char* RadiusName() { return "SplatRadius"; }
  static const char* LODName() { return "SplatLOD"; }
  static const char* DegreeName() { return "SplatDegree"; }
  /** Field data: 1 when the splats' normals are consistently oriented. */
  static const char* NormalsOrientedName() { return "SplatNormalsOriented"; }
  ///@}

  /** One vertex cell per point of `pd`, replacing its verts. */
  static void AddVertexCells(vtkPolyData* pd);

  /**
   * The degree of a splat set (field data SplatDegree), or -1 when `pd` lacks
   * any part of the data model (arrays, components, tuple counts).
   */
  static int GetSplatDegree(vtkPolyData* pd);

protected:
  vtkSplatDataModel() = default;
  ~vtkSplatDataModel() override = default;

private:
  vtkSplatDataModel(const vtkSplatDataModel&) = delete;
  void operator=(const vtkSplatDataModel&) = delete;
};

#endif
