// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtk_glew.h"

#include "vtkAlgebraicSplatMapper.h"

#include "vtkAlgebraicSplatCompositeFS.h"
#include "vtkAlgebraicSplatFS.h"
#include "vtkAlgebraicSplatGS.h"
#include "vtkAlgebraicSplatVS.h"
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
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLIndexBufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
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
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <set>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkAlgebraicSplatMapper);

// The octree of the input's field data (see vtkAlgebraicSplatFitter).
struct vtkAlgebraicSplatMapper::Octree
{
  struct Node
  {
    double Sphere[4];
    vtkIdType FirstChild, ChildCount, Begin, End;
  };
  std::vector<Node> Nodes;
  std::vector<vtkIdType> LevelEnds; // Levels per node
  std::vector<double> LevelQuality; // s of each level
  std::vector<double> MeanRadius;   // per node: mean R / s over its splats
  int Levels = 1;
};

// The float targets of the two-pass blend, sized to the renderer's viewport.
struct vtkAlgebraicSplatMapper::BlendTargets
{
  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  vtkNew<vtkTextureObject> Accumulation;  // sum w C, sum w
  vtkNew<vtkTextureObject> DepthCoverage; // min true depth, min (1 - coverage)
  vtkNew<vtkTextureObject> Depth;         // the scene's depth, then the visibility pass
  vtkNew<vtkOpenGLFramebufferObject> CopyFramebuffer;
  vtkNew<vtkTextureObject> VisibleDepth; // a copy of Depth after the visibility pass
  std::unique_ptr<vtkOpenGLQuadHelper> Composite;
  int Width = 0;
  int Height = 0;
  int DepthFormat = -1; // vtkTextureObject depth format; -2: depth and stencil
  bool Warned = false;

  void Release(vtkWindow* win)
  {
    this->Framebuffer->ReleaseGraphicsResources(win);
    this->Accumulation->ReleaseGraphicsResources(win);
    this->DepthCoverage->ReleaseGraphicsResources(win);
    this->Depth->ReleaseGraphicsResources(win);
    this->CopyFramebuffer->ReleaseGraphicsResources(win);
    this->VisibleDepth->ReleaseGraphicsResources(win);
    if (this->Composite)
    {
      this->Composite->ReleaseGraphicsResources(win);
      this->Composite.reset();
    }
    this->Width = this->Height = 0;
    this->DepthFormat = -1;
  }
};

namespace
{
// Is this the light's view of a vtkShadowMapBakerPass? It needs the hits'
// depth, drawn opaque in one pass.
bool IsShadowMapBake(vtkActor* act)
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

// The depth format of the framebuffer bound for reading, as a vtkTextureObject
// depth format (-2 for depth with stencil), or -1 when it has no depth.
int ReadDepthFormat(GLuint framebuffer)
{
  const GLenum attachment = framebuffer ? GL_DEPTH_ATTACHMENT : GL_DEPTH;
  GLint type = GL_NONE;
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
  if (type == GL_NONE)
  {
    return -1;
  }
  GLint bits = 0, component = 0, stencil = 0;
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &bits);
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &component);
  if (framebuffer)
  {
    glGetFramebufferAttachmentParameteriv(
      GL_READ_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type != GL_NONE)
    {
      glGetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER,
        GL_STENCIL_ATTACHMENT,
        GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE,
        &stencil);
    }
  }
  if (stencil > 0)
  {
    return bits == 24 && component != GL_FLOAT ? -2 : -1;
  }
  if (component == GL_FLOAT)
  {
    return vtkTextureObject::Float32;
  }
  return bits <= 16 ? vtkTextureObject::Fixed16
                    : (bits <= 24 ? vtkTextureObject::Fixed24 : vtkTextureObject::Fixed32);
}

