# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Run the Python examples headless on small inputs: each must exit 0, print
its report and write a non-empty PNG that is not a blank background (the
sweep's PNG is its plot).

render_scan.py also reads scans written here: a bumpy sphere as OBJ, OFF and
binary STL (through OpenMesh) and MeshLab-style range maps as PLY (a camera
element before the vertices, flags and quality per vertex, a range_grid
element; ASCII and binary of both byte orders), which VTK 9.1's vtkPLYReader
misreads or crashes on. pointsurfaces.scanio must read those with the right
points, and every bad file (truncated, garbage, missing, an unknown
extension) must end render_scan.py with exit status 1 and one line on stderr
naming the file: no signal, no traceback."""
import os
import shutil
import struct
import subprocess
import sys

import numpy as np
import pointsurfaces
from pstesting import data_file, fail
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
EXAMPLES = os.path.join(ROOT, "Examples", "Python")
TEMP = os.path.abspath(os.environ.get("POINTSURFACES_TEMP_DIR", "."))
os.makedirs(TEMP, exist_ok=True)
SCANS = os.path.join(TEMP, "scans")  # the inputs written below, remade every run
shutil.rmtree(SCANS, ignore_errors=True)
os.makedirs(SCANS)

def temp(name):
    path = os.path.join(TEMP, name)
    if os.path.exists(path):
        os.remove(path)
    return path


def bumpy_sphere(rings=24, segments=48):
    """Points (n x 3, float32) and triangles (m x 3) of a sphere with bumps."""
    theta = np.linspace(0.0, np.pi, rings + 1)[1:-1]
    phi = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    t, p = [a.ravel() for a in np.meshgrid(theta, phi, indexing="ij")]
    t = np.concatenate(([0.0], t, [np.pi]))
    p = np.concatenate(([0.0], p, [0.0]))
    r = 1.0 + 0.15 * np.sin(3.0 * t) * np.cos(2.0 * p)
    xyz = np.column_stack((r * np.sin(t) * np.cos(p), r * np.sin(t) * np.sin(p), r * np.cos(t)))
    ring = lambda i, j: 1 + i * segments + j % segments  # noqa: E731
    south = len(xyz) - 1
    tris = []
    for j in range(segments):
        tris.append((0, ring(0, j), ring(0, j + 1)))
        tris.append((south, ring(rings - 2, j + 1), ring(rings - 2, j)))
        for i in range(rings - 2):
            tris.append((ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)))
            tris.append((ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)))
    return xyz.astype(np.float32), np.array(tris)


def write_obj(path, xyz, tris):
    with open(path, "w") as f:
        f.write("# bumpy sphere\n")
        f.writelines("v %.9g %.9g %.9g\n" % tuple(v) for v in xyz)
        f.writelines("f %d %d %d\n" % tuple(t + 1) for t in tris)


def write_off(path, xyz, tris):
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(xyz), len(tris)))
        f.writelines("%.9g %.9g %.9g\n" % tuple(v) for v in xyz)
        f.writelines("3 %d %d %d\n" % tuple(t) for t in tris)


def write_stl(path, xyz, tris):
    """Binary STL: 80-byte header, face count, per face a normal, 3 corners, 2 bytes."""
    corners = xyz[tris]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    record = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    faces = np.zeros(len(tris), dtype=record)
    faces["normal"], faces["corners"] = normals, corners
    with open(path, "wb") as f:
        f.write(b"bumpy sphere".ljust(80, b" ") + struct.pack("<I", len(tris)) + faces.tobytes())


# MeshLab's range-map PLY: a camera element first (float properties, the
# viewport as int), then the vertices with flags and quality, faces with
# flags, and a range_grid (one list a grid cell: the vertex there, or none).
CAMERA = ["view_px", "view_py", "view_pz", "x_axisx", "x_axisy", "x_axisz", "y_axisx",
          "y_axisy", "y_axisz", "z_axisx", "z_axisy", "z_axisz", "focal", "scalex", "scaley",
          "centerx", "centery", "viewportx", "viewporty", "k1", "k2", "k3", "k4"]


def colours(xyz):
    return (np.clip(np.abs(xyz), 0.0, 1.0) * 255).astype(np.uint8)


def write_range_map(path, form, xyz, tris):
    n, grid = len(xyz), 2 * len(xyz)  # every other grid cell holds a vertex
    types = ["int" if name.startswith("viewport") else "float" for name in CAMERA]
    header = ["ply", "format %s 1.0" % form, "comment MeshLab-style range map",
              "element camera 1"]
    header += ["property %s %s" % t for t in zip(types, CAMERA)]
    header += ["element vertex %d" % n, "property float x", "property float y",
               "property float z", "property uchar flags", "property float quality",
               "property uchar red", "property uchar green", "property uchar blue",
               "property uchar alpha"]
    if tris is not None:
        header += ["element face %d" % len(tris), "property uchar flags",
                   "property list uchar int vertex_indices"]
    header += ["element range_grid %d" % grid, "property list uchar int vertex_indices",
               "end_header"]
    camera = [0.0, 0.0, 5.0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 800.0, 0.01, 0.01, 320.0, 240.0,
              640, 480, 0.0, 0.0, 0.0, 0.0]
    quality = np.linspace(0.0, 1.0, n)
    colour = colours(xyz)
    cells = [[i // 2] if i % 2 == 0 else [] for i in range(grid)]
    with open(path, "wb") as f:
        f.write(("\n".join(header) + "\n").encode("ascii"))
        if form == "ascii":
            lines = [" ".join(str(int(v)) if t == "int" else "%g" % v
                              for t, v in zip(types, camera))]
            lines += ["%.9g %.9g %.9g 0 %g %d %d %d 255" % (*v, q, *c)
                      for v, q, c in zip(xyz, quality, colour)]
            if tris is not None:
                lines += ["0 3 %d %d %d" % tuple(t) for t in tris]
            lines += [" ".join(map(str, [len(c)] + c)) for c in cells]
            f.write(("\n".join(lines) + "\n").encode("ascii"))
            return
        e = "<" if form == "binary_little_endian" else ">"
        f.write(b"".join(struct.pack(e + ("i" if t == "int" else "f"), v)
                         for t, v in zip(types, camera)))
        f.write(b"".join(struct.pack(e + "3fBf4B", *v, 0, q, *c, 255)
                         for v, q, c in zip(xyz, quality, colour)))
        if tris is not None:
            f.write(b"".join(struct.pack(e + "2B3i", 0, 3, *t) for t in tris))
        f.write(b"".join(struct.pack(e + "B%di" % len(c), len(c), *c) for c in cells))


xyz, tris = bumpy_sphere()
scan = lambda name: os.path.join(SCANS, name)  # noqa: E731
write_obj(scan("sphere.obj"), xyz, tris)
write_off(scan("sphere.off"), xyz, tris)
write_stl(scan("sphere.stl"), xyz, tris)
range_maps = {"rangemap_ascii.ply": ("ascii", tris),
              "rangemap_le.ply": ("binary_little_endian", tris),
              "rangemap_be.ply": ("binary_big_endian", None)}
for name, (form, faces) in range_maps.items():
    write_range_map(scan(name), form, xyz, faces)

frames = os.path.join(TEMP, "animation")
# (script, arguments, text the report must hold, the image it must write)
runs = [
    ("render_scan.py", [data_file("bunny.vtp"), temp("render_scan.png"), "--size", "160"],
     "splats:", os.path.join(TEMP, "render_scan.png")),
    ("molecule_metaballs.py", [data_file("hemoglobin_chainA.pdb"), temp("molecule_metaballs.png"),
                               "--size", "160", "--shadows"],
     "atoms:        1079", os.path.join(TEMP, "molecule_metaballs.png")),
    ("particle_animation.py", ["--out", frames, "--frames", "3", "--particles", "2000",
                               "--size", "160", "--vdb"],
     "uploads:      3", os.path.join(frames, "frame_0002.png")),
    # A LAMMPS run's dump: its six snapshots are the frames.
    ("particle_animation.py", [os.path.join(ROOT, "IO", "Testing", "Data", "lammps",
                                            "melt.lammpstrj"),
                               "--out", os.path.join(TEMP, "lammps"), "--size", "120"],
     "frames:       6", os.path.join(TEMP, "lammps", "frame_0005.png")),
    # A GROMACS .xtc, its radii from a .gro of the same atoms: its four frames.
    ("particle_animation.py", [os.path.join(ROOT, "IO", "Testing", "Data", "gromacs",
                                            "water_p3.xtc"),
                               "--structure", os.path.join(ROOT, "IO", "Testing", "Data",
                                                           "gromacs", "water_traj.gro"),
                               "--out", os.path.join(TEMP, "xtc"), "--size", "120"],
     "frames:       4", os.path.join(TEMP, "xtc", "frame_0003.png")),
    ("speed_accuracy_sweep.py", [data_file("hemoglobin_chainA.pdb"), temp("sweep.png"),
                                 "--size", "96", "--steps", "0.4,0.1", "--bisections", "0,5"],
     "sweep:        4 settings", os.path.join(TEMP, "sweep.png")),
]
# A splat file drawn within a budget, its pages loaded by a thread (the Bunny's, made by the script).
if pointsurfaces.OPTIONAL_MODULES.get("RenderingHDF5"):
    runs.append(("view_splat_file.py", ["--png", temp("view_splat_file.png"), "--size", "120",
                                        "--orbit", "3", "--budget", "0.3"],
                 "resident:", os.path.join(TEMP, "view_splat_file.png")))
# Meshes through OpenMesh, and the range map that crashes vtkPLYReader (binary, with faces).
for name in ("sphere.obj", "sphere.off", "sphere.stl", "rangemap_le.ply"):
    out = os.path.join(SCANS, os.path.splitext(name)[0] + "_" + name[-3:] + ".png")
    runs.append(("render_scan.py", [scan(name), out, "--size", "96"],
                 "points:       %d" % len(xyz), out))
for script, arguments, expected, out in runs:
    if os.path.exists(out):
        os.remove(out)
    args = [sys.executable, os.path.join(EXAMPLES, script)] + arguments
    result = subprocess.run(args, capture_output=True, text=True, timeout=600, cwd=TEMP)
    if result.returncode != 0 or expected not in result.stdout:
        fail("%s failed (%d):\n%s\n%s" % (script, result.returncode, result.stdout, result.stderr))
    reader = vtkPNGReader()
    reader.SetFileName(out)
    reader.Update()
    pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())
    if pixels.size == 0 or (pixels.max(axis=0) - pixels.min(axis=0)).max() < 50:
        fail("%s wrote a blank image" % script)
    print("%s: %s" % (script, result.stdout.splitlines()[0]))
# The animation's level sets are OpenVDB files that its reader side accepts as VDB.
from pointsurfaces.scanio import ScanReadError, read_scan  # noqa: E402
if not pointsurfaces.vtkOpenVDBPointsReader.CanReadFile(os.path.join(frames, "frame_0002.vdb")):
    fail("particle_animation.py --vdb wrote no OpenVDB file")

# The meshes through OpenMesh: every vertex and face; STL has no vertex
# normals or colours (OpenMesh leaves uninitialised ones behind).
for name in ("sphere.obj", "sphere.off", "sphere.stl"):
    poly = read_scan(scan(name))
    points = vtk_to_numpy(poly.GetPoints().GetData())
    if name.endswith(".stl"):  # OpenMesh merges the corners in its own order
        points = points[np.lexsort(points.T)]
        written = xyz[np.lexsort(xyz.T)]
    else:
        written = xyz
    if not np.array_equal(points, written) or poly.GetNumberOfPolys() != len(tris):
        fail("%s: %d points and %d faces, not the %d and %d written"
             % (name, len(points), poly.GetNumberOfPolys(), len(xyz), len(tris)))
    if name.endswith(".stl") and (poly.GetPointData().GetNumberOfArrays()
                                  or poly.GetCellData().GetNumberOfArrays()):
        fail("%s: arrays that STL does not have" % name)

# The range maps: every vertex in place (past the camera), faces, colours and
# the per-vertex properties as arrays; the range grid skipped.
for name, (form, faces) in range_maps.items():
    poly = read_scan(scan(name))
    points = vtk_to_numpy(poly.GetPoints().GetData())
    if poly.GetNumberOfPoints() != len(xyz) or not np.array_equal(points, xyz):
        fail("%s: %d points, not the %d written" % (name, poly.GetNumberOfPoints(), len(xyz)))
    if poly.GetNumberOfPolys() != (0 if faces is None else len(tris)):
        fail("%s: %d faces" % (name, poly.GetNumberOfPolys()))
    rgba = vtk_to_numpy(poly.GetPointData().GetScalars())
    if rgba.shape != (len(xyz), 4) or not np.array_equal(rgba[:, :3], colours(xyz)):
        fail("%s: wrong colours" % name)
    for array in ("flags", "quality"):
        if poly.GetPointData().GetArray(array) is None:
            fail("%s: no %s array" % (name, array))
    print("%s: %d points, %d faces" % (name, poly.GetNumberOfPoints(), poly.GetNumberOfPolys()))

# Bad files: exit status 1 (not a signal), one line on stderr naming the file.
with open(scan("rangemap_ascii.ply"), "rb") as f:
    text = f.read()
with open(scan("rangemap_le.ply"), "rb") as f:
    binary = f.read()
bad = {"truncated_ascii.ply": text[:len(text) // 2],        # inside the vertices
       "truncated_binary.ply": binary[:len(binary) - 8000]}  # inside the faces
garbage = np.random.default_rng(13).integers(0, 256, 4096, dtype=np.uint8).tobytes()
for ext in ("ply", "obj", "off", "stl", "vtp", "pcd", "xyz"):
    bad["garbage." + ext] = garbage
bad["scan.unknown"] = text
for name, content in bad.items():
    with open(scan(name), "wb") as f:
        f.write(content)
cases = [scan(name) for name in bad] + [scan("missing.ply")]
for path in cases:
    if path.endswith(".ply") and os.path.exists(path):
        try:
            read_scan(path)
            fail("read_scan accepted %s" % path)
        except ScanReadError as e:
            if path not in str(e):
                fail("read_scan's error does not name %s: %s" % (path, e))
    out = temp("bad_scan.png")
    result = subprocess.run([sys.executable, os.path.join(EXAMPLES, "render_scan.py"), path, out],
                            capture_output=True, text=True, timeout=300)
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    if (result.returncode != 1 or len(lines) != 1 or path not in lines[0]
            or os.path.exists(out)):
        fail("render_scan.py %s: exit status %d (want 1), stderr:\n%s"
             % (path, result.returncode, result.stderr))
    print("%s: %s" % (os.path.basename(path), lines[0]))
print("TestPythonExamples: passed")
