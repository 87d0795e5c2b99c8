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
``.ply``                    this module's PLY reader (numpy), see below
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

PLY is read here rather than by VTK 9.1's vtkPLYReader, which does not
step over elements other than ``vertex`` and ``face``: with any element
before ``vertex`` (MeshLab's range maps start with a ``camera``) it takes
the camera's numbers for vertices, and it crashes (SIGSEGV or SIGABRT) on
such a binary file that also has faces, on a truncated file, on face
indices out of range, on a vertex without ``z``, and hangs on a huge count
in a small file. OpenMesh 9's PLY reader does no better (it refuses binary files with
an element it does not know, such as ``range_grid``, accepts a truncated
ASCII file, and aborts on a huge count). This reader parses the header,
walks every element by its declared property types (scalars and lists,
ASCII and binary of either byte order), checks each against the file's
size, and keeps the ``vertex`` element (x, y, z; nx, ny, nz as "Normals";
red, green, blue [, alpha] as the "RGB" scalars; every other scalar
property as a point array of its own name) and the ``face`` element's
``vertex_indices`` as polygons. Other elements (camera, range_grid, edge,
material ...) are skipped.
"""
import os
import re
import struct
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
            if not hasattr(_io, "vtkPCDReader"):
                raise ScanReadError("%s: this build has no PCD reader" % path)
            poly = _read_vtk(_io.vtkPCDReader, path, warnings.append)
        else:
            poly = _read_vtk(_io.vtkOpenMeshReader, path, warnings.append)
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
    return _polydata(xyz, {}, None)


# --- .ply ----------------------------------------------------------------------

# PLY's type names and their numpy codes (int64 and uint64 are common extensions).
_PLY_TYPES = {
    "char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1",
    "short": "i2", "int16": "i2", "ushort": "u2", "uint16": "u2",
    "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
    "int64": "i8", "uint64": "u8",
    "float": "f4", "float32": "f4", "double": "f8", "float64": "f8",
}
_PLY_FORMATS = {"ascii": None, "binary_little_endian": "<", "binary_big_endian": ">"}
_STRUCT_CODES = {"i1": "b", "u1": "B", "i2": "h", "u2": "H", "i4": "i", "u4": "I",
                 "i8": "q", "u8": "Q", "f4": "f", "f8": "d"}


class _Property:
    def __init__(self, name, code, count_code=None):
        self.name, self.code, self.count_code = name, code, count_code

    @property
    def is_list(self):
        return self.count_code is not None


class _Element:
    def __init__(self, name, count):
        self.name, self.count, self.properties = name, count, []

    def __str__(self):
        return "element %s" % self.name


def read_ply(path, warn=None):
    """Read a PLY file (any elements, ASCII or binary) into a new vtkPolyData.

    Raises ScanReadError for a damaged or truncated file.
    """
    warn = warn or _print_warning
    with open(path, "rb") as f:
        data = f.read()
    order, elements, body = _ply_header(data, path)
    vertex = next(e for e in elements if e.name == "vertex")
    face = next((e for e in elements if e.name == "face"), None)
    face_list = None
    if face is not None:
        face_list = next((p for p in face.properties if p.is_list and
                          p.name in ("vertex_indices", "vertex_index")), None)
    wanted = {vertex: [p for p in vertex.properties if not p.is_list]}
    if face_list is not None:
        wanted[face] = [face_list]
    values = {}
    if order is None:
        tokens = data[body:].split()
        at = 0
        for element in elements:
            at, values[element] = _ascii_element(tokens, at, element, wanted.get(element, []),
                                                 path)
    else:
        at = body
        for element in elements:
            at, values[element] = _binary_element(data, at, element, order,
                                                  wanted.get(element, []), path)
    columns = values[vertex]
    xyz = np.column_stack([columns.pop(axis) for axis in ("x", "y", "z")])
    if not all(p.code == "f4" for p in vertex.properties if p.name in ("x", "y", "z")):
        xyz = xyz.astype(np.float64)
    polys = None
    if face_list is not None:
        counts, indices = values[face][face_list.name]
        if not np.issubdtype(indices.dtype, np.integer):
            raise ScanReadError("%s: the face indices are not integers" % path)
        if indices.size and (indices.min() < 0 or indices.max() >= vertex.count):
            bad = indices[(indices < 0) | (indices >= vertex.count)][0]
            raise ScanReadError("%s: a face refers to vertex %d, but there are %d vertices"
                                % (path, bad, vertex.count))
        if (counts < 3).any():
            warn("%s: faces with fewer than three corners left out: %d"
                 % (path, np.count_nonzero(counts < 3)))
            keep = np.repeat(counts >= 3, counts)
            counts, indices = counts[counts >= 3], indices[keep]
        polys = (counts, indices)
    return _polydata(xyz, columns, polys)


def _ply_header(data, path):
    """(byte order or None for ASCII, [_Element], offset of the body)."""
    if data[:4] not in (b"ply\n", b"ply\r"):
        raise ScanReadError("%s: not a PLY file (it does not start with 'ply')" % path)
    end = re.search(rb"(?:^|[\r\n])end_header[ \t]*(\r\n|\r|\n)", data)
    if end is None:
        raise ScanReadError("%s: the PLY header has no end_header line" % path)
    try:
        lines = data[:end.start()].decode("ascii").splitlines()
    except UnicodeDecodeError:
        raise ScanReadError("%s: the PLY header is not text" % path) from None
    order, formatted, elements = None, False, []
    for number, line in enumerate(lines[1:], 2):
        words = line.split()
        if not words or words[0] in ("comment", "obj_info"):
            continue
        where = "%s: PLY header line %d" % (path, number)
        if words[0] == "format" and len(words) == 3 and words[1] in _PLY_FORMATS:
            order, formatted = _PLY_FORMATS[words[1]], True
        elif words[0] == "format":
            raise ScanReadError("%s: unknown format %r" % (where, " ".join(words[1:])))
        elif words[0] == "element" and len(words) == 3:
            if not words[2].isdigit():
                raise ScanReadError("%s: bad element count %r" % (where, words[2]))
            elements.append(_Element(words[1], int(words[2])))
        elif words[0] == "property" and elements and words[-1] in (
                q.name for q in elements[-1].properties):
            raise ScanReadError("%s: a second property %r in %s" % (where, words[-1], elements[-1]))
        elif words[0] == "property" and elements and len(words) == 3 and words[1] in _PLY_TYPES:
            elements[-1].properties.append(_Property(words[2], _PLY_TYPES[words[1]]))
        elif (words[0] == "property" and elements and len(words) == 5 and words[1] == "list"
              and _PLY_TYPES.get(words[2], "f")[0] in "iu" and words[3] in _PLY_TYPES):
            elements[-1].properties.append(
                _Property(words[4], _PLY_TYPES[words[3]], _PLY_TYPES[words[2]]))
        else:
            raise ScanReadError("%s: cannot parse %r" % (where, line.strip()))
    if not formatted:
        raise ScanReadError("%s: the PLY header has no format line" % path)
    vertex = next((e for e in elements if e.name == "vertex"), None)
    scalars = {p.name for p in vertex.properties if not p.is_list} if vertex else set()
    if not {"x", "y", "z"} <= scalars:
        raise ScanReadError("%s: the PLY header has no vertex element with x, y and z" % path)
    return order, elements, end.end()


def _ascii_element(tokens, at, element, wanted, path):
    """Walk one ASCII element from token ``at``: (next token, {name: values})."""
    if not element.properties or element.count == 0:
        return at, {p.name: _empty(p) for p in wanted}
    if not any(p.is_list for p in element.properties):
        width = len(element.properties)
        end = at + element.count * width
        if end > len(tokens):
            raise _truncated(path, element)
        if not wanted:
            return end, {}
        table = np.array(tokens[at:end]).reshape(element.count, width)
        names = [p.name for p in element.properties]
        return end, {p.name: _numbers(table[:, names.index(p.name)], p.code, path, element)
                     for p in wanted}
    # Lists: read the first record's list lengths and try them for every record.
    width, first = 0, []
    for p in element.properties:
        if p.is_list:
            if at + width >= len(tokens):
                raise _truncated(path, element)
            n = _count(tokens[at + width], path, element)
            first.append(n)
            width += 1 + n
        else:
            width += 1
    end = at + element.count * width
    if end <= len(tokens):
        table = np.array(tokens[at:end]).reshape(element.count, width)
        column, uniform, columns = 0, True, {}
        for p, n in zip(element.properties, _list_lengths(element, first)):
            if p.is_list:
                lengths = _numbers(table[:, column], "f8", path, element)
                uniform = uniform and bool((lengths == n).all())
                columns[p.name] = (column + 1, n)
                column += 1 + n
            else:
                columns[p.name] = (column, None)
                column += 1
        if uniform:
            out = {}
            for p in wanted:
                column, n = columns[p.name]
                if p.is_list:
                    items = _numbers(table[:, column:column + n].reshape(-1), p.code, path,
                                     element)
                    out[p.name] = (np.full(element.count, n, dtype=np.int64), items)
                else:
                    out[p.name] = _numbers(table[:, column], p.code, path, element)
            return end, out
    # Lists of different lengths: one record at a time.
    starts = {p.name: [] for p in wanted}
    lengths = {p.name: [] for p in wanted if p.is_list}
    want = set(starts)
    for _ in range(element.count):
        for p in element.properties:
            if at >= len(tokens):
                raise _truncated(path, element)
            n = _count(tokens[at], path, element) if p.is_list else None
            if p.name in want:
                starts[p.name].append(at + 1 if p.is_list else at)
                if p.is_list:
                    lengths[p.name].append(n)
            at += 1 + n if p.is_list else 1
            if at > len(tokens):
                raise _truncated(path, element)
    out = {}
    for p in wanted:
        begin = np.asarray(starts[p.name], dtype=np.int64)
        if p.is_list:
            counts = np.asarray(lengths[p.name], dtype=np.int64)
            picked = [tokens[i] for i in _ranges(begin, counts)]
            out[p.name] = (counts, _numbers(np.array(picked, dtype=bytes), p.code, path, element))
        else:
            out[p.name] = _numbers(np.array([tokens[i] for i in begin], dtype=bytes), p.code,
                                   path, element)
    return at, out


def _binary_element(data, at, element, order, wanted, path):
    """Walk one binary element from byte ``at``: (next byte, {name: values})."""
    size = {p.name: np.dtype(p.code).itemsize for p in element.properties}
    if element.count == 0 or not element.properties:
        return at, {p.name: _empty(p) for p in wanted}
    if not any(p.is_list for p in element.properties):
        record = np.dtype([(p.name, order + p.code) for p in element.properties])
        end = at + element.count * record.itemsize
        if end > len(data):
            raise _truncated(path, element, end, len(data))
        table = np.frombuffer(data, dtype=record, count=element.count, offset=at)
        return end, {p.name: table[p.name].astype(np.dtype(p.code).newbyteorder("="))
                     for p in wanted}
    # Lists: read the first record's list lengths and try them for every record.
    first, width = [], 0
    for p in element.properties:
        if p.is_list:
            n = _binary_count(data, at + width, p, order, path, element)
            first.append(n)
            width += np.dtype(p.count_code).itemsize + n * size[p.name]
        else:
            width += size[p.name]
    end = at + element.count * width
    if end <= len(data):
        fields = []
        for p, n in zip(element.properties, _list_lengths(element, first)):
            if p.is_list:
                fields.append((p.name + "#count", order + p.count_code))
                fields.append((p.name, order + p.code, (n,)))
            else:
                fields.append((p.name, order + p.code))
        table = np.frombuffer(data, dtype=np.dtype(fields), count=element.count, offset=at)
        lists = [p for p in element.properties if p.is_list]
        if all((table[p.name + "#count"] == n).all() for p, n in zip(lists, first)):
            out = {}
            for p in wanted:
                column = table[p.name].astype(np.dtype(p.code).newbyteorder("="))
                if p.is_list:
                    n = first[lists.index(p)]
                    out[p.name] = (np.full(element.count, n, dtype=np.int64), column.reshape(-1))
                else:
                    out[p.name] = column
            return end, out
    return _binary_records(data, at, element, order, wanted, path)


def _binary_records(data, at, element, order, wanted, path):
    """Walk a binary element one record at a time (lists of different lengths)."""
    steps = []
    for p in element.properties:
        item = np.dtype(p.code).itemsize
        if p.is_list:
            steps.append((p.name, struct.Struct(order + _STRUCT_CODES[p.count_code]), item))
        else:
            steps.append((p.name, None, item))
    starts = {p.name: [] for p in wanted}
    lengths = {p.name: [] for p in wanted if p.is_list}
    total = len(data)
    for _ in range(element.count):
        for name, counter, item in steps:
            if counter is None:
                if name in starts:
                    starts[name].append(at)
                at += item
            else:
                if at + counter.size > total:
                    raise _truncated(path, element, at + counter.size, total)
                n = counter.unpack_from(data, at)[0]
                if n < 0:
                    raise ScanReadError("%s: %s has a list of negative length" % (path, element))
                at += counter.size
                if name in starts:
                    starts[name].append(at)
                    lengths[name].append(n)
                at += n * item
            if at > total:
                raise _truncated(path, element, at, total)
    raw = np.frombuffer(data, dtype=np.uint8)
    out = {}
    for p in wanted:
        dtype = np.dtype(order + p.code)
        begin = np.asarray(starts[p.name], dtype=np.int64)
        if p.is_list:
            counts = np.asarray(lengths[p.name], dtype=np.int64)
            begin = _ranges(begin, counts, dtype.itemsize)
        picked = raw[begin[:, None] + np.arange(dtype.itemsize)].reshape(-1)
        column = picked.view(dtype).astype(dtype.newbyteorder("="))
        out[p.name] = (counts, column) if p.is_list else column
    return at, out


def _list_lengths(element, first):
    """The first record's length for each property (None for scalars)."""
    lengths = iter(first)
    return [next(lengths) if p.is_list else None for p in element.properties]


