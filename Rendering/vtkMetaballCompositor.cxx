// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkMetaballCompositor.h"

#include "vtkMatrix4x4.h"
#include "vtkMetaballCompositeFS.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLRenderer.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkProperty.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "psShaderHooks.h"

#include <string>

vtkStandardNewMacro(vtkMetaballCompositor);

namespace
{
// The composite shader's //VTK::Light::Impl: one psLight call per light of
// the renderer, with VTK's uniforms for it (vtkOpenGLRenderer's names: a
// headlight has lightColor0 only). The first four lights can be shadowed.
std::string LightCalls(int complexity, int count)
{
  std::string code;
  for (int k = 0; k < count; ++k)
  {
    const std::string i = std::to_string(k);
    const std::string lit = k < 4 ? "1.0 - blocked[" + i + "]" : "1.0";
    if (complexity == 1)
    {
      code +=
        "result += psLight(n, toEye, base.rgb, lightColor0, vec3(0.0, 0.0, 1.0), " + lit + ");\n";
      break;
    }
    code += "toLight = -lightDirectionVC" + i + ";\nstrength = 1.0;\n";
    if (complexity >= 3)
    {
      code += "if (lightPositional" + i + " != 0)\n{\n  toLight = psPositional(p.xyz, " +
        "lightPositionVC" + i + ", lightDirectionVC" + i + ", lightAttenuation" + i +
        ", lightConeAngle" + i + ", lightExponent" + i + ", strength);\n}\n";
    }
    code += "result += strength * psLight(n, toEye, base.rgb, lightColor" + i + ", toLight, " +
      lit + ");\n";
  }
  return code;
}

// The material's uniforms of the composite shader.
void SetMaterial(vtkShaderProgram* program, vtkProperty* prop)
{
  const double* ambientColor = prop->GetAmbientColor();
  const double* specularColor = prop->GetSpecularColor();
  const float ac[3] = { static_cast<float>(ambientColor[0]),
    static_cast<float>(ambientColor[1]),
    static_cast<float>(ambientColor[2]) };
  const float sc[3] = { static_cast<float>(specularColor[0]),
    static_cast<float>(specularColor[1]),
    static_cast<float>(specularColor[2]) };
  program->SetUniformf("ambient", static_cast<float>(prop->GetAmbient()));
  program->SetUniformf("diffuse", static_cast<float>(prop->GetDiffuse()));
  program->SetUniformf("specular", static_cast<float>(prop->GetSpecular()));
  program->SetUniformf("specularPower", static_cast<float>(prop->GetSpecularPower()));
  program->SetUniform3f("ambientColor", ac);
  program->SetUniform3f("specularColor", sc);
  program->SetUniformf("opacity", static_cast<float>(prop->GetOpacity()));
}

} // namespace

//------------------------------------------------------------------------------
vtkMetaballCompositor::vtkMetaballCompositor() = default;

//------------------------------------------------------------------------------
vtkMetaballCompositor::~vtkMetaballCompositor() = default;

//------------------------------------------------------------------------------
bool vtkMetaballCompositor::Ready(vtkRenderer* ren, int complexity, int lights)
{
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  if (!this->Quad || complexity != this->Lighting || lights != this->Lights)
  {
    auto* oren = static_cast<vtkOpenGLRenderer*>(ren);
    std::string source = vtkMetaballCompositeFS;
    const std::string declarations = "#define LIGHTING_COMPLEXITY " + std::to_string(complexity) +
      "\n" + (complexity > 0 ? oren->GetLightingUniforms() : "");
    if (!pointsurfaces::ReplaceHook(source, "//VTK::Light::Dec", declarations) ||
      !pointsurfaces::ReplaceHook(source, "//VTK::Light::Impl", LightCalls(complexity, lights)))
    {
      vtkErrorMacro(<< "vtkMetaballCompositeFS lacks its //VTK::Light hooks: nothing is drawn.");
      return false;
    }
    if (this->Quad)
    {
      this->Quad->ReleaseGraphicsResources(renWin);
    }
    this->Quad.reset(new vtkOpenGLQuadHelper(renWin, nullptr, source.c_str(), ""));
    this->Lighting = complexity;
    this->Lights = lights;
  }
  else
  {
    renWin->GetShaderCache()->ReadyShaderProgram(this->Quad->Program);
  }
  if (!this->Quad->Program)
  {
    vtkErrorMacro(<< "The metaball shading shader did not compile.");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkMetaballCompositor::Draw(vtkRenderer* ren,
  vtkProperty* prop,
  const pointsurfaces::MetaballView& view,
  const pointsurfaces::MetaballImages& images,
  vtkTextureObject* shadows)
{
  auto* oren = vtkOpenGLRenderer::SafeDownCast(ren);
  const int complexity = oren && prop->GetLighting() ? oren->GetLightingComplexity() : 0;
  const int lights = complexity > 0 ? oren->GetLightingCount() : 0;
  if (!this->Ready(ren, complexity, lights))
  {
    return false;
  }
  vtkShaderProgram* program = this->Quad->Program;
  auto* renWin = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow());
  const pointsurfaces::CompositeDepthState depthState(renWin->GetState());
  images.Color->Activate();
  images.Normal->Activate();
  images.Depth->Activate();
  program->SetUniformi("colorTexture", images.Color->GetTextureUnit());
  program->SetUniformi("normalTexture", images.Normal->GetTextureUnit());
  program->SetUniformi("depthTexture", images.Depth->GetTextureUnit());
  program->SetUniformi("shadows", shadows ? 1 : 0);
  if (shadows)
  {
    shadows->Activate();
    program->SetUniformi("shadowTexture", shadows->GetTextureUnit());
  }
  vtkNew<vtkMatrix4x4> clipToView;
  clipToView->DeepCopy(view.ClipToView);
  program->SetUniformMatrix("clipToView", clipToView);
  program->SetUniformi("parallelProjection", view.Parallel ? 1 : 0);
  if (complexity > 0)
  {
    oren->UpdateLightingUniforms(program);
  }
  SetMaterial(program, prop);
  this->Quad->Render();
  images.Color->Deactivate();
  images.Normal->Deactivate();
  images.Depth->Deactivate();
  if (shadows)
  {
    shadows->Deactivate();
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMetaballCompositor::ReleaseGraphicsResources(vtkWindow* win)
{
  if (this->Quad)
  {
    this->Quad->ReleaseGraphicsResources(win);
    this->Quad.reset();
  }
  this->Lighting = this->Lights = -1;
}

//------------------------------------------------------------------------------
void vtkMetaballCompositor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Lighting: " << this->Lighting << ", lights: " << this->Lights << "\n";
}
