// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psMetaballFrame.h
 * @brief What the passes of vtkMetaballMapper share: the balls, the view and the images.
 *
 * The mapper uploads the balls (MetaballBalls), picks a ray caster that
 * casts them from a view (MetaballView) into images (MetaballImages), and
 * hands those to the shadow, shading and selection passes. Each pass is its
 * own class (vtkMetaballGPURayCaster, vtkMetaballCPURayCaster,
 * vtkMetaballShadowHelper, vtkMetaballSelectionHelper); these structs are
 * the data they all read, owned by the mapper. Private to
 * PointSurfaces::Rendering.
 */
#ifndef psMetaballFrame_h
#define psMetaballFrame_h

#include "psOpenGL.h" // before any GL header

#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkShaderStorageBuffer.h"
#include "vtkTextureObject.h"
#include "vtkType.h"

#include "psBallExtraction.h"

#include <algorithm>
#include <vector>

class vtkProperty;
class vtkUnsignedCharArray;
class vtkWindow;

namespace pointsurfaces
{
/**
 * The input's balls: in float on the GPU; in double as extracted and in
 * float on the host only when HostValid (the CPU ray caster and a selection
 * read those; vtkMetaballUploader sends the GPU's without them).
 */
struct MetaballBalls
{
  /** xyz relative to Shift and radius (0: unusable), per ball; colour (rgba8); strength. */
  vtkNew<vtkShaderStorageBuffer> Balls, Colors, Strengths;
  /** The same in host memory (the CPU ray caster reads these). */
  std::vector<float> HostBalls, HostStrengths;
  std::vector<unsigned int> HostColors;
  /** The balls as the field extracted them, in double (the selection reads these). */
  BallArrays Extracted;
  double Shift[3] = { 0.0, 0.0, 0.0 }; ///< subtracted from the centres before float
  vtkIdType Count = 0;                 ///< balls uploaded; 0 when the upload failed
  bool HasStrengths = false;
  bool ColorPerBall = true; ///< else Colors holds one colour for all
  bool HostValid = false;   ///< Extracted and the host arrays hold the uploaded balls
  double MinRadius = 1.0;   ///< the smallest usable radius

  /**
   * The balls of `set` in float, relative to Shift, into the host arrays;
   * an invalid ball (psMetaball's ValidBall, or a strength beyond float)
   * gets radius 0, which the grids skip. Sets MinRadius; returns how many
   * were invalid.
   */
  vtkIdType Convert(const MetaballSet& set);

  /** The n colours (rgba8): `mapped` when it has four components, else prop's diffuse colour. */
  void ConvertColors(vtkUnsignedCharArray* mapped, vtkProperty* prop, vtkIdType n);

  void ReleaseGraphicsResources(vtkWindow* win)
  {
    this->Balls->ReleaseGraphicsResources(win);
    this->Colors->ReleaseGraphicsResources(win);
    this->Strengths->ReleaseGraphicsResources(win);
    this->Count = 0;
    this->HostValid = false;
  }
};

/**
 * The view of a cast: the float balls (shifted) to view space, the
 * projection and its inverse (row-major), and what the balls and the mapper
 * were. Two casts with the Same view give the same hits.
 */
struct MetaballView
{
  double WorldToView[16] = {};
  double ViewToClip[16] = {};
  double ClipToView[16] = {};
  bool Parallel = false;
  int Width = 0, Height = 0;
  vtkMTimeType Upload = 0, Mapper = 0;

  bool Same(const MetaballView& o) const
  {
    return std::equal(this->WorldToView, this->WorldToView + 16, o.WorldToView) &&
      std::equal(this->ViewToClip, this->ViewToClip + 16, o.ViewToClip) &&
      this->Parallel == o.Parallel && this->Width == o.Width && this->Height == o.Height &&
      this->Upload == o.Upload && this->Mapper == o.Mapper;
  }
};

/**
 * The ray casters' output, per viewport pixel (rows from the bottom): colour
 * (rgba8, alpha 0 on a miss), view-space normal and view distance (rgba32f),
 * window depth (r32f).
 */
struct MetaballImages
{
  vtkNew<vtkTextureObject> Color, Normal, Depth;
  int Width = 0, Height = 0;

