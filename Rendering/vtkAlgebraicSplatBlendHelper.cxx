// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkAlgebraicSplatBlendHelper.h"

#include "vtkAlgebraicSplatCompositeFS.h"

#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

vtkStandardNewMacro(vtkAlgebraicSplatBlendHelper);

// The float targets of the two-pass blend, sized to the renderer's viewport.
struct vtkAlgebraicSplatBlendHelper::Targets
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
  // The default framebuffer names its stencil GL_STENCIL, an object GL_STENCIL_ATTACHMENT.
  const GLenum stencilAttachment = framebuffer ? GL_STENCIL_ATTACHMENT : GL_STENCIL;
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, stencilAttachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
  if (type != GL_NONE)
  {
    glGetFramebufferAttachmentParameteriv(
      GL_READ_FRAMEBUFFER, stencilAttachment, GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE, &stencil);
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

// vtkOpenGLState's Push on construction and Pop on every way out: the
// framebuffer bindings, viewport, blending, depth and program as they were.
class ScopedStatePush
{
public:
  explicit ScopedStatePush(vtkOpenGLState* state)
    : State(state)
  {
    this->State->Push();
  }
  ~ScopedStatePush() { this->State->Pop(); }
  ScopedStatePush(const ScopedStatePush&) = delete;
  ScopedStatePush& operator=(const ScopedStatePush&) = delete;

private:
  vtkOpenGLState* State;
};
} // namespace

//------------------------------------------------------------------------------
vtkAlgebraicSplatBlendHelper::vtkAlgebraicSplatBlendHelper()
  : T(new Targets)
{
}

//------------------------------------------------------------------------------
vtkAlgebraicSplatBlendHelper::~vtkAlgebraicSplatBlendHelper() = default;

