#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""A close look at one part of a scan: its mesh and its splats from the same close camera,
with that view's masked SSIM, masked RMSE and coverage IoU (as bench_splat_quality.py
scores its whole-model views) and the diagnostic picture mesh | splats | difference.

    closeup_splats.py MODEL.ply OUT.png [--focus FX FY FZ] [--distance D]
                      [--azimuth A] [--elevation E] [--size N]
                      [--fitter-option NAME VALUE] [--no-blend]

The whole-model views of bench_splat_quality.py are 512 pixels for a whole statue: a
flake a few splats wide covers a pixel or two there. A close camera shows it. FX FY FZ
place the focal point as fractions of the mesh's bounding box (0.5 0.5 0.5: its centre),
D is the camera's distance in mesh diagonals, A and E turn it about the model's up axis
(z for horse and lucy, else y) from the front, in degrees. Prints one CSV row.
"""
import argparse
import math
import os
import sys

import pointsurfaces

import bench_csv
import bench_splat_quality as quality


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("model", help="a mesh with triangles, .ply or .vtp")
    parser.add_argument("output", help="the diagnostic picture (PNG)")
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

    mesh = quality.load_mesh(args.model)
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
    splats = quality.splat_actor(fitter.GetOutput())
    if args.no_blend:
        splats.GetMapper().SetBlending(False)
    scene.show(splats)
    image = scene.image(state)
    row = quality.score_images(reference, image)
    row.update(model=name, splats=fitter.GetOutput().GetNumberOfPoints(),
               options=" ".join("%s=%s" % o for o in options), blending=not args.no_blend)
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    quality.write_diagnostic(args.output, reference, image)
    bench_csv.write_rows(os.devnull, [row])
    return 0


if __name__ == "__main__":
    sys.exit(main())
