// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkAlgebraicSplatRepresentation
 * @brief   ParaView's "Algebraic Splats" representation: splats ray-cast by vtkAlgebraicSplatMapper.
 *
 * A surface representation whose mappers are vtkAlgebraicSplatMapper (through
 * vtkPointSurfacesDelegatingMapper, which takes ParaView's composite data
 * and colouring), so the output of the Algebraic Splat Fitter shows as the
 * smooth, lit, depth-correct surface of its splats, coloured like any other
 * representation. The mapper's knobs are forwarded: two-pass blending and
 * its depth offset and sharpness, adaptive anti-aliasing and its silhouette
 * threshold, octree culling and the LOD pixel error. ParaView's decimated
 * interaction LOD is suppressed: decimation would drop the splat arrays, and
 * the mapper has its own level of detail.
 */
#ifndef vtkAlgebraicSplatRepresentation_h
#define vtkAlgebraicSplatRepresentation_h

#include "PointSurfacesParaViewRepresentationsModule.h" // For export macro
#include "vtkGeometryRepresentationWithFaces.h"
#include "vtkSmartPointer.h" // For the mappers

#include <vector> // For the mappers

class vtkAlgebraicSplatMapper;
class vtkPointSurfacesDelegatingMapper;

class POINTSURFACESPARAVIEWREPRESENTATIONS_EXPORT vtkAlgebraicSplatRepresentation
  : public vtkGeometryRepresentationWithFaces
{
public:
  static vtkAlgebraicSplatRepresentation* New();
  vtkTypeMacro(vtkAlgebraicSplatRepresentation, vtkGeometryRepresentationWithFaces);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Forwarded to every splat mapper; see vtkAlgebraicSplatMapper. */
  void SetSplatBlending(bool on);
  void SetSplatBlendDepthOffset(double offset);
  void SetSplatBlendSharpness(double sharpness);
  void SetSplatAntiAliasing(int grid);
  void SetSplatSilhouetteThreshold(double threshold);
  void SetSplatCulling(bool on);
  void SetSplatLODPixelError(double pixels);
  ///@}

  void SetSuppressLOD(bool) override { this->Superclass::SetSuppressLOD(true); }

  /**
   * The surface is drawn opaque: an Opacity below 1 is kept at 1, with a
   * warning. (The mapper's own passes do not take part in ParaView's depth
   * peeling; drawn translucent, the surface broke into stripes and holes.)
   */
  void SetOpacity(double opacity) override;

  /**
   * The id arrays that selection reports through (ParaView's
   * "vtkOriginalPointIds" by default), handed to both mappers. The
   * superclass would cast its mapper to vtkCompositePolyDataMapper2 and
   * crash on these mappers when the user selects.
   */
  void SetArrayIdNames(const char* pointArray, const char* cellArray) override;

protected:
  vtkAlgebraicSplatRepresentation();
  ~vtkAlgebraicSplatRepresentation() override;

  /**
   * Opaque, whatever the colouring: no ordered compositing. (Direct colours
   * under MPI otherwise had ParaView redistribute the data among the ranks,
   * which lost the splats' octree and took a splat file's preview from the
   * rank that draws the file.)
   */
  bool NeedsOrderedCompositing() override { return false; }

  /**
   * Put `mapper` in the main mapper's place (a subclass's delegating mapper),
   * drawing through the first splat mapper, and wire it to the actor.
   */
  void SetMainMapper(vtkPointSurfacesDelegatingMapper* mapper);

  /** The splat mappers the knobs go to: the main one's and the LOD's first. */
  std::vector<vtkSmartPointer<vtkAlgebraicSplatMapper>> Splats;

private:
  vtkAlgebraicSplatRepresentation(const vtkAlgebraicSplatRepresentation&) = delete;
  void operator=(const vtkAlgebraicSplatRepresentation&) = delete;
};

#endif
