// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballGhostBalls
 * @brief   Adds the balls of other processes that reach this process's balls, so that split
 *          metaballs blend across the cuts.
 *
 * A metaball surface is a sum over all balls: when particles are split
 * across MPI ranks (ParaView's pvbatch or pvserver after RedistributeDataSet,
 * a distributed simulation), each rank that draws only its own balls loses
 * the blend at the cut and composites a seam. This filter gives each rank
 * copies of the other ranks' balls whose support (the sphere of radius R)
 * reaches the box that its own balls' supports cover. With non-negative
 * strengths that is enough for depth compositing to give exactly the serial
 * surface, colours and normals included: wherever a rank's own ball
 * reaches, its field equals the whole field, and elsewhere it is nowhere
 * above the whole field, so its hits are never nearer than the true ones
 * (see pointsurfaces::BallsReachingBox). No clipping to regions is needed,
 * and it holds for any split, not only spatial ones, although only a
 * spatial split keeps the ghosts few. Negative strengths break the bound:
 * the filter warns and the seam may show.
 *
 * Radii are found as vtkMetaballMapper finds them (RadiusArrayName, else
 * Radius, times RadiusScale); give the filter the mapper's values. The
 * exchange is two collective steps on the controller (an all-gather of
 * boxes and a gather per rank), so every rank must execute the filter.
 *
 * Output: a vtkPolyData for a vtkPointSet input (its points, point data and,
 * for polydata, its cells), or, for a composite input, the same structure
 * with each point-set leaf so converted. The ghosts follow the points of
 * the first non-empty leaf, with the point arrays the two share, and are
 * marked vtkDataSetAttributes::DUPLICATEPOINT in a vtkGhostType array
 * (created with zeros for the own points when the input has none). With one
 * process, or no controller, the output is the input so converted.
 */
#ifndef vtkMetaballGhostBalls_h
#define vtkMetaballGhostBalls_h

#include "PointSurfacesFiltersParallelModule.h" // For export macro
#include "vtkDataObjectAlgorithm.h"

#include <string> // For the array names

class vtkMultiProcessController;

class POINTSURFACESFILTERSPARALLEL_EXPORT vtkMetaballGhostBalls : public vtkDataObjectAlgorithm
{
public:
  static vtkMetaballGhostBalls* New();
  vtkTypeMacro(vtkMetaballGhostBalls, vtkDataObjectAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The controller to exchange balls over. Default: the global controller. */
  void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /** Point array of support radii, as vtkMetaballMapper's; empty: Radius for all. */
  vtkSetStdStringFromCharMacro(RadiusArrayName);
  vtkGetCharFromStdStringMacro(RadiusArrayName);
  ///@}

  ///@{
  /** Support radius when there is no radius array (default 1). */
  vtkSetMacro(Radius, double);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /** Factor on every radius (default 1). */
  vtkSetMacro(RadiusScale, double);
  vtkGetMacro(RadiusScale, double);
  ///@}

  ///@{
  /** Point array of strengths, checked for negative values only. */
  vtkSetStdStringFromCharMacro(StrengthArrayName);
  vtkGetCharFromStdStringMacro(StrengthArrayName);
  ///@}

  /** Ghost balls this process received in the last update. */
  vtkGetMacro(NumberOfGhostBalls, vtkIdType);

protected:
  vtkMetaballGhostBalls();
  ~vtkMetaballGhostBalls() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  vtkMultiProcessController* Controller = nullptr;
  std::string RadiusArrayName;
  double Radius = 1.0;
  double RadiusScale = 1.0;
  std::string StrengthArrayName;
  vtkIdType NumberOfGhostBalls = 0;

private:
  vtkMetaballGhostBalls(const vtkMetaballGhostBalls&) = delete;
  void operator=(const vtkMetaballGhostBalls&) = delete;
};

#endif
