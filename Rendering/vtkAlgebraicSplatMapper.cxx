// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtk_glew.h"

#include "vtkAlgebraicSplatMapper.h"

#include "vtkAlgebraicSplatFS.h"
#include "vtkAlgebraicSplatGS.h"
#include "vtkAlgebraicSplatVS.h"
#include "vtkSplatRoots.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLActor.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLIndexBufferObject.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSplatDataModel.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
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

namespace
{
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
vtkAlgebraicSplatMapper::vtkAlgebraicSplatMapper() = default;

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

  vtkShaderProgram::Substitute(VSSource, "//VTK::Camera::Dec", "uniform mat4 MCVCMatrix;");
  vtkShaderProgram::Substitute(FSSource, "//VTK::PositionVC::Dec", "in vec4 vertexVCVSOutput;");
  vtkShaderProgram::Substitute(
    FSSource, "//VTK::PositionVC::Impl", "vec4 vertexVC = vertexVCVSOutput;\n");
  vtkShaderProgram::Substitute(FSSource,
    "//VTK::Normal::Dec",
    "#define SPLAT_DEGREE " + std::to_string(std::max(1, this->Degree)) + "\n" + declarations);
  vtkShaderProgram::Substitute(FSSource, "//VTK::Depth::Impl", Block(fs, "SplatImpl"));
  vtkShaderProgram::Substitute(FSSource, "//VTK::Normal::Impl", "");
  shaders[vtkShader::Vertex]->SetSource(VSSource);
  shaders[vtkShader::Fragment]->SetSource(FSSource);
  this->ShaderDegree = this->Degree;
  this->Superclass::ReplaceShaderValues(shaders, ren, act);
}

//------------------------------------------------------------------------------
bool vtkAlgebraicSplatMapper::GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO,
  vtkRenderer* ren,
  vtkActor* act)
{
  // The superclass must always run: it records the lighting complexity that
  // the shader is then built for. The degree is compiled into the shader.
  const bool changed = this->Superclass::GetNeedToRebuildShaders(cellBO, ren, act);
  return changed || this->ShaderDegree != this->Degree;
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
    if (!act->GetIsIdentity())
    {
      vtkMatrix4x4* mcwc;
      vtkMatrix3x3* anorms;
      static_cast<vtkOpenGLActor*>(act)->GetKeyMatrices(mcwc, anorms);
      vtkMatrix4x4::Multiply4x4(mcwc, wcvc, this->TempMatrix4);
      program->SetUniformMatrix("MCVCMatrix", this->TempMatrix4);
    }
    else
    {
      program->SetUniformMatrix("MCVCMatrix", wcvc);
    }
  }
  if (program->IsUniformUsed("cameraParallel"))
  {
    program->SetUniformi("cameraParallel", cam->GetParallelProjection());
  }
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::BuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  vtkPolyData* poly = this->CurrentInput;
  this->Degree = vtkSplatDataModel::GetSplatDegree(poly);
  this->Primitives[PrimitivePoints].IBO->IndexCount = 0;
  this->Primitives[PrimitiveLines].IBO->IndexCount = 0;
  this->Primitives[PrimitiveTriStrips].IBO->IndexCount = 0;
  this->Primitives[PrimitiveTris].IBO->IndexCount = 0;
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
  for (vtkIdType i = 0; i < n; ++i)
  {
    sizes->SetTypedComponent(i, 0, static_cast<float>(size->GetTuple1(i)));
    sizes->SetTypedComponent(i, 1, static_cast<float>(radius->GetTuple1(i)));
    const int level = lod ? static_cast<int>(lod->GetTuple1(i)) : 0;
    const double s = quality && level >= 0 && level < quality->GetNumberOfTuples()
      ? quality->GetTuple1(level)
      : 1.0;
    sizes->SetTypedComponent(i, 2, static_cast<float>(radius->GetTuple1(i) / s));
    for (int k = 0; k < 16; ++k)
    {
      c[k / 4]->SetTypedComponent(
        i, k % 4, k < m ? static_cast<float>(coeffs->GetComponent(i, k)) : 0.0f);
    }
  }

  // Colours through the usual mapper colouring, or the actor's colour.
  this->MapScalars(1.0);
  this->VBOs->CacheDataArray("vertexMC", poly->GetPoints()->GetData(), ren, VTK_FLOAT);
  this->VBOs->CacheDataArray(
    "splatNormalMC", pd->GetArray(vtkSplatDataModel::NormalName()), ren, VTK_FLOAT);
  this->VBOs->CacheDataArray(
    "splatTangentMC", pd->GetArray(vtkSplatDataModel::TangentName()), ren, VTK_FLOAT);
  this->VBOs->CacheDataArray("splatSizeMC", sizes, ren, VTK_FLOAT);
  const char* names[4] = { "splatC0", "splatC1", "splatC2", "splatC3" };
  for (int k = 0; k < 4; ++k)
  {
    this->VBOs->CacheDataArray(names[k], c[k], ren, VTK_FLOAT);
  }
  this->VBOs->CacheDataArray("scalarColor", this->Colors, ren, VTK_UNSIGNED_CHAR);
  this->VBOs->BuildAllVBOs(ren);
  this->Primitives[PrimitiveTris].IBO->IndexCount = n;
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
  vtkShaderProgram* program = this->Primitives[PrimitiveTris].Program;
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
void vtkAlgebraicSplatMapper::RenderPieceDraw(vtkRenderer* ren, vtkActor* act)
{
  const int n = this->VBOs->GetNumberOfTuples("vertexMC");
  this->NumberOfRenderedSplats = 0;
  if (n <= 0 || this->Degree <= 0)
  {
    return;
  }
  this->UpdateShaders(this->Primitives[PrimitiveTris], ren, act);
  this->Primitives[PrimitiveTris].Program->SetUniformf("lodQuality", 0.0f);
  // Picking numbers primitives per draw call: draw everything in one.
  if (this->Nodes && !ren->GetSelector())
  {
    this->DrawOctree(ren, act);
    return;
  }
  glDrawArrays(GL_POINTS, 0, static_cast<GLuint>(n));
  this->NumberOfRenderedSplats = n;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Degree: " << this->Degree << "\n";
  os << indent << "Culling: " << this->Culling << "\n";
  os << indent << "LODPixelError: " << this->LODPixelError << "\n";
}
