// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkAlgebraicSplatMapper
 * @brief   Ray casts algebraic splats on the GPU: polynomial patches bounded to discs.
 *
 * Renders the output of vtkAlgebraicSplatFitter (the splat data model of
 * DESIGN.md section 3) after chapter 4 of "Algebraic Splats and Metaballs":
 * each splat is drawn as a screen-space quad that bounds its volume (the
 * disc of radius R times the height range of g over it, built in a geometry
 * shader), and each fragment casts its ray in the splat's normalised frame,
 * solves F(t) = g(u, v) - w = 0 in closed form (degree 1 to 4, the float
 * solvers of glsl/vtkSplatRoots.glsl), keeps the nearest root inside the
 * disc, shades it with VTK's lights and material using the normal from the
 * gradient of g, and writes its true depth, so splats intersect correctly
 * with every other actor. Scalars are coloured as by any VTK mapper.
 *
 * Culling and continuous level of detail (thesis 3.4, 4.3.1): when the input
 * carries the octree of vtkAlgebraicSplatFitter, nodes whose bounding sphere
 * lies outside the view frustum are skipped, and each visible leaf draws the
 * prefix of its level-sorted splats down to the first level whose splats
 * are at most LODPixelError pixels across on screen. Without an octree, or
 * while a vtkHardwareSelector picks (its ids need one draw), every splat is
 * drawn.
 *
 * Not implemented yet: two-pass blending, adaptive anti-aliasing and
 * shadows (thesis 4.2-4.3); splats are drawn opaque.
 */
#ifndef vtkAlgebraicSplatMapper_h
#define vtkAlgebraicSplatMapper_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkOpenGLPolyDataMapper.h"

#include <memory> // For the octree

class POINTSURFACESRENDERING_EXPORT vtkAlgebraicSplatMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkAlgebraicSplatMapper* New();
  vtkTypeMacro(vtkAlgebraicSplatMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The degree of the splats being drawn (from the input's SplatDegree), or -1. */
  vtkGetMacro(Degree, int);

  ///@{
  /** Skip octree nodes outside the view frustum. Default on. */
  vtkSetMacro(Culling, bool);
  vtkGetMacro(Culling, bool);
  vtkBooleanMacro(Culling, bool);
  ///@}

  ///@{
  /**
   * Continuous LOD: a leaf draws its levels down to the first one whose
   * splats (diameter 2 R) are at most this many pixels across; 0 draws every
   * level. Default 0.
   */
  vtkSetClampMacro(LODPixelError, double, 0.0, 1e6);
  vtkGetMacro(LODPixelError, double);
  ///@}

  /** Splats drawn by the last render (after culling and LOD). */
  vtkGetMacro(NumberOfRenderedSplats, vtkIdType);

protected:
  vtkAlgebraicSplatMapper();
  ~vtkAlgebraicSplatMapper() override = default;

  void ComputeBounds() override;
  void GetShaderTemplate(std::map<vtkShader::Type, vtkShader*> shaders,
    vtkRenderer* ren,
    vtkActor* act) override;
  void ReplaceShaderValues(std::map<vtkShader::Type, vtkShader*> shaders,
    vtkRenderer* ren,
    vtkActor* act) override;
  void SetCameraShaderParameters(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  bool GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act) override;
  void BuildBufferObjects(vtkRenderer* ren, vtkActor* act) override;
  void RenderPieceDraw(vtkRenderer* ren, vtkActor* act) override;

  void ReadOctree(vtkPolyData* poly);
  void DrawOctree(vtkRenderer* ren, vtkActor* act);

  int Degree = -1;
  int ShaderDegree = -1;
  bool Culling = true;
  double LODPixelError = 0.0;
  vtkIdType NumberOfRenderedSplats = 0;

private:
  struct Octree;
  std::shared_ptr<Octree> Nodes;

  vtkAlgebraicSplatMapper(const vtkAlgebraicSplatMapper&) = delete;
  void operator=(const vtkAlgebraicSplatMapper&) = delete;
};

#endif