// The text between //VTK::<name>::Begin and //VTK::<name>::End of `source`.
std::string Block(const std::string& source, const std::string& name)
{
  const std::string begin = "//VTK::" + name + "::Begin";
  const std::string end = "//VTK::" + name + "::End";
  const size_t b = source.find(begin);
  const size_t e = source.find(end);
  if (b == std::string::npos || e == std::string::npos || e < b)
  {
    return std::string();
  }
  return source.substr(b + begin.size(), e - b - begin.size());
}
} // namespace

//------------------------------------------------------------------------------
vtkAlgebraicSplatMapper::vtkAlgebraicSplatMapper()
  : Targets(new BlendTargets)
{
  this->VisibilityBO.PrimitiveType = PrimitiveTris;
}

//------------------------------------------------------------------------------
vtkAlgebraicSplatMapper::~vtkAlgebraicSplatMapper() = default;

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::ReleaseGraphicsResources(vtkWindow* win)
{
  this->ShaderFailed = false;
  this->VisibilityBO.ReleaseGraphicsResources(win);
  this->BuiltVariants.clear();
  this->Targets->Release(win);
  this->Superclass::ReleaseGraphicsResources(win);
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::ComputeBounds()
{
  // Points only: the bounds are the origins padded by the disc radii.
  vtkPolyData* input = this->GetInput();
  if (!input || input->GetNumberOfPoints() == 0)
  {
    vtkMath::UninitializeBounds(this->Bounds);
    return;
  }
  input->GetPoints()->GetBounds(this->Bounds);
  vtkDataArray* radius = input->GetPointData()->GetArray(vtkSplatDataModel::RadiusName());
  double pad = 0.0;
  if (radius)
  {
    double range[2];
    radius->GetRange(range, 0);
    pad = range[1];
  }
  // The patch may rise above its disc by about its radius.
  for (int i = 0; i < 3; ++i)
  {
    this->Bounds[2 * i] -= 2.0 * pad;
    this->Bounds[2 * i + 1] += 2.0 * pad;
  }
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
  std::string VSSource = shaders[vtkShader::Vertex]->GetSource();
  std::string FSSource = shaders[vtkShader::Fragment]->GetSource();
  const std::string fs = vtkAlgebraicSplatFS;
  std::string declarations = Block(fs, "SplatDecl");
  vtkShaderProgram::Substitute(declarations, "//VTK::SplatRoots::Dec", vtkSplatRoots);

  const std::string degree =
    "#define SPLAT_DEGREE " + std::to_string(std::max(1, this->Degree)) + "\n";
  const std::string variant = "#define SPLAT_PASS " + std::to_string(this->Variant.Pass) +
    "\n#define SPLAT_SAMPLES " + std::to_string(this->Variant.Samples) +
    "\n#define SPLAT_SHOW_SILHOUETTE " + (this->Variant.ShowSilhouette ? "1" : "0") +
    "\n#define SPLAT_CULL_FACES " + std::to_string(this->Variant.Cull) + "\n";
  vtkShaderProgram::Substitute(VSSource, "//VTK::SplatDegree::Dec", degree);
  vtkShaderProgram::Substitute(VSSource, "//VTK::Camera::Dec", "uniform mat4 MCVCMatrix;");
  vtkShaderProgram::Substitute(FSSource, "//VTK::PositionVC::Dec", "in vec4 vertexVCVSOutput;");
  vtkShaderProgram::Substitute(
    FSSource, "//VTK::PositionVC::Impl", "vec4 vertexVC = vertexVCVSOutput;\n");
  // The bounding faces are never behind the hit: conservative depth keeps
  // early depth rejection working. The blending pass does not write depth.
  const std::string conservative =
    "#ifdef GL_ARB_conservative_depth\nlayout(depth_greater) out float gl_FragDepth;\n#endif\n";
  vtkShaderProgram::Substitute(FSSource,
    "//VTK::System::Dec",
    "//VTK::System::Dec\n#extension GL_ARB_conservative_depth : enable\n");
  vtkShaderProgram::Substitute(FSSource,
    "//VTK::Normal::Dec",
    degree + variant + (this->Variant.Pass == 2 ? std::string() : conservative) + declarations);
  vtkShaderProgram::Substitute(FSSource, "//VTK::Depth::Impl", Block(fs, "SplatImpl"));
  vtkShaderProgram::Substitute(FSSource, "//VTK::Normal::Impl", "");
  // The blend passes' outputs go last in main(), after VTK's lighting.
  vtkShaderProgram::Substitute(
    FSSource, "//VTK::Coincident::Impl", "//VTK::Coincident::Impl\n" + Block(fs, "SplatOutput"));
  shaders[vtkShader::Vertex]->SetSource(VSSource);
  shaders[vtkShader::Fragment]->SetSource(FSSource);
  this->BuiltVariants[this->LastBoundBO] = this->Variant;
  this->Superclass::ReplaceShaderValues(shaders, ren, act);

  // vtkShadowMapBakerPass stores the fragment's depth from gl_FragCoord,
  // which is the bounding quad's: give it the ray-cast hit's.
  FSSource = shaders[vtkShader::Fragment]->GetSource();
  vtkShaderProgram::Substitute(FSSource, "ldepth =  gl_FragCoord.z;", "ldepth = splatDepth;");
  vtkShaderProgram::Substitute(FSSource, "1.0/gl_FragCoord.w", "splatClipW");
  shaders[vtkShader::Fragment]->SetSource(FSSource);
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
  if (program->IsUniformUsed("splatPixelStep"))
  {
    // NDC spans 2 over the viewport; x_ndc = P00 x / -z (perspective) or
    // P00 x + c (parallel): a pixel is 2 / (P00 width) on the plane z = -1,
    // or in view units.
    int width = 1, height = 1;
    ren->GetTiledSize(&width, &height);
    const float step[2] = { static_cast<float>(2.0 / (vcdc->GetElement(0, 0) * std::max(width, 1))),
      static_cast<float>(2.0 / (vcdc->GetElement(1, 1) * std::max(height, 1))) };
    program->SetUniform2f("splatPixelStep", step);
  }
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::BuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  vtkPolyData* poly = this->CurrentInput;
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
    this->VBOBuildTime.Modified();
    return;
  }
  const vtkIdType n = poly->GetNumberOfPoints();
  vtkPointData* pd = poly->GetPointData();
  vtkDataArray* coeffs = pd->GetArray(vtkSplatDataModel::CoefficientsName());
  vtkDataArray* size = pd->GetArray(vtkSplatDataModel::FeatureSizeName());
  vtkDataArray* radius = pd->GetArray(vtkSplatDataModel::RadiusName());
  vtkDataArray* lod = pd->GetArray(vtkSplatDataModel::LODName());
  vtkDataArray* quality = poly->GetFieldData()->GetArray("SplatLODQuality");
  vtkDataArray* normals = pd->GetArray(vtkSplatDataModel::NormalName());
  vtkDataArray* tangents = pd->GetArray(vtkSplatDataModel::TangentName());
  vtkDataArray* points = poly->GetPoints()->GetData();
  // Positions go to the GPU relative to the bounds' centre, in double first,
  // so that float keeps their precision at any offset (1e7 and beyond);
  // SetCameraShaderParameters adds the shift back into MCVCMatrix.
  double bounds[6];
  poly->GetPoints()->GetBounds(bounds);
  for (int k = 0; k < 3; ++k)
  {
    this->Shift[k] = std::isfinite(bounds[2 * k] + bounds[2 * k + 1])
      ? 0.5 * (bounds[2 * k] + bounds[2 * k + 1])
      : 0.0;
  }
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
  const int m = coeffs->GetNumberOfComponents();
  std::atomic<vtkIdType> invalid(0);
  vtkSMPTools::For(0,
    n,
    [&](vtkIdType begin, vtkIdType end)
    {
      vtkIdType bad = 0;
      for (vtkIdType i = begin; i < end; ++i)
      {
        double p[3], nn[3], t[3];
        points->GetTuple(i, p);
        normals->GetTuple(i, nn);
        tangents->GetTuple(i, t);
        const double h = size->GetTuple1(i), r = radius->GetTuple1(i);
        bool ok = h > 0.0 && r > 0.0 && std::isfinite(h) && std::isfinite(r) &&
          vtkMath::Norm(nn) > 0.0 && vtkMath::Norm(t) > 0.0;
        for (int k = 0; k < 3; ++k)
        {
          ok = ok && std::isfinite(p[k]) && std::isfinite(nn[k]) && std::isfinite(t[k]);
          positions->SetTypedComponent(i, k, static_cast<float>(p[k] - this->Shift[k]));
        }
        for (int k = 0; k < 16; ++k)
        {
          const double value = k < m ? coeffs->GetComponent(i, k) : 0.0;
          ok = ok && std::isfinite(value);
          c[k / 4]->SetTypedComponent(i, k % 4, static_cast<float>(value));
        }
        const int level = lod ? static_cast<int>(lod->GetTuple1(i)) : 0;
        const double s = quality && level >= 0 && level < quality->GetNumberOfTuples()
          ? quality->GetTuple1(level)
          : 1.0;
        // An invalid splat gets a zero radius: the geometry shader drops it.
        sizes->SetTypedComponent(i, 0, ok ? static_cast<float>(h) : 1.0f);
        sizes->SetTypedComponent(i, 1, ok ? static_cast<float>(r) : 0.0f);
        sizes->SetTypedComponent(i, 2, ok && s > 0.0 ? static_cast<float>(r / s) : 0.0f);
        bad += ok ? 0 : 1;
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
  this->VBOs->CacheDataArray("scalarColor", this->Colors, ren, VTK_UNSIGNED_CHAR);
  this->VBOs->BuildAllVBOs(ren);
  this->Primitives[PrimitiveTris].IBO->IndexCount = n;
  this->VisibilityBO.IBO->IndexCount = n;
  this->ReadOctree(poly);
  this->VBOBuildTime.Modified();
  (void)act;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::ReadOctree(vtkPolyData* poly)
{
  this->Nodes.reset();
  vtkFieldData* fd = poly->GetFieldData();
  vtkDataArray* sphere = fd->GetArray("OctreeNodeSphere");
  vtkDataArray* children = fd->GetArray("OctreeNodeChildren");
  vtkDataArray* range = fd->GetArray("OctreeNodeRange");
  vtkDataArray* ends = fd->GetArray("OctreeNodeLevelEnds");
  vtkDataArray* quality = fd->GetArray("SplatLODQuality");
  vtkDataArray* radius = poly->GetPointData()->GetArray(vtkSplatDataModel::RadiusName());
  vtkDataArray* lod = poly->GetPointData()->GetArray(vtkSplatDataModel::LODName());
  const vtkIdType count = sphere ? sphere->GetNumberOfTuples() : 0;
  if (!count || !children || !range || !ends || !quality || !radius || !lod ||
    children->GetNumberOfTuples() != count || range->GetNumberOfTuples() != count ||
    ends->GetNumberOfTuples() != count ||
    ends->GetNumberOfComponents() != quality->GetNumberOfTuples())
  {
    return; // no (usable) octree: draw everything
  }
  // A filter that moved the points after fitting (a transform, say) leaves
  // the octree behind: culling by it would hide the splats. Check that the
  // root's sphere still holds every splat.
  {
    double root[4];
    sphere->GetTuple(0, root);
    const vtkIdType n = poly->GetNumberOfPoints();
    const double r2 = root[3] * root[3] * (1.0 + 1e-6) + 1e-300;
    vtkIdType outside = 0;
    for (vtkIdType i = 0; i < n && outside == 0; ++i)
    {
      double p[3];
      poly->GetPoint(i, p);
      outside += vtkMath::Distance2BetweenPoints(p, root) > r2 ? 1 : 0;
    }
    if (outside > 0)
    {
      vtkWarningMacro(<< "The octree in the input's field data does not hold its splats (were "
                         "the points moved after fitting?): it is ignored, every splat is drawn.");
      return;
    }
  }
  // A filter that split, subset or reordered the splats (ParaView's
  // RedistributeDataSet between ranks, a threshold, a merge) leaves ranges
  // that no longer index them: check every range before using one.
  {
    const vtkIdType n = poly->GetNumberOfPoints();
    const int levels = ends->GetNumberOfComponents();
    bool valid = static_cast<vtkIdType>(range->GetComponent(0, 0)) == 0 &&
      static_cast<vtkIdType>(range->GetComponent(0, 1)) == n;
    for (vtkIdType i = 0; i < count && valid; ++i)
    {
      const double begin = range->GetComponent(i, 0), end = range->GetComponent(i, 1);
      const double first = children->GetComponent(i, 0), number = children->GetComponent(i, 1);
      valid = begin >= 0 && begin <= end && end <= n && number >= 0 &&
        (number == 0 || (first > i && first + number <= count));
      for (int l = 0; l < levels && valid; ++l)
      {
        const double e = ends->GetComponent(i, l);
        valid = e >= begin && e <= end;
      }
    }
    for (vtkIdType k = 0; k < n && valid; ++k)
    {
      const double level = lod->GetTuple1(k);
      valid = level >= 0 && level < levels;
    }
    if (!valid)
    {
      vtkWarningMacro(<< "The octree in the input's field data does not index its " << n
                      << " splats (were splats split, removed or reordered after fitting?): it is "
                         "ignored, every splat is drawn.");
      return;
    }
  }
  auto tree = std::make_shared<Octree>();
  tree->Levels = ends->GetNumberOfComponents();
  for (int l = 0; l < tree->Levels; ++l)
  {
    tree->LevelQuality.push_back(quality->GetTuple1(l));
  }
  tree->Nodes.resize(count);
  tree->LevelEnds.resize(count * tree->Levels);
  tree->MeanRadius.resize(count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    Octree::Node& node = tree->Nodes[i];
    sphere->GetTuple(i, node.Sphere);
    node.FirstChild = static_cast<vtkIdType>(children->GetComponent(i, 0));
    node.ChildCount = static_cast<vtkIdType>(children->GetComponent(i, 1));
    node.Begin = static_cast<vtkIdType>(range->GetComponent(i, 0));
    node.End = static_cast<vtkIdType>(range->GetComponent(i, 1));
    for (int l = 0; l < tree->Levels; ++l)
    {
      tree->LevelEnds[i * tree->Levels + l] = static_cast<vtkIdType>(ends->GetComponent(i, l));
    }
    // R / s is the splats' feature size scale: R at level l is about s_l times it.
    double sum = 0.0, largest = 0.0;
    for (vtkIdType k = node.Begin; k < node.End; ++k)
    {
      sum += radius->GetTuple1(k) / tree->LevelQuality[static_cast<int>(lod->GetTuple1(k))];
      largest = std::max(largest, radius->GetTuple1(k));
    }
    // The sphere holds the discs; a patch may also rise up to R above its
    // disc, so the cylinder reaches sqrt(2) R from the origin.
    node.Sphere[3] += (std::sqrt(2.0) - 1.0) * largest;
    tree->MeanRadius[i] = node.End > node.Begin ? sum / (node.End - node.Begin) : 0.0;
  }
  this->Nodes = tree;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::DrawOctree(vtkRenderer* ren, vtkActor* act)
{
  const Octree& tree = *this->Nodes;
  vtkShaderProgram* program = this->CurrentBO->Program;
  vtkCamera* cam = ren->GetActiveCamera();
  double planes[24];
  cam->GetFrustumPlanes(ren->GetTiledAspectRatio(), planes);
  int size[2];
  ren->GetTiledSize(&size[0], &size[1]);
  double eye[3];
  cam->GetPosition(eye);
  const double tanHalf = std::tan(0.5 * vtkMath::RadiansFromDegrees(cam->GetViewAngle()));
  vtkMatrix4x4* mcwc = act->GetMatrix();
  const bool identity = act->GetIsIdentity();
  // Pixels per world unit at distance d.
  auto pixelsPerUnit = [&](double d)
  {
    return cam->GetParallelProjection() ? size[1] / (2.0 * cam->GetParallelScale())
                                        : size[1] / (2.0 * std::max(d, 1e-30) * tanHalf);
  };
  std::vector<vtkIdType> stack{ 0 };
  this->NumberOfRenderedSplats = 0;
  while (!stack.empty())
  {
    const vtkIdType id = stack.back();
    stack.pop_back();
    const Octree::Node& node = tree.Nodes[id];
    double c[4] = { node.Sphere[0], node.Sphere[1], node.Sphere[2], 1.0 };
    double r = node.Sphere[3];
    if (!identity)
    {
      mcwc->MultiplyPoint(c, c);
      double scale = 0.0; // the largest axis scale of the actor
      for (int a = 0; a < 3; ++a)
      {
        scale = std::max(scale,
          std::sqrt(mcwc->GetElement(0, a) * mcwc->GetElement(0, a) +
            mcwc->GetElement(1, a) * mcwc->GetElement(1, a) +
            mcwc->GetElement(2, a) * mcwc->GetElement(2, a)));
      }
      r *= scale;
    }
    bool outside = false;
    for (int p = 0; this->Culling && p < 6 && !outside; ++p)
    {
      const double* e = planes + 4 * p;
      outside = e[0] * c[0] + e[1] * c[1] + e[2] * c[2] + e[3] < -r;
    }
    if (outside)
    {
      continue;
    }
    if (node.ChildCount > 0)
    {
      for (vtkIdType k = 0; k < node.ChildCount; ++k)
      {
        stack.push_back(node.FirstChild + k);
      }
      continue;
    }
    // Continuous LOD: levels down to the first whose splats are small enough.
    int level = tree.Levels - 1;
    if (this->LODPixelError > 0.0)
    {
      const double d = std::max(std::sqrt(vtkMath::Distance2BetweenPoints(c, eye)) - r, 1e-30);
      const double ppu = pixelsPerUnit(d);
      for (int l = 0; l < tree.Levels; ++l)
      {
        if (2.0 * tree.LevelQuality[l] * tree.MeanRadius[id] * ppu <= this->LODPixelError)
        {
          level = l;
          break;
        }
      }
    }
    const vtkIdType end = tree.LevelEnds[id * tree.Levels + level];
    if (end > node.Begin)
    {
      program->SetUniformf("lodQuality", static_cast<float>(tree.LevelQuality[level]));
      glDrawArrays(
        GL_POINTS, static_cast<GLint>(node.Begin), static_cast<GLsizei>(end - node.Begin));
      this->NumberOfRenderedSplats += end - node.Begin;
    }
  }
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
  this->RenderBlended(ren, act);
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
  this->UpdateShaders(cellBO, ren, act);
  vtkShaderProgram* program = cellBO.Program;
  if (!program)
  {
    // VTK's UpdateShaders would reuse the null program on the next frame
    // (and crash): remember the failure, and rebuild once something changes.
    vtkErrorMacro(<< "The splat shader (pass " << variant.Pass
                  << ") did not compile: the splats are not drawn.");
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
void vtkAlgebraicSplatMapper::RenderBlended(vtkRenderer* ren, vtkActor* act)
{
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  vtkOpenGLState* ostate = renWin->GetState();
  BlendTargets& t = *this->Targets;

  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  const int width = viewport[2], height = viewport[3];
  if (width <= 0 || height <= 0)
  {
    return;
  }
  GLint scene = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &scene);

  ostate->Push();
  ostate->vtkglBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<unsigned int>(scene));
  const int depthFormat = ReadDepthFormat(static_cast<GLuint>(scene));
  if (width != t.Width || height != t.Height || depthFormat != t.DepthFormat)
  {
    t.Framebuffer->SetContext(renWin);
    t.Accumulation->SetContext(renWin);
    t.DepthCoverage->SetContext(renWin);
    t.Depth->SetContext(renWin);
    t.CopyFramebuffer->SetContext(renWin);
    t.VisibleDepth->SetContext(renWin);
    t.Accumulation->Allocate2D(width, height, 4, VTK_FLOAT);
    t.DepthCoverage->Allocate2D(width, height, 2, VTK_FLOAT);
    for (vtkTextureObject* depth : { t.Depth.GetPointer(), t.VisibleDepth.GetPointer() })
    {
      if (depthFormat == -2)
      {
        depth->AllocateDepthStencil(width, height);
      }
      else
      {
        depth->AllocateDepth(
          width, height, depthFormat >= 0 ? depthFormat : vtkTextureObject::Float32);
      }
    }
    t.CopyFramebuffer->Bind(GL_DRAW_FRAMEBUFFER);
    t.CopyFramebuffer->AddDepthAttachment(t.VisibleDepth);
    // Depth only: no colour buffer to draw to (without this the framebuffer
    // is incomplete before GL 4.1).
    ostate->vtkglDrawBuffer(GL_NONE);
    t.Framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
    t.Framebuffer->AddColorAttachment(0, t.Accumulation);
    t.Framebuffer->AddColorAttachment(1, t.DepthCoverage);
    t.Framebuffer->AddDepthAttachment(t.Depth);
    t.Width = width;
    t.Height = height;
    t.DepthFormat = depthFormat;
  }
  t.Framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  t.Framebuffer->ActivateDrawBuffers(2);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ostate->vtkglViewport(0, 0, width, height);

  // The scene's depth, so that the actors drawn before hide the splats.
  bool copied = false;
  if (depthFormat != -1)
  {
    for (int k = 0; k < 16 && glGetError() != GL_NO_ERROR; ++k)
    {
    }
    glBlitFramebuffer(viewport[0],
      viewport[1],
      viewport[0] + width,
      viewport[1] + height,
      0,
      0,
      width,
      height,
      GL_DEPTH_BUFFER_BIT,
      GL_NEAREST);
    copied = glGetError() == GL_NO_ERROR;
  }
  if (!copied)
  {
    if (!t.Warned)
    {
      vtkWarningMacro(<< "Cannot copy the scene's depth buffer; blended splats are drawn "
                         "without occlusion by the actors drawn before them.");
      t.Warned = true;
    }
    ostate->vtkglDepthMask(GL_TRUE);
    ostate->vtkglClearDepth(1.0);
    ostate->vtkglClear(GL_DEPTH_BUFFER_BIT);
  }
  const GLfloat zero[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  const GLfloat one[4] = { 1.0f, 1.0f, 1.0f, 1.0f };
  glClearBufferfv(GL_COLOR, 0, zero);
  glClearBufferfv(GL_COLOR, 1, one);

  // Visibility: the nearest hits pushed back by delta h. The nearest hit of
  // the pixel centre's ray is enough here: no supersampling.
  ShaderVariant visibility;
  visibility.Pass = 1;
  vtkShaderProgram* program = this->UseVariant(visibility, ren, act);
  if (!program)
  {
    ostate->Pop();
    return;
  }
  const float offset = static_cast<float>(this->Blending ? this->BlendDepthOffset : 1e-3);
  program->SetUniformf("splatBlendOffset", offset);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_LESS);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglDisable(GL_BLEND);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  this->DrawSplats(ren, act, true);

  // Blending: every hit in front of that depth, weighted. The shader reads
  // a copy of it, while the depth test drops fragments behind it unshaded.
  t.Framebuffer->Bind(GL_READ_FRAMEBUFFER);
  t.CopyFramebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  glBlitFramebuffer(0,
    0,
    width,
    height,
    0,
    0,
    width,
    height,
    depthFormat == -2 ? GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT : GL_DEPTH_BUFFER_BIT,
    GL_NEAREST);
  t.Framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  t.Framebuffer->ActivateDrawBuffers(2);
  ShaderVariant blending;
  blending.Pass = 2;
  blending.Samples = this->AntiAliasing;
  blending.ShowSilhouette = this->ShowSilhouettePixels;
  program = this->UseVariant(blending, ren, act);
  if (!program)
  {
    ostate->Pop();
    return;
  }
  program->SetUniformf(
    "splatBlendSharpness", static_cast<float>(this->Blending ? this->BlendSharpness : 0.0));
  t.VisibleDepth->Activate();
  program->SetUniformi("splatVisibleDepth", t.VisibleDepth->GetTextureUnit());
  // The hit is compared with the stored depth, which its format rounded.
  const double steps = depthFormat == vtkTextureObject::Fixed16
    ? 65535.0
    : (depthFormat == vtkTextureObject::Fixed24 || depthFormat == -2 ? 16777215.0 : 4194304.0);
  program->SetUniformf("splatDepthTolerance", static_cast<float>(1.0 / steps));
  const GLboolean offsetWasOn = glIsEnabled(GL_POLYGON_OFFSET_FILL);
  GLfloat offsetFactor = 0.0f, offsetUnits = 0.0f;
  glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &offsetFactor);
  glGetFloatv(GL_POLYGON_OFFSET_UNITS, &offsetUnits);
  if (this->AntiAliasing > 1)
  {
    // Silhouette pixels get their sub-pixel rays (the geometry shader grows
    // each splat's quad by half a pixel), which meet the splat's box nearer
    // than the centre's depth by up to half a pixel's depth slopes: pull the
    // quads' depth forward by a whole one, so that the early test stays
    // conservative for them too.
    const float margin[2] = { 1.0f / width, 1.0f / height };
    program->SetUniform2f("splatOutlineMargin", margin);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(-1.0f, -1.0f);
  }
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  ostate->vtkglDepthFunc(GL_LEQUAL);
  ostate->vtkglDepthMask(GL_FALSE);
  ostate->vtkglEnable(GL_BLEND);
  glBlendEquationi(0, GL_FUNC_ADD);
  glBlendFunci(0, GL_ONE, GL_ONE);
  glBlendEquationi(1, GL_MIN);
  glBlendFunci(1, GL_ONE, GL_ONE);
  this->DrawSplats(ren, act, true);
  if (!offsetWasOn)
  {
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  glPolygonOffset(offsetFactor, offsetUnits);
  t.VisibleDepth->Deactivate();
  ostate->Pop(); // the scene's framebuffer, viewport, blending and program

  // Normalise and composite with the true depth.
  ostate->Push();
  if (!t.Composite)
  {
    t.Composite.reset(new vtkOpenGLQuadHelper(renWin, nullptr, vtkAlgebraicSplatCompositeFS, ""));
  }
  else
  {
    renWin->GetShaderCache()->ReadyShaderProgram(t.Composite->Program);
  }
  if (!t.Composite->Program)
  {
    ostate->Pop();
    vtkErrorMacro(<< "The splat compositing shader did not compile.");
    return;
  }
  t.Accumulation->Activate();
  t.DepthCoverage->Activate();
  t.Composite->Program->SetUniformi("accumulation", t.Accumulation->GetTextureUnit());
  t.Composite->Program->SetUniformi("depthCoverage", t.DepthCoverage->GetTextureUnit());
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_ALWAYS);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglEnable(GL_BLEND);
  ostate->vtkglBlendEquation(GL_FUNC_ADD);
  ostate->vtkglBlendFuncSeparate(
    GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  t.Composite->Render();
  t.Accumulation->Deactivate();
  t.DepthCoverage->Deactivate();
  ostate->Pop();
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