def _ranges(begin, counts, step=1):
    """Concatenated begin[i] + step * arange(counts[i])."""
    if counts.sum() == 0:
        return np.zeros(0, dtype=np.int64)
    offsets = np.repeat(begin - step * (np.cumsum(counts) - counts), counts)
    return offsets + step * np.arange(counts.sum(), dtype=np.int64)


def _binary_count(data, at, p, order, path, element):
    counter = struct.Struct(order + _STRUCT_CODES[p.count_code])
    if at + counter.size > len(data):
        raise _truncated(path, element, at + counter.size, len(data))
    n = counter.unpack_from(data, at)[0]
    if n < 0:
        raise ScanReadError("%s: %s has a list of negative length" % (path, element))
    return n


def _count(token, path, element):
    try:
        n = int(token)
    except ValueError:
        raise ScanReadError("%s: %s has the list length %r, not a whole number"
                            % (path, element, token.decode("ascii", "replace"))) from None
    if n < 0:
        raise ScanReadError("%s: %s has a list of negative length" % (path, element))
    return n


def _numbers(words, code, path, element):
    """ASCII words to numbers of the PLY type ``code``."""
    try:
        values = words.astype(np.float64)
    except ValueError as e:
        raise ScanReadError("%s: %s holds something that is not a number (%s)"
                            % (path, element, str(e).split(": ")[-1])) from None
    if code[0] in "iu":
        limits = np.iinfo(code)
        if not ((values >= limits.min) & (values <= limits.max)).all():  # NaN fails too
            raise ScanReadError("%s: %s holds a number that is not a %s"
                                % (path, element, np.dtype(code).name))
    with np.errstate(over="ignore"):  # a double beyond float's range: inf, dropped later
        return values.astype(code)


