# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Read a scan into a vtkPolyData, with one clear error for a bad file.

::

    from pointsurfaces.scanio import ScanReadError, read_scan
    try:
        poly = read_scan("scan.ply")
    except ScanReadError as e:
        sys.exit(str(e))             # one line that names the file

==========================  ==============================================
``.ply``                    pointsurfaces.vtkPLYScanReader, see below
``.vtp``                    VTK's vtkXMLPolyDataReader
``.pcd``                    pointsurfaces.vtkPCDReader (PCL)
``.obj .off .om .stl``      pointsurfaces.vtkOpenMeshReader (OpenMesh)
``.xyz``                    x y z per line, further columns ignored, lines
                            with fewer than three words and ``#`` lines skipped
==========================  ==============================================

A missing, empty, truncated or damaged file, or an extension not listed,
raises ScanReadError, whose text is one line naming the file; errors that
VTK's readers report are collected, not printed, and the first one becomes
that line. Their warnings, and this module's own (points with NaN or
infinite coordinates are dropped, with the cells that use them), go to
``warn``: one line each on stderr by default.

PLY is read by this project's vtkPLYScanReader (C++, IO/vtkPLYScanReader.h)
rather than by VTK 9.1's vtkPLYReader, which does not step over elements
other than ``vertex`` and ``face``: with any element before ``vertex``
(MeshLab's range maps start with a ``camera``) it takes the camera's
numbers for vertices, and it crashes (SIGSEGV or SIGABRT) on such a binary
file that also has faces, on a truncated file, on face indices out of
range, on a vertex without ``z``, and hangs on a huge count in a small
file. OpenMesh 9's PLY reader does no better (it refuses binary files with
an element it does not know, such as ``range_grid``, accepts a truncated
ASCII file, and aborts on a huge count). vtkPLYScanReader parses the
header, walks every element by its declared property types (scalars and
lists, ASCII and binary of either byte order), checks each against the
file's size before it allocates anything, and keeps the ``vertex`` element
(x, y, z; nx, ny, nz as "Normals"; red, green, blue [, alpha] as the "RGB"
scalars; every other scalar property as a point array of its own name and
type) and the ``face`` element's ``vertex_indices`` as polygons (faces
with fewer than three corners left out, with a warning). Other elements
(camera, range_grid, edge, material ...) are skipped. It leaves out points
with NaN or infinite coordinates itself, with the same warning.
"""
import importlib
import os
import re
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_ID_TYPE
from vtkmodules.vtkCommonCore import (vtkLogger, vtkOutputWindow, vtkPoints,
                                      vtkStringOutputWindow)
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkDataSetAttributes, vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from . import PointSurfacesIO as _io

__all__ = ["EXTENSIONS", "ScanReadError", "read_ply", "read_scan"]

#: The extensions read_scan() accepts, lower case.
EXTENSIONS = (".ply", ".vtp", ".pcd", ".xyz", ".obj", ".off", ".om", ".stl")


class ScanReadError(Exception):
    """A scan that cannot be read; str() is one line that names the file."""


def read_scan(path, warn=None):
    """Read a scan (see the module's table) into a new vtkPolyData.

    Raises ScanReadError for a file that cannot be read or holds no points.
    ``warn`` receives each warning as one line (default: printed to stderr).
    """
    path = os.fspath(path)
    warnings = []  # passed on only when the file can be read: a bad file gets one line
    ext = os.path.splitext(path)[1].lower()
    if ext not in EXTENSIONS:
        raise ScanReadError("%s: cannot read %s files (readable: %s)"
                            % (path, ext or "extension-less", " ".join(EXTENSIONS)))
    if not os.path.exists(path):
        raise ScanReadError("%s: no such file" % path)
    if not os.path.isfile(path):
        raise ScanReadError("%s: not a regular file" % path)
    try:
        with open(path, "rb") as f:
            if not f.read(1):
                raise ScanReadError("%s: the file is empty" % path)
        if ext == ".ply":
            poly = read_ply(path, warnings.append)
        elif ext == ".xyz":
            poly = _read_xyz(path)
        elif ext == ".vtp":
            poly = _read_vtk(vtkXMLPolyDataReader, path, warnings.append)
        elif ext == ".pcd":
            poly = _read_vtk(_optional_reader(path, "IOPCL", "vtkPCDReader"), path,
                             warnings.append)
        else:
            poly = _read_vtk(_optional_reader(path, "IOOpenMesh", "vtkOpenMeshReader"), path,
                             warnings.append)
    except OSError as e:
        raise ScanReadError("%s: %s" % (path, e.strerror or e)) from None
    except MemoryError:
        raise ScanReadError("%s: too large to read into memory" % path) from None
    poly = _drop_nonfinite(poly, path, warnings.append)
    if poly.GetNumberOfPoints() == 0:
        raise ScanReadError("%s: no points" % path)
    for line in warnings:
        (warn or _print_warning)(line)
    return poly


def _optional_reader(path, module, name):
    """The reader class `name` of the optional module PointSurfaces::`module`."""
    try:
        return getattr(importlib.import_module("pointsurfaces.PointSurfaces" + module), name)
    except (ImportError, AttributeError):
        raise ScanReadError("%s: this build has no %s (PointSurfaces::%s was not built: its "
                            "library was not found, or its POINTSURFACES_USE_ option is off)"
                            % (path, name, module)) from None


def _print_warning(line):
    print("warning: " + line, file=sys.stderr)


# --- VTK's readers -----------------------------------------------------------

# How vtkOutputWindow receives a message: a header line, the text, a blank line.
_VTK_MESSAGE = re.compile(
    r"^(ERROR|Warning|Generic Warning): In [^\n]*, line \d+\n(.*?)(?:\n\n|\Z)", re.S | re.M)


def _read_vtk(reader_class, path, warn):
    """Run a VTK reader with its messages collected instead of printed."""
    reader = reader_class()
    reader.SetFileName(path)
    window = vtkStringOutputWindow()
    previous = vtkOutputWindow.GetInstance()
    verbosity = vtkLogger.GetCurrentVerbosityCutoff()
    vtkOutputWindow.SetInstance(window)
    vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)
    try:
        reader.Update()
    finally:
        vtkOutputWindow.SetInstance(previous)
        vtkLogger.SetStderrVerbosity(verbosity)
    errors, warnings = [], []
    for kind, text in _VTK_MESSAGE.findall(window.GetOutput()):
        # "vtkSomeClass (0x1234): what happened\n(details)": keep what happened.
        text = re.sub(r"^\w+ \(0x[0-9a-fA-F]+\): ", "", text.strip()).split("\n")[0].strip()
        (errors if kind == "ERROR" else warnings).append(text)
    if errors:
        raise ScanReadError(_naming(path, errors[0]))
    for text in warnings:
        warn(_naming(path, text))
    poly = vtkPolyData()
    poly.ShallowCopy(reader.GetOutput())
    return poly


def _naming(path, text):
    return text if path in text else "%s: %s" % (path, text)


# --- .xyz ----------------------------------------------------------------------

def _read_xyz(path):
    with open(path, "rb") as f:
        lines = f.read().splitlines()
    rows, numbers = [], []
    for number, line in enumerate(lines, 1):
        words = line.split()
        if len(words) >= 3 and not words[0].startswith(b"#"):
            rows.append(words[:3])
            numbers.append(number)
    if not rows:
        raise ScanReadError("%s: no line holds three numbers" % path)
    try:
        xyz = np.array(rows).astype(np.float64)
    except ValueError:
        for row, number in zip(rows, numbers):
            try:
                [float(w) for w in row]
            except ValueError:
                raise ScanReadError("%s: line %d does not start with three numbers"
                                    % (path, number)) from None
        raise
    return _polydata(xyz)


# --- .ply ----------------------------------------------------------------------

def read_ply(path, warn=None):
    """Read a PLY file (any elements, ASCII or binary) into a new vtkPolyData,
    with pointsurfaces.vtkPLYScanReader (see the module's docstring).

    Raises ScanReadError, one line naming the file, for a missing, empty,
    damaged or truncated file or one without points. ``warn`` receives each
    warning as one line (default: printed to stderr).
    """
    return _read_vtk(_io.vtkPLYScanReader, os.fspath(path), warn or _print_warning)


# --- vtkPolyData ---------------------------------------------------------------

def _polydata(xyz):
    """Points (n x 3) as a vtkPolyData without cells."""
    poly = vtkPolyData()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz), deep=True))
    poly.SetPoints(points)
    return poly


def _drop_nonfinite(poly, path, warn):
    """Leave out points with NaN or infinite coordinates, and the cells using them
    (cell arrays are not carried over then)."""
    if poly.GetNumberOfPoints() == 0:
        return poly
    xyz = vtk_to_numpy(poly.GetPoints().GetData())
    finite = np.isfinite(xyz).all(axis=1)
    if finite.all():
        return poly
    warn("%s: %d of %d points with NaN or infinite coordinates left out"
         % (path, np.count_nonzero(~finite), len(finite)))
    keep = np.flatnonzero(finite)
    renumber = np.full(len(finite), -1, dtype=np.int64)
    renumber[keep] = np.arange(len(keep))
    out = vtkPolyData()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz[keep]), deep=True))
    out.SetPoints(points)
    source, target = poly.GetPointData(), out.GetPointData()
    for i in range(source.GetNumberOfArrays()):
        array = source.GetArray(i)
        if array is None:  # a string array: not carried
            continue
        kept = numpy_to_vtk(np.ascontiguousarray(vtk_to_numpy(array)[keep]), deep=True)
        kept.SetName(array.GetName())
        target.AddArray(kept)
    for attribute in range(vtkDataSetAttributes.NUM_ATTRIBUTES):
        array = source.GetAbstractAttribute(attribute)
        if array is not None and array.GetName() and target.HasArray(array.GetName()):
            target.SetActiveAttribute(array.GetName(), attribute)
    for get, put in ((poly.GetVerts, out.SetVerts), (poly.GetLines, out.SetLines),
                     (poly.GetPolys, out.SetPolys), (poly.GetStrips, out.SetStrips)):
        cells = get()
        if cells is None or cells.GetNumberOfCells() == 0:
            continue
        offsets = vtk_to_numpy(cells.GetOffsetsArray()).astype(np.int64)
        connectivity = renumber[vtk_to_numpy(cells.GetConnectivityArray()).astype(np.int64)]
        counts = np.diff(offsets)
        whole = counts > 0
        whole[np.repeat(np.arange(len(counts)), counts)[connectivity < 0]] = False
        kept_counts = counts[whole]
        kept = vtkCellArray()
        kept.SetData(
            numpy_to_vtk(np.concatenate(([0], np.cumsum(kept_counts))).astype(np.int64),
                         deep=True, array_type=VTK_ID_TYPE),
            numpy_to_vtk(connectivity[np.repeat(whole, counts)], deep=True,
                         array_type=VTK_ID_TYPE))
        put(kept)
    return out
