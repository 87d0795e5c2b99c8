// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtk_glew.h"

#include "vtkAlgebraicSplatMapper.h"

#include "vtkAlgebraicSplatFS.h"
#include "vtkAlgebraicSplatGS.h"
#include "vtkAlgebraicSplatVS.h"
#include "vtkSplatRoots.h"

#include "vtkActor.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
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
#include <string>

vtkStandardNewMacro(vtkAlgebraicSplatMapper);

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
  // The degree is compiled into the fragment shader.
  return this->ShaderDegree != this->Degree ||
    this->Superclass::GetNeedToRebuildShaders(cellBO, ren, act);
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
  vtkNew<vtkFloatArray> sizes;
  sizes->SetNumberOfComponents(2);
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
  this->VBOBuildTime.Modified();
  (void)act;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::RenderPieceDraw(vtkRenderer* ren, vtkActor* act)
{
  const int n = this->VBOs->GetNumberOfTuples("vertexMC");
  if (n > 0 && this->Degree > 0)
  {
    this->UpdateShaders(this->Primitives[PrimitiveTris], ren, act);
    glDrawArrays(GL_POINTS, 0, static_cast<GLuint>(n));
  }
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Degree: " << this->Degree << "\n";
}
