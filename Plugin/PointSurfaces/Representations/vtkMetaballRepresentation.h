// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMetaballRepresentation
 * @brief   ParaView's "Metaballs" representation: particles as a blobby surface by vtkMetaballMapper.
 *
 * A surface representation whose mappers are vtkMetaballMapper (through
 * vtkPointSurfacesDelegatingMapper), so any point set (particles, atoms,
 * stars) shows as the iso-surface of its metaball field, ray-cast on the
 * GPU every frame and coloured through ParaView's colour map. The mapper's
 * knobs are forwarded: kernel, threshold, radius array or constant radius
 * and its scale, strength array, marching step and bisections, tile size
 * and slabs, and shadows. ParaView's decimated interaction LOD is
 * suppressed: the metaball surface of decimated points is another surface.
 *
 * Split across server ranks, each rank's balls gain the other ranks' balls
 * that reach them (vtkMetaballGhostBalls, between ParaView's geometry filter
 * and the delivery), so the ranks' surfaces blend across the cuts and depth
 * compositing gives the serial picture. The exchange runs in RequestData,
 * which ParaView executes on every rank. Where the view does not render
 * each rank's own piece (a client rendering locally what pvserver ranks
 * computed; tile and CAVE displays), the ghosts would count twice beside
 * their owners: there the mappers leave them out. Radii are taken in data
 * coordinates: an actor scale that differs between axes can make the
 * exchange miss balls near the cuts.
 */
#ifndef vtkMetaballRepresentation_h
#define vtkMetaballRepresentation_h

#include "PointSurfacesParaViewRepresentationsModule.h" // For export macro
#include "vtkGeometryRepresentationWithFaces.h"
#include "vtkMetaballField.h" // For the field
#include "vtkNew.h"           // For the field

class vtkMetaballGhostBalls;
class vtkMetaballMapper;

class POINTSURFACESPARAVIEWREPRESENTATIONS_EXPORT vtkMetaballRepresentation
  : public vtkGeometryRepresentationWithFaces
{
public:
  static vtkMetaballRepresentation* New();
  vtkTypeMacro(vtkMetaballRepresentation, vtkGeometryRepresentationWithFaces);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Forwarded to the field that both metaball mappers and the ghost
   * exchange share (see vtkMetaballField), or to both mappers (see
   * vtkMetaballMapper).
   */
  void SetMetaballKernel(int kernel);
  void SetMetaballThreshold(double threshold);
  void SetMetaballRadiusArray(const char* name);
  void SetMetaballRadius(double radius);
  void SetMetaballRadiusScale(double scale);
  void SetMetaballStrengthArray(const char* name);
  void SetMetaballDensityArray(const char* name);
  void SetMetaballRayCaster(int caster);
  void SetMetaballStepScale(double scale);
  void SetMetaballBisections(int count);
  void SetMetaballTileSize(int pixels);
  void SetMetaballSlabs(int count);
  void SetMetaballShadows(bool on);
  void SetMetaballMemoryLimit(vtkIdType kibibytes);
  void SetMetaballLevelOfDetailPixels(double pixels);
  ///@}

  void SetSuppressLOD(bool) override { this->Superclass::SetSuppressLOD(true); }

  /**
   * The surface is drawn opaque: an Opacity below 1 is kept at 1, with a
   * warning. (The mapper's own passes do not take part in ParaView's depth
   * peeling; drawn translucent, the surface broke into stripes and holes.)
   */
  void SetOpacity(double opacity) override;

  /**
   * The id arrays that selection reports through (ParaView's
   * "vtkOriginalPointIds" by default), handed to both mappers. The
   * superclass would cast its mapper to vtkCompositePolyDataMapper2 and
   * crash on these mappers when the user selects.
   */
  void SetArrayIdNames(const char* pointArray, const char* cellArray) override;

  /**
   * As the superclass, but the view must not move this data between ranks:
   * its ghost balls are made for this split (and ordered compositing is
   * never needed for it: the surface is opaque). Unless the view renders
   * each rank's piece where it is, the mappers skip the ghosts.
   */
  int ProcessViewRequest(vtkInformationRequestKey* request_type,
    vtkInformation* inInfo,
    vtkInformation* outInfo) override;

protected:
  vtkMetaballRepresentation();
  ~vtkMetaballRepresentation() override;

  /** The superclass's pipeline with the ghost exchange after its geometry filter. */
  void SetupDefaults() override;

  /** Opaque: no ordered compositing, whatever the colouring. */
  bool NeedsOrderedCompositing() override { return false; }

  vtkNew<vtkMetaballField> Field; // shared by both mappers and the ghost exchange
  vtkMetaballMapper* Balls[2];
  vtkMetaballGhostBalls* Ghosts;

private:
  vtkMetaballRepresentation(const vtkMetaballRepresentation&) = delete;
  void operator=(const vtkMetaballRepresentation&) = delete;
};

#endif