def _empty(p):
    values = np.zeros(0, dtype=p.code)
    return (np.zeros(0, dtype=np.int64), values) if p.is_list else values


def _truncated(path, element, needed=None, size=None):
    if needed is None:
        return ScanReadError("%s: truncated: the file ends inside %s" % (path, element))
    return ScanReadError("%s: truncated: %s needs %d bytes, the file has %d"
                         % (path, element, needed, size))


# --- vtkPolyData ---------------------------------------------------------------

def _polydata(xyz, columns, polys):
    """Points (n x 3), point arrays by name, polygons as (counts, indices)."""
    poly = vtkPolyData()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz), deep=True))
    poly.SetPoints(points)
    attributes = poly.GetPointData()
    if all(name in columns for name in ("nx", "ny", "nz")):
        normals = [columns.pop(name) for name in ("nx", "ny", "nz")]
        array = numpy_to_vtk(np.column_stack(normals).astype(np.float32), deep=True)
        array.SetName("Normals")
        attributes.SetNormals(array)
    for red, green, blue, alpha in (("red", "green", "blue", "alpha"),
                                    ("diffuse_red", "diffuse_green", "diffuse_blue",
                                     "diffuse_alpha")):
        if all(name in columns for name in (red, green, blue)):
            channels = [columns.pop(name) for name in (red, green, blue, alpha)
                        if name in columns]
            rgb = np.column_stack(channels)
            if rgb.dtype.kind == "f":
                rgb = np.rint(255.0 * np.clip(np.nan_to_num(rgb), 0.0, 1.0))
            array = numpy_to_vtk(np.clip(rgb, 0, 255).astype(np.uint8), deep=True)
            array.SetName("RGB")
            attributes.SetScalars(array)
            break
    for name, values in columns.items():
        array = numpy_to_vtk(np.ascontiguousarray(values), deep=True)
        array.SetName(name)
        attributes.AddArray(array)
    if polys is not None and len(polys[0]):
        counts, indices = polys
        offsets = np.concatenate(([0], np.cumsum(counts))).astype(np.int64)
        cells = vtkCellArray()
        cells.SetData(numpy_to_vtk(offsets, deep=True, array_type=VTK_ID_TYPE),
                      numpy_to_vtk(indices.astype(np.int64), deep=True, array_type=VTK_ID_TYPE))
        poly.SetPolys(cells)
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
