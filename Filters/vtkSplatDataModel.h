// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSplatDataModel
 * @brief   The splat data model: array names, checks and octree, shared by producers and readers.
 *
 * Splats are a vtkPolyData with one vertex (a point and a vertex cell) per
 * splat, at the splat's origin o. vtkAlgebraicSplatFitter and
 * vtkMultiResolutionSplatBuilder write them; vtkSplatErrorMetric and
 * vtkAlgebraicSplatMapper read them. Being plain VTK arrays, they pass
 * through every VTK filter and writer. Point arrays:
 *
 * - SplatNormal (3): the unit normal n of the splat's reference plane;
 * - SplatTangent (3): a unit tangent t in that plane; the second axis is
 *   b = n x t;
 * - SplatFeatureSize (1): the feature size h, the unit of the normalised
 *   frame;
 * - SplatCoefficients (3, 6, 10 or 15 for degree 1 to 4): the height
 *   polynomial g(u, v);
 * - SplatRadius (1): the disc radius R in world units;
 * - SplatLOD (1, int): the level where the splat first appears, 0 the
 *   coarsest.
 *
 * A point p has the normalised coordinates u = (p - o).t / h,
 * v = (p - o).b / h and height (p - o).n / h; the splat is the patch
 * height = g(u, v) over the disc u^2 + v^2 <= (R / h)^2. The coefficients
 * follow the monomials ordered by total degree, then by descending power of
 * u: 1, u, v, u^2, uv, v^2, u^3, u^2 v, u v^2, v^3, u^4, ... (a fit at a
 * lower degree leaves zeros in the higher ones). The normalised frame keeps
 * the coefficients of order 1 at any model scale or offset, which float32
 * on the GPU depends on. Input point arrays are carried over as
 * MLS-weighted averages.
 *
 * Field data: SplatDegree (the degree d), SplatNormalsOriented (1 when the
 * normals' signs are consistent; face culling needs it) and SplatLODQuality
 * (the quality factor s of each level, coarsest first). With an octree
 * (AddOctree), one tuple per node, nodes numbered depth first from the root
 * (node 0) with a node's children contiguous: OctreeNodeBounds (6),
 * OctreeNodeSphere (4, discs included), OctreeNodeChildren (first child,
 * child count), OctreeNodeRange (begin, end in point order) and
 * OctreeNodeLevelEnds (the end of each level's prefix of the range). The
 * points are then grouped by leaf and, within a leaf, sorted by level, so
 * that levels 0 to l of a leaf are the points from begin to LevelEnds[l].
 * A partly loaded set (vtkStreamingSplatMapper's pages) adds
 * OctreeNodePresentLevels: how many levels each node holds.
 *
 * GetSplatDegree checks that a data set carries the model; GetOctree reads
 * the octree back and refuses one that no longer fits its splats.
 */
#ifndef vtkSplatDataModel_h
#define vtkSplatDataModel_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "vtkObject.h"

#ifndef __VTK_WRAP__
#include "psOctree.h" // For the octree
#include <vector>     // For the levels' quality
#endif

class vtkPolyData;

class POINTSURFACESFILTERS_EXPORT vtkSplatDataModel : public vtkObject
{
public:
  static vtkSplatDataModel* New();
  vtkTypeMacro(vtkSplatDataModel, vtkObject);

  ///@{
  /** Array names of the data model. */
  static const char* NormalName() { return "SplatNormal"; }
  static const char* TangentName() { return "SplatTangent"; }
  static const char* FeatureSizeName() { return "SplatFeatureSize"; }
  static const char* CoefficientsName() { return "SplatCoefficients"; }
  static const char* RadiusName() { return "SplatRadius"; }
  /** Optional: largest deviation of a covered point from the patch, world units. */
  static const char* MaxDeviationName() { return "SplatMaxDeviation"; }
  /**
   * Optional: the error bound the splat was fitted and bounded to, world
   * units (vtkAlgebraicSplatFitter's MaximumDeviation in its ToleranceUnit,
   * for this splat's neighbourhood).
   */
  static const char* ToleranceName() { return "SplatTolerance"; }
  /**
   * Optional: the disc radius before it was bounded, world units. Level of
   * detail scales it with the finest level drawn, and never draws a disc
   * past SplatRadius.
   */
  static const char* NominalRadiusName() { return "SplatNominalRadius"; }
  static const char* LODName() { return "SplatLOD"; }
  static const char* DegreeName() { return "SplatDegree"; }
  /** Field data: 1 when the splats' normals are consistently oriented. */
  static const char* NormalsOrientedName() { return "SplatNormalsOriented"; }
  /** Field data: the quality factor s of each LOD level, coarsest first. */
  static const char* LODQualityName() { return "SplatLODQuality"; }
  ///@}

  ///@{
  /** Field data of the octree, one tuple per node (see AddOctree). */
  static const char* OctreeNodeBoundsName() { return "OctreeNodeBounds"; }
  static const char* OctreeNodeSphereName() { return "OctreeNodeSphere"; }
  static const char* OctreeNodeChildrenName() { return "OctreeNodeChildren"; }
  static const char* OctreeNodeRangeName() { return "OctreeNodeRange"; }
  static const char* OctreeNodeLevelEndsName() { return "OctreeNodeLevelEnds"; }
  /** Optional: the levels each node holds, of a partly loaded set (Octree::PresentLevels). */
  static const char* OctreeNodePresentLevelsName() { return "OctreeNodePresentLevels"; }
  ///@}

  /** What GetOctree found. */
  enum OctreeStatus
  {
    NoOctree = 0,    ///< no octree arrays, or incomplete ones
    ValidOctree = 1, ///< the octree indexes the splats and holds them
    MovedSplats = 2, ///< the root's sphere does not hold the splats (moved after fitting)
    StaleIndex =
      3 ///< the ranges or levels do not index the splats, or a leaf does not hold its own (split, reordered)
  };

  /** One vertex cell per point of `pd`, replacing its verts. */
  static void AddVertexCells(vtkPolyData* pd);

#ifndef __VTK_WRAP__
  /**
   * The field data of a splat set: its degree (DegreeName), the s of each
   * level (LODQualityName) and whether its normals are oriented
   * (NormalsOrientedName).
   */
  static void AddSetFields(vtkPolyData* pd,
    int degree,
    const std::vector<double>& levelQuality,
    bool oriented);
#endif

  /**
   * The degree of a splat set (field data SplatDegree), or -1 when `pd` lacks
   * any part of the data model (arrays, components, tuple counts).
   */
  static int GetSplatDegree(vtkPolyData* pd);

  /**
   * Bounds of the splats themselves: each disc of radius SplatRadius in its
   * plane, raised by the range its patch takes over the disc (the range
   * the splat mapper's geometry shader draws), so that ResetCamera frames
   * splats as it frames the points they were fitted to. Splats with
   * non-finite or non-positive sizes are left out. Returns false (and
   * uninitialised bounds) when `pd` lacks the data model or has no valid
   * splat.
   */
  static bool ComputeSplatBounds(vtkPolyData* pd, double bounds[6]);

#ifndef __VTK_WRAP__
  /**
   * Store `tree` in the field data of `pd`, whose points must already be in
   * the tree's order (grouped by leaf, and by level within a leaf):
   * OctreeNodeBounds (6), OctreeNodeSphere (4, the discs included),
   * OctreeNodeChildren (first child, child count), OctreeNodeRange (begin,
   * end) and OctreeNodeLevelEnds (one end per level).
   */
  static void AddOctree(vtkPolyData* pd, const pointsurfaces::Octree& tree);

  /**
   * Read the octree of `pd` back, with the s of each level (LODQualityName),
   * after checking that it still indexes and holds the splats: a filter
   * that moved, split, subset or reordered the points after fitting leaves
   * an octree that would cull or draw the wrong splats. Order is left empty.
   */
  static OctreeStatus GetOctree(vtkPolyData* pd,
    pointsurfaces::Octree& tree,
    std::vector<double>& levelQuality);
#endif

protected:
  vtkSplatDataModel() = default;
  ~vtkSplatDataModel() override = default;

private:
  vtkSplatDataModel(const vtkSplatDataModel&) = delete;
  void operator=(const vtkSplatDataModel&) = delete;
};

#endif
