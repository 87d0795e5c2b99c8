// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psSplatStream.h
 * @brief The splat fit of a point set larger than memory, chunk by chunk, on plain arrays.
 *
 * BuildSplats holds every point, its index and its fits at once: about 330
 * bytes a point at the defaults, so a 100M-point lidar survey needs some
 * 33 GB. SplatStream holds one chunk at a time:
 *
 * 1. AddPoints() takes the points in batches of any size (a reader's
 *    pieces, a file read in blocks) and spills them to a scratch file,
 *    with their bounds. Points with a NaN or infinite coordinate are
 *    dropped and counted.
 * 2. Run() counts the points in a 64 x 64 x 64 grid over the bounds, splits
 *    the occupied cells in halves of their longest axis at the slab that
 *    halves their points (a k-d tree) until no chunk holds more than
 *    ChunkPoints points, and writes each point to its chunk's file.
 * 3. Chunk after chunk, in the k-d tree's depth-first order: its points and
 *    a halo of the neighbouring chunks' points around it (as wide as a
 *    fit's neighbours and a disc's reach, measured on the chunk) go to
 *    BuildSplats as one chunk (ChunkContext): only its own points are
 *    chosen; every fit and bound sees the halo, so a splat at a border is
 *    the splat the in-memory fit gives there; the points that earlier
 *    chunks' splats claimed start claimed, and the halo points that this
 *    chunk's splats claim are recorded (one byte a point, a bit a level),
 *    so that no border is covered twice nor left open. This is the
 *    in-memory selection run chunk after chunk, as BuildSplats's parallel
 *    slabs run it slab after slab.
 * 4. Without input normals, the chunk's splats are oriented with copies of
 *    the earlier chunks' splats in its halo (OrientSplats): each connected
 *    part takes the side its copies vote for, and the parts that meet
 *    across chunks are joined (a union-find with parity). When the last
 *    chunk is done, each joined part is oriented as OrientSplats orients a
 *    part: a closed one (its area-weighted normals nearly cancel) by the
 *    sign of its flux, an open one so that its highest splat faces up.
 *    What OrientSplats adds inside a closed part (the 26 views from
 *    outside) is not done across chunks.
 * 5. The splats go to a scratch file of fixed-size records, with the
 *    input's attributes (float components) MLS-weighted as the in-memory
 *    fitter carries them; ReadSplats() reads any range of them back with
 *    the final orientation applied, and the origins, radii and levels of
 *    all of them (Sketch) stay in memory for a file writer's octree.
 *
 * Memory: the largest chunk with its halo (BuildSplats's ~330 bytes a
 * point), one byte a point of claims, and 52 bytes a splat of sketch.
 * Disk: 24 + 4 (c + 3) bytes a point twice (spill and chunks, c attribute
 * components, normals as 3 floats when given) and about 280 + 4 c bytes a
 * splat. Selection All or Quality (levels included); FixedCount (LOP)
 * needs every point at once and is refused.
 */
#ifndef psSplatStream_h
#define psSplatStream_h

#include "PointSurfacesFiltersModule.h" // For export macro
#include "psSplatBuilder.h"             // For BuildParameters

#include <atomic>     // For the abort flag
#include <cstdio>     // For the scratch files
#include <functional> // For progress
#include <memory>     // For the implementation
#include <string>     // For paths and errors
#include <vector>     // For batches

