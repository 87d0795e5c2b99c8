// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballSelectionHelper
 * @brief   Hardware selection of vtkMetaballMapper's balls.
 *
 * Each pass of a vtkHardwareSelector draws, for every hit pixel of the
 * selector's area, the pass's colour (the prop's, or the low or high 24 bits
 * of a ball id), unlit, at the hit's depth. The ball of a pixel is the one
 * whose kernel term dominates at the hit's surface point (double precision,
 * pointsurfaces::DominantBall), found through a perspective grid over the
 * area alone; the ids are worked out once per cast and area and reused by
 * every pass. Private to vtkMetaballMapper.
 */
#ifndef vtkMetaballSelectionHelper_h
#define vtkMetaballSelectionHelper_h

#include "PointSurfacesRenderingModule.h" // For export macro
#include "vtkNew.h"                       // For the members
#include "vtkObject.h"

#include "psMetaballFrame.h" // For the frame's data

#include <memory> // For the quad
#include <vector> // For the caches

class vtkDataArray;
class vtkHardwareSelector;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class POINTSURFACESRENDERING_EXPORT vtkMetaballSelectionHelper : public vtkObject
{
public:
  static vtkMetaballSelectionHelper* New();
  vtkTypeMacro(vtkMetaballSelectionHelper, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * One pass of `selector` over the hits of the cast `serial` (`view`,
   * `images`). (x0, y0): the viewport's origin in the window. `ids`: the
   * input's id array to report (ParaView's original ids), or null.
   */
  void Draw(vtkOpenGLRenderWindow* renWin,
    vtkHardwareSelector* selector,
    int x0,
    int y0,
    const pointsurfaces::MetaballView& view,
    unsigned long serial,
    const pointsurfaces::MetaballBalls& balls,
    const pointsurfaces::MetaballImages& images,
    vtkDataArray* ids);

  /** Forgets the cached ids (a new cast, or released resources). */
  void Invalidate() { this->Serial = 0; }

  void ReleaseGraphicsResources(vtkWindow* win);

protected:
  vtkMetaballSelectionHelper();
  ~vtkMetaballSelectionHelper() override;

private:
  /** The ball dominating each hit pixel of `area` (viewport pixels) into Ids. */
  void PickBalls(const int area[4],
    const pointsurfaces::MetaballView& view,
    const pointsurfaces::MetaballBalls& balls,
    const pointsurfaces::MetaballImages& images);
  /** The pass's colour per hit pixel of the area, into Pixels. */
  void PassColors(vtkHardwareSelector* selector,
    const int area[4],
    int width,
    int height,
    vtkDataArray* ids);
  /** The unlit composite program, compiled and ready; null on failure. */
  bool ReadyComposite(vtkOpenGLRenderWindow* renWin);

  std::vector<vtkIdType> Ids; // per pixel of Area: ball id, -1: hit without a ball, -2: no hit
  unsigned long Serial = 0;   // the cast Ids come from
  int Area[4] = { 0, 0, -1, -1 };
  std::vector<unsigned char> Pixels;
  vtkNew<vtkTextureObject> Image;
  std::unique_ptr<vtkOpenGLQuadHelper> Composite;

  vtkMetaballSelectionHelper(const vtkMetaballSelectionHelper&) = delete;
  void operator=(const vtkMetaballSelectionHelper&) = delete;
};

#endif
