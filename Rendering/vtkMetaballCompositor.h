// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballCompositor
 * @brief   Shades vtkMetaballMapper's ray-cast images into the scene.
 *
 * A full-screen pass (vtkMetaballCompositeFS.glsl through
 * vtkOpenGLQuadHelper) that lights each hit pixel with the renderer's
 * lights, as VTK's mappers do (vtkOpenGLRenderer's lighting declarations
 * and uniforms, one light call per light compiled in, rebuilt when the
 * lighting changes), darkens it by the shadow image, and writes it with the
 * hit's true depth, depth-tested against the rest of the scene. Private to
 * vtkMetaballMapper.
 */
#ifndef vtkMetaballCompositor_h
#define vtkMetaballCompositor_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkObject.h"

#include "psMetaballFrame.h" // For the frame's data

#include <memory> // For the quad

class vtkOpenGLQuadHelper;
class vtkProperty;
class vtkRenderer;
class vtkTextureObject;
class vtkWindow;

class POINTSURFACESRENDERING_EXPORT vtkMetaballCompositor : public vtkObject
{
public:
  static vtkMetaballCompositor* New();
  vtkTypeMacro(vtkMetaballCompositor, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Draws the images of the cast `view` with the material `prop` and the
   * renderer's lights; `shadows` (null: none) blocks the first four lights.
   * False, with an error reported, when the shader is unusable.
   */
  bool Draw(vtkRenderer* ren,
    vtkProperty* prop,
    const pointsurfaces::MetaballView& view,
    const pointsurfaces::MetaballImages& images,
    vtkTextureObject* shadows);

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkMetaballCompositor();
  ~vtkMetaballCompositor() override;

private:
  /** The quad's program for this lighting, built or readied; false on failure. */
  bool Ready(vtkRenderer* ren, int complexity, int lights);

  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
  int Lighting = -1; // the lighting complexity and light count the quad was built for
  int Lights = -1;

  vtkMetaballCompositor(const vtkMetaballCompositor&) = delete;
  void operator=(const vtkMetaballCompositor&) = delete;
};

#endif