namespace pointsurfaces
{
struct StreamParameters
{
  BuildParameters Build;
  /** Most points (own, halo excluded) in one chunk. */
  long long ChunkPoints = 2000000;
  /** Where the scratch files go; empty: the system's temporary directory. */
  std::string ScratchDirectory;
  /** Orient the splats when the input has no normals. */
  bool Orient = true;
  /** Coincident points closer than this share of the bounds' diagonal are merged. */
  double MergeTolerance = 1e-6;
};

/** A splat as the scratch file holds it: BuiltSplat without the weights. */
struct StreamedSplat
{
  Splat Fitted;
  double Radius = 0.0;
  double MaxDeviation = 0.0;
  double NominalRadius = 0.0;
  double Tolerance = 0.0;
  int Level = 0;
  long long Source = -1; ///< the point it grew from: its position among the finite points added
};

/** What a run did, for the filter's report and the benchmarks. */
struct StreamStatistics
{
  long long Points = 0;       ///< finite points added
  long long Dropped = 0;      ///< points with a NaN or infinite coordinate
  long long Merged = 0;       ///< coincident points merged into another
  long long Chunks = 0;       ///< chunks fitted
  long long LargestChunk = 0; ///< most points of a chunk, its halo included
  long long HaloPoints = 0;   ///< halo points loaded, summed over chunks
  long long Degenerate = 0;   ///< chosen positions that gave no splat
  long long Reduced = 0;      ///< splats fitted at a lower degree
  long long Parts = 0;        ///< oriented parts after joining across chunks
  long long FlippedParts = 0; ///< of them, turned over by the final pass
  double ScratchBytes = 0.0;  ///< bytes written to scratch files
  /** The unit of the bound (ToleranceUnit::Automatic resolved on the first chunk). */
  ToleranceUnit Tolerance = ToleranceUnit::Spacing;
  /** ToleranceUnit::Automatic: the first chunk's noise, which decided it. */
  SampleNoise Noise;
};

class POINTSURFACESFILTERS_EXPORT SplatStream
{
public:
  /**
   * `attributes` float components a point carries besides its coordinates
   * (colours, intensity: MLS-weighted onto the splats); `normals` whether
   * AddPoints receives unit normals (they orient the splats and take part
   * in the bound's normal test). A Selection it cannot stream (FixedCount),
   * more than 8 levels or a scratch directory it cannot make set Error()
   * here, before any point is spilled, and every call after fails.
   */
  SplatStream(const StreamParameters& params, int attributes, bool normals);
  ~SplatStream();
  SplatStream(const SplatStream&) = delete;
  SplatStream& operator=(const SplatStream&) = delete;

  /**
   * `n` points: xyz triples, with `normals` (3 a point) when the stream was
   * made with normals, and `attributes` components a point (or null: zeros).
   * False, with Error() set, when the scratch file cannot be written.
   */
  bool AddPoints(const double* xyz, const float* normals, const float* attributes, long long n);

  /**
   * Fit every chunk. `progress(f)` with f in [0, 1]; `abort`, when set,
   * stops after the current chunk with what was fitted. False, with
   * Error() set, on a scratch file error or after a refusal (above).
   */
  bool Run(const std::function<void(double)>& progress = nullptr,
    const std::atomic<bool>* abort = nullptr);

  /** The splats fitted, after Run(). */
  long long NumberOfSplats() const;
  /**
   * Splats [first, first + count) in the order fitted (chunk by chunk),
   * oriented, with `Attributes()` float components each in `attributes`.
   */
  bool ReadSplats(long long first,
    long long count,
    std::vector<StreamedSplat>& splats,
    std::vector<float>& attributes) const;
  /** Splats `ids` (any order, as ReadSplats), in that order. */
  bool ReadSplatsAt(const std::vector<long long>& ids,
    std::vector<StreamedSplat>& splats,
    std::vector<float>& attributes) const;
  /** After Run(): every splat's origin (3 a splat), disc radius and level, in memory. */
  const std::vector<double>& Origins() const;
  const std::vector<double>& Radii() const;
  const std::vector<int>& Levels() const;
  /** s of each level. */
  const std::vector<double>& LevelQuality() const;
  /** Whether the splats' normals face consistently (input normals or Orient). */
  bool Oriented() const;
  int Attributes() const;
  const StreamStatistics& Statistics() const;
  const std::string& Error() const;

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};
} // namespace pointsurfaces

#endif
