// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkAlgebraicSplatMapper
 * @brief   Ray casts algebraic splats on the GPU: polynomial patches bounded to discs.
 *
 * Renders the output of vtkAlgebraicSplatFitter (the splat data model: see
 * vtkSplatDataModel) after chapter 4 of N. K. R. Bolla, "High Quality
 * Rendering of Large Point-based Surfaces", M.S. thesis, IIIT Hyderabad,
 * 2010 ([Bolla 2010]):
 * each splat is drawn as the eye-facing faces of a box that bounds its
 * volume (the square around its disc of radius R times the height range of
 * g over the disc, built in a geometry shader; a quad at the near plane
 * where the box crosses it), so that each pixel the splat may cover is ray
 * cast once, and each fragment casts its ray in the splat's normalised frame,
 * solves F(t) = g(u, v) - w = 0 in closed form (degree 1 to 4, the float
 * solvers of glsl/vtkSplatRoots.glsl), keeps the nearest root inside the
 * disc, shades it with VTK's lights and material using the normal from the
 * gradient of g, and writes its true depth, so splats intersect correctly
 * with every other actor. Scalars are coloured as by any VTK mapper.
 *
 * Culling and continuous level of detail ([Bolla 2010] 3.4, 4.3.1): when the input
 * carries the octree of vtkAlgebraicSplatFitter, nodes whose bounding sphere
 * lies outside the view frustum are skipped, and each visible leaf draws the
 * prefix of its level-sorted splats down to the first level whose splats
 * are at most LODPixelError pixels across on screen. Where that octree no
 * longer indexes the splats (a filter moved, reordered, split or removed
 * them, as ParaView's RedistributeDataSet does over MPI ranks), the mapper
 * builds an octree of its own over the splats it has, from their LOD
 * levels and radii, and draws its ranges through an index buffer; the
 * vertex buffers stay in the input's order. Without an octree, or while
 * a vtkHardwareSelector picks (its ids need one draw), every splat is
 * drawn.
 *
 * Two-pass blending ([Bolla 2010] 4.2, on by default): a visibility pass writes
 * each pixel's nearest hit pushed back along the ray by BlendDepthOffset
 * times the splat's feature size; a blending pass accumulates the shaded
 * colours of every hit in front of that depth, weighted by a Gaussian of
 * the hit's distance from its splat's centre, in a float target; the
 * normalised colour is composited into VTK's framebuffer with the nearest
 * hit's true depth. Overlapping splats thus blend smoothly, and the splats
 * still intersect correctly with other actors drawn before or after them.
 *
 * Adaptive anti-aliasing ([Bolla 2010] 4.3): with AntiAliasing n = 2 or 3, the
 * pixels where a splat is seen at a grazing angle (or missed by less than
 * a pixel near such an angle) cast n x n sub-pixel rays; all other pixels
 * cast one. ShowSilhouettePixels paints those pixels magenta.
 *
 * Face culling follows the actor's property (BackfaceCulling,
 * FrontfaceCulling) by the splats' oriented normals: a splat is skipped
 * when every normal of its patch faces away from (or towards) the eye. The
 * normals must be consistently oriented (SplatNormalsOriented in the field
 * data: input normals, or vtkAlgebraicSplatFitter's OrientNormals);
 * otherwise a warning says so and nothing is culled. It assumes a uniform
 * actor scale.
 *
 * Shadows ([Bolla 2010] 4.3.2) work through VTK's vtkShadowMapBakerPass and
 * vtkShadowMapPass: the light's depth map is drawn from the ray-cast hits,
 * and the shadow lookup uses the hit point.
 *
 * Hardware picking (vtkHardwareSelector) and the shadow map are drawn in
 * one opaque pass, without blending.
 */
#ifndef vtkAlgebraicSplatMapper_h
#define vtkAlgebraicSplatMapper_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkNew.h"                       // For the blend helper
#include "vtkOpenGLPolyDataMapper.h"

#include <map>     // For the built variants
#include <memory>  // For the octree
#include <string>  // For the missing hooks message
#include <utility> // For the changed rows
#include <vector>  // For the draw order

class vtkAlgebraicSplatBlendHelper;
class vtkOpenGLBufferObject;
class vtkUnsignedCharArray;
namespace pointsurfaces
{
struct DrawRange;
struct LODOctree;
struct LODView;
}

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

  /**
   * Splats of the input that cannot be drawn (NaN or infinite values, a zero
   * radius, feature size, normal or tangent), counted when the buffers are
   * built; a warning names them too.
   */
  vtkGetMacro(NumberOfInvalidSplats, vtkIdType);

  ///@{
  /**
   * Two-pass blending of overlapping splats ([Bolla 2010] 4.2). Default on; off
   * draws each pixel's nearest splat opaque, in one pass.
   */
  vtkSetMacro(Blending, bool);
  vtkGetMacro(Blending, bool);
  vtkBooleanMacro(Blending, bool);
  ///@}

  ///@{
  /**
   * delta of the visibility pass, in units of each splat's feature size h:
   * hits up to delta h behind the nearest one are blended. Default 0.5.
   */
  vtkSetClampMacro(BlendDepthOffset, double, 0.0, 100.0);
  vtkGetMacro(BlendDepthOffset, double);
  ///@}

  ///@{
  /**
   * k of the blending weight exp(-k r^2 / R^2), r the hit's distance from
   * the splat's centre in its plane and R the disc radius; 0 weights all
   * hits equally. Default 3 (a weight of 0.05 at the disc's rim).
   */
  vtkSetClampMacro(BlendSharpness, double, 0.0, 100.0);
  vtkGetMacro(BlendSharpness, double);
  ///@}

  ///@{
  /**
   * Adaptive anti-aliasing: silhouette pixels cast n x n rays, n = 2 or 3;
   * 1 turns it off. Default 1.
   */
  vtkSetClampMacro(AntiAliasing, int, 1, 3);
  vtkGetMacro(AntiAliasing, int);
  ///@}

  ///@{
  /**
   * A hit is a silhouette pixel when the cosine between its normal and the
   * ray is below this value. Default 0.25.
   */
  vtkSetClampMacro(SilhouetteThreshold, double, 0.0, 1.0);
  vtkGetMacro(SilhouetteThreshold, double);
  ///@}

  ///@{
  /** Paint the silhouette pixels magenta, as in [Bolla 2010] Figure 4.4. Default off. */
  vtkSetMacro(ShowSilhouettePixels, bool);
  vtkGetMacro(ShowSilhouettePixels, bool);
  vtkBooleanMacro(ShowSilhouettePixels, bool);
  ///@}

  /**
   * Bytes per splat in the GPU's vertex buffers after the last render:
   * origin, frame, sizes, colour and only the coefficients the degree needs.
   */
  int GetGPUBytesPerSplat();

  /**
   * When the splats' vertex buffers and LOD octree were last built from the
   * input. A render rebuilds them only when the input's points, splat
   * arrays or field data changed, or Modified() was called on the input
   * itself (or the graphics resources were released):
   * a new colour array, new values in one, a lookup table, a scalar range or
   * an actor property uploads the colours alone, or nothing when the splats
   * take the actor's colour. So editing a colour map in ParaView costs one
   * pass over the colours per render, not a rebuild of every splat's buffers.
   */
  vtkMTimeType GetGeometryBuildTime() const { return this->GeometryBuildTime.GetMTime(); }

  void ReleaseGraphicsResources(vtkWindow* win) override;

  /**
   * Always 0: scalars are mapped to colours on the splats, one colour per
   * splat, whatever InterpolateScalarsBeforeMapping says (ParaView turns it
   * on for every display). A splat carries one value, so there is nothing
   * to interpolate before mapping; overlapping splats blend the mapped
   * colours.
   */
  int CanUseTextureMapForColoring(vtkDataObject* input) override;

protected:
  vtkAlgebraicSplatMapper();
  ~vtkAlgebraicSplatMapper() override;

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

  void ReplaceShaderCoincidentOffset(std::map<vtkShader::Type, vtkShader*> shaders,
    vtkRenderer* ren,
    vtkActor* act) override;

  /**
   * The input's degree and orientation flag, the index counts cleared;
   * false, with an error when it has points, when it is not a splat set.
   */
  bool ResetForInput(vtkPolyData* poly);
  /**
   * Nodes from the input's octree; where it no longer indexes the splats
   * (moved, reordered, split), an octree of the mapper's own over them;
   * none when the input has no octree.
   */
  virtual void ReadOctree(vtkPolyData* poly);
  /** Those nodes (null when none), for a subclass's ReadOctree to adjust. */
  pointsurfaces::LODOctree* GetLODNodes() { return this->Nodes.get(); }
  /**
   * For a subclass's ReadOctree that makes the nodes itself: draw `nodes`
   * (null: every splat), whose ranges index the input's rows, or a row
   * space of the subclass's own that TranslateDrawRanges maps to rows.
   */
  void SetLODNodes(std::unique_ptr<pointsurfaces::LODOctree> nodes);
  /**
   * The ranges the octree selected for a view, made rows of the vertex
   * buffers: a subclass whose nodes index rows of its own (a range may
   * become several, each keeping its Level and Quality) replaces them.
   * Default: none, the ranges are rows.
   */
  virtual void TranslateDrawRanges(std::vector<pointsurfaces::DrawRange>& ranges);
  /** Whether those nodes are the input's octree (false: the mapper built its own). */
  bool LODNodesFromInput() const { return this->Nodes && this->DrawOrder.empty(); }
  /**
   * The view that culls and picks levels: `ren`'s camera and tiled viewport,
   * `act`'s matrix, Culling and LODPixelError.
   */
  void MakeLODView(vtkRenderer* ren, vtkActor* act, pointsurfaces::LODView& view);
  /**
   * Where the buffers go relative to (subtracted on the GPU so that float
   * keeps the positions' precision). Default: the centre of the points'
   * bounds.
   */
  virtual void ComputePositionShift(vtkPolyData* poly, double shift[3]);

  ///@{
  /**
   * For a subclass that keeps its input as rows it rewrites in place
   * (vtkStreamingSplatMapper: its pages come and go):
   *
   * - RowsInUse: per row, 0 where the row holds no splat: it is drawn as
   *   nothing and not counted as invalid. Empty (the default): every row
   *   holds one.
   * - RowUpdatePending with ChangedRows: only the rows [first, second) of
   *   ChangedRows were rewritten (or left) since the last build. When the
   *   input's arrays are the same objects, of the same length, the next
   *   build converts and uploads those rows alone (and the colours, which
   *   MapScalars maps whole), then calls ReadOctree; otherwise it builds
   *   everything. The build consumes both.
   * - LastBuildRows: the rows the last build converted and uploaded.
   */
  std::vector<unsigned char> RowsInUse;
  std::vector<std::pair<vtkIdType, vtkIdType>> ChangedRows;
  bool RowUpdatePending = false;
  vtkIdType LastBuildRows = 0;
  ///@}

  /** Is this the light's view of a vtkShadowMapBakerPass (drawn opaque, in one pass)? */
  static bool IsShadowMapBake(vtkActor* act);
  void DrawSplats(vtkRenderer* ren, vtkActor* act, bool useOctree);
  void DrawOctree(vtkRenderer* ren, vtkActor* act);

  /**
   * What a fragment shader is compiled for besides the degree: the pass
   * (0 opaque, 1 visibility, 2 blending), the silhouette pixels' n x n
   * rays, whether they are painted, and the faces culled (filled in by
   * UseVariant from the actor's property). Constants rather than uniforms, so
   * that a software rasteriser does not run the branches no pixel takes.
   */
  struct ShaderVariant
  {
    int Pass = 0;
    int Samples = 1;
    bool ShowSilhouette = false;
    int Cull = 0;    // face culling: bit 0 back faces, bit 1 front faces
    int Degree = -1; // the splats'
    bool operator!=(const ShaderVariant& o) const
    {
      return this->Pass != o.Pass || this->Samples != o.Samples ||
        this->ShowSilhouette != o.ShowSilhouette || this->Cull != o.Cull ||
        this->Degree != o.Degree;
    }
  };
  /**
   * Makes the program of `variant` current and sets the uniforms every pass
   * reads; returns it. The visibility pass has a helper (program and VAO)
   * of its own, so that a blended frame switches programs without
   * rebuilding either.
   */
  vtkShaderProgram* UseVariant(const ShaderVariant& variant, vtkRenderer* ren, vtkActor* act);

  int Degree = -1;
  bool NormalsOriented = false; // the input's SplatNormalsOriented
  bool WarnedUnoriented = false;
  // A splat shader failed to compile: nothing is drawn (and no compile
  // retried) until the mapper or the actor's shader property changes.
  bool ShaderFailed = false;
  bool MissingHooks = false;       // the last shader build lacked a hook or marker
  std::string MissingHooksMessage; // which ones, reported once by UseVariant
  vtkTimeStamp ShaderFailedTime;
  // ComputeBounds' cache: the splats' bounds, for the input they were computed from.
  vtkTimeStamp SplatBoundsTime;
  vtkPolyData* SplatBoundsInput = nullptr;
  double SplatBounds[6] = { 0, 0, 0, 0, 0, 0 };
  ShaderVariant Variant; // the one to build
  // What each helper's program was built for.
  std::map<const vtkOpenGLHelper*, ShaderVariant> BuiltVariants;
  vtkOpenGLHelper VisibilityBO;         // the visibility pass's program and VAO
  vtkOpenGLHelper* CurrentBO = nullptr; // the one drawing
  bool Culling = true;
  double LODPixelError = 0.0;
  vtkIdType NumberOfRenderedSplats = 0;
  vtkIdType NumberOfInvalidSplats = 0;
  double Shift[3] = { 0.0, 0.0, 0.0 }; // subtracted from the positions on the GPU
  bool Blending = true;
  double BlendDepthOffset = 0.5;
  double BlendSharpness = 3.0;
  int AntiAliasing = 1;
  double SilhouetteThreshold = 0.25;
  bool ShowSilhouettePixels = false;

private:
  std::unique_ptr<pointsurfaces::LODOctree> Nodes; // the input's octree, when usable
  vtkNew<vtkAlgebraicSplatBlendHelper> Blend;      // the two-pass blend's targets and passes
  // With an octree of the mapper's own (the input's no longer indexes its
  // splats): the input id of each octree position, and its index buffer.
  std::vector<unsigned int> DrawOrder;
  vtkNew<vtkOpenGLBufferObject> DrawOrderBO;
  bool DrawOrderUploaded = false;
  // What the vertex buffers were built from: the input, its points and
  // splat arrays (not its other arrays: a colour array that changes is
  // uploaded alone) and their newest MTime, with the field data's (the LOD
  // octree, the levels' s) and the input's own. Empty: none built.
  std::vector<const void*> GeometrySources;
  vtkMTimeType GeometrySourcesTime = 0;
  vtkTimeStamp GeometryBuildTime;
  static std::vector<const void*> GeometrySourcesOf(vtkPolyData* poly, vtkMTimeType& newest);
  // The key of the colour VBO in the window's VBO cache: the mapper's own,
  // so that the colours uploaded into it alone (UploadColors) never reach a
  // VBO that another mapper shares through the cache.
  vtkNew<vtkUnsignedCharArray> ColorKey;
  // Only the colours changed since the last build: upload them (or nothing,
  // without scalar colouring); false when the buffers must be rebuilt.
  bool UploadColors(vtkRenderer* ren, vtkPolyData* poly);
  // Only ChangedRows changed (RowUpdatePending): convert and upload them;
  // false when the buffers must be rebuilt.
  bool UploadRows(vtkRenderer* ren, vtkPolyData* poly);
  // Per row of the buffers: 1 where the splat is invalid (NaN, a zero radius...).
  std::vector<unsigned char> RowInvalid;

  vtkAlgebraicSplatMapper(const vtkAlgebraicSplatMapper&) = delete;
  void operator=(const vtkAlgebraicSplatMapper&) = delete;
};

#endif
