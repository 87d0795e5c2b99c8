// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psSplatFile.h
 * @brief The multi-resolution splat file (HDF5): written in blocks, read by page and level.
 *
 * One HDF5 file holds a splat set in the order of its page octree (a
 * psOctree whose leaves hold at most PageSplats splats, each leaf's
 * splats sorted by level, coarsest first), so that a page's levels 0..l
 * are one contiguous run of rows in every column:
 *
 *     /                      attributes: PointSurfacesSplatFile (version,
 *                            1), Complete (1 once the writer closed it),
 *                            Degree, Levels, LevelQuality[Levels],
 *                            NumberOfSplats, NumberOfInputPoints, Oriented,
 *                            Bounds[6]
 *     /Splats/Origin         float64 [N, 3]  splat origins
 *     /Splats/Normal         float32 [N, 3]  (the splat data model's arrays,
 *     /Splats/Tangent        float32 [N, 3]   vtkSplatDataModel)
 *     /Splats/FeatureSize    float32 [N]
 *     /Splats/Coefficients   float32 [N, m]  m = MonomialCount(Degree)
 *     /Splats/Radius, MaxDeviation, NominalRadius, Tolerance  float32 [N]
 *     /Splats/LOD            int32   [N]
 *     /Attributes/<name>     float32 [N, c]  the input's point arrays, MLS-weighted
 *                                            (integer arrays as their integer type,
 *                                            rounded: SplatFileInfo::AttributeTypes)
 *     (each column but Origin and Coefficients, and each attribute: attribute
 *      Range, the whole column's value ranges, SplatFileInfo::Ranges, and
 *      RangeRows, the rows that hold their ends, SplatFileInfo::RangeRows)
 *     /Octree/Bounds         float64 [M, 6]  per node, discs included
 *     /Octree/Sphere         float64 [M, 4]
 *     /Octree/Children       int32   [M, 2]  first child, child count
 *     /Octree/Range          int64   [M, 2]  rows [begin, end)
 *     /Octree/LevelEnds      int64   [M, Levels]
 *     /Octree/MeanScale      float64 [M]     mean R / s of the node's splats
 *     /Octree/Reach          float64 [M]     sphere radius that holds its patches
 *
 * Columns are chunked by 65 536 rows, so that reading a page touches its
 * chunks only. The origins stay in double (coordinates near 1e7 keep
 * their millimetres); everything else is float, what the mapper draws
 * with: about 30 + 4 m + 4 c bytes a splat (cubic: 94).
 *
 * SplatFileReader::Open checks everything it will index with (the format's
 * version and completeness, every column's shape, the octree's ranges,
 * children and level ends) and says what is wrong in one line: a
 * truncated, damaged, foreign or unfinished file is refused before
 * anything is read from it.
 *
 * Every HDF5 call of the writer and the reader holds one process-wide lock,
 * so that a reader may run on a loading thread (vtkStreamingSplatMapper)
 * beside other splat files whether or not the HDF5 library was built
 * thread-safe.
 */
#ifndef psSplatFile_h
#define psSplatFile_h

#include "PointSurfacesIOHDF5Module.h" // For export macro
#include "psSplatLOD.h"                // For LODOctree

#include <cstddef>    // For size_t
#include <functional> // For the fetch
#include <map>        // For the ranges
#include <memory>     // For the implementation
#include <string>     // For names and errors
#include <vector>     // For columns

