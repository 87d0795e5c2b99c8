// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psSplatOrientation.h
 * @brief Consistent orientation of splat normals fitted without input normals.
 *
 * A weighted plane's normal has no sign of its own: fitted from bare points,
 * neighbouring splats face either way, which shading hides (it is two-sided)
 * but back-face culling, normal colouring and every downstream filter that
 * reads SplatNormal do not. OrientSplats propagates one sign over each
 * connected part of the splats' k-nearest-neighbour graph along its minimum
 * spanning tree under the cost 1 - |n_i . n_j| (Hoppe et al., "Surface
 * reconstruction from unorganized points", 1992) plus |e . n_i| + |e . n_j|
 * for the edge's unit vector e, so that the sign passes between nearly
 * parallel normals along the surface first. Each part is seeded at its highest
 * splat (largest z), whose normal is made to point up. A part whose normals
 * nearly cancel (a closed surface) is then turned over as a whole when the
 * area-weighted sum of (x - c).n, three times its volume for outward
 * normals, says it faces inward: the highest splat can lie on the underside
 * of a thin tip (a wing's, on Lucy), where "up" is inward. Flipping a
 * splat turns its frame (n, t, b) into (-n, t, -b) and its polynomial into
 * g'(u, v) = -g(u, -v), so it describes the same surface.
 *
 * Where two sheets of the surface lie closer than the splats' spacing (a
 * thin plate, a fold of drapery), the graph joins them and their
 * antiparallel normals cost nothing by angle alone (Hoppe's known limit):
 * one sheet could end up facing inward. An edge between the sheets runs
 * along their normals, and the second term makes it dear, so that the sign
 * goes round by the rim instead (a closed 40 x 12 x 2 box at spacing 1: 98
 * of its 190 face splats faced inward by angle alone, none now; of Lucy's
 * splats, a third disagreed with the rest, and 1.4 % now point against her
 * mesh's outward normals). Two sheets that touch, with no rim between them
 * in the graph, can still be crossed: a fold's two walls, a wing against a
 * body, two parts a spacing apart, where the flux, a sum over the whole
 * part, outweighs the sheet that came out inward.
 *
 * So, on a closed part, what is seen from outside decides each sheet's
 * side: the discs are drawn into depth images from the 26 directions of a
 * cube's neighbours, and a splat seen from enough of them (at less than
 * about 80 degrees to its normal) that nine tenths of them, weighted by
 * |n.u|, find it facing them, or facing away, is a seed with that side. When any seed disagrees with the tree's result, the tree
 * grows again over the part from all seeds at once, so that each sheet
 * takes its sign from its own seeds and only the faces hidden from every
 * view (inside a narrow gap or fold) are reached across it. Of Lucy's
 * splats, 0.3 % then point inward at the defaults (1.4 % without), and at
 * most 3 % at any setting of s, degree and tolerance measured (up to 62 %
 * without); two spheres a spacing apart, the second of which the tree
 * turned wholly inward, come out outward. Open sheets (a range scan) are
 * seen from both sides and keep the seed's rule.
 *
 * The trees are minimum spanning trees of the graph's edges sorted once
 * by cost (Kruskal's algorithm); growing again from several seeds is the
 * same with the seeds joined into one node from the start.
 */
#ifndef psSplatOrientation_h
#define psSplatOrientation_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "psSplatFit.h"                 // For Splat

#include <vector> // For the splats

namespace pointsurfaces
{
/**
 * How large the flux of a part's normals must be, as a share of its largest
 * possible value, to decide which way is out.
 */
constexpr double OrientationDecisive = 0.1;
/**
 * A part whose area-weighted normals sum to more than this share of its
 * area is an open sheet, not a closed surface.
 */
constexpr double OrientationOpenSheet = 0.3;

/** Turn a splat over: the same surface, seen from its other side. */
POINTSURFACESFILTERS_EXPORT void FlipSplat(Splat& splat);

/**
 * Orient `splats` consistently, with `k` nearest neighbours per splat (by
 * origin) in the graph. Returns the number of splats flipped. `parts`, when
 * given, receives the number of connected parts (each with its own seed).
 * `radii`, when given (one per splat), are the discs' radii for the views
 * from outside; otherwise each splat's h stands in. `partOf`, when given,
 * receives each splat's part (0 .. parts - 1), the connected parts of the
 * graph that were oriented each from its own seed. Without `outside`, each
 * part only takes its seed's side along its tree: no flux and no views
 * decide a closed part's side (for a piece of a surface, whose side is
 * decided with the whole, as psSplatStream.h does: a piece of a closed
 * surface seen through its cut would be seen from inside).
 */
POINTSURFACESFILTERS_EXPORT long long OrientSplats(const std::vector<Splat*>& splats,
  int k = 8,
  long long* parts = nullptr,
  const std::vector<double>* radii = nullptr,
  std::vector<long long>* partOf = nullptr,
  bool outside = true);
} // namespace pointsurfaces

#endif
