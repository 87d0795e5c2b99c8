#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""A close look at one part of a scan: its mesh and its splats from the same close camera,
with that view's masked SSIM, masked RMSE and coverage IoU (as bench_splat_quality.py
scores its whole-model views) and the diagnostic picture mesh | splats | difference.

    closeup_splats.py [MODEL] [OUT.png] [--focus FX FY FZ] [--distance D]
                      [--azimuth A] [--elevation E] [--size N]
                      [--fitter-option NAME VALUE] [--no-blend]

The whole-model views of bench_splat_quality.py are 512 pixels for a whole statue: a
flake a few splats wide covers a pixel or two there. A close camera shows it. FX FY FZ
place the focal point as fractions of the mesh's bounding box (0.5 0.5 0.5: its centre),
D is the camera's distance in mesh diagonals, A and E turn it about the model's up axis
(z for horse and lucy, else y) from the front, in degrees. Prints one CSV row.

Flakes, counted: besides the image scores, the row holds flake_pixels, the pixels where
the splats' depth lies more than one point spacing (the mesh's mean edge length) in front
of the mesh's, both covered: a patch that stands off the surface toward the viewer, such
as a disc hanging over a fold. flake_fraction is their share of the mesh's pixels. They
are orange in the difference panel.
"""
import argparse
import math
import os
import sys

import numpy as np
import pointsurfaces
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkFloatArray

import bench_csv
import bench_splat_quality as quality


def view_depth(scene, state):
    """Depth along the view axis of each pixel of the last render (rows bottom-up; inf where
    nothing was drawn), from the depth buffer and the state's perspective clipping range."""
    w, h = scene.size
    z = vtkFloatArray()
    scene.window.GetZbufferData(0, 0, w - 1, h - 1, z)
    z = vtk_to_numpy(z).reshape(h, w).astype(np.float64)
    near, far = state["clip"]
    ndc = 2.0 * z - 1.0
    with np.errstate(divide="ignore"):
        depth = 2.0 * near * far / (far + near - ndc * (far - near))
    depth[z >= 1.0] = np.inf
    return depth


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("model", nargs="?", default=quality.BUNNY,
                        help="a mesh with triangles, any file pointsurfaces.scanio reads "
                             "(default: Testing/Data/bunny.vtp)")
    parser.add_argument("output", nargs="?", default="closeup.png",
                        help="the diagnostic picture (default: closeup.png)")
    parser.add_argument("--focus", nargs=3, type=float, default=[0.5, 0.5, 0.5],
                        metavar=("FX", "FY", "FZ"))
    parser.add_argument("--distance", type=float, default=0.3, help="in mesh diagonals")
    parser.add_argument("--azimuth", type=float, default=0.0)
    parser.add_argument("--elevation", type=float, default=0.0)
    parser.add_argument("--size", type=int, default=400)
    parser.add_argument("--fitter-option", nargs=2, action="append", default=[],
                        metavar=("NAME", "VALUE"),
                        help="call the fitter's SetNAME(VALUE) (a number); the defaults otherwise")
    parser.add_argument("--no-blend", action="store_true", help="opaque splats, one pass")
    args = parser.parse_args()
    options = bench_csv.fitter_options(parser, args.fitter_option,
                                       pointsurfaces.vtkAlgebraicSplatFitter)

    try:
        mesh = quality.load_mesh(args.model)
    except quality.ScanReadError as e:
        sys.exit("closeup_splats.py: %s" % e)
    if mesh.GetNumberOfPolys() == 0:
        sys.exit("closeup_splats.py: %s has no triangles" % args.model)
    fitter = pointsurfaces.vtkAlgebraicSplatFitter()
    fitter.SetInputData(quality.scan_of(mesh))
    for name, value in options:
        getattr(fitter, "Set" + name)(value)
    fitter.Update()

    name = os.path.basename(args.model).split(".")[0]
    up_axis = next((axis for prefix, axis in quality.UP_AXIS.items() if name.startswith(prefix)),
                   "y")
    b = mesh.GetBounds()
    focal = [b[2 * i] + f * (b[2 * i + 1] - b[2 * i]) for i, f in enumerate(args.focus)]
    a, e = math.radians(args.azimuth), math.radians(args.elevation)
    if up_axis == "z":
        up, direction = (0, 0, 1), (math.cos(e) * math.sin(a), -math.cos(e) * math.cos(a),
                                    math.sin(e))
    else:
        up, direction = (0, 1, 0), (math.cos(e) * math.sin(a), math.sin(e),
                                    math.cos(e) * math.cos(a))
    reach = args.distance * mesh.GetLength()
    state = dict(position=[focal[i] + reach * direction[i] for i in range(3)], focal=focal,
                 up=up, angle=30.0, clip=(0.01 * reach, reach + mesh.GetLength()))

    scene = quality.Scene((args.size, args.size))
    scene.show(quality.mesh_actor(mesh))
    reference = scene.image(state)
    reference_depth = view_depth(scene, state)
    splats = quality.splat_actor(fitter.GetOutput())
    if args.no_blend:
        splats.GetMapper().SetBlending(False)
    scene.show(splats)
    image = scene.image(state)
    splat_depth = view_depth(scene, state)
    both = np.isfinite(reference_depth) & np.isfinite(splat_depth)
    flakes = np.zeros_like(both)
    flakes[both] = reference_depth[both] - splat_depth[both] > quality.mean_edge_length(mesh)
    row = quality.score_images(reference, image)
    row.update(flake_pixels=int(flakes.sum()),
               flake_fraction=float(flakes.sum()) / max(1, row["covered_reference"]))
    row.update(model=name, splats=fitter.GetOutput().GetNumberOfPoints(),
               options=" ".join("%s=%s" % o for o in options), blending=not args.no_blend)
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    quality.write_diagnostic(args.output, reference, image, flakes)
    bench_csv.write_rows(os.devnull, [row])
    return 0


if __name__ == "__main__":
    sys.exit(main())
