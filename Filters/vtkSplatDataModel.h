// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSplatDataModel
 * @brief   Names and helpers of the splat data model (DESIGN.md section 3), shared by its producers and consumers.
 *
 * Splats are a vtkPolyData with one vertex per splat and the point arrays
 * named here. The fitter writes them, the error metric and the mappers read
 * them; keeping the names and the checks in one place keeps them in step.
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
  ///@}

  /** What GetOctree found. */
  enum OctreeStatus
  {
    NoOctree = 0,    ///< no octree arrays, or incomplete ones
    ValidOctree = 1, ///< the octree indexes the splats and holds them
    MovedSplats = 2, ///< the root's sphere does not hold the splats (moved after fitting)
    StaleIndex = 3   ///< the node ranges or levels do not index the splats (split, reordered)
  };

  /** One vertex cell per point of `pd`, replacing its verts. */
  static void AddVertexCells(vtkPolyData* pd);

  /**
   * The degree of a splat set (field data SplatDegree), or -1 when `pd` lacks
   * any part of the data model (arrays, components, tuple counts).
   */
  static int GetSplatDegree(vtkPolyData* pd);

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
