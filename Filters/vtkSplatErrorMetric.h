// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSplatErrorMetric
 * @brief   Measures how far the original points lie from an algebraic splat surface.
 *
 * Input 0 is the original point set, input 1 the splats of
 * vtkAlgebraicSplatFitter. The output is input 0's points with point arrays
 *
 * - `SplatError`: delta_i = sum_j e_ij theta(||o_j - p_i||) of section 3.3.3
 *   of N. K. R. Bolla, "High Quality Rendering of Large Point-based
 *   Surfaces", M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]), e_ij the
 *   orthogonal distance to splat j;
 * - `SurfaceDistance`: distance to the blended splat surface;
 * - `SplatCoverage`: number of discs covering the point (0: a hole);
 *
 * and field data `SplatErrorPhi` (sum of delta_i), `SurfaceDistanceRMS`,
 * `SurfaceDistanceMaximum` (one-sided Hausdorff distance), `UncoveredPoints`
 * and `BoundsDiagonal` (for relative figures). Points with NaN coordinates
 * are skipped and counted.
 */
#ifndef vtkSplatErrorMetric_h
#define vtkSplatErrorMetric_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class POINTSURFACESFILTERS_EXPORT vtkSplatErrorMetric : public vtkPolyDataAlgorithm
{
public:
  static vtkSplatErrorMetric* New();
  vtkTypeMacro(vtkSplatErrorMetric, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The splats (input 1). */
  void SetSplatConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetSplatData(vtkDataObject* splats) { this->SetInputData(1, splats); }
  ///@}

  ///@{
  /** Results of the last run. */
  vtkGetMacro(RMSDistance, double);
  vtkGetMacro(MaximumDistance, double);
  vtkGetMacro(Phi, double);
  vtkGetMacro(NumberOfUncoveredPoints, vtkIdType);
  ///@}

protected:
  vtkSplatErrorMetric();
  ~vtkSplatErrorMetric() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double RMSDistance = 0.0;
  double MaximumDistance = 0.0;
  double Phi = 0.0;
  vtkIdType NumberOfUncoveredPoints = 0;

private:
  vtkSplatErrorMetric(const vtkSplatErrorMetric&) = delete;
  void operator=(const vtkSplatErrorMetric&) = delete;
};

#endif
