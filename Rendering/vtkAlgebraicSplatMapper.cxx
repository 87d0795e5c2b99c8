// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkAlgebraicSplatMapper.h"

#include "psOctree.h" // For BuildOctree
#include "psRealArrayView.h"
#include "psShaderHooks.h"
#include "psSplatLOD.h"
#include "vtkAlgebraicSplatBlendHelper.h"
#include "vtkAlgebraicSplatFS.h"
#include "vtkAlgebraicSplatGS.h"
#include "vtkAlgebraicSplatVS.h"
#include "vtkCallbackCommand.h"
#include "vtkSplatRoots.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseVectorKey.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLActor.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLIndexBufferObject.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexBufferObject.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkShaderProgram.h"
#include "vtkShaderProperty.h"
#include "vtkSplatDataModel.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkAlgebraicSplatMapper);

//------------------------------------------------------------------------------
vtkAlgebraicSplatMapper::vtkAlgebraicSplatMapper()
{
  this->VisibilityBO.PrimitiveType = PrimitiveTris;
}

//------------------------------------------------------------------------------
vtkAlgebraicSplatMapper::~vtkAlgebraicSplatMapper() = default;

//------------------------------------------------------------------------------
int vtkAlgebraicSplatMapper::CanUseTextureMapForColoring(vtkDataObject*)
{
  return 0;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::ReleaseGraphicsResources(vtkWindow* win)
{
  this->ShaderFailed = false;
  this->VisibilityBO.ReleaseGraphicsResources(win);
  this->BuiltVariants.clear();
  this->Blend->ReleaseGraphicsResources(win);
  this->DrawOrderBO->ReleaseGraphicsResources();
  this->DrawOrderUploaded = false;
  this->GeometrySources.clear(); // the vertex buffers go with the context
  this->Superclass::ReleaseGraphicsResources(win);
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::ComputeBounds()
{
  // The splats' own discs and heights (cached: the camera asks every frame).
  vtkPolyData* input = this->GetInput();
  if (!input || input->GetNumberOfPoints() == 0)
  {
    vtkMath::UninitializeBounds(this->Bounds);
    return;
  }
  if (this->SplatBoundsTime > input->GetMTime() && this->SplatBoundsInput == input)
  {
    std::copy(this->SplatBounds, this->SplatBounds + 6, this->Bounds);
    return;
  }
  if (!vtkSplatDataModel::ComputeSplatBounds(input, this->Bounds))
  {
    // Not the data model (or no valid splat): the points, padded by the
    // largest radius if there is one.
    input->GetPoints()->GetBounds(this->Bounds);
    vtkDataArray* radius = input->GetPointData()->GetArray(vtkSplatDataModel::RadiusName());
    double range[2] = { 0.0, 0.0 };
    if (radius)
    {
      radius->GetRange(range, 0);
    }
    for (int i = 0; i < 3; ++i)
    {
      this->Bounds[2 * i] -= range[1];
      this->Bounds[2 * i + 1] += range[1];
    }
  }
  std::copy(this->Bounds, this->Bounds + 6, this->SplatBounds);
  this->SplatBoundsInput = input;
  this->SplatBoundsTime.Modified();
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::GetShaderTemplate(std::map<vtkShader::Type, vtkShader*> shaders,
  vtkRenderer* ren,
  vtkActor* act)
{
  this->Superclass::GetShaderTemplate(shaders, ren, act);
  shaders[vtkShader::Vertex]->SetSource(vtkAlgebraicSplatVS);
  shaders[vtkShader::Geometry]->SetSource(vtkAlgebraicSplatGS);
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::ReplaceShaderValues(std::map<vtkShader::Type, vtkShader*> shaders,
  vtkRenderer* ren,
  vtkActor* act)
{
  // Every hook and marker must be found: a template whose text differs
  // would otherwise drop the splat code silently. A missing one is
  // reported, and UseVariant then draws nothing with this program.
  std::vector<std::string> missing;
  auto require = [&missing](bool found, const std::string& what)
  {
    if (!found)
    {
      missing.push_back(what);
    }
  };
  std::string VSSource = shaders[vtkShader::Vertex]->GetSource();
  std::string FSSource = shaders[vtkShader::Fragment]->GetSource();
  const std::string fs = vtkAlgebraicSplatFS;
  std::string declarations, implementation, output;
  require(pointsurfaces::ExtractBlock(fs, "SplatDecl", declarations), "block SplatDecl");
  require(pointsurfaces::ExtractBlock(fs, "SplatImpl", implementation), "block SplatImpl");
  require(pointsurfaces::ExtractBlock(fs, "SplatOutput", output), "block SplatOutput");
  require(pointsurfaces::ReplaceHook(declarations, "//VTK::SplatRoots::Dec", vtkSplatRoots, true),
    "SplatDecl: //VTK::SplatRoots::Dec");

  const std::string degree =
    "#define SPLAT_DEGREE " + std::to_string(std::max(1, this->Degree)) + "\n";
  const std::string variant = "#define SPLAT_PASS " + std::to_string(this->Variant.Pass) +
    "\n#define SPLAT_SAMPLES " + std::to_string(this->Variant.Samples) +
    "\n#define SPLAT_SHOW_SILHOUETTE " + (this->Variant.ShowSilhouette ? "1" : "0") +
    "\n#define SPLAT_CULL_FACES " + std::to_string(this->Variant.Cull) + "\n";
  require(pointsurfaces::ReplaceHook(VSSource, "//VTK::SplatDegree::Dec", degree, true),
    "vertex: //VTK::SplatDegree::Dec");
  require(
    pointsurfaces::ReplaceHook(VSSource, "//VTK::Camera::Dec", "uniform mat4 MCVCMatrix;", true),
    "vertex: //VTK::Camera::Dec");
  require(pointsurfaces::ReplaceHook(
            FSSource, "//VTK::PositionVC::Dec", "in vec4 vertexVCVSOutput;", true),
    "fragment: //VTK::PositionVC::Dec");
  require(pointsurfaces::ReplaceHook(
            FSSource, "//VTK::PositionVC::Impl", "vec4 vertexVC = vertexVCVSOutput;\n", true),
    "fragment: //VTK::PositionVC::Impl");
  // The bounding faces are never behind the hit: conservative depth keeps
  // early depth rejection working. The blending pass does not write depth.
  const std::string conservative =
    "#ifdef GL_ARB_conservative_depth\nlayout(depth_greater) out float gl_FragDepth;\n#endif\n";
  require(pointsurfaces::ReplaceHook(FSSource,
            "//VTK::System::Dec",
            "//VTK::System::Dec\n#extension GL_ARB_conservative_depth : enable\n"),
    "fragment: //VTK::System::Dec");
  require(
    pointsurfaces::ReplaceHook(FSSource,
      "//VTK::Normal::Dec",
      degree + variant + (this->Variant.Pass == 2 ? std::string() : conservative) + declarations,
      true),
    "fragment: //VTK::Normal::Dec");
  require(pointsurfaces::ReplaceHook(FSSource, "//VTK::Depth::Impl", implementation, true),
    "fragment: //VTK::Depth::Impl");
  require(pointsurfaces::ReplaceHook(FSSource, "//VTK::Normal::Impl", "", true),
    "fragment: //VTK::Normal::Impl");
  // The blend passes' outputs go last in main(), after VTK's lighting.
  require(pointsurfaces::ReplaceHook(
            FSSource, "//VTK::Coincident::Impl", "//VTK::Coincident::Impl\n" + output),
    "fragment: //VTK::Coincident::Impl");
  shaders[vtkShader::Vertex]->SetSource(VSSource);
  shaders[vtkShader::Fragment]->SetSource(FSSource);
  this->BuiltVariants[this->LastBoundBO] = this->Variant;
  this->Superclass::ReplaceShaderValues(shaders, ren, act);

  // vtkShadowMapBakerPass stores the fragment's depth from gl_FragCoord,
  // which is the bounding quad's: give it the ray-cast hit's. Its text is
  // VTK's, so a VTK that words it differently must be caught here.
  if (IsShadowMapBake(act))
  {
    FSSource = shaders[vtkShader::Fragment]->GetSource();
    require(pointsurfaces::ReplaceHook(
              FSSource, "ldepth =  gl_FragCoord.z;", "ldepth = splatDepth;", true),
      "vtkShadowMapBakerPass: ldepth =  gl_FragCoord.z;");
    require(pointsurfaces::ReplaceHook(FSSource, "1.0/gl_FragCoord.w", "splatClipW", true),
      "vtkShadowMapBakerPass: 1.0/gl_FragCoord.w");
    shaders[vtkShader::Fragment]->SetSource(FSSource);
  }
  this->MissingHooks = !missing.empty();
  if (this->MissingHooks)
  {
    // A shader without the splat code would not compile, or draw the
    // bounding faces: give the program an empty fragment shader instead.
    shaders[vtkShader::Fragment]->SetSource(
      "//VTK::System::Dec\n//VTK::Output::Dec\nvoid main()\n{\n  discard;\n}\n");
    std::string list;
    for (const std::string& m : missing)
    {
      list += "\n  " + m;
    }
    // Reported by UseVariant, once.
    this->MissingHooksMessage =
      "The splat shaders lack hooks or markers that the mapper fills in (pass " +
      std::to_string(this->Variant.Pass) + "); the splats are not drawn. Missing:" + list;
  }
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::ReplaceShaderCoincidentOffset(std::map<vtkShader::Type, vtkShader*>,
  vtkRenderer*,
  vtkActor*)
{
  // The splats write their exact depth; a coincident-topology offset (which
  // ParaView turns on globally) would replace it with the quad's.
}

//------------------------------------------------------------------------------
bool vtkAlgebraicSplatMapper::GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO,
  vtkRenderer* ren,
  vtkActor* act)
{
  // The superclass must always run: it records the lighting complexity that
  // the shader is then built for. The degree and the variant are compiled
  // into the shader; switching back to a variant built before finds its
  // program in the window's shader cache.
  const bool changed = this->Superclass::GetNeedToRebuildShaders(cellBO, ren, act);
  auto built = this->BuiltVariants.find(&cellBO);
  return changed || built == this->BuiltVariants.end() || built->second != this->Variant;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::SetCameraShaderParameters(vtkOpenGLHelper& cellBO,
  vtkRenderer* ren,
  vtkActor* act)
{
  vtkShaderProgram* program = cellBO.Program;
  auto* cam = static_cast<vtkOpenGLCamera*>(ren->GetActiveCamera());
  vtkMatrix4x4* wcdc;
  vtkMatrix4x4* wcvc;
  vtkMatrix3x3* norms;
  vtkMatrix4x4* vcdc;
  cam->GetKeyMatrices(ren, wcvc, norms, vcdc, wcdc);
  if (program->IsUniformUsed("VCDCMatrix"))
  {
    program->SetUniformMatrix("VCDCMatrix", vcdc);
  }
  if (program->IsUniformUsed("MCVCMatrix"))
  {
    // VTK's key matrices are transposed: the shift goes first, in the last row.
    vtkNew<vtkMatrix4x4> shift;
    for (int k = 0; k < 3; ++k)
    {
      shift->SetElement(3, k, this->Shift[k]);
    }
    if (!act->GetIsIdentity())
    {
      vtkMatrix4x4* mcwc;
      vtkMatrix3x3* anorms;
      static_cast<vtkOpenGLActor*>(act)->GetKeyMatrices(mcwc, anorms);
      vtkMatrix4x4::Multiply4x4(shift, mcwc, this->TempMatrix4);
      vtkMatrix4x4::Multiply4x4(this->TempMatrix4, wcvc, this->TempMatrix4);
    }
    else
    {
      vtkMatrix4x4::Multiply4x4(shift, wcvc, this->TempMatrix4);
    }
    program->SetUniformMatrix("MCVCMatrix", this->TempMatrix4);
  }
  if (program->IsUniformUsed("cameraParallel"))
  {
    program->SetUniformi("cameraParallel", cam->GetParallelProjection());
  }
  if (program->IsUniformUsed("splatPixelStep") || program->IsUniformUsed("splatPixelToView"))
  {
    // The viewport in force (a pass into a framebuffer of its own, such as
    // a shadow map's, sets its own; the renderer's tiled size is not it).
    // Window x to NDC: 2 (x - x0) / width - 1. NDC to the view plane, with P
    // the projection (vcdc is its transpose): x = (ndc + P02 - P03) / P00 at
    // z = -1 (perspective, w = -z = 1), x = (ndc - P02 z - P03) / P00
    // (parallel, in view units); y likewise. A pixel is 2 / (P00 width).
    GLint viewport[4] = { 0, 0, 1, 1 };
    static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow())
      ->GetState()
      ->vtkglGetIntegerv(GL_VIEWPORT, viewport);
    const bool parallel = cam->GetParallelProjection() != 0;
    float step[2], toView[4];
    for (int k = 0; k < 2; ++k)
    {
      const double scale = vcdc->GetElement(k, k);
      const double size = std::max(viewport[2 + k], 1);
      const double shear = vcdc->GetElement(2, k), shift = vcdc->GetElement(3, k);
      step[k] = static_cast<float>(2.0 / (scale * size));
      toView[k] = static_cast<float>(
        ((-2.0 * viewport[k] / size - 1.0) + (parallel ? 0.0 : shear) - shift) / scale);
      toView[2 + k] = static_cast<float>(parallel ? -shear / scale : 0.0);
    }
    program->SetUniform2f("splatPixelStep", step);
    program->SetUniform4f("splatPixelToView", toView);
  }
}

//------------------------------------------------------------------------------
bool vtkAlgebraicSplatMapper::ResetForInput(vtkPolyData* poly)
{
  this->Degree = vtkSplatDataModel::GetSplatDegree(poly);
  this->ShaderFailed = false; // new input: worth another try
  vtkDataArray* oriented =
    poly ? poly->GetFieldData()->GetArray(vtkSplatDataModel::NormalsOrientedName()) : nullptr;
  this->NormalsOriented =
    oriented && oriented->GetNumberOfTuples() > 0 && oriented->GetTuple1(0) != 0.0;
  this->WarnedUnoriented = false;
  this->Primitives[PrimitivePoints].IBO->IndexCount = 0;
  this->Primitives[PrimitiveLines].IBO->IndexCount = 0;
  this->Primitives[PrimitiveTriStrips].IBO->IndexCount = 0;
  this->Primitives[PrimitiveTris].IBO->IndexCount = 0;
  this->VisibilityBO.IBO->IndexCount = 0;
  if (this->Degree < 0)
  {
    if (poly && poly->GetNumberOfPoints() > 0)
    {
      vtkErrorMacro(<< "The input is not a splat set (see vtkSplatDataModel): nothing is drawn.");
    }
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
std::vector<const void*> vtkAlgebraicSplatMapper::GeometrySourcesOf(vtkPolyData* poly,
  vtkMTimeType& newest)
{
  newest = 0;
  if (!poly || !poly->GetPoints())
  {
    return {};
  }
  std::vector<const void*> sources{ poly, poly->GetPoints(), poly->GetFieldData() };
  // The poly data's own time (not its arrays'): Modified() on it, as after
  // writing into its arrays without telling them, rebuilds everything.
  newest = std::max({ poly->vtkObject::GetMTime(),
    poly->GetPoints()->GetMTime(),
    poly->GetFieldData()->GetMTime() });
  for (const char* name : { vtkSplatDataModel::CoefficientsName(),
         vtkSplatDataModel::FeatureSizeName(),
         vtkSplatDataModel::RadiusName(),
         vtkSplatDataModel::NominalRadiusName(),
         vtkSplatDataModel::LODName(),
         vtkSplatDataModel::NormalName(),
         vtkSplatDataModel::TangentName() })
  {
    vtkDataArray* array = poly->GetPointData()->GetArray(name);
    sources.push_back(array);
    newest = std::max(newest, array ? array->GetMTime() : 0);
  }
  return sources;
}

//------------------------------------------------------------------------------
bool vtkAlgebraicSplatMapper::UploadColors(vtkRenderer* ren, vtkPolyData* poly)
{
  // The superclass asks for a rebuild whenever the mapper (colour array,
  // lookup table, scalar range), the actor's property or the input changed.
  // The geometry depends only on the input's points, splat arrays and field
  // data: when none of them changed, only the colours can have.
  vtkMTimeType newest = 0;
  if (!poly || this->GeometrySources.empty() || this->Degree < 0 ||
    GeometrySourcesOf(poly, newest) != this->GeometrySources ||
    newest != this->GeometrySourcesTime ||
    this->VBOs->GetNumberOfTuples("vertexMC") != poly->GetNumberOfPoints())
  {
    return false;
  }
  this->MapScalars(1.0);
  vtkOpenGLVertexBufferObject* vbo = this->VBOs->GetVBO("scalarColor");
  const bool colored = this->Colors && this->Colors->GetNumberOfTuples() > 0;
  if (colored != (vbo != nullptr))
  {
    return false; // colours appear or go: other attributes, another shader
  }
  if (vbo)
  {
    if (this->Colors->GetNumberOfTuples() != poly->GetNumberOfPoints() ||
      this->Colors->GetNumberOfComponents() != static_cast<int>(vbo->GetNumberOfComponents()))
    {
      return false;
    }
    vtkOpenGLRenderWindow* win = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
    if (win)
    {
      win->MakeCurrent();
    }
    vbo->UploadDataArray(this->Colors);
  }
  return true;
}

//------------------------------------------------------------------------------
namespace
{
// The input's splats as the vertex buffers hold them, row by row: the
// position less the shift, the normal and tangent, (h, R, R / s) and 16
// coefficients. An invalid splat (a NaN or infinite value, a zero radius,
// feature size, normal or tangent) and a row not in use get a zero radius,
// which the geometry shader drops.
class SplatRowWriter
{
public:
  SplatRowWriter(vtkPolyData* poly, const double shift[3], const unsigned char* inUse)
    : N(poly->GetNumberOfPoints())
    , P(poly->GetPoints()->GetData(), N)
    , Normal(poly->GetPointData()->GetArray(vtkSplatDataModel::NormalName()), N)
    , Tangent(poly->GetPointData()->GetArray(vtkSplatDataModel::TangentName()), N)
    , H(poly->GetPointData()->GetArray(vtkSplatDataModel::FeatureSizeName()), N)
    , R(poly->GetPointData()->GetArray(vtkSplatDataModel::RadiusName()), N)
    , C(poly->GetPointData()->GetArray(vtkSplatDataModel::CoefficientsName()), N)
    , Nominal(poly->GetPointData()->GetArray(vtkSplatDataModel::NominalRadiusName()), N)
    , Level(poly->GetPointData()->GetArray(vtkSplatDataModel::LODName()), N)
    , Quality(poly->GetFieldData()->GetArray(vtkSplatDataModel::LODQualityName()), 1)
    , InUse(inUse)
  {
    vtkDataArray* quality = poly->GetFieldData()->GetArray(vtkSplatDataModel::LODQualityName());
    this->Levels = quality ? quality->GetNumberOfTuples() : 0;
    vtkDataArray* coeffs = poly->GetPointData()->GetArray(vtkSplatDataModel::CoefficientsName());
    this->M = coeffs ? coeffs->GetNumberOfComponents() : 0;
    std::copy(shift, shift + 3, this->Shift);
  }

  enum Kind
  {
    Valid,
    Invalid,
    Unused
  };

  /**
   * Row i into xyz[3], hrs[3] and cc[k][4] (the four coefficient vec4s), and
   * the normal and tangent into nt[6] when it is given.
   */
  Kind Write(vtkIdType i, float* xyz, float* hrs, float* const cc[4], float* nt) const
  {
    if (this->InUse && !this->InUse[i])
    {
      std::fill_n(xyz, 3, 0.0f);
      hrs[0] = 1.0f;
      hrs[1] = hrs[2] = 0.0f;
      for (int k = 0; k < 4; ++k)
      {
        std::fill_n(cc[k], 4, 0.0f);
      }
      if (nt)
      {
        std::fill_n(nt, 6, 0.0f);
      }
      return Unused;
    }
    const double nn[3] = { this->Normal(i, 0), this->Normal(i, 1), this->Normal(i, 2) };
    const double t[3] = { this->Tangent(i, 0), this->Tangent(i, 1), this->Tangent(i, 2) };
    const double h = this->H(i, 0), r = this->R(i, 0);
    bool ok = h > 0.0 && r > 0.0 && std::isfinite(h) && std::isfinite(r) &&
      vtkMath::Norm(nn) > 0.0 && vtkMath::Norm(t) > 0.0;
    for (int k = 0; k < 3; ++k)
    {
      const double p = this->P(i, k);
      ok = ok && std::isfinite(p) && std::isfinite(nn[k]) && std::isfinite(t[k]);
      xyz[k] = static_cast<float>(p - this->Shift[k]);
      if (nt)
      {
        nt[k] = static_cast<float>(nn[k]);
        nt[3 + k] = static_cast<float>(t[k]);
      }
    }
    for (int k = 0; k < 16; ++k)
    {
      const double value = k < this->M ? this->C(i, k) : 0.0;
      ok = ok && std::isfinite(value);
      cc[k / 4][k % 4] = static_cast<float>(value);
    }
    const int level = this->Level.Present() ? static_cast<int>(this->Level(i, 0)) : 0;
    const double s =
      this->Quality.Present() && level >= 0 && level < this->Levels ? this->Quality(level, 0) : 1.0;
    hrs[0] = ok ? static_cast<float>(h) : 1.0f;
    hrs[1] = ok ? static_cast<float>(r) : 0.0f;
    // LOD scales the unbounded disc with s; the bound still holds (see the VS).
    const double scaled = this->Nominal.Present() ? std::max(r, this->Nominal(i, 0)) : r;
    hrs[2] = ok && s > 0.0 ? static_cast<float>(scaled / s) : 0.0f;
    return ok ? Valid : Invalid;
  }

private:
  vtkIdType N;
  pointsurfaces::RealArrayView P, Normal, Tangent, H, R, C, Nominal, Level, Quality;
  const unsigned char* InUse;
  vtkIdType Levels = 0;
  int M = 0;
  double Shift[3] = { 0.0, 0.0, 0.0 };
};

// Rows [begin, end) of `vbo` from `data` (tightly packed tuples of the VBO's
// element size).
void UploadVBORows(vtkOpenGLVertexBufferObject* vbo,
  vtkIdType begin,
  vtkIdType end,
  const void* data)
{
  if (!vbo || end <= begin || !vbo->Bind())
  {
    return;
  }
  const size_t stride = vbo->GetStride();
  glBufferSubData(GL_ARRAY_BUFFER,
    static_cast<GLintptr>(stride * static_cast<size_t>(begin)),
    static_cast<GLsizeiptr>(stride * static_cast<size_t>(end - begin)),
    data);
  vbo->Release();
}
} // namespace

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::ComputePositionShift(vtkPolyData* poly, double shift[3])
{
  double bounds[6];
  poly->GetPoints()->GetBounds(bounds);
  for (int k = 0; k < 3; ++k)
  {
    shift[k] = std::isfinite(bounds[2 * k] + bounds[2 * k + 1])
      ? 0.5 * (bounds[2 * k] + bounds[2 * k + 1])
      : 0.0;
  }
}

//------------------------------------------------------------------------------
bool vtkAlgebraicSplatMapper::UploadRows(vtkRenderer* ren, vtkPolyData* poly)
{
  const vtkIdType n = poly ? poly->GetNumberOfPoints() : 0;
  vtkMTimeType newest = 0;
  if (!this->RowUpdatePending || !poly || this->GeometrySources.empty() || this->Degree < 0 ||
    GeometrySourcesOf(poly, newest) != this->GeometrySources ||
    this->VBOs->GetNumberOfTuples("vertexMC") != n ||
    static_cast<vtkIdType>(this->RowInvalid.size()) != n ||
    vtkSplatDataModel::GetSplatDegree(poly) != this->Degree ||
    (!this->RowsInUse.empty() && static_cast<vtkIdType>(this->RowsInUse.size()) != n))
  {
    return false;
  }
  this->MapScalars(1.0);
  vtkOpenGLVertexBufferObject* colorVBO = this->VBOs->GetVBO("scalarColor");
  const bool colored = this->Colors && this->Colors->GetNumberOfTuples() > 0;
  if (colored != (colorVBO != nullptr) ||
    (colored &&
      (this->Colors->GetNumberOfTuples() != n ||
        this->Colors->GetNumberOfComponents() !=
          static_cast<int>(colorVBO->GetNumberOfComponents()))))
  {
    return false; // colours appear or go: other attributes, another shader
  }
  vtkOpenGLRenderWindow* win = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (win)
  {
    win->MakeCurrent();
  }
  const SplatRowWriter writer(
    poly, this->Shift, this->RowsInUse.empty() ? nullptr : this->RowsInUse.data());
  vtkOpenGLVertexBufferObject* positionVBO = this->VBOs->GetVBO("vertexMC");
  vtkOpenGLVertexBufferObject* normalVBO = this->VBOs->GetVBO("splatNormalMC");
  vtkOpenGLVertexBufferObject* tangentVBO = this->VBOs->GetVBO("splatTangentMC");
  vtkOpenGLVertexBufferObject* sizeVBO = this->VBOs->GetVBO("splatSizeMC");
  vtkOpenGLVertexBufferObject* coeffVBO[4] = { this->VBOs->GetVBO("splatC0"),
    this->VBOs->GetVBO("splatC1"),
    this->VBOs->GetVBO("splatC2"),
    this->VBOs->GetVBO("splatC3") };
  // The changed rows as disjoint runs: rows freed and written again in one
  // update are converted once.
  std::vector<std::pair<vtkIdType, vtkIdType>> runs;
  std::sort(this->ChangedRows.begin(), this->ChangedRows.end());
  for (const auto& range : this->ChangedRows)
  {
    const vtkIdType begin = std::max<vtkIdType>(0, range.first);
    const vtkIdType end = std::min(n, range.second);
    if (end <= begin)
    {
      continue;
    }
    if (!runs.empty() && begin <= runs.back().second)
    {
      runs.back().second = std::max(runs.back().second, end);
    }
    else
    {
      runs.emplace_back(begin, end);
    }
  }
  vtkIdType added = 0, rows = 0;
  std::vector<float> xyz, normal, tangent, hrs, c[4];
  for (const auto& run : runs)
  {
    const vtkIdType begin = run.first, end = run.second;
    const size_t count = static_cast<size_t>(end - begin);
    if (!this->RowsInUse.empty() &&
      std::none_of(this->RowsInUse.begin() + begin,
        this->RowsInUse.begin() + end,
        [](unsigned char used) { return used != 0; }))
    {
      // Rows freed: a zero radius is all the geometry shader needs to drop them.
      hrs.assign(3 * count, 0.0f);
      for (size_t j = 0; j < count; ++j)
      {
        hrs[3 * j] = 1.0f;
      }
      for (vtkIdType i = begin; i < end; ++i)
      {
        added -= this->RowInvalid[i];
        this->RowInvalid[i] = 0;
      }
      UploadVBORows(sizeVBO, begin, end, hrs.data());
      continue;
    }
    xyz.resize(3 * count);
    normal.resize(3 * count);
    tangent.resize(3 * count);
    hrs.resize(3 * count);
    for (auto& a : c)
    {
      a.resize(4 * count);
    }
    std::atomic<vtkIdType> delta(0);
    vtkSMPTools::For(begin,
      end,
      [&](vtkIdType first, vtkIdType last)
      {
        vtkIdType local = 0;
        float nt[6];
        for (vtkIdType i = first; i < last; ++i)
        {
          const size_t j = static_cast<size_t>(i - begin);
          float* const cc[4] = { &c[0][4 * j], &c[1][4 * j], &c[2][4 * j], &c[3][4 * j] };
          const SplatRowWriter::Kind kind = writer.Write(i, &xyz[3 * j], &hrs[3 * j], cc, nt);
          std::copy_n(nt, 3, &normal[3 * j]);
          std::copy_n(nt + 3, 3, &tangent[3 * j]);
          const unsigned char invalid = kind == SplatRowWriter::Invalid ? 1 : 0;
          local += static_cast<vtkIdType>(invalid) - this->RowInvalid[i];
          this->RowInvalid[i] = invalid;
        }
        delta += local;
      });
    added += delta;
    UploadVBORows(positionVBO, begin, end, xyz.data());
    UploadVBORows(normalVBO, begin, end, normal.data());
    UploadVBORows(tangentVBO, begin, end, tangent.data());
    UploadVBORows(sizeVBO, begin, end, hrs.data());
    for (int k = 0; k < 4 && k < this->Degree; ++k)
    {
      UploadVBORows(coeffVBO[k], begin, end, c[k].data());
    }
    rows += end - begin;
  }
  if (colored)
  {
    // MapScalars maps every row (the colour array was modified with them).
    colorVBO->UploadDataArray(this->Colors);
  }
  this->NumberOfInvalidSplats += added;
  if (added > 0)
  {
    vtkWarningMacro(<< added
                    << " more splats have a NaN or infinite value, or a zero radius, "
                       "feature size, normal or tangent: they are not drawn ("
                    << this->NumberOfInvalidSplats << " in all).");
  }
  this->ChangedRows.clear();
  this->RowUpdatePending = false;
  this->LastBuildRows = rows;
  this->ReadOctree(poly);
  this->GeometrySources = GeometrySourcesOf(poly, this->GeometrySourcesTime);
  this->GeometryBuildTime.Modified();
  return true;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::BuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  vtkPolyData* poly = this->CurrentInput;
  this->LastBuildRows = 0;
  if (this->UploadColors(ren, poly) || this->UploadRows(ren, poly))
  {
    this->VBOBuildTime.Modified();
    return;
  }
  this->ChangedRows.clear();
  this->RowUpdatePending = false;
  this->GeometrySources.clear();
  if (!this->ResetForInput(poly))
  {
    this->VBOBuildTime.Modified();
    return;
  }
  const vtkIdType n = poly->GetNumberOfPoints();
  vtkPointData* pd = poly->GetPointData();
  vtkDataArray* normals = pd->GetArray(vtkSplatDataModel::NormalName());
  vtkDataArray* tangents = pd->GetArray(vtkSplatDataModel::TangentName());
  // Positions go to the GPU relative to the bounds' centre, in double first,
  // so that float keeps their precision at any offset (1e7 and beyond);
  // SetCameraShaderParameters adds the shift back into MCVCMatrix.
  this->ComputePositionShift(poly, this->Shift);
  vtkNew<vtkFloatArray> positions;
  positions->SetNumberOfComponents(3);
  positions->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> sizes;
  sizes->SetNumberOfComponents(3);
  sizes->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> c[4];
  for (auto& a : c)
  {
    a->SetNumberOfComponents(4);
    a->SetNumberOfTuples(n);
  }
  // (vtkSplatDataModel::GetSplatDegree checked the first six's shapes.)
  const bool rowsInUse = static_cast<vtkIdType>(this->RowsInUse.size()) == n;
  const SplatRowWriter writer(poly, this->Shift, rowsInUse ? this->RowsInUse.data() : nullptr);
  float* xyz = positions->GetPointer(0);
  float* hrs = sizes->GetPointer(0);
  float* cc[4] = {
    c[0]->GetPointer(0), c[1]->GetPointer(0), c[2]->GetPointer(0), c[3]->GetPointer(0)
  };
  this->RowInvalid.assign(static_cast<size_t>(n), 0);
  unsigned char* rowInvalid = this->RowInvalid.data();
  std::atomic<vtkIdType> invalid(0);
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      vtkIdType bad = 0;
      for (vtkIdType i = begin; i < end; ++i)
      {
        float* const row[4] = { cc[0] + 4 * i, cc[1] + 4 * i, cc[2] + 4 * i, cc[3] + 4 * i };
        const bool isInvalid =
          writer.Write(i, xyz + 3 * i, hrs + 3 * i, row, nullptr) == SplatRowWriter::Invalid;
        rowInvalid[i] = isInvalid ? 1 : 0;
        bad += isInvalid ? 1 : 0;
      }
      invalid += bad;
    });
  this->NumberOfInvalidSplats = invalid;
  if (invalid > 0)
  {
    vtkWarningMacro(<< invalid << " of " << n
                    << " splats have a NaN or infinite value, or a zero radius, feature size, "
                       "normal or tangent: they are not drawn.");
  }

  // Colours through the usual mapper colouring, or the actor's colour.
  this->MapScalars(1.0);
  this->VBOs->CacheDataArray("vertexMC", positions, ren, VTK_FLOAT);
  this->VBOs->CacheDataArray("splatNormalMC", normals, ren, VTK_FLOAT);
  this->VBOs->CacheDataArray("splatTangentMC", tangents, ren, VTK_FLOAT);
  this->VBOs->CacheDataArray("splatSizeMC", sizes, ren, VTK_FLOAT);
  // Degree 1 needs 3 coefficients, 2 needs 6, 3 needs 10 and 4 needs 15.
  const char* names[4] = { "splatC0", "splatC1", "splatC2", "splatC3" };
  for (int k = 0; k < 4; ++k)
  {
    this->VBOs->CacheDataArray(
      names[k], k < this->Degree ? c[k].GetPointer() : nullptr, ren, VTK_FLOAT);
  }
  // The colours' VBO is cached under the mapper's own key (see UploadColors).
  const bool colored = this->Colors && this->Colors->GetNumberOfTuples() > 0;
  if (colored)
  {
    this->ColorKey->ShallowCopy(this->Colors);
    this->ColorKey->Modified();
  }
  this->VBOs->CacheDataArray(
    "scalarColor", colored ? this->ColorKey.GetPointer() : nullptr, ren, VTK_UNSIGNED_CHAR);
  this->VBOs->BuildAllVBOs(ren);
  this->Primitives[PrimitiveTris].IBO->IndexCount = n;
  this->VisibilityBO.IBO->IndexCount = n;
  this->LastBuildRows = n;
  this->ReadOctree(poly);
  this->GeometrySources = GeometrySourcesOf(poly, this->GeometrySourcesTime);
  this->GeometryBuildTime.Modified();
  this->VBOBuildTime.Modified();
  (void)act;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::ReadOctree(vtkPolyData* poly)
{
  this->Nodes.reset();
  this->DrawOrder.clear();
  this->DrawOrderUploaded = false;
  pointsurfaces::Octree tree;
  std::vector<double> quality;
  const vtkSplatDataModel::OctreeStatus status = vtkSplatDataModel::GetOctree(poly, tree, quality);
  if (status == vtkSplatDataModel::NoOctree)
  {
    return; // draw everything
  }
  const vtkIdType n = poly->GetNumberOfPoints();
  vtkDataArray* radius = poly->GetPointData()->GetArray(vtkSplatDataModel::RadiusName());
  vtkDataArray* lod = poly->GetPointData()->GetArray(vtkSplatDataModel::LODName());
  std::vector<double> radii;
  std::vector<int> levels;
  if (status == vtkSplatDataModel::ValidOctree)
  {
    // GetOctree checked every level against the octree's.
    const pointsurfaces::RealArrayView r(radius, n), l(lod, n);
    radii.resize(n);
    levels.resize(n);
    for (vtkIdType k = 0; k < n; ++k)
    {
      radii[k] = r(k, 0);
      levels[k] = static_cast<int>(l(k, 0));
    }
  }
  else
  {
    // The fit's octree no longer indexes these splats: they were moved
    // (a Transform), reordered, split or removed (a Threshold, ParaView's
    // RedistributeDataSet over MPI ranks). The LOD still holds per splat,
    // so the mapper builds an octree of its own over them and draws its
    // ranges through an index buffer of input ids, leaving the vertex
    // buffers (and the ids that picking reports) in the input's order.
    // Splats with a NaN position or radius are drawn as nothing anyway
    // (BuildBufferObjects): they are left out of it.
    vtkDataArray* q = poly->GetFieldData()->GetArray(vtkSplatDataModel::LODQualityName());
    const int L = q ? static_cast<int>(q->GetNumberOfTuples()) : 0;
    std::vector<double> xyz;
    std::vector<vtkIdType> ids;
    bool usable = L > 0 && n < (vtkIdType(1) << 31);
    for (vtkIdType k = 0; k < n && usable; ++k)
    {
      const double level = lod->GetComponent(k, 0);
      usable = level >= 0.0 && level < L && level == std::floor(level);
      double p[3];
      poly->GetPoint(k, p);
      const double r = radius->GetComponent(k, 0);
      if (usable && std::isfinite(p[0] + p[1] + p[2]) && r >= 0.0 && std::isfinite(r))
      {
        ids.push_back(k);
        xyz.insert(xyz.end(), p, p + 3);
        radii.push_back(r);
        levels.push_back(static_cast<int>(level));
      }
    }
    if (!usable || ids.empty())
    {
      vtkWarningMacro(<< "The octree in the input's field data does not index its " << n
                      << " splats (moved, split, removed or reordered after fitting), and their "
                         "LOD levels do not allow one of the mapper's own (a level outside "
                         "SplatLODQuality): every splat is drawn.");
      return;
    }
    quality.resize(L);
    for (int l = 0; l < L; ++l)
    {
      quality[l] = q->GetComponent(l, 0);
    }
    const long long m = static_cast<long long>(ids.size());
    tree = pointsurfaces::BuildOctree(xyz.data(), radii.data(), levels.data(), m, L, 64);
    std::vector<double> sortedRadii(m);
    std::vector<int> sortedLevels(m);
    this->DrawOrder.resize(m);
    for (long long k = 0; k < m; ++k)
    {
      const long long i = tree.Order[k];
      sortedRadii[k] = radii[i];
      sortedLevels[k] = levels[i];
      this->DrawOrder[k] = static_cast<unsigned int>(ids[i]);
    }
    radii.swap(sortedRadii);
    levels.swap(sortedLevels);
    vtkDebugMacro(<< "The input's octree does not index its " << n
                  << " splats: the mapper built its own (" << tree.Nodes.size() << " nodes).");
  }
  this->Nodes = std::make_unique<pointsurfaces::LODOctree>(
    pointsurfaces::MakeLODOctree(std::move(tree), std::move(quality), radii.data(), levels.data()));
}

//------------------------------------------------------------------------------
bool vtkAlgebraicSplatMapper::IsShadowMapBake(vtkActor* act)
{
  vtkInformation* info = act->GetPropertyKeys();
  if (!info || !info->Has(vtkOpenGLRenderPass::RenderPasses()))
  {
    return false;
  }
  const int n = info->Length(vtkOpenGLRenderPass::RenderPasses());
  for (int i = 0; i < n; ++i)
  {
    vtkObjectBase* pass = info->Get(vtkOpenGLRenderPass::RenderPasses(), i);
    if (pass && pass->IsA("vtkShadowMapBakerPass"))
    {
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::MakeLODView(vtkRenderer* ren,
  vtkActor* act,
  pointsurfaces::LODView& view)
{
  vtkCamera* cam = ren->GetActiveCamera();
  cam->GetFrustumPlanes(ren->GetTiledAspectRatio(), view.Planes);
  cam->GetPosition(view.Eye);
  int size[2];
  ren->GetTiledSize(&size[0], &size[1]);
  view.ViewportHeight = size[1];
  view.Parallel = cam->GetParallelProjection() != 0;
  view.ParallelScale = cam->GetParallelScale();
  view.TanHalfAngle = std::tan(0.5 * vtkMath::RadiansFromDegrees(cam->GetViewAngle()));
  view.ModelIsIdentity = act->GetIsIdentity();
  if (!view.ModelIsIdentity)
  {
    std::copy(act->GetMatrix()->GetData(), act->GetMatrix()->GetData() + 16, view.ModelToWorld);
  }
  view.Cull = this->Culling;
  view.PixelError = this->LODPixelError;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::DrawOctree(vtkRenderer* ren, vtkActor* act)
{
  vtkShaderProgram* program = this->CurrentBO->Program;
  pointsurfaces::LODView view;
  this->MakeLODView(ren, act, view);
  this->NumberOfRenderedSplats = 0;
  // The mapper's own octree (ReadOctree) indexes the input through DrawOrder.
  const bool indexed = !this->DrawOrder.empty();
  if (indexed)
  {
    if (!this->DrawOrderUploaded)
    {
      this->DrawOrderUploaded =
        this->DrawOrderBO->Upload(this->DrawOrder, vtkOpenGLBufferObject::ElementArrayBuffer);
    }
    if (!this->DrawOrderUploaded || !this->DrawOrderBO->Bind())
    {
      // No index buffer: every splat, in one draw.
      this->DrawOrderBO->Release();
      this->DrawSplats(ren, act, false);
      return;
    }
  }
  std::vector<pointsurfaces::DrawRange> ranges =
    pointsurfaces::SelectDrawRanges(*this->Nodes, view);
  if (indexed)
  {
    for (const pointsurfaces::DrawRange& range : ranges)
    {
      program->SetUniformf("lodQuality", static_cast<float>(range.Quality));
      const GLsizei count = static_cast<GLsizei>(range.End - range.Begin);
      glDrawElements(GL_POINTS,
        count,
        GL_UNSIGNED_INT,
        reinterpret_cast<const void*>(static_cast<size_t>(range.Begin) * sizeof(unsigned int)));
      this->NumberOfRenderedSplats += range.End - range.Begin;
    }
    this->DrawOrderBO->Release();
    return;
  }
  this->TranslateDrawRanges(ranges);
  // One draw call per run of ranges drawn with the same s, in their order.
  std::vector<GLint> firsts;
  std::vector<GLsizei> counts;
  for (size_t k = 0; k < ranges.size();)
  {
    const double quality = ranges[k].Quality;
    firsts.clear();
    counts.clear();
    for (; k < ranges.size() && ranges[k].Quality == quality; ++k)
    {
      if (ranges[k].End > ranges[k].Begin)
      {
        firsts.push_back(static_cast<GLint>(ranges[k].Begin));
        counts.push_back(static_cast<GLsizei>(ranges[k].End - ranges[k].Begin));
        this->NumberOfRenderedSplats += ranges[k].End - ranges[k].Begin;
      }
    }
    if (!firsts.empty())
    {
      program->SetUniformf("lodQuality", static_cast<float>(quality));
      glMultiDrawArrays(
        GL_POINTS, firsts.data(), counts.data(), static_cast<GLsizei>(firsts.size()));
    }
  }
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::TranslateDrawRanges(std::vector<pointsurfaces::DrawRange>&) {}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::SetLODNodes(std::unique_ptr<pointsurfaces::LODOctree> nodes)
{
  this->Nodes = std::move(nodes);
  this->DrawOrder.clear();
  this->DrawOrderUploaded = false;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::DrawSplats(vtkRenderer* ren, vtkActor* act, bool useOctree)
{
  if (this->Nodes && useOctree)
  {
    this->DrawOctree(ren, act);
    return;
  }
  const int n = this->VBOs->GetNumberOfTuples("vertexMC");
  this->CurrentBO->Program->SetUniformf("lodQuality", 0.0f);
  glDrawArrays(GL_POINTS, 0, static_cast<GLuint>(n));
  this->NumberOfRenderedSplats = n;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::RenderPieceDraw(vtkRenderer* ren, vtkActor* act)
{
  const int n = this->VBOs->GetNumberOfTuples("vertexMC");
  this->NumberOfRenderedSplats = 0;
  if (n <= 0 || this->Degree <= 0)
  {
    return;
  }
  // The property's face culling (GL_CULL_FACE, by winding) would cut the
  // bounding faces, whose winding means nothing: the geometry shader culls
  // by the splats' normals instead.
  vtkOpenGLState* ostate = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow())->GetState();
  vtkOpenGLState::ScopedglEnableDisable cullFace(ostate, GL_CULL_FACE);
  ostate->vtkglDisable(GL_CULL_FACE);
  // Picking numbers primitives per draw call: draw everything in one, opaque.
  // The light's view of a shadow map needs the hits' depth only.
  const bool picking = ren->GetSelector() != nullptr;
  if (picking || IsShadowMapBake(act) || (!this->Blending && this->AntiAliasing <= 1))
  {
    ShaderVariant opaque;
    opaque.ShowSilhouette = this->ShowSilhouettePixels && !picking;
    if (!this->UseVariant(opaque, ren, act))
    {
      return;
    }
    this->DrawSplats(ren, act, !picking);
    return;
  }
  vtkAlgebraicSplatBlendHelper::Settings settings;
  settings.Blending = this->Blending;
  settings.BlendDepthOffset = this->BlendDepthOffset;
  settings.BlendSharpness = this->BlendSharpness;
  settings.AntiAliasing = this->AntiAliasing;
  vtkAlgebraicSplatBlendHelper::Passes passes;
  passes.UseVisibility = [&]()
  {
    ShaderVariant visibility;
    visibility.Pass = 1;
    return this->UseVariant(visibility, ren, act);
  };
  passes.UseBlending = [&]()
  {
    ShaderVariant blending;
    blending.Pass = 2;
    blending.Samples = this->AntiAliasing;
    blending.ShowSilhouette = this->ShowSilhouettePixels;
    return this->UseVariant(blending, ren, act);
  };
  passes.Draw = [&]() { this->DrawSplats(ren, act, true); };
  this->Blend->Render(
    static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow()), settings, passes, this);
}

//------------------------------------------------------------------------------
vtkShaderProgram* vtkAlgebraicSplatMapper::UseVariant(const ShaderVariant& variant,
  vtkRenderer* ren,
  vtkActor* act)
{
  vtkProperty* property = act->GetProperty();
  int cull = (property->GetBackfaceCulling() ? 1 : 0) | (property->GetFrontfaceCulling() ? 2 : 0);
  if (cull && !this->NormalsOriented)
  {
    if (!this->WarnedUnoriented)
    {
      vtkWarningMacro(<< "Face culling needs consistently oriented splat normals "
                         "(SplatNormalsOriented in the field data: input normals, or "
                         "vtkAlgebraicSplatFitter's OrientNormals); nothing is culled.");
      this->WarnedUnoriented = true;
    }
    cull = 0;
  }
  if (this->ShaderFailed)
  {
    const vtkMTimeType changed = std::max(this->GetMTime(), act->GetShaderProperty()->GetMTime());
    if (changed <= this->ShaderFailedTime.GetMTime())
    {
      return nullptr;
    }
    this->ShaderFailed = false;
  }
  this->Variant = variant;
  this->Variant.Cull = cull;
  this->Variant.Degree = this->Degree;
  vtkOpenGLHelper& cellBO =
    variant.Pass == 1 ? this->VisibilityBO : this->Primitives[PrimitiveTris];
  this->CurrentBO = &cellBO;
  this->MissingHooks = false;
  // VTK 9.6's UpdateShaders reports a failed compile itself, on every frame,
  // and may leave the previous program in cellBO; VTK 9.1's leaves a null
  // program and says nothing. The errors raised on this mapper while the
  // shaders are built are caught here, so that either way a failure is
  // reported once, by the message below (or the missing hooks' own).
  std::string caught;
  vtkNew<vtkCallbackCommand> catcher;
  catcher->SetClientData(&caught);
  catcher->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void* callData)
    {
      auto* text = static_cast<std::string*>(clientData);
      if (text->empty() && callData)
      {
        // "ERROR: In file, line n\nclass (address): message": the message.
        std::string message = static_cast<const char*>(callData);
        const size_t start = message.find("): ");
        message = start == std::string::npos ? message : message.substr(start + 3);
        *text = message.substr(0, message.find_last_not_of("\n") + 1);
      }
    });
  catcher->SetAbortFlagOnExecute(1);
  const unsigned long catching = this->AddObserver(vtkCommand::ErrorEvent, catcher, 1000.0f);
  this->UpdateShaders(cellBO, ren, act);
  this->RemoveObserver(catching);
  vtkShaderProgram* program = cellBO.Program;
  if (this->MissingHooks)
  {
    // ReplaceShaderValues named the hooks; the program lacks the splat code.
    vtkErrorMacro(<< this->MissingHooksMessage);
    this->ShaderFailed = true;
    this->ShaderFailedTime.Modified();
    this->BuiltVariants.erase(&cellBO);
    return nullptr;
  }
  if (!program || !caught.empty())
  {
    // VTK 9.1's UpdateShaders would reuse the null program on the next frame
    // (and crash): remember the failure, and rebuild once something changes.
    vtkErrorMacro(<< "The splat shader (pass " << variant.Pass
                  << ") did not compile: the splats are not drawn."
                  << (caught.empty() ? "" : " VTK: ") << caught);
    this->ShaderFailed = true;
    this->ShaderFailedTime.Modified();
    this->BuiltVariants.erase(&cellBO);
    return nullptr;
  }
  program->SetUniformf("splatSilhouetteCos", static_cast<float>(this->SilhouetteThreshold));
  program->SetUniformf("splatBlendSharpness", static_cast<float>(this->BlendSharpness));
  program->SetUniformi("splatCullFaces", cull);
  const float noMargin[2] = { 0.0f, 0.0f };
  program->SetUniform2f("splatOutlineMargin", noMargin);
  return program;
}

//------------------------------------------------------------------------------
int vtkAlgebraicSplatMapper::GetGPUBytesPerSplat()
{
  std::set<vtkOpenGLVertexBufferObject*> buffers;
  int bytes = 0;
  for (const char* name : { "vertexMC",
         "splatNormalMC",
         "splatTangentMC",
         "splatSizeMC",
         "splatC0",
         "splatC1",
         "splatC2",
         "splatC3",
         "scalarColor" })
  {
    vtkOpenGLVertexBufferObject* vbo = this->VBOs->GetVBO(name);
    if (vbo && buffers.insert(vbo).second)
    {
      bytes += static_cast<int>(vbo->GetStride());
    }
  }
  return bytes;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Degree: " << this->Degree << "\n";
  os << indent << "Culling: " << this->Culling << "\n";
  os << indent << "LODPixelError: " << this->LODPixelError << "\n";
  os << indent << "Blending: " << this->Blending << "\n";
  os << indent << "BlendDepthOffset: " << this->BlendDepthOffset << "\n";
  os << indent << "BlendSharpness: " << this->BlendSharpness << "\n";
  os << indent << "AntiAliasing: " << this->AntiAliasing << "\n";
  os << indent << "SilhouetteThreshold: " << this->SilhouetteThreshold << "\n";
  os << indent << "ShowSilhouettePixels: " << this->ShowSilhouettePixels << "\n";
}
