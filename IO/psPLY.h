// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psPLY.h
 * @brief PLY files (ASCII and binary of either byte order, any elements), as plain functions.
 *
 * A PLY file is a text header
 *
 *     ply
 *     format ascii 1.0          (or binary_little_endian, binary_big_endian)
 *     comment ...               (and obj_info lines: skipped)
 *     element camera 1          (any elements, in any order)
 *     property float view_px
 *     element vertex 8
 *     property float x          (char uchar short ushort int uint int64 uint64
 *     property float y           float double, or int8 ... float64)
 *     property float z
 *     property list uchar int vertex_indices
 *     end_header
 *
 * followed by each element's records in header order. ReadPLY() walks every
 * element by its declared types (scalars and lists), checking each against
 * the size of the file before it allocates anything, and keeps the first
 * `vertex` element's scalar properties and the `face` element's
 * `vertex_indices` (or `vertex_index`) lists; other elements (MeshLab's
 * camera and range_grid, edges, materials) are stepped over. The rules and
 * the error texts are those of the numpy reader that pointsurfaces.scanio
 * had before this one.
 */
#ifndef psPLY_h
#define psPLY_h

#include <cstddef> // For sizes
#include <cstdint> // For indices
#include <string>  // For names and errors
#include <vector>  // For values

namespace pointsurfaces
{
/** The most properties one element may declare (a header with more is refused). */
constexpr std::size_t MaximumProperties = 4096;

/** PLY's value types (int64 and uint64 are common extensions). */
enum class PLYType : unsigned char
{
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Int64,
  UInt64,
  Float32,
  Float64
};

/** Bytes of one value of `type`. */
std::size_t PLYTypeSize(PLYType type);
/** True for the integer types (char to uint64). */
bool PLYTypeIsInteger(PLYType type);
/** The type's name as numpy spells it ("uint8", "float32"), as the error texts use it. */
const char* PLYTypeName(PLYType type);

/** `v` as a float, rounded to nearest; beyond float's range infinite (as numpy's astype). */
float PLYFloat(double v);

/** One scalar property of the vertex element: a value per vertex. */
struct PLYColumn
{
  std::string Name;
  PLYType Type = PLYType::Float32;
  std::vector<unsigned char> Bytes; ///< the values, in this machine's byte order
  /** Value `k` as a double. */
  double Value(std::size_t k) const;
};

/** What ReadPLY keeps of a file. */
struct PLYMesh
{
  std::size_t NumberOfPoints = 0;
  /** The vertex element's scalar properties in header order (x, y and z among them). */
  std::vector<PLYColumn> Columns;
  /** Polygon k is FaceConnectivity[FaceOffsets[k] .. FaceOffsets[k + 1]); empty without faces. */
  std::vector<std::int64_t> FaceOffsets;
  std::vector<std::int64_t> FaceConnectivity;
  /** One line each, without the file's name (faces with fewer than three corners). */
  std::vector<std::string> Warnings;

  /** The column of that name, or null. */
  const PLYColumn* Find(const std::string& name) const;
};

/** True when `data` starts as a PLY file does ("ply" and a line break). */
bool HasPLYMagic(const char* data, std::size_t size);

/**
 * Reads the PLY file held in `data` into `mesh`. False, with `error` set
 * (one line, without the file's name), for a damaged or truncated file, a
 * header without a vertex element holding x, y and z, face indices that are
 * not integers or name no vertex.
 */
bool ReadPLY(const char* data, std::size_t size, PLYMesh& mesh, std::string& error);

/** ReadPLY on the file `path` (also false for a missing or empty file). */
bool ReadPLYFile(const std::string& path, PLYMesh& mesh, std::string& error);

/**
 * Piece `piece` of `pieces` of the file's vertices (the vertex element's
 * scalar properties of records [n piece / pieces, n (piece + 1) / pieces)),
 * without faces. In a binary file whose vertex records have a fixed size
 * and come after elements of fixed-size records only, just those records
 * are read (`streamed` true): a file of any size is read piece by piece in
 * bounded memory. Otherwise (ASCII, lists before the vertices) the whole
 * file is read and the piece kept. False, with `error` set, as ReadPLYFile.
 */
bool ReadPLYFilePiece(const std::string& path,
  std::size_t piece,
  std::size_t pieces,
  PLYMesh& mesh,
  bool& streamed,
  std::string& error);

/**
 * Leaves out the points with a NaN or infinite x, y or z, with the faces
 * that use them (the others renumbered). Returns how many were left out.
 */
std::size_t DropNonFinitePoints(PLYMesh& mesh);

/**
 * Colours as bytes, `channels.size()` per point: integer channels clipped to
 * 0..255; when any channel is floating point, every channel is taken as 0..1
 * (NaN as 0), clipped and scaled by 255 with rounding to even, in float
 * when the channels fit one (as numpy promotes them), else in double.
 */
std::vector<unsigned char> PLYColours(const std::vector<const PLYColumn*>& channels,
  std::size_t numberOfPoints);

} // namespace pointsurfaces

#endif
