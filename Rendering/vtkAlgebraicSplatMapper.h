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
 * This is the core of the mapper. Two-pass blending, adaptive anti-aliasing,
 * octree culling with continuous LOD and shadows (thesis 4.2-4.3) are not
 * implemented yet: every splat is drawn, opaque.
 */
#ifndef vtkAlgebraicSplatMapper_h
#define vtkAlgebraicSplatMapper_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkOpenGLPolyDataMapper.h"

class POINTSURFACESRENDERING_EXPORT vtkAlgebraicSplatMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkAlgebraicSplatMapper* New();
  vtkTypeMacro(vtkAlgebraicSplatMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The degree of the splats being drawn (from the input's SplatDegree), or -1. */
  vtkGetMacro(Degree, int);

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

  int Degree = -1;
  int ShaderDegree = -1;

private:
  vtkAlgebraicSplatMapper(const vtkAlgebraicSplatMapper&) = delete;
  void operator=(const vtkAlgebraicSplatMapper&) = delete;
};

#endif
