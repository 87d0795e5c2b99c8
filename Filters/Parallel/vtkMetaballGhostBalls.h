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
 * strengths that makes depth compositing give the serial surface: wherever
 * a rank's own ball reaches, its field equals the whole field, and elsewhere
 * it is nowhere above the whole field, so its hits are never nearer than the
 * true ones (see pointsurfaces::BallsReachingBox). The field at every hit,
 * and so colour and normal, is the serial one; only the ray marcher's
 * sampling differs between ranks (its step follows each rank's smallest
 * radius). No clipping to regions is needed, and it holds for any split,
 * but only a spatial split keeps the ghosts few: where the ranks' boxes
 * overlap widely, most balls go to most ranks. Negative strengths break the
 * bound (the filter warns, and seams may show). Shadows see only a rank's
 * own and ghost balls: occluders further away on other ranks cast none.
 *
 * Radii are found by the rule of vtkMetaballField, the one the mapper
 * uses; give the filter the mapper's field (SetField). Where that rule
 * takes the radii from the spacing of the balls (no radius array, no
 * constant radius), each process alone would measure another spacing, and
 * the surfaces would not meet at the cuts. With more than one process this
 * filter therefore measures the mean nearest-neighbour spacing of all
 * processes' own balls together: each process finds its balls' nearest
 * neighbours among its own (pointsurfaces::NearestNeighbours), asks the
 * processes whose boxes the distance reaches for a nearer one (balls near
 * the cuts), and the sums and counts of all processes are added in rank
 * order, so that every process gets the same number, the serial one up to
 * rounding (a position held by two processes counts on each). The balls
 * are exchanged with radii from it, and it goes into each output leaf's
 * field data as the one-value array "MetaballMeanSpacing"
 * (pointsurfaces::MeanSpacingArrayName), which the mappers' rule reads
 * instead of measuring their piece. The measuring is kept for unchanged
 * leaves. The exchange is collective (all-gathers of boxes and spacings,
 * then gathers and scatters to each rank in turn), so every rank must
 * execute the filter. With one process, or no controller, nothing is
 * measured here (the mapper measures what it draws).
 *
 * Output: the balls as point clouds (one vertex per point; input cells and
 * cell data are not kept): a vtkPolyData for a vtkPointSet input, or, for a
 * composite input, the same structure with each point-set leaf so converted
 * (other leaves passed through). Point data and field data are kept. Input
 * points flagged vtkDataSetAttributes::DUPLICATEPOINT in vtkGhostType are
 * another process's balls: they are dropped, and their owner sends them
 * where they reach. With more than one process, the ghosts follow the own
 * points of the first leaf that has any, flagged DUPLICATEPOINT in a new
 * vtkGhostType array (0 for the own points); point arrays the ghosts lack
 * are zero there, with a warning. With one process, or no controller, the
 * output is the input's non-duplicate points, sharing the input's arrays
 * when nothing is dropped: vtkMetaballRepresentation uses this to drop
 * ghosts before one process renders every rank's balls.
 */
#ifndef vtkMetaballGhostBalls_h
#define vtkMetaballGhostBalls_h

#include "PointSurfacesFiltersParallelModule.h" // For export macro
#include "vtkDataObjectAlgorithm.h"
#include "vtkMetaballField.h" // For the field
#include "vtkSmartPointer.h"  // For the field

#include <memory> // For the neighbours
#include <set>    // For the missing arrays
#include <string> // For the missing arrays
#include <vector> // For the leaves

class vtkMultiProcessController;
class vtkPointSet;
class vtkPolyData;

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
  /**
   * The metaball field whose balls are exchanged: their radii (by the
   * field's rule, the spacing measured over all processes) decide which
   * balls reach other processes, and negative strengths are warned about (see
   * vtkMetaballField). Share the mapper's field (SetField) so that both
   * read the same balls; null restores a field of its own. Default: a field
   * of its own.
   */
  void SetField(vtkMetaballField* field);
  vtkMetaballField* GetField() { return this->Field; }
  ///@}

  /** Also the field's modification time. */
  vtkMTimeType GetMTime() override;

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

#ifndef __VTK_WRAP__
  /**
   * The mean nearest-neighbour spacing of all processes' own balls of the
   * leaves whose radii follow the spacing (`sources`), each ball's nearest
   * neighbour sought on every process; 0 when no process has two such
   * balls. The same number on every process; collective.
   */
  double SpacingOfAllProcesses(const std::vector<vtkPointSet*>& leaves,
    const std::vector<std::vector<vtkIdType>>& own,
    const std::vector<pointsurfaces::RadiusSource>& sources);

  /**
   * This process's own balls of the leaves whose radii follow the spacing
   * (`sources`), with their nearest neighbours here; measured again only
   * when a leaf changed.
   */
  const pointsurfaces::NearestNeighbours& OwnNeighbours(const std::vector<vtkPointSet*>& leaves,
    const std::vector<std::vector<vtkIdType>>& own,
    const std::vector<pointsurfaces::RadiusSource>& sources);

  /**
   * Lowers `distances` (of `mine`'s points) to their nearest neighbour on
   * any process: each process asks the others about its points whose
   * distance reaches their boxes. Collective.
   */
  void NearestOnAllProcesses(const pointsurfaces::NearestNeighbours& mine,
    std::vector<double>& distances);

  /**
   * The ghosts: every process's own balls (`centres`, `radii`) that reach
   * this process's box, gathered here from all processes as one point
   * cloud (null when none). Arrays that some pieces lack go to `missing`.
   * Collective.
   */
  vtkSmartPointer<vtkPolyData> ExchangeGhosts(const std::vector<vtkPointSet*>& leaves,
    const std::vector<std::vector<vtkIdType>>& own,
    std::vector<double>& centres,
    std::vector<double>& radii,
    std::set<std::string>& missing);
#endif

  vtkMultiProcessController* Controller = nullptr;
  vtkSmartPointer<vtkMetaballField> Field;
  vtkIdType NumberOfGhostBalls = 0;

#ifndef __VTK_WRAP__
  // This process's balls whose radii follow the spacing, with their nearest
  // neighbours here, and the leaves (addresses, compared and never
  // followed, and modification times) they were taken from.
  std::unique_ptr<pointsurfaces::NearestNeighbours> Neighbours;
  std::vector<const void*> SpacingLeaves;
  std::vector<vtkMTimeType> SpacingTimes;
#endif

private:
  vtkMetaballGhostBalls(const vtkMetaballGhostBalls&) = delete;
  void operator=(const vtkMetaballGhostBalls&) = delete;
};

#endif