namespace pointsurfaces
{
/** The modification time of `path` in nanoseconds (-1 when it cannot be read): reopen a changed file. */
POINTSURFACESIOHDF5_EXPORT long long FileModificationStamp(const std::string& path);

/** Splats at most per page (the page octree's bucket). */
constexpr int PageSplats = 16384;

struct SplatFileInfo
{
  int Degree = 3;
  long long Splats = 0;
  long long InputPoints = 0;
  bool Oriented = false;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  std::vector<std::string> AttributeNames;
  std::vector<int> AttributeComponents;
  /**
   * Each attribute's VTK data type (vtkType.h; missing entries: VTK_FLOAT).
   * Integer types are stored as such (8 to 64 bits, signed or not: a
   * colour stays 3 bytes a splat and reads back as unsigned char), rounded
   * to the nearest integer and clamped to the type on writing; every other
   * type as float32. Values travel as float, so integers beyond 2^24 lose
   * their last bits.
   */
  std::vector<int> AttributeTypes;
  /** The VTK data type of attribute `a`. */
  int AttributeType(size_t a) const;
  /**
   * The whole file's value ranges, by dataset ("Splats/Radius",
   * "Attributes/<name>"): [min, max] of each component's finite values,
   * then of the magnitude of the tuples whose components are all finite
   * when there are several components. The writer stores them as each
   * dataset's Range attribute (every column but Origin and Coefficients,
   * and every attribute); a file without them (written before 2026-12-06)
   * or with one that does not fit its dataset has none here. A reader of
   * some pages gives its arrays these ranges (vtkSplatFileReader), so that
   * a colour map fits the whole file, not the pages read.
   */
  std::map<std::string, std::vector<double>> Ranges;
  /**
   * For each range of Ranges, the row (splat) of the file that holds each
   * of its ends, in the same order: a reader of some pages can load these
   * few splats too, so that ranges computed from the values (ParaView 5.13
   * and later) are the whole file's. Stored as each dataset's RangeRows
   * attribute (older files have none; rows outside
   * the file are refused, and that dataset then has none here).
   */
  std::map<std::string, std::vector<long long>> RangeRows;
  /** The page octree with the s of each level (Pages.Tree.Levels levels). */
  LODOctree Pages;
};

/** Numbers in a range of SplatFileInfo::Ranges for `components` components. */
inline size_t SplatRangeSize(int components)
{
  return 2 * static_cast<size_t>(components > 1 ? components + 1 : components);
}

/** Rows of splats, column by column, as the file stores them. */
struct POINTSURFACESIOHDF5_EXPORT SplatColumns
{
  long long Count = 0;
  std::vector<double> Origin;
  std::vector<float> Normal, Tangent, FeatureSize, Coefficients;
  std::vector<float> Radius, MaxDeviation, NominalRadius, Tolerance;
  std::vector<int> LOD;
  std::vector<std::vector<float>> Attributes; ///< one per attribute, components a row
  /** Sizes every column for `count` rows of `degree` and those attributes. */
  void Resize(long long count, int degree, const std::vector<int>& components);
  /** Appends row `row` of `from` (of the same degree and attributes; none outside it). */
  void Append(const SplatColumns& from, long long row);
};

/** Every row of info.RangeRows, sorted, each once: the splats that hold the file's ranges. */
POINTSURFACESIOHDF5_EXPORT std::vector<long long> RangeEndRows(const SplatFileInfo& info);

class POINTSURFACESIOHDF5_EXPORT SplatFileWriter
{
public:
  SplatFileWriter();
  ~SplatFileWriter();
  /**
   * Create `path` for `info` (its Splats rows and its Pages, whose ranges
   * the rows will follow). False with `error` set when it cannot be made.
   */
  bool Open(const std::string& path, const SplatFileInfo& info, std::string& error);
  /** Rows [first, first + block.Count). */
  bool Write(long long first, const SplatColumns& block, std::string& error);
  /** The octree and the header, then Complete: the file is whole only after this. */
  bool Close(std::string& error);

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};

/** Fill rows 0 .. ids.size() - 1 of `out` (sized already) with splats `ids`; false on error. */
using SplatFetch = std::function<bool(const std::vector<long long>& ids, SplatColumns& out)>;

/**
 * Write `n` splats as a splat file: their page octree from their `origins`,
 * disc `radii` and `levels` (s of each in `levelQuality`), then their rows
 * in its order, fetched block by block. `info` gives the degree, the
 * attributes, the input's point count and whether the normals are oriented.
 */
POINTSURFACESIOHDF5_EXPORT bool WriteSplatFile(const std::string& path,
  SplatFileInfo info,
  const double* origins,
  const double* radii,
  const int* levels,
  long long n,
  const std::vector<double>& levelQuality,
  const SplatFetch& fetch,
  std::string& error,
  int pageSplats = PageSplats);

class POINTSURFACESIOHDF5_EXPORT SplatFileReader
{
public:
  SplatFileReader();
  ~SplatFileReader();
  /**
   * Open and check `path`; false with `error` set (one line) for a file it
   * cannot use. With CheckInChildProcess (the default where supported,
   * Linux), a file is first opened and checked, and its chunk indexes
   * walked, in a forked child process, once per file version in this
   * process: HDF5 1.10 (Debian 12) can crash on a damaged file's metadata
   * (a use after free in its object header cache, found by fuzzing), and
   * then only the child ends, and the file is reported as damaged.
   */
  bool Open(const std::string& path, std::string& error);
  void SetCheckInChildProcess(bool check);
  const SplatFileInfo& Info() const;
  /** Rows [first, first + count), appended to `out` (Resize'd to hold them). */
  bool Read(long long first, long long count, SplatColumns& out, std::string& error);
  /** Bytes one splat takes in a vtkPolyData of the splat data model (the budget's unit). */
  double BytesPerSplat() const;

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};
} // namespace pointsurfaces

#endif
