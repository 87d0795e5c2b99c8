#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Per-frame cost and image error of vtkMetaballMapper against a sample-and-contour pipeline.

    bench_metaballs.py [INPUT ...] [--data DIR] [--out DIR] [--frames N] [--smoke]
                       [--grids N ...]

INPUT names a scene (default: all of them):

    scattered-10K, -100K, -1M  balls scattered in a cube (made by the script)
    halo           a dark-matter halo from an N-body run, radius 1.5 x spacing
    hyg-stars      the HYG star catalogue within 100 pc
    adk-solvated   adenylate kinase in water (PDB), radius 2 x van der Waals
    halo-sph       the halo as SPH gas, each particle's radius its smoothing
                   length from its 32 nearest neighbours (spread over 30x)
    gadget-gas     the gas of a Gadget-4 snapshot, radius its smoothing length
    water-gro      SPC water from a GROMACS run (IO/Testing/Data/gromacs)
    lammps-melt    a Lennard-Jones melt from a LAMMPS run (IO/Testing/Data/lammps)
    vesicle        a coarse-grained vesicle of two bead leaflets (made by the script)
    sds-monolayer  the SDS surfactant monolayers of LAMMPS's CG-SDK example
                   (from Debian's lammps-examples; skipped without it)

By default the data sets are the small ones a clone has: halo and halo-sph read
Testing/Data/halo_2k.xyz (the first 2 000 particles of the halo), adk-solvated
Testing/Data/adk_solvated_2k.pdb (its first 2 000 atoms), gadget-gas
IO/Testing/Data/gadget/lcdm_gas_z5_subset.hdf5; hyg-stars has no committed
sample and is skipped. --data DIR reads the full-size files from DIR (or a
folder one level below it) instead: halo_32k.xyz, hyg_stars.vtp,
adk_solvated.pdb and gadget4_lcdm_gas_z5.hdf5; a scene whose file is not there
is skipped, with one line on stderr. --smoke (what ctest runs): 2 000 scattered
balls, at most the first 2 000 of the halo, star, protein and Gadget files, one
96 x 96 size, one frame.

For each scene the same window draws:

- vtkMetaballMapper's CPU ray caster at its defaults (step scale 0.1, 10
  bisections) and at a coarser and a finer setting, and its GPU ray caster
  (compute shaders) at the defaults: grid build and ray cast times (the
  mapper's statistics), frame time, pairs; on the CPU path also the samples
  per ray and the share of empty (ray, voxel) visits;
- sphere imposters (vtkOpenGLSphereMapper) of the same balls at their lone
  iso-radius, the cheapest particle drawing there is: the frame-time yardstick;
- the reference: vtkMetaballMapper at step scale 0.02 and 20 bisections, or
  the next coarser step (0.05, 0.1) where a GL implementation cuts rays at
  0.02 (llvmpipe's loop limit; the mapper counts them): the CSV's
  reference column says which;
- the sample-and-contour peer: the same field (Wyvill's kernel, T = 0.5)
  sampled on an n^3 grid with numpy, vtkFlyingEdges3D at T, and an ordinary
  mapper; its dynamic-frame time is sampling + contouring + drawing;
- OpenVDB's particles-to-level-set plus mesh (vtkOpenVDBParticleMesher,
  Spheres: the union of each ball's lone iso-sphere) and the exact metaball
  field through an OpenVDB level set (MetaballField), meshed by
  volumeToMesh, at voxels of R/4 and R/8 (coarsened to at most 5e7 sampled
  voxels); its dynamic-frame time is level set + mesh + drawing;
- vtkOpenGLFluidMapper (screen-space particle surfaces), time only.

Each image's RMSE against the reference is recorded, so that the methods can
be compared at equal error. Particles move every frame in a dynamic scene,
so the peer's whole pipeline is part of its frame. CSV goes to stdout and
<out>/metaballs.csv, plots to <out>/metaballs_<input>.png.
"""
import argparse
import csv
import os
import sys
import time

import numpy as np

import pointsurfaces  # noqa: F401  (the EGL window factory)
from pointsurfaces import vtkMetaballMapper, vtkOpenVDBParticleMesher
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkImageData, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D
from vtkmodules.vtkIOChemistry import vtkPDBReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkVolume
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLFluidMapper, vtkOpenGLSphereMapper

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from bench_csv import IO_DATA, TEST_DATA, find_input, scatter_time_vs_rmse, skip  # noqa: E402
from bench_scene import OffscreenScene, material as shared_material  # noqa: E402
from metaball_kernels import wyvill  # noqa: E402

# The scenes read from files: (the committed file, the full-size file's name in --data).
FILES = {"halo": (os.path.join(TEST_DATA, "halo_2k.xyz"), "halo_32k.xyz"),
         "halo-sph": (os.path.join(TEST_DATA, "halo_2k.xyz"), "halo_32k.xyz"),
         "hyg-stars": (None, "hyg_stars.vtp"),
         "adk-solvated": (os.path.join(TEST_DATA, "adk_solvated_2k.pdb"), "adk_solvated.pdb"),
         "gadget-gas": (os.path.join(IO_DATA, "gadget", "lcdm_gas_z5_subset.hdf5"),
                        "gadget4_lcdm_gas_z5.hdf5")}
SCENES = ["scattered-10K", "scattered-100K", "scattered-1M", "halo", "hyg-stars",
          "adk-solvated", "halo-sph", "gadget-gas", "water-gro", "lammps-melt", "vesicle",
          "sds-monolayer"]

FIELDS = ["input", "balls", "size", "method", "setting", "frame_ms", "build_ms", "render_ms",
          "pairs", "incomplete", "rmse", "reference", "samples_per_ray", "empty_visits",
          "vs_imposters"]


def scattered(n, seed=1):
    rng = np.random.default_rng(seed)
    # Balls in a unit cube, radii so that neighbours overlap (about 8 per support).
    centres = rng.uniform(-1.0, 1.0, size=(n, 3))
    radius = 1.6 * (8.0 / n) ** (1.0 / 3.0)
    return centres, np.full(n, radius)


def input_file(name, data):
    """The file scene `name` reads: committed, or its full-size file in `data`; None
    (after one line on stderr) where there is none."""
    committed, full = FILES[name]
    if data:
        return find_input(data, full, name)
    if committed is None:
        skip(name, "no committed sample; --data DIR with %s reads it" % full)
    return committed


def load(name, smoke, data=None):
    """(centres, radii) of scene `name`, or (None, None) after one line on stderr saying
    why it is skipped."""
    path = input_file(name, data) if name in FILES else None
    if name in FILES and path is None:
        return None, None
    if name.startswith("scattered-"):
        n = {"10K": 10000, "100K": 100000, "1M": 1000000}[name.split("-")[1]]
        return scattered(n if not smoke else 2000)
    if name == "halo":
        xyz = np.loadtxt(path)
        if smoke:
            xyz = xyz[:2000]
        spacing = np.ptp(xyz, axis=0).max() / len(xyz) ** (1.0 / 3.0)
        return xyz, np.full(len(xyz), 1.5 * spacing)
    if name == "hyg-stars":
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(path)
        reader.Update()
        xyz = vtk_to_numpy(reader.GetOutput().GetPoints().GetData()).astype(np.float64)
        xyz = xyz[np.isfinite(xyz).all(axis=1)]
        if smoke:
            xyz = xyz[:2000]
        # Stars within 100 pc, where the catalogue is dense.
        near = np.linalg.norm(xyz, axis=1) < 100.0
        xyz = xyz[near]
        return xyz, np.full(len(xyz), 6.0)
    if name == "adk-solvated":
        reader = vtkPDBReader()
        reader.SetFileName(path)
        # vtkPDBReader leaves the water and ions of a simulation without a
        # radius; vtkAtomRadii gives them their element's.
        from pointsurfaces import vtkAtomRadii
        radii = vtkAtomRadii()
        radii.SetInputConnection(reader.GetOutputPort())
        radii.Update()
        out = radii.GetOutput()
        xyz = vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64)
        radius = vtk_to_numpy(out.GetPointData().GetArray("radius")).astype(np.float64)
        radius = 2.0 * (radius[:, 0] if radius.ndim > 1 else radius)  # vtkPDBReader: 3 components
        if smoke:
            xyz, radius = xyz[:2000], radius[:2000]
        return xyz, radius
    if name == "halo-sph":
        # SPH gas: the smoothing length from the 32 nearest neighbours
        # (Gadget's and SWIFT's neighbour counts are 32 to 64), as the radius.
        from scipy.spatial import cKDTree
        xyz = np.loadtxt(path)
        if smoke:
            xyz = xyz[:2000]
        distances, _ = cKDTree(xyz).query(xyz, k=33)
        return xyz, distances[:, 32]
    if name == "vesicle":
        # A coarse-grained vesicle, made here (no run of a CG force field is
        # at hand): two leaflets of lipid beads 0.8 nm apart on spheres of
        # radius 6 and 4.4 nm (Fibonacci lattices, 1 086 beads), beads of
        # radius 0.6 nm (support 1.2 nm), jittered by 0.1 nm.
        rng = np.random.default_rng(7)
        leaflets = []
        for radius in (6.0, 4.4):
            count = int(4.0 * np.pi * radius ** 2 / 0.64)
            k = np.arange(count) + 0.5
            polar = np.arccos(1.0 - 2.0 * k / count)
            azimuth = np.pi * (1.0 + 5.0 ** 0.5) * k
            leaflets.append(radius * np.column_stack([np.cos(azimuth) * np.sin(polar),
                                                      np.sin(azimuth) * np.sin(polar),
                                                      np.cos(polar)]))
        xyz = np.vstack(leaflets) + rng.normal(0.0, 0.1, size=(sum(map(len, leaflets)), 3))
        return xyz, np.full(len(xyz), 1.2)
    if name == "sds-monolayer":
        # A coarse-grained membrane from a real simulation: the two SDS
        # surfactant monolayers (SDK force field: SO4, CM and CT beads, and
        # the sodium ions) of LAMMPS's CG-SDK example, its equilibrated data
        # file as Debian's lammps-examples package ships it (not committed:
        # the scene is skipped without that package). The CG water is left
        # out, as a membrane's solvent is hidden. Support radius: the bead
        # type's LJ sigma (4.1 to 4.6 Angstrom), so that a lone bead shows
        # at about half of it.
        path = "/usr/share/lammps/examples/PACKAGES/cgsdk/sds-monolayer/data.sds.gz"
        if not os.path.exists(path):
            skip(name, "no %s (Debian's lammps-examples)" % path)
            return None, None
        import gzip
        sigma = {1: 4.321, 2: 4.506, 3: 4.585, 4: 4.371}
        xyz, radius = [], []
        with gzip.open(path, "rt") as f:
            section = None
            for line in f:
                words = line.split()
                if not words:
                    continue
                if words[0][0].isalpha():
                    section = words[0]
                    continue
                if section == "Atoms" and int(words[2]) in sigma:
                    xyz.append([float(v) for v in words[4:7]])
                    radius.append(sigma[int(words[2])])
        xyz, radius = np.array(xyz), np.array(radius)
        if smoke:
            xyz, radius = xyz[:2000], radius[:2000]
        return xyz, radius
    if name == "gadget-gas":
        # SPH gas of a Gadget-4 cosmological snapshot (z = 5), the radius its
        # smoothing length (Gadget's: the kernel's support).
        from pointsurfaces import vtkGadgetHDF5Reader
        reader = vtkGadgetHDF5Reader()
        reader.SetFileName(path)
        reader.Update()
        out = reader.GetOutput()
        if out.GetNumberOfPoints() == 0:
            skip(name, "no gas particles in " + path)
            return None, None
        xyz = vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64)
        h = vtk_to_numpy(out.GetPointData().GetArray("SmoothingLength")).astype(np.float64)
        if smoke:
            xyz, h = xyz[:2000], h[:2000]
        return xyz, h
    if name == "water-gro":
        # A sparse liquid: SPC water from a short GROMACS run (its first frame),
        # radii twice the reader's van der Waals radii (nm), as for the proteins.
        from pointsurfaces import vtkGromacsGroReader
        reader = vtkGromacsGroReader()
        reader.SetFileName(os.path.join(IO_DATA, "gromacs", "water_traj.gro"))
        reader.Update()
        out = reader.GetOutput()
        xyz = vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64)
        radius = vtk_to_numpy(out.GetPointData().GetArray("radius")).astype(np.float64)
        return xyz, 2.0 * radius
    if name == "lammps-melt":
        # A Lennard-Jones melt from a short LAMMPS run (its first frame): atoms
        # of diameter sigma, support radius sigma.
        from pointsurfaces import vtkLAMMPSDumpReader
        reader = vtkLAMMPSDumpReader()
        reader.SetFileName(os.path.join(IO_DATA, "lammps", "melt.lammpstrj"))
        reader.Update()
        xyz = vtk_to_numpy(reader.GetOutput().GetPoints().GetData()).astype(np.float64)
        return xyz, np.ones(len(xyz))
    raise ValueError(name)


def poly_of(centres, radii):
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(centres.astype(np.float64), deep=True))
    poly = vtkPolyData()
    poly.SetPoints(pts)
    r = numpy_to_vtk(radii.astype(np.float32), deep=True)
    r.SetName("Radius")
    poly.GetPointData().AddArray(r)
    return poly


def sample_field(centres, radii, n, threshold):
    """The Wyvill field on an n^3 grid over the balls' bounds (numpy splatting)."""
    lo = (centres - radii[:, None]).min(axis=0)
    hi = (centres + radii[:, None]).max(axis=0)
    h = (hi - lo).max() / (n - 1)
    dims = np.minimum(np.ceil((hi - lo) / h).astype(int) + 1, n)
    field = np.zeros(dims[::-1], dtype=np.float32)  # z, y, x
    base = np.floor((centres - lo) / h).astype(int)
    # Balls grouped by their reach in samples, so that small balls do not pay
    # for the largest (SPH radii spread over 30x).
    reaches = np.ceil(radii / h).astype(int)
    for reach in np.unique(reaches):
        group = reaches == reach
        offsets = range(-reach, reach + 1)
        for dz in offsets:
            for dy in offsets:
                for dx in offsets:
                    idx = base[group] + np.array([dx, dy, dz])
                    inside = ((idx >= 0) & (idx < dims)).all(axis=1)
                    if not inside.any():
                        continue
                    i = idx[inside]
                    c = centres[group][inside]
                    p = lo + i * h
                    d2 = ((p - c) ** 2).sum(axis=1)
                    x = d2 / radii[group][inside] ** 2
                    value = wyvill(x).astype(np.float32)
                    keep = value > 0
                    np.add.at(field, (i[keep, 2], i[keep, 1], i[keep, 0]), value[keep])
    image = vtkImageData()
    image.SetDimensions(*dims)
    image.SetOrigin(*lo)
    image.SetSpacing(h, h, h)
    image.GetPointData().SetScalars(numpy_to_vtk(field.ravel(), deep=True))
    return image


class Scene(OffscreenScene):
    """The shared scene, its camera fitted to each run's bounds."""

    def show(self, actor, bounds):
        super().show(actor)
        self.renderer.ResetCamera(bounds)
        self.renderer.ResetCameraClippingRange(bounds)

    def image(self):
        return self.pixels()

    def frame_ms(self, frames, before=None):
        return self.timed_frames(frames, before)[0]


def imposters(scene, poly, radii, bounds, frames):
    """Median dynamic frame of vtkOpenGLSphereMapper drawing every ball as a sphere of
    its lone iso-radius (Wyvill, T = 0.5)."""
    iso = numpy_to_vtk((LONE_ISO * radii).astype(np.float32), deep=True)
    iso.SetName("IsoRadius")
    spheres = vtkPolyData()
    spheres.SetPoints(poly.GetPoints())
    verts = vtkCellArray()  # the sphere mapper draws the vertices
    count = poly.GetNumberOfPoints()
    verts.SetData(numpy_to_vtkIdTypeArray(np.arange(count + 1, dtype=np.int64), deep=True),
                  numpy_to_vtkIdTypeArray(np.arange(count, dtype=np.int64), deep=True))
    spheres.SetVerts(verts)
    spheres.GetPointData().AddArray(iso)
    mapper = vtkOpenGLSphereMapper()
    mapper.SetInputData(spheres)
    mapper.SetScaleArray("IsoRadius")
    mapper.ScalarVisibilityOff()
    actor = material(vtkActor())
    actor.SetMapper(mapper)
    scene.show(actor, bounds)
    scene.image()
    return scene.frame_ms(frames, before=poly.GetPoints().Modified)


# The radius, in units of R, at which a lone ball reaches T = 0.5 (Wyvill).
LONE_ISO = 0.4737


def material(actor):
    return shared_material(actor, (0.85, 0.75, 0.6), ambient=0.0, diffuse=1.0, specular=0.2)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("inputs", nargs="*", default=SCENES, metavar="INPUT",
                        help="scenes to run (default: all): %s" % " ".join(SCENES))
    parser.add_argument("--data", metavar="DIR",
                        help="folder of the full-size files (%s); default: the committed "
                             "small ones" % ", ".join(sorted({f for _, f in FILES.values()})))
    parser.add_argument("--out", default="bench-results",
                        help="folder for metaballs.csv and metaballs_<input>.png")
    parser.add_argument("--frames", type=int, default=3, help="frames per time median")
    parser.add_argument("--smoke", action="store_true",
                        help="2 000 balls a scene, 96 x 96, one frame (what ctest runs)")
    parser.add_argument("--grids", type=int, nargs="+",
                        help="sample-and-contour grid sizes (default: 64 128 256, 64 128 over 50K)")
    args = parser.parse_args()
    for name in args.inputs:
        if name not in SCENES:
            parser.error("no scene %s (scenes: %s)" % (name, " ".join(SCENES)))
    os.makedirs(args.out, exist_ok=True)
    frames = 1 if args.smoke else args.frames
    rows = []
    for name in args.inputs:
        centres, radii = load(name, args.smoke, args.data)
        if centres is None:
            continue
        centres = np.asarray(centres, dtype=np.float64).reshape(-1, 3)
        radii = np.asarray(radii, dtype=np.float64).ravel()
        n = len(centres)
        # Two resolutions; 1M balls at the lower one only on llvmpipe.
        sizes = [(96, 96)] if args.smoke else ([(256, 256)] if n >= 500000 else [(256, 256), (512, 512)])
        poly = poly_of(centres, radii)
        bounds = list(np.ravel(np.column_stack([(centres - radii[:, None]).min(axis=0),
                                                (centres + radii[:, None]).max(axis=0)])))
        for size in sizes:
            scene = Scene(size)
            label = "%dx%d" % size

            def metaballs(step, bisections, caster=vtkMetaballMapper.CPU):
                mapper = vtkMetaballMapper()
                mapper.GetField().SetRadiusArrayName("Radius")  # poly_of's
                mapper.SetRayCaster(caster)
                mapper.SetInputDataObject(poly)
                mapper.SetStepScale(step)
                mapper.SetBisections(bisections)
                actor = material(vtkActor())
                actor.SetMapper(mapper)
                scene.show(actor, bounds)
                return mapper

            # The finest step whose rays all run to their end.
            for reference_step in (0.02, 0.05, 0.1):
                reference_mapper = metaballs(reference_step, 20, vtkMetaballMapper.CPU)
                reference_mapper.CollectStatisticsOn()  # this frame's cut rays, read at once
                reference = scene.image()
                if reference_mapper.GetNumberOfIncompleteRays() == 0:
                    break
                print("# %s %s: %d reference rays cut at step %g, trying a coarser step" % (
                    name, label, reference_mapper.GetNumberOfIncompleteRays(), reference_step))
            reference_setting = "step %g, 20 bisections" % reference_step

            # Sphere imposters at the lone iso-radius: the frame-time yardstick.
            imposter_ms = imposters(scene, poly, radii, bounds, frames)
            rows.append(dict(input=name, balls=n, size=label, method="sphere-imposters",
                             setting="lone iso-radius", frame_ms="%.1f" % imposter_ms,
                             build_ms="", render_ms="", pairs="", incomplete="", rmse=""))

            settings = [(vtkMetaballMapper.CPU, step, bisections)
                        for step, bisections in ((0.4, 4), (0.1, 10), (0.05, 10))]
            settings.append((vtkMetaballMapper.GPU, 0.1, 10))
            for caster, step, bisections in settings:
                mapper = metaballs(step, bisections, caster)
                image = scene.image()
                # A dynamic frame: the particles move (Modified), so they are uploaded again.
                ms = scene.frame_ms(frames, before=poly.GetPoints().Modified)
                cpu = caster == vtkMetaballMapper.CPU
                rays = max(mapper.GetNumberOfRays(), 1)
                visits = max(mapper.GetNumberOfVoxelVisits(), 1)
                rows.append(dict(input=name, balls=n, size=label,
                                 method="metaballs-cpu" if cpu else "metaballs-gpu",
                                 setting="step %g, %d bisections" % (step, bisections),
                                 frame_ms="%.1f" % ms,
                                 build_ms="%.2f" % mapper.GetGridBuildTime(),
                                 render_ms="%.1f" % mapper.GetRayCastTime(),
                                 pairs=mapper.GetNumberOfPairs(),
                                 incomplete=mapper.GetNumberOfIncompleteRays(),
                                 rmse="%.4f" % np.sqrt(np.mean((image - reference) ** 2)),
                                 samples_per_ray="%.2f" % ((mapper.GetNumberOfSamples() +
                                                            mapper.GetNumberOfBisectionSamples())
                                                           / rays) if cpu else "",
                                 empty_visits="%.3f" % (mapper.GetNumberOfEmptyVoxelVisits()
                                                        / visits) if cpu else "",
                                 vs_imposters="%.1f" % (ms / imposter_ms)))
            def mesh_row(method, setting, mesh, build_ms):
                """Draws a peer's mesh; its dynamic frame is building it plus drawing it."""
                surface = vtkPolyData()
                surface.ShallowCopy(mesh)
                mesh_mapper = vtkPolyDataMapper()
                mesh_mapper.SetInputData(surface)
                mesh_mapper.ScalarVisibilityOff()
                actor = material(vtkActor())
                actor.SetMapper(mesh_mapper)
                scene.show(actor, bounds)
                image = scene.image()
                draw_ms = scene.frame_ms(frames, before=surface.Modified)
                rows.append(dict(input=name, balls=n, size=label, method=method, setting=setting,
                                 frame_ms="%.1f" % (build_ms + draw_ms),
                                 build_ms="%.1f" % build_ms, render_ms="%.1f" % draw_ms,
                                 pairs=surface.GetNumberOfCells(), incomplete=0,
                                 rmse="%.4f" % np.sqrt(np.mean((image - reference) ** 2))))

            grids = (32,) if args.smoke else (args.grids or ((64, 128) if n > 50000 else (64, 128, 256)))
            for grid in grids:
                t0 = time.perf_counter()
                image_data = sample_field(centres, radii, grid, 0.5)
                sample_ms = 1000.0 * (time.perf_counter() - t0)
                contour = vtkFlyingEdges3D()
                contour.SetInputData(image_data)
                contour.SetValue(0, 0.5)
                contour.ComputeNormalsOn()
                t0 = time.perf_counter()
                contour.Update()
                contour_ms = 1000.0 * (time.perf_counter() - t0)
                mesh_row("sample+flying-edges", "%d^3 grid" % grid, contour.GetOutput(),
                         sample_ms + contour_ms)
            # OpenVDB: particles (or the field) to a level set, then a mesh.
            median = float(np.median(radii))
            budget = (4.0 / 3.0 * np.pi * float(np.sum(radii ** 3)) / 5e7) ** (1.0 / 3.0)
            fractions = (4,) if args.smoke else (4, 8)
            for method, label_method in ((vtkOpenVDBParticleMesher.Spheres, "openvdb-spheres"),
                                         (vtkOpenVDBParticleMesher.MetaballField, "openvdb-field")):
                for fraction in fractions:
                    voxel = max(median / fraction, budget)
                    mesher = vtkOpenVDBParticleMesher()
                    mesher.GetField().SetRadiusArrayName("Radius")  # poly_of's
                    mesher.SetInputData(poly)
                    mesher.SetMethod(method)
                    mesher.SetVoxelSize(voxel)
                    t0 = time.perf_counter()
                    mesher.Update()
                    build_ms = 1000.0 * (time.perf_counter() - t0)
                    mesh_row(label_method, "voxel R/%d" % round(median / voxel),
                             mesher.GetOutput(), build_ms)
            fluid = vtkOpenGLFluidMapper()
            fluid.SetInputData(poly)
            fluid.SetParticleRadius(float(np.median(radii)) * 0.5)
            volume = vtkVolume()  # the fluid mapper is a volume mapper
            volume.SetMapper(fluid)
            scene.renderer.RemoveAllViewProps()
            scene.renderer.AddVolume(volume)
            scene.renderer.ResetCamera(bounds)
            scene.image()
            ms = scene.frame_ms(frames, before=poly.GetPoints().Modified)
            rows.append(dict(input=name, balls=n, size=label, method="fluid-mapper",
                             setting="radius R/2", frame_ms="%.1f" % ms, build_ms="",
                             render_ms="", pairs="", incomplete="", rmse=""))
            for r in rows:
                if r["input"] == name and r["size"] == label:
                    r["reference"] = reference_setting
            reference_mapper.ReleaseGraphicsResources(scene.window)
            # Written after every input and size, so a long run keeps what it measured.
            with open(os.path.join(args.out, "metaballs.csv"), "w", newline="") as f:
                writer = csv.DictWriter(f, fieldnames=FIELDS)
                writer.writeheader()
                writer.writerows(rows)

    fields = FIELDS
    writer = csv.DictWriter(sys.stdout, fieldnames=fields)
    writer.writeheader()
    writer.writerows(rows)

    for name in dict.fromkeys(r["input"] for r in rows):
        scatter_time_vs_rmse(
            [r for r in rows if r["input"] == name],
            (("metaballs-cpu", "o"), ("metaballs-gpu", "D"), ("sample+flying-edges", "s"),
             ("openvdb-spheres", "^"), ("openvdb-field", "v")),
            os.path.join(args.out, "metaballs_%s.png" % name), name, "RMSE vs fine ray cast",
            xlabel="dynamic frame time (ms, median)",
            note=lambda r: "%s %s" % (r["size"], r["setting"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