  /** Sized to the viewport (a no-op when it is). */
  void Resize(vtkOpenGLRenderWindow* renWin, int width, int height)
  {
    if (width == this->Width && height == this->Height)
    {
      return;
    }
    for (vtkTextureObject* t : { this->Color.Get(), this->Normal.Get(), this->Depth.Get() })
    {
      t->SetContext(renWin);
    }
    this->Color->Allocate2D(width, height, 4, VTK_UNSIGNED_CHAR);
    this->Normal->Allocate2D(width, height, 4, VTK_FLOAT);
    this->Depth->Allocate2D(width, height, 1, VTK_FLOAT);
    this->Width = width;
    this->Height = height;
  }

  void ReleaseGraphicsResources(vtkWindow* win)
  {
    this->Color->ReleaseGraphicsResources(win);
    this->Normal->ReleaseGraphicsResources(win);
    this->Depth->ReleaseGraphicsResources(win);
    this->Width = this->Height = 0;
  }
};

/** The mapper's settings that a cast reads. */
struct MetaballCastRequest
{
  MetaballView View;
  int TileSize = 16;
  int Slabs = 16;
  double StepScale = 0.1;
  int Bisections = 10;
  double LevelOfDetailPixels = 0.0; ///< the GPU caster's level of detail (0: none)
  double MemoryLimit = 0.0;         ///< bytes for the CPU caster; 0: the free physical memory
  MetaballKernel Kernel = MetaballKernel::Wyvill;
  double Threshold = 0.5;
  bool CollectStatistics = false;
};

// The composite passes' depth and blend state: depth-tested against the
// scene (LEQUAL, written), no blending; the previous state comes back when it
// goes out of scope. Only what is changed is saved, not Push and Pop: VTK
// 9.6's Pop binds again the buffers its cache holds, which may have been
// deleted since (by this mapper's shader rebuild or by another mapper).
struct CompositeDepthState
{
  vtkOpenGLState::ScopedglEnableDisable DepthTest;
  vtkOpenGLState::ScopedglEnableDisable Blend;
  vtkOpenGLState::ScopedglDepthFunc DepthFunc;
  vtkOpenGLState::ScopedglDepthMask DepthMask;

  explicit CompositeDepthState(vtkOpenGLState* ostate)
    : DepthTest(ostate, GL_DEPTH_TEST)
    , Blend(ostate, GL_BLEND)
    , DepthFunc(ostate)
    , DepthMask(ostate)
  {
    ostate->vtkglEnable(GL_DEPTH_TEST);
    ostate->vtkglDepthFunc(GL_LEQUAL);
    ostate->vtkglDepthMask(GL_TRUE);
    ostate->vtkglDisable(GL_BLEND);
  }
};

/** Fills a whole texture from the host (rows from the bottom). */
inline void UploadTexture(vtkTextureObject* texture,
  int width,
  int height,
  GLenum format,
  GLenum type,
  const void* data)
{
  texture->Bind();
  texture->GetContext()->GetState()->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, format, type, data);
  texture->Deactivate();
}

/**
 * Reads a whole texture back (rows from the bottom, 4-byte pixels or
 * larger, so that no row padding applies); false on a GL error of its own
 * (errors left pending by others are cleared first).
 */
inline bool ReadTexture(vtkTextureObject* texture, GLenum format, GLenum type, void* data)
{
  for (int k = 0; k < 16 && glGetError() != GL_NO_ERROR; ++k)
  {
  }
  texture->Bind();
  glGetTexImage(GL_TEXTURE_2D, 0, format, type, data);
  texture->Deactivate();
  return glGetError() == GL_NO_ERROR;
}

/** The rgba8 colour (as a little-endian uint) of `prop`'s diffuse colour, opaque. */
unsigned int PlainColor(vtkProperty* prop);

/** A row-major 4x4 matrix in float, for a uniform. */
inline void ToFloat(const double m[16], float out[16])
{
  for (int k = 0; k < 16; ++k)
  {
    out[k] = static_cast<float>(m[k]);
  }
}
} // namespace pointsurfaces

#endif
