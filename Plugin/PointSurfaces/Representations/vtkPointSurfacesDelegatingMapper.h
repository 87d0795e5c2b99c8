// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkPointSurfacesDelegatingMapper
 * @brief   Feeds ParaView's composite geometry to a point-surface mapper.
 *
 * ParaView's geometry representations hand their mappers a
 * vtkMultiBlockDataSet, even for one vtkPolyData, and expect them to take
 * the colouring settings (scalar mode, array, lookup table) that the
 * representation sets. vtkAlgebraicSplatMapper and vtkMetaballMapper draw
 * one vtkPolyData (or vtkPointSet). This mapper sits in the representation's
 * place: it gathers the point-set leaves of the composite input (appending
 * them when there are several, once per input change), hands the result
 * and its own colouring settings to the delegate, and forwards rendering,
 * bounds and resource release. With SkipDuplicatePoints, points flagged as
 * another process's (DUPLICATEPOINT in vtkGhostType) are left out first.
 */
#ifndef vtkPointSurfacesDelegatingMapper_h
#define vtkPointSurfacesDelegatingMapper_h

#include "PointSurfacesParaViewRepresentationsModule.h" // For export macro
#include "vtkMapper.h"
#include "vtkSmartPointer.h" // For members
#include "vtkTimeStamp.h"    // For the flattening time

class vtkDataObject;
class vtkInformation;
class vtkMetaballGhostBalls;

class POINTSURFACESPARAVIEWREPRESENTATIONS_EXPORT vtkPointSurfacesDelegatingMapper
  : public vtkMapper
{
public:
  static vtkPointSurfacesDelegatingMapper* New();
  vtkTypeMacro(vtkPointSurfacesDelegatingMapper, vtkMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The mapper that draws (a vtkAlgebraicSplatMapper or a vtkMetaballMapper). */
  void SetDelegate(vtkMapper* delegate);
  vtkMapper* GetDelegate() { return this->Delegate; }
  ///@}

  ///@{
  /**
   * Leave out points flagged DUPLICATEPOINT (another process's ghost balls)
   * before the delegate sees the data; off by default. On where one process
   * renders what several made, so that no ghost counts beside its owner.
   */
  void SetSkipDuplicatePoints(bool skip);
  bool GetSkipDuplicatePoints() { return this->SkipDuplicatePoints; }
  ///@}

  /**
   * Whether each rank renders its own piece and the images are composited
   * by depth, for the view of a REQUEST_RENDER pass (`viewRequest`, the
   * inInfo of vtkPVDataRepresentation::ProcessViewRequest): data gathered
   * to one process, and tile and CAVE displays, are not. Without a view,
   * whether there are several processes.
   */
  static bool RendersPiecewise(vtkInformation* viewRequest);

  void Render(vtkRenderer* ren, vtkActor* act) override;
  double* GetBounds() override;
  void GetBounds(double bounds[6]) override { this->vtkMapper::GetBounds(bounds); }
  void ReleaseGraphicsResources(vtkWindow* window) override;
  bool HasOpaqueGeometry() override;
  bool HasTranslucentPolygonalGeometry() override;
  /** As the delegate: both mappers draw ids under a hardware selector. */
  bool GetSupportsSelection() override;

protected:
  vtkPointSurfacesDelegatingMapper();
  ~vtkPointSurfacesDelegatingMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  /** The input as one data set for the delegate (null when it has no points). */
  vtkDataObject* Flatten();

  vtkSmartPointer<vtkMapper> Delegate;
  bool SkipDuplicatePoints = false;
  vtkSmartPointer<vtkMetaballGhostBalls> Skipper; // drops duplicate points, alone
  vtkSmartPointer<vtkDataObject> Flat;
  vtkTimeStamp FlatTime;

private:
  vtkPointSurfacesDelegatingMapper(const vtkPointSurfacesDelegatingMapper&) = delete;
  void operator=(const vtkPointSurfacesDelegatingMapper&) = delete;
};

#endif