//------------------------------------------------------------------------------
void vtkAlgebraicSplatBlendHelper::ReleaseGraphicsResources(vtkWindow* win)
{
  this->T->Release(win);
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatBlendHelper::Render(vtkOpenGLRenderWindow* renWin,
  const Settings& settings,
  const Passes& passes,
  vtkObject* owner)
{
  GLint viewport[4];
  renWin->GetState()->vtkglGetIntegerv(GL_VIEWPORT, viewport);
  if (viewport[2] <= 0 || viewport[3] <= 0)
  {
    return;
  }
  // The accumulation, in the scene's framebuffer, viewport, blending and
  // program as they were when it ends; then the composite, likewise.
  if (this->Accumulate(renWin, viewport, settings, passes, owner))
  {
    this->Composite(renWin, owner);
  }
}

//------------------------------------------------------------------------------
bool vtkAlgebraicSplatBlendHelper::Accumulate(vtkOpenGLRenderWindow* renWin,
  const int viewport[4],
  const Settings& settings,
  const Passes& passes,
  vtkObject* owner)
{
  vtkOpenGLState* ostate = renWin->GetState();
  Targets& t = *this->T;
  const int width = viewport[2], height = viewport[3];
  GLint scene = 0, sampleBuffers = 0;
  ostate->vtkglGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &scene);
  ostate->vtkglGetIntegerv(GL_SAMPLE_BUFFERS, &sampleBuffers); // of the scene's framebuffer

  const ScopedStatePush push(ostate);
  ostate->vtkglBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<unsigned int>(scene));
  const int depthFormat = ReadDepthFormat(static_cast<GLuint>(scene));
  if (width != t.Width || height != t.Height || depthFormat != t.DepthFormat)
  {
    this->AllocateTargets(renWin, width, height, depthFormat);
  }
  t.Framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  t.Framebuffer->ActivateDrawBuffers(2);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ostate->vtkglViewport(0, 0, width, height);
  this->CopySceneDepth(ostate, viewport, sampleBuffers != 0, depthFormat, owner);
  const GLfloat zero[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  const GLfloat one[4] = { 1.0f, 1.0f, 1.0f, 1.0f };
  glClearBufferfv(GL_COLOR, 0, zero);
  glClearBufferfv(GL_COLOR, 1, one);

  // Visibility: the nearest hits pushed back by delta h. The nearest hit of
  // the pixel centre's ray is enough here: no supersampling.
  vtkShaderProgram* program = passes.UseVisibility();
  if (!program)
  {
    return false;
  }
  const float offset = static_cast<float>(settings.Blending ? settings.BlendDepthOffset : 1e-3);
  program->SetUniformf("splatBlendOffset", offset);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_LESS);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  passes.Draw();

  return this->Blend(ostate, width, height, depthFormat, settings, passes);
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatBlendHelper::AllocateTargets(vtkOpenGLRenderWindow* renWin,
  int width,
  int height,
  int depthFormat)
{
  vtkOpenGLState* ostate = renWin->GetState();
  Targets& t = *this->T;
  // New textures, not new storage in the old ones: VTK 9.6's AllocateDepth
  // on a texture that has storage keeps the old format (seen on Mesa 26: a
  // Float32 request after a Fixed32 one stayed GL_DEPTH_COMPONENT32, and
  // the depth blit failed on the mismatch).
  for (vtkTextureObject* texture : { t.Accumulation.GetPointer(),
         t.DepthCoverage.GetPointer(),
         t.Depth.GetPointer(),
         t.VisibleDepth.GetPointer() })
  {
    texture->ReleaseGraphicsResources(renWin);
  }
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
  // Detach first: the framebuffers know their attachments by object and
  // would keep the released textures' names.
  t.CopyFramebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  t.CopyFramebuffer->RemoveDepthAttachment();
  t.CopyFramebuffer->AddDepthAttachment(t.VisibleDepth);
  // Depth only: no colour buffer to draw to (without this the framebuffer
  // is incomplete before GL 4.1).
  ostate->vtkglDrawBuffer(GL_NONE);
  t.Framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  t.Framebuffer->RemoveColorAttachments(2);
  t.Framebuffer->RemoveDepthAttachment();
  t.Framebuffer->AddColorAttachment(0, t.Accumulation);
  t.Framebuffer->AddColorAttachment(1, t.DepthCoverage);
  t.Framebuffer->AddDepthAttachment(t.Depth);
  t.Width = width;
  t.Height = height;
  t.DepthFormat = depthFormat;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatBlendHelper::CopySceneDepth(vtkOpenGLState* ostate,
  const int viewport[4],
  bool multisampled,
  int depthFormat,
  vtkObject* owner)
{
  Targets& t = *this->T;
  const int width = viewport[2], height = viewport[3];
  // The scene's depth, so that the actors drawn before hide the splats. A
  // depth blit needs the same depth (and stencil) format on both sides; the
  // targets were allocated in the scene's own format, so the blit works
  // whenever that format is one a texture can hold (ReadDepthFormat: not
  // -1); a multisampled scene is resolved by the blit when the viewport
  // starts at the origin, the only place its rectangle may be.
  const bool copied =
    depthFormat != -1 && (!multisampled || (viewport[0] == 0 && viewport[1] == 0));
  if (copied)
  {
    ostate->vtkglBlitFramebuffer(viewport[0],
      viewport[1],
      viewport[0] + width,
      viewport[1] + height,
      0,
      0,
      width,
      height,
      GL_DEPTH_BUFFER_BIT,
      GL_NEAREST);
  }
  if (!copied)
  {
    if (!t.Warned)
    {
      vtkWarningWithObjectMacro(owner,
        << "Cannot copy the scene's depth buffer; blended splats are drawn "
           "without occlusion by the actors drawn before them.");
      t.Warned = true;
    }
    ostate->vtkglDepthMask(GL_TRUE);
    ostate->vtkglClearDepth(1.0);
    ostate->vtkglClear(GL_DEPTH_BUFFER_BIT);
  }
}

//------------------------------------------------------------------------------
bool vtkAlgebraicSplatBlendHelper::Blend(vtkOpenGLState* ostate,
  int width,
  int height,
  int depthFormat,
  const Settings& settings,
  const Passes& passes)
{
  Targets& t = *this->T;
  // Blending: every hit in front of that depth, weighted. The shader reads
  // a copy of it, while the depth test drops fragments behind it unshaded.
  t.Framebuffer->Bind(GL_READ_FRAMEBUFFER);
  t.CopyFramebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  ostate->vtkglBlitFramebuffer(0,
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
  vtkShaderProgram* program = passes.UseBlending();
  if (!program)
  {
    return false;
  }
  program->SetUniformf(
    "splatBlendSharpness", static_cast<float>(settings.Blending ? settings.BlendSharpness : 0.0));
  t.VisibleDepth->Activate();
  program->SetUniformi("splatVisibleDepth", t.VisibleDepth->GetTextureUnit());
  // The hit is compared with the stored depth, which its format rounded.
  const double steps = depthFormat == vtkTextureObject::Fixed16
    ? 65535.0
    : (depthFormat == vtkTextureObject::Fixed24 || depthFormat == -2 ? 16777215.0 : 4194304.0);
  program->SetUniformf("splatDepthTolerance", static_cast<float>(1.0 / steps));
  // VTK 9.1's vtkOpenGLState does not cache polygon offset: it forwards the
  // enable and the queries, and glPolygonOffset has no wrapper; both are
  // restored below.
  GLboolean offsetWasOn = GL_FALSE;
  ostate->vtkglGetBooleanv(GL_POLYGON_OFFSET_FILL, &offsetWasOn);
  GLfloat offsetFactor = 0.0f, offsetUnits = 0.0f;
  ostate->vtkglGetFloatv(GL_POLYGON_OFFSET_FACTOR, &offsetFactor);
  ostate->vtkglGetFloatv(GL_POLYGON_OFFSET_UNITS, &offsetUnits);
  if (settings.AntiAliasing > 1)
  {
    // Silhouette pixels get their sub-pixel rays (the geometry shader grows
    // each splat's quad by half a pixel), which meet the splat's box nearer
    // than the centre's depth by up to half a pixel's depth slopes: pull the
    // quads' depth forward by a whole one, so that the early test stays
    // conservative for them too.
    const float margin[2] = { 1.0f / width, 1.0f / height };
    program->SetUniform2f("splatOutlineMargin", margin);
    ostate->vtkglEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(-1.0f, -1.0f);
  }
  ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  ostate->vtkglDepthFunc(GL_LEQUAL);
  ostate->vtkglDepthMask(GL_FALSE);
  ostate->vtkglEnable(GL_BLEND);
  // Per-target blending (sum for the colours, minimum for the depth and
  // coverage) has no vtkOpenGLState wrapper. The state's Pop re-applies only
  // what its own cache changed (VTK 9.2 on), so the blend state as it was
  // is put back on every target by hand after the draw: otherwise the
  // state's cache and GL disagree ("Error in cache state for
  // GL_BLEND_SRC_RGB" in ParaView) and later draws blend wrongly.
  GLint equation[2], func[4];
  glGetIntegerv(GL_BLEND_EQUATION_RGB, &equation[0]);
  glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &equation[1]);
  glGetIntegerv(GL_BLEND_SRC_RGB, &func[0]);
  glGetIntegerv(GL_BLEND_DST_RGB, &func[1]);
  glGetIntegerv(GL_BLEND_SRC_ALPHA, &func[2]);
  glGetIntegerv(GL_BLEND_DST_ALPHA, &func[3]);
  glBlendEquationi(0, GL_FUNC_ADD);
  glBlendFunci(0, GL_ONE, GL_ONE);
  glBlendEquationi(1, GL_MIN);
  glBlendFunci(1, GL_ONE, GL_ONE);
  passes.Draw();
  glBlendEquationSeparate(equation[0], equation[1]);
  glBlendFuncSeparate(func[0], func[1], func[2], func[3]);
  if (!offsetWasOn)
  {
    ostate->vtkglDisable(GL_POLYGON_OFFSET_FILL);
  }
  glPolygonOffset(offsetFactor, offsetUnits);
  t.VisibleDepth->Deactivate();
  return true;
}

//------------------------------------------------------------------------------
void vtkAlgebraicSplatBlendHelper::Composite(vtkOpenGLRenderWindow* renWin, vtkObject* owner)
{
  // Normalise and composite with the true depth.
  vtkOpenGLState* ostate = renWin->GetState();
  Targets& t = *this->T;
  const ScopedStatePush push(ostate);
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
    vtkErrorWithObjectMacro(owner, << "The splat compositing shader did not compile.");
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
}
