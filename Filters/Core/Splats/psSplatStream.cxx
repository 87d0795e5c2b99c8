// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psSplatStream.h"

#include "psPointIndex.h"
#include "psSplatOrientation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <type_traits>

namespace pointsurfaces
{
namespace
{
static_assert(std::is_trivially_copyable<StreamedSplat>::value, "records are written as bytes");

// Cells of the grid that the chunks are cut from, per axis.
constexpr int Cells = 64;
// Points whose spacing is measured to size a chunk's halo.
constexpr int HaloSamples = 256;
// The halo, in units of the largest sampled fit neighbourhood's radius
// grown by the widest disc: margin for the samples that were not taken.
constexpr double HaloMargin = 1.5;
// Points read or written per block of a scratch file.
constexpr long long Block = 65536;

// A scratch file read or written in blocks of fixed-size records.
class Scratch
{
public:
  Scratch() = default;
  ~Scratch() { this->Close(); }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;

  bool Open(const std::string& path, const char* mode)
  {
    this->Close();
    this->File = std::fopen(path.c_str(), mode);
    return this->File != nullptr;
  }
  void Close()
  {
    if (this->File)
    {
      std::fclose(this->File);
      this->File = nullptr;
    }
  }
  bool Write(const void* data, size_t bytes)
  {
    return bytes == 0 || (this->File && std::fwrite(data, 1, bytes, this->File) == bytes);
  }
  bool Read(void* data, size_t bytes)
  {
    return bytes == 0 || (this->File && std::fread(data, 1, bytes, this->File) == bytes);
  }
  bool Seek(long long offset)
  {
    return this->File && fseeko(this->File, static_cast<off_t>(offset), SEEK_SET) == 0;
  }
  bool Flush() { return this->File && std::fflush(this->File) == 0; }

private:
  std::FILE* File = nullptr;
};

// Points with their input ids, normals and attributes, in memory.
struct PointBatch
{
  std::vector<long long> Ids;
  std::vector<double> XYZ;
  std::vector<float> Normals;
  std::vector<float> Attributes;
  void Clear()
  {
    this->Ids.clear();
    this->XYZ.clear();
    this->Normals.clear();
    this->Attributes.clear();
  }
  long long Size() const { return static_cast<long long>(this->Ids.size()); }
};

// Union-find with parity: each node knows whether it faces as its root does.
struct PartForest
{
  std::vector<long long> Parent;
  std::vector<char> Parity; // relative to Parent

  long long Add()
  {
    this->Parent.push_back(static_cast<long long>(this->Parent.size()));
    this->Parity.push_back(0);
    return this->Parent.back();
  }
  // The root of `i`, and in `parity` whether i faces against it.
  long long Find(long long i, char& parity)
  {
    parity = 0;
    long long r = i;
    while (this->Parent[r] != r)
    {
      parity ^= this->Parity[r];
      r = this->Parent[r];
    }
    // Compress: every node on the path points at the root with its parity.
    char p = parity;
    while (this->Parent[i] != r)
    {
      const long long next = this->Parent[i];
      const char step = this->Parity[i];
      this->Parent[i] = r;
      this->Parity[i] = p;
      p ^= step;
      i = next;
    }
    return r;
  }
  // Join a and b so that a faces against b when `against`; false when they are joined already.
  bool Join(long long a, long long b, char against)
  {
    char pa = 0, pb = 0;
    const long long ra = this->Find(a, pa), rb = this->Find(b, pb);
    if (ra == rb)
    {
      return false;
    }
    this->Parent[ra] = rb;
    this->Parity[ra] = static_cast<char>(pa ^ pb ^ against);
    return true;
  }
};

struct Chunk
{
  int Lo[3] = { 0, 0, 0 }; // cells [Lo, Hi)
  int Hi[3] = { 0, 0, 0 };
  double Box[6] = { 0, 0, 0, 0, 0, 0 };
  long long Count = 0;
  long long SplatBegin = 0; // its splats in fitted order
  long long SplatEnd = 0;
};

bool Overlaps(const double a[6], const double b[6])
{
  for (int c = 0; c < 3; ++c)
  {
    if (a[2 * c] > b[2 * c + 1] || b[2 * c] > a[2 * c + 1])
    {
      return false;
    }
  }
  return true;
}

bool Inside(const double box[6], const double* p)
{
  return p[0] >= box[0] && p[0] <= box[1] && p[1] >= box[2] && p[1] <= box[3] && p[2] >= box[4] &&
    p[2] <= box[5];
}
} // namespace

struct SplatStream::Impl
{
  StreamParameters Params;
  int A = 0;
  bool HasNormals = false;
  std::string Error;
  StreamStatistics Stats;

  std::filesystem::path Directory;
  Scratch Spill;
  double Lo[3] = { 0, 0, 0 }, Hi[3] = { 0, 0, 0 };
  double CellSize[3] = { 1, 1, 1 };

  std::vector<Chunk> Chunks;
  std::vector<int> ChunkOfCell;
  std::vector<unsigned char> Claims;

  Scratch Store;
  long long SplatCount = 0;
  std::vector<double> Origins, Radii;
  std::vector<int> Levels;
  std::vector<float> Normals, Scales;
  std::vector<long long> Node; // each splat's part node, -1 unoriented
  PartForest Forest;
  std::vector<char> FinalFlip; // per part node
  std::vector<double> LevelQuality;
  bool Oriented = false;

  size_t PointRecord() const { return 24 + 4 * (3 * (this->HasNormals ? 1 : 0) + this->A); }
  size_t ChunkRecord() const { return 8 + this->PointRecord(); }
  size_t SplatRecord() const { return sizeof(StreamedSplat) + 4 * static_cast<size_t>(this->A); }
  std::string ChunkPath(size_t c) const
  {
    return (this->Directory / ("chunk" + std::to_string(c) + ".bin")).string();
  }

  bool Fail(const std::string& message)
  {
    this->Error = message;
    return false;
  }
  bool MakeDirectory();
  int CellOf(const double* p, int axis) const
  {
    const int c = static_cast<int>((p[axis] - this->Lo[axis]) / this->CellSize[axis]);
    return std::min(Cells - 1, std::max(0, c));
  }
  int CellIndex(const double* p) const
  {
    return (this->CellOf(p, 2) * Cells + this->CellOf(p, 1)) * Cells + this->CellOf(p, 0);
  }
  bool Plan(const std::vector<long long>& counts);
  void Split(const int lo[3], const int hi[3], const std::vector<long long>& prefix);
  long long CountIn(const int lo[3], const int hi[3], const std::vector<long long>& prefix) const;
  bool Distribute();
  bool ReadChunk(size_t c, const double* keep, PointBatch& into);
  bool FitChunk(size_t c,
    const std::function<void(double)>& progress,
    const std::atomic<bool>* abort);
  // `index`: that of `own`'s points.
  double HaloWidth(const PointBatch& own, const PointIndex& index) const;
  void Orient(size_t c,
    const double box[6],
    std::vector<BuiltSplat>& splats,
    std::vector<long long>& nodes);
  void FinishOrientation();
};

//------------------------------------------------------------------------------
bool SplatStream::Impl::MakeDirectory()
{
  std::error_code ec;
  std::filesystem::path base = this->Params.ScratchDirectory.empty()
    ? std::filesystem::temp_directory_path(ec)
    : std::filesystem::path(this->Params.ScratchDirectory);
  std::string pattern = (base / "pointsurfaces-stream-XXXXXX").string();
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (!mkdtemp(buffer.data()))
  {
    return this->Fail(
      "cannot make a scratch directory in " + base.string() + ": " + std::strerror(errno));
  }
  this->Directory = buffer.data();
  return true;
}

//------------------------------------------------------------------------------
SplatStream::SplatStream(const StreamParameters& params, int attributes, bool normals)
  : P(new Impl)
{
  P->Params = params;
  P->A = std::max(0, attributes);
  P->HasNormals = normals;
  // Refused before any point is read and spilled.
  if (params.Build.Select == Selection::FixedCount)
  {
    P->Fail("a streaming fit selects by quality or keeps every point: FixedCount (LOP) "
            "needs every point at once");
  }
  else if (params.Build.Levels > 8)
  {
    P->Fail("a streaming fit has at most 8 levels");
  }
  else if (P->MakeDirectory() && !P->Spill.Open((P->Directory / "spill.bin").string(), "w+b"))
  {
    P->Fail("cannot write the scratch file in " + P->Directory.string());
  }
}

//------------------------------------------------------------------------------
SplatStream::~SplatStream()
{
  P->Spill.Close();
  P->Store.Close();
  if (!P->Directory.empty())
  {
    std::error_code ec;
    std::filesystem::remove_all(P->Directory, ec);
  }
}

//------------------------------------------------------------------------------
bool SplatStream::AddPoints(const double* xyz,
  const float* normals,
  const float* attributes,
  long long n)
{
  if (!P->Error.empty())
  {
    return false;
  }
  const size_t rec = P->PointRecord();
  std::vector<unsigned char> buffer;
  buffer.reserve(static_cast<size_t>(std::min(n, Block)) * rec);
  const int nc = 3 * (P->HasNormals ? 1 : 0);
  std::vector<float> extra(static_cast<size_t>(nc + P->A), 0.0f);
  for (long long i = 0; i < n; ++i)
  {
    const double* p = xyz + 3 * i;
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
    {
      ++P->Stats.Dropped;
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      P->Lo[c] = P->Stats.Points ? std::min(P->Lo[c], p[c]) : p[c];
      P->Hi[c] = P->Stats.Points ? std::max(P->Hi[c], p[c]) : p[c];
    }
    ++P->Stats.Points;
    for (int c = 0; c < nc; ++c)
    {
      extra[c] = normals ? normals[3 * i + c] : 0.0f;
    }
    for (int c = 0; c < P->A; ++c)
    {
      extra[nc + c] = attributes ? attributes[i * P->A + c] : 0.0f;
    }
    const size_t at = buffer.size();
    buffer.resize(at + rec);
    std::memcpy(&buffer[at], p, 24);
    if (!extra.empty())
    {
      std::memcpy(&buffer[at + 24], extra.data(), 4 * extra.size());
    }
    if (buffer.size() >= static_cast<size_t>(Block) * rec)
    {
      if (!P->Spill.Write(buffer.data(), buffer.size()))
      {
        return P->Fail(
          "cannot write the scratch file in " + P->Directory.string() + " (disk full?)");
      }
      P->Stats.ScratchBytes += static_cast<double>(buffer.size());
      buffer.clear();
    }
  }
  if (!P->Spill.Write(buffer.data(), buffer.size()))
  {
    return P->Fail("cannot write the scratch file in " + P->Directory.string() + " (disk full?)");
  }
  P->Stats.ScratchBytes += static_cast<double>(buffer.size());
  return true;
}

//------------------------------------------------------------------------------
long long SplatStream::Impl::CountIn(const int lo[3],
  const int hi[3],
  const std::vector<long long>& prefix) const
{
  // prefix is the 3D summed-area table of the counts, (Cells + 1)^3.
  auto at = [&](int x, int y, int z)
  { return prefix[(static_cast<size_t>(z) * (Cells + 1) + y) * (Cells + 1) + x]; };
  return at(hi[0], hi[1], hi[2]) - at(lo[0], hi[1], hi[2]) - at(hi[0], lo[1], hi[2]) -
    at(hi[0], hi[1], lo[2]) + at(lo[0], lo[1], hi[2]) + at(lo[0], hi[1], lo[2]) +
    at(hi[0], lo[1], lo[2]) - at(lo[0], lo[1], lo[2]);
}

//------------------------------------------------------------------------------
void SplatStream::Impl::Split(const int lo_[3],
  const int hi_[3],
  const std::vector<long long>& prefix)
{
  const long long count = this->CountIn(lo_, hi_, prefix);
  if (count == 0)
  {
    return;
  }
  // The box shrunk to its occupied cells: no halo reaches into empty space.
  int lo[3] = { lo_[0], lo_[1], lo_[2] }, hi[3] = { hi_[0], hi_[1], hi_[2] };
  for (int c = 0; c < 3; ++c)
  {
    int a[3] = { lo[0], lo[1], lo[2] }, b[3] = { hi[0], hi[1], hi[2] };
    for (a[c] = lo[c], b[c] = lo[c] + 1; this->CountIn(a, b, prefix) == 0; ++a[c], ++b[c])
    {
      lo[c] = a[c] + 1;
    }
    a[c] = hi[c] - 1;
    b[c] = hi[c];
    while (this->CountIn(a, b, prefix) == 0)
    {
      hi[c] = a[c];
      --a[c];
      --b[c];
    }
  }
  int axis = -1;
  double longest = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    const double extent = (hi[c] - lo[c]) * this->CellSize[c];
    if (hi[c] - lo[c] > 1 && extent > longest)
    {
      axis = c;
      longest = extent;
    }
  }
  if (count <= this->Params.ChunkPoints || axis < 0)
  {
    Chunk chunk;
    for (int c = 0; c < 3; ++c)
    {
      chunk.Lo[c] = lo[c];
      chunk.Hi[c] = hi[c];
      chunk.Box[2 * c] = this->Lo[c] + lo[c] * this->CellSize[c];
      chunk.Box[2 * c + 1] = this->Lo[c] + hi[c] * this->CellSize[c];
    }
    chunk.Count = count;
    this->Chunks.push_back(chunk);
    return;
  }
  // Halves of the longest axis at the slab that splits the points most
  // evenly (a k-d split): chunks of ChunkPoints / 2 to ChunkPoints points,
  // as far as the cells allow, and a depth-first walk keeps neighbouring
  // chunks close in the fitted order.
  int split = lo[axis] + 1;
  long long best = -1;
  int a[3] = { lo[0], lo[1], lo[2] }, b[3] = { hi[0], hi[1], hi[2] };
  for (int m = lo[axis] + 1; m < hi[axis]; ++m)
  {
    b[axis] = m;
    const long long below = this->CountIn(a, b, prefix);
    const long long off = std::abs(2 * below - count);
    if (best < 0 || off < best)
    {
      best = off;
      split = m;
    }
  }
  int upper[3] = { lo[0], lo[1], lo[2] }, lower[3] = { hi[0], hi[1], hi[2] };
  lower[axis] = split;
  upper[axis] = split;
  this->Split(lo, lower, prefix);
  this->Split(upper, hi, prefix);
}

//------------------------------------------------------------------------------
bool SplatStream::Impl::Plan(const std::vector<long long>& counts)
{
  const size_t side = Cells + 1;
  std::vector<long long> prefix(side * side * side, 0);
  for (int z = 1; z <= Cells; ++z)
  {
    for (int y = 1; y <= Cells; ++y)
    {
      for (int x = 1; x <= Cells; ++x)
      {
        auto at = [&](int i, int j, int k) -> long long&
        { return prefix[(static_cast<size_t>(k) * side + j) * side + i]; };
        at(x, y, z) = counts[(static_cast<size_t>(z - 1) * Cells + (y - 1)) * Cells + (x - 1)] +
          at(x - 1, y, z) + at(x, y - 1, z) + at(x, y, z - 1) - at(x - 1, y - 1, z) -
          at(x - 1, y, z - 1) - at(x, y - 1, z - 1) + at(x - 1, y - 1, z - 1);
      }
    }
  }
  const int lo[3] = { 0, 0, 0 }, hi[3] = { Cells, Cells, Cells };
  this->Split(lo, hi, prefix);
  this->ChunkOfCell.assign(static_cast<size_t>(Cells) * Cells * Cells, -1);
  for (size_t k = 0; k < this->Chunks.size(); ++k)
  {
    const Chunk& ch = this->Chunks[k];
    for (int z = ch.Lo[2]; z < ch.Hi[2]; ++z)
    {
      for (int y = ch.Lo[1]; y < ch.Hi[1]; ++y)
      {
        for (int x = ch.Lo[0]; x < ch.Hi[0]; ++x)
        {
          this->ChunkOfCell[(static_cast<size_t>(z) * Cells + y) * Cells + x] = static_cast<int>(k);
        }
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool SplatStream::Impl::Distribute()
{
  const size_t rec = this->PointRecord();
  std::vector<unsigned char> block(static_cast<size_t>(Block) * rec);
  const long long n = this->Stats.Points;
  auto spillPass = [&](const std::function<bool(long long, const unsigned char*)>& each)
  {
    if (!this->Spill.Flush() || !this->Spill.Seek(0))
    {
      return false;
    }
    for (long long first = 0; first < n; first += Block)
    {
      const long long count = std::min(Block, n - first);
      if (!this->Spill.Read(block.data(), static_cast<size_t>(count) * rec))
      {
        return false;
      }
      for (long long i = 0; i < count; ++i)
      {
        if (!each(first + i, &block[static_cast<size_t>(i) * rec]))
        {
          return false;
        }
      }
    }
    return true;
  };
  // Counts per cell, then the chunks.
  for (int c = 0; c < 3; ++c)
  {
    const double extent = this->Hi[c] - this->Lo[c];
    this->CellSize[c] = extent > 0.0 ? extent / Cells : 1.0;
  }
  std::vector<long long> counts(static_cast<size_t>(Cells) * Cells * Cells, 0);
  if (!spillPass(
        [&](long long, const unsigned char* r)
        {
          double p[3];
          std::memcpy(p, r, 24);
          ++counts[this->CellIndex(p)];
          return true;
        }))
  {
    return this->Fail("cannot read the scratch file in " + this->Directory.string());
  }
  this->Plan(counts);
  // Each point to its chunk's file, with its id.
  std::vector<std::unique_ptr<Scratch>> files(this->Chunks.size());
  std::vector<std::vector<unsigned char>> pending(this->Chunks.size());
  const size_t crec = this->ChunkRecord();
  for (size_t k = 0; k < files.size(); ++k)
  {
    files[k] = std::make_unique<Scratch>();
    if (!files[k]->Open(this->ChunkPath(k), "wb"))
    {
      return this->Fail("cannot write the chunk files in " + this->Directory.string());
    }
  }
  // At most ~64 MiB waiting in memory over all chunks.
  const size_t flushAt =
    std::max<size_t>(crec * 256, (64u << 20) / std::max<size_t>(1, files.size()));
  bool ok = spillPass(
    [&](long long id, const unsigned char* r)
    {
      double p[3];
      std::memcpy(p, r, 24);
      const int k = this->ChunkOfCell[this->CellIndex(p)];
      std::vector<unsigned char>& out = pending[k];
      const size_t at = out.size();
      out.resize(at + crec);
      std::memcpy(&out[at], &id, 8);
      std::memcpy(&out[at + 8], r, rec);
      if (out.size() >= flushAt)
      {
        if (!files[k]->Write(out.data(), out.size()))
        {
          return false;
        }
        this->Stats.ScratchBytes += static_cast<double>(out.size());
        out.clear();
      }
      return true;
    });
  for (size_t k = 0; ok && k < files.size(); ++k)
  {
    ok = files[k]->Write(pending[k].data(), pending[k].size());
    this->Stats.ScratchBytes += static_cast<double>(pending[k].size());
    files[k]->Close();
  }
  if (!ok)
  {
    return this->Fail(
      "cannot write the chunk files in " + this->Directory.string() + " (disk full?)");
  }
  // The spill is read no more.
  this->Spill.Close();
  std::error_code ec;
  std::filesystem::remove(this->Directory / "spill.bin", ec);
  return true;
}

//------------------------------------------------------------------------------
bool SplatStream::Impl::ReadChunk(size_t c, const double* keep, PointBatch& into)
{
  Scratch file;
  if (!file.Open(this->ChunkPath(c), "rb"))
  {
    return this->Fail("cannot read the chunk file " + this->ChunkPath(c));
  }
  const size_t crec = this->ChunkRecord();
  const int nc = this->HasNormals ? 3 : 0;
  std::vector<unsigned char> block(static_cast<size_t>(Block) * crec);
  const long long n = this->Chunks[c].Count;
  for (long long first = 0; first < n; first += Block)
  {
    const long long count = std::min(Block, n - first);
    if (!file.Read(block.data(), static_cast<size_t>(count) * crec))
    {
      return this->Fail("cannot read the chunk file " + this->ChunkPath(c));
    }
    for (long long i = 0; i < count; ++i)
    {
      const unsigned char* r = &block[static_cast<size_t>(i) * crec];
      double p[3];
      std::memcpy(p, r + 8, 24);
      if (keep && !Inside(keep, p))
      {
        continue;
      }
      long long id;
      std::memcpy(&id, r, 8);
      into.Ids.push_back(id);
      into.XYZ.insert(into.XYZ.end(), p, p + 3);
      float values[3];
      for (int k = 0; k < nc; ++k)
      {
        std::memcpy(&values[k], r + 32 + 4 * k, 4);
      }
      into.Normals.insert(into.Normals.end(), values, values + nc);
      if (this->A > 0)
      {
        const size_t at = into.Attributes.size();
        into.Attributes.resize(at + this->A);
        std::memcpy(into.Attributes.data() + at, r + 32 + 4 * nc, 4 * static_cast<size_t>(this->A));
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
double SplatStream::Impl::HaloWidth(const PointBatch& own, const PointIndex& index) const
{
  // The radius of the widest fit neighbourhood among a sample of the
  // chunk's points, grown by the widest disc: a splat reaches no farther
  // from its point. A chunk too small to tell gets its own diagonal.
  const BuildParameters& b = this->Params.Build;
  const long long n = own.Size();
  const int k = std::max(b.Fit.NumberOfNeighbors, b.Fit.FeatureSizeNeighbors + 1) + 1;
  const double wide = std::max(1.0, b.MaximumFeatureScale);
  const double s = std::max(b.Quality, b.Levels > 1 ? b.CoarsestQuality : b.Quality);
  if (n <= k)
  {
    double box[6] = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
    for (long long i = 0; i < n; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        box[2 * c] = std::min(box[2 * c], own.XYZ[3 * i + c]);
        box[2 * c + 1] = std::max(box[2 * c + 1], own.XYZ[3 * i + c]);
      }
    }
    const double d = std::sqrt((box[1] - box[0]) * (box[1] - box[0]) +
      (box[3] - box[2]) * (box[3] - box[2]) + (box[5] - box[4]) * (box[5] - box[4]));
    return n > 1 ? 4.0 * d : 0.0;
  }
  std::vector<int> ids;
  std::vector<double> d2;
  double widest = 0.0;
  const long long step = std::max<long long>(1, n / HaloSamples);
  for (long long i = 0; i < n; i += step)
  {
    index.Nearest(&own.XYZ[3 * i], k, ids, d2);
    if (!d2.empty())
    {
      widest = std::max(widest, std::sqrt(d2.back()));
    }
  }
  return HaloMargin * wide * (1.0 + std::max(1.0, b.RadiusScale) * s) * widest;
}

//------------------------------------------------------------------------------
void SplatStream::Impl::Orient(size_t c,
  const double box[6],
  std::vector<BuiltSplat>& splats,
  std::vector<long long>& nodes)
{
  // Copies of the earlier chunks' splats around this one, as they were
  // written, so that the parts here take the side of those they meet.
  std::vector<Splat> copies;
  std::vector<long long> copyOf;
  for (size_t d = 0; d < c; ++d)
  {
    if (!Overlaps(this->Chunks[d].Box, box))
    {
      continue;
    }
    for (long long j = this->Chunks[d].SplatBegin; j < this->Chunks[d].SplatEnd; ++j)
    {
      if (!Inside(box, &this->Origins[3 * j]) || this->Node[j] < 0)
      {
        continue;
      }
      Splat s;
      for (int k = 0; k < 3; ++k)
      {
        s.Frame.Origin[k] = this->Origins[3 * j + k];
        s.Frame.Normal[k] = this->Normals[3 * j + k];
      }
      // Any tangent frame: only the normal's side matters here.
      const double* nn = s.Frame.Normal;
      const double t[3] = { std::abs(nn[0]) < 0.9 ? 0.0 : -nn[1],
        std::abs(nn[0]) < 0.9 ? nn[2] : nn[0],
        std::abs(nn[0]) < 0.9 ? -nn[1] : 0.0 };
      const double tl = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
      for (int k = 0; k < 3; ++k)
      {
        s.Frame.Tangent[k] = tl > 0.0 ? t[k] / tl : (k == 0 ? 1.0 : 0.0);
      }
      s.Frame.Bitangent[0] = nn[1] * s.Frame.Tangent[2] - nn[2] * s.Frame.Tangent[1];
      s.Frame.Bitangent[1] = nn[2] * s.Frame.Tangent[0] - nn[0] * s.Frame.Tangent[2];
      s.Frame.Bitangent[2] = nn[0] * s.Frame.Tangent[1] - nn[1] * s.Frame.Tangent[0];
      s.Frame.Scale = this->Scales[j];
      s.Fit.Degree = 1;
      s.Fit.Status = FitStatus::Ok;
      copies.push_back(s);
      copyOf.push_back(j);
    }
  }
  const size_t own = splats.size();
  std::vector<Splat*> all;
  std::vector<double> radii;
  all.reserve(own + copies.size());
  radii.reserve(own + copies.size());
  for (BuiltSplat& b : splats)
  {
    all.push_back(&b.Fitted);
    radii.push_back(b.Radius);
  }
  for (size_t k = 0; k < copies.size(); ++k)
  {
    all.push_back(&copies[k]);
    radii.push_back(this->Radii[copyOf[k]]);
  }
  std::vector<long long> partOf;
  long long parts = 0;
  // Sides along the trees only: flux and views see a piece of a closed
  // surface through its cut; the whole decides (FinishOrientation).
  OrientSplats(all, 8, &parts, &radii, &partOf, false);
  // One node per part; each part joins the earlier parts its copies belong
  // to, facing as most of their copies say, the strongest vote first.
  std::vector<long long> node(static_cast<size_t>(parts), -1);
  for (long long p = 0; p < parts; ++p)
  {
    node[p] = this->Forest.Add();
  }
  std::vector<std::vector<std::pair<long long, double>>> votes(static_cast<size_t>(parts));
  for (size_t k = 0; k < copies.size(); ++k)
  {
    const long long j = copyOf[k];
    char parity = 0;
    const long long root = this->Forest.Find(this->Node[j], parity);
    double agree = 0.0;
    for (int i = 0; i < 3; ++i)
    {
      agree += copies[k].Frame.Normal[i] * this->Normals[3 * j + i];
    }
    // +1: the part faces as the copy's root does.
    const double side = (agree >= 0.0 ? 1.0 : -1.0) * (parity ? -1.0 : 1.0);
    auto& v = votes[partOf[own + k]];
    auto it = std::find_if(v.begin(), v.end(), [&](const auto& e) { return e.first == root; });
    if (it == v.end())
    {
      v.emplace_back(root, side);
    }
    else
    {
      it->second += side;
    }
  }
  for (long long p = 0; p < parts; ++p)
  {
    auto& v = votes[p];
    std::sort(v.begin(),
      v.end(),
      [](const auto& a, const auto& b) { return std::abs(a.second) > std::abs(b.second); });
    for (const auto& e : v)
    {
      this->Forest.Join(node[p], e.first, e.second < 0.0 ? 1 : 0);
    }
  }
  nodes.resize(own);
  for (size_t k = 0; k < own; ++k)
  {
    nodes[k] = node[partOf[k]];
  }
}

//------------------------------------------------------------------------------
void SplatStream::Impl::FinishOrientation()
{
  // Each joined part as OrientSplats orients a part: closed, by its flux;
  // open, with its highest splat facing up.
  const long long nodes = static_cast<long long>(this->Forest.Parent.size());
  std::vector<long long> rootOf(static_cast<size_t>(nodes));
  std::vector<char> parityOf(static_cast<size_t>(nodes));
  for (long long i = 0; i < nodes; ++i)
  {
    rootOf[i] = this->Forest.Find(i, parityOf[i]);
  }
  struct Sums
  {
    double W = 0, C[3] = { 0, 0, 0 }, Flux = 0, Magnitude = 0, Area[3] = { 0, 0, 0 };
    double Top = -1e300, TopNz = 0;
    long long Count = 0;
  };
  std::vector<Sums> sums(static_cast<size_t>(nodes));
  const long long n = this->SplatCount;
  auto facing = [&](long long j, double m[3])
  {
    const double sign = parityOf[this->Node[j]] ? -1.0 : 1.0;
    for (int c = 0; c < 3; ++c)
    {
      m[c] = sign * this->Normals[3 * j + c];
    }
  };
  for (long long j = 0; j < n; ++j)
  {
    if (this->Node[j] < 0)
    {
      continue;
    }
    Sums& s = sums[rootOf[this->Node[j]]];
    const double w = static_cast<double>(this->Scales[j]) * this->Scales[j];
    for (int c = 0; c < 3; ++c)
    {
      s.C[c] += w * this->Origins[3 * j + c];
    }
    s.W += w;
    ++s.Count;
  }
  for (long long j = 0; j < n; ++j)
  {
    if (this->Node[j] < 0)
    {
      continue;
    }
    Sums& s = sums[rootOf[this->Node[j]]];
    const double w = static_cast<double>(this->Scales[j]) * this->Scales[j];
    double m[3];
    facing(j, m);
    double along = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      along += (this->Origins[3 * j + c] - s.C[c] / s.W) * m[c];
      s.Area[c] += w * m[c];
    }
    s.Flux += w * along;
    s.Magnitude += w * std::abs(along);
    if (this->Origins[3 * j + 2] > s.Top)
    {
      s.Top = this->Origins[3 * j + 2];
      s.TopNz = m[2];
    }
  }
  std::vector<char> rootFlip(static_cast<size_t>(nodes), 0);
  this->Stats.Parts = 0;
  this->Stats.FlippedParts = 0;
  for (long long r = 0; r < nodes; ++r)
  {
    const Sums& s = sums[r];
    if (s.Count == 0)
    {
      continue;
    }
    ++this->Stats.Parts;
    const double open = s.W > 0.0
      ? std::sqrt(s.Area[0] * s.Area[0] + s.Area[1] * s.Area[1] + s.Area[2] * s.Area[2]) / s.W
      : 1.0;
    const bool closed = s.Count >= 4 && open < OrientationOpenSheet;
    rootFlip[r] =
      closed ? (s.Flux < -OrientationDecisive * s.Magnitude ? 1 : 0) : (s.TopNz < 0.0 ? 1 : 0);
    this->Stats.FlippedParts += rootFlip[r];
  }
  this->FinalFlip.assign(static_cast<size_t>(nodes), 0);
  for (long long i = 0; i < nodes; ++i)
  {
    this->FinalFlip[i] = static_cast<char>(parityOf[i] ^ rootFlip[rootOf[i]]);
  }
}

//------------------------------------------------------------------------------
bool SplatStream::Impl::FitChunk(size_t c,
  const std::function<void(double)>& progress,
  const std::atomic<bool>* abort)
{
  Chunk& chunk = this->Chunks[c];
  PointBatch points;
  if (!this->ReadChunk(c, nullptr, points))
  {
    return false;
  }
  const long long own = points.Size();
  double w = 0.0;
  {
    // The own points' index, before the halo's points move them.
    const PointIndex index(points.XYZ.data(), own);
    // ToleranceUnit::Automatic: the first chunk's own points decide for every chunk.
    if (this->Params.Build.Tolerance == ToleranceUnit::Automatic)
    {
      this->Stats.Noise = MeasureSampleNoise(points.XYZ.data(), own, index);
      this->Params.Build = ResolveTolerance(this->Params.Build, this->Stats.Noise);
    }
    this->Stats.Tolerance = this->Params.Build.Tolerance;
    w = this->HaloWidth(points, index);
  }
  double box[6];
  for (int k = 0; k < 3; ++k)
  {
    box[2 * k] = chunk.Box[2 * k] - w;
    box[2 * k + 1] = chunk.Box[2 * k + 1] + w;
  }
  for (size_t d = 0; d < this->Chunks.size(); ++d)
  {
    if (d != c && Overlaps(this->Chunks[d].Box, box) && !this->ReadChunk(d, box, points))
    {
      return false;
    }
  }
  const long long loaded = points.Size();
  this->Stats.HaloPoints += loaded - own;
  this->Stats.LargestChunk = std::max(this->Stats.LargestChunk, loaded);

  // Coincident points merged (own points first, so a chunk keeps its own).
  const double diagonal = std::sqrt((this->Hi[0] - this->Lo[0]) * (this->Hi[0] - this->Lo[0]) +
    (this->Hi[1] - this->Lo[1]) * (this->Hi[1] - this->Lo[1]) +
    (this->Hi[2] - this->Lo[2]) * (this->Hi[2] - this->Lo[2]));
  std::vector<long long> keep = this->Params.MergeTolerance > 0.0 && loaded > 1
    ? UniquePoints(points.XYZ.data(), loaded, this->Params.MergeTolerance * diagonal)
    : std::vector<long long>();
  if (keep.empty())
  {
    keep.resize(static_cast<size_t>(loaded));
    std::iota(keep.begin(), keep.end(), 0LL);
  }
  const long long n = static_cast<long long>(keep.size());
  std::vector<double> xyz(static_cast<size_t>(3 * n)), normals;
  std::vector<unsigned char> halo(static_cast<size_t>(n)), claimed(static_cast<size_t>(n), 0);
  std::vector<long long> ids(static_cast<size_t>(n));
  if (this->HasNormals)
  {
    normals.resize(static_cast<size_t>(3 * n));
  }
  long long ownKept = 0;
  for (long long k = 0; k < n; ++k)
  {
    const long long i = keep[k];
    std::copy(&points.XYZ[3 * i], &points.XYZ[3 * i] + 3, &xyz[3 * k]);
    for (int j = 0; this->HasNormals && j < 3; ++j)
    {
      normals[3 * k + j] = points.Normals[3 * i + j];
    }
    ids[k] = points.Ids[i];
    halo[k] = i >= own ? 1 : 0;
    ownKept += i < own ? 1 : 0;
    claimed[k] = i < own ? this->Claims[points.Ids[i]] : 0;
  }
  this->Stats.Merged += own - ownKept;
  if (ownKept == 0)
  {
    return true;
  }

  BuildParameters build = this->Params.Build;
  build.KeepWeights = this->A > 0;
  ChunkContext context;
  context.Halo = halo.data();
  context.ClaimedBefore = claimed.data();
  BuildResult result = n >= 3 ? BuildSplats(xyz.data(),
                                  n,
                                  this->HasNormals ? normals.data() : nullptr,
                                  build,
                                  progress,
                                  abort,
                                  &context)
                              : BuildResult();
  if (this->LevelQuality.empty() && !result.LevelQuality.empty())
  {
    this->LevelQuality = result.LevelQuality;
  }
  for (size_t level = 0; level < context.HaloClaims.size() && level < 8; ++level)
  {
    for (long long k : context.HaloClaims[level])
    {
      this->Claims[ids[k]] |= static_cast<unsigned char>(1u << level);
    }
  }
  this->Stats.Degenerate += result.Degenerate;
  this->Stats.Reduced += result.Reduced;

  std::vector<long long> nodes(result.Splats.size(), -1);
  if (!this->HasNormals && this->Params.Orient)
  {
    this->Orient(c, box, result.Splats, nodes);
  }

  // Attributes, MLS-weighted, and the records.
  const size_t rec = this->SplatRecord();
  std::vector<unsigned char> out(rec * result.Splats.size());
  std::vector<float> carried(static_cast<size_t>(this->A));
  chunk.SplatBegin = this->SplatCount;
  for (size_t k = 0; k < result.Splats.size(); ++k)
  {
    const BuiltSplat& b = result.Splats[k];
    StreamedSplat s;
    s.Fitted = b.Fitted;
    s.Radius = b.Radius;
    s.MaxDeviation = b.MaxDeviation;
    s.NominalRadius = b.NominalRadius;
    s.Tolerance = b.Tolerance * b.Fitted.Spacing;
    s.Level = b.Level;
    s.Source = b.Source >= 0 ? ids[b.Source] : -1;
    std::fill(carried.begin(), carried.end(), 0.0f);
    double sum = 0.0;
    for (size_t j = 0; j < b.Weights.size(); ++j)
    {
      sum += b.Weights[j];
    }
    for (size_t j = 0; this->A > 0 && j < b.Ids.size(); ++j)
    {
      const double wj = sum > 0.0 ? b.Weights[j] / sum : 1.0 / b.Ids.size();
      const long long i = keep[b.Ids[j]];
      for (int a = 0; a < this->A; ++a)
      {
        carried[a] += static_cast<float>(wj * points.Attributes[i * this->A + a]);
      }
    }
    std::memcpy(&out[k * rec], &s, sizeof(s));
    if (!carried.empty())
    {
      std::memcpy(&out[k * rec + sizeof(s)], carried.data(), 4 * carried.size());
    }
    for (int j = 0; j < 3; ++j)
    {
      this->Origins.push_back(s.Fitted.Frame.Origin[j]);
      this->Normals.push_back(static_cast<float>(s.Fitted.Frame.Normal[j]));
    }
    this->Radii.push_back(s.Radius);
    this->Levels.push_back(s.Level);
    this->Scales.push_back(static_cast<float>(s.Fitted.Frame.Scale));
    this->Node.push_back(nodes[k]);
  }
  if (!this->Store.Write(out.data(), out.size()))
  {
    return this->Fail(
      "cannot write the splats' scratch file in " + this->Directory.string() + " (disk full?)");
  }
  this->Stats.ScratchBytes += static_cast<double>(out.size());
  this->SplatCount += static_cast<long long>(result.Splats.size());
  chunk.SplatEnd = this->SplatCount;
  // This chunk's points are never read again: its file is removed once no
  // later chunk's halo reaches it (then, at the end).
  return true;
}

//------------------------------------------------------------------------------
bool SplatStream::Run(const std::function<void(double)>& progress, const std::atomic<bool>* abort)
{
  if (!P->Error.empty())
  {
    return false;
  }
  if (P->Stats.Points == 0)
  {
    P->Oriented = P->HasNormals;
    return true;
  }
  if (!P->Distribute())
  {
    return false;
  }
  P->Claims.assign(static_cast<size_t>(P->Stats.Points), 0);
  if (!P->Store.Open((P->Directory / "splats.bin").string(), "w+b"))
  {
    return P->Fail("cannot write the splats' scratch file in " + P->Directory.string());
  }
  const size_t chunks = P->Chunks.size();
  for (size_t c = 0; c < chunks; ++c)
  {
    if (abort && abort->load())
    {
      break;
    }
    auto inner = [&](double f)
    {
      if (progress)
      {
        progress((static_cast<double>(c) + f) / static_cast<double>(chunks));
      }
    };
    if (!P->FitChunk(c, inner, abort))
    {
      return false;
    }
    ++P->Stats.Chunks;
  }
  for (size_t c = 0; c < chunks; ++c)
  {
    std::error_code ec;
    std::filesystem::remove(P->ChunkPath(c), ec);
  }
  if (!P->Store.Flush())
  {
    return P->Fail("cannot write the splats' scratch file in " + P->Directory.string());
  }
  P->Oriented = P->HasNormals || P->Params.Orient;
  if (!P->HasNormals && P->Params.Orient)
  {
    P->FinishOrientation();
  }
  if (P->LevelQuality.empty())
  {
    P->LevelQuality.push_back(P->Params.Build.Quality);
  }
  if (progress)
  {
    progress(1.0);
  }
  return true;
}

//------------------------------------------------------------------------------
bool SplatStream::ReadSplats(long long first,
  long long count,
  std::vector<StreamedSplat>& splats,
  std::vector<float>& attributes) const
{
  splats.clear();
  attributes.clear();
  first = std::max(0LL, first);
  count = std::max(0LL, std::min(count, P->SplatCount - first));
  if (count == 0)
  {
    return true;
  }
  const size_t rec = P->SplatRecord();
  std::vector<unsigned char> buffer(rec * static_cast<size_t>(count));
  if (!P->Store.Seek(static_cast<long long>(rec) * first) ||
    !P->Store.Read(buffer.data(), buffer.size()))
  {
    return false;
  }
  splats.resize(static_cast<size_t>(count));
  attributes.resize(static_cast<size_t>(count) * P->A);
  for (long long k = 0; k < count; ++k)
  {
    std::memcpy(&splats[k], &buffer[k * rec], sizeof(StreamedSplat));
    if (P->A > 0)
    {
      std::memcpy(attributes.data() + k * P->A, &buffer[k * rec + sizeof(StreamedSplat)], 4 * P->A);
    }
    const long long node = P->Node[first + k];
    if (node >= 0 && !P->FinalFlip.empty() && P->FinalFlip[node])
    {
      FlipSplat(splats[k].Fitted);
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool SplatStream::ReadSplatsAt(const std::vector<long long>& ids,
  std::vector<StreamedSplat>& splats,
  std::vector<float>& attributes) const
{
  // Sorted, then read in runs of consecutive records.
  std::vector<size_t> order(ids.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return ids[a] < ids[b]; });
  splats.resize(ids.size());
  attributes.resize(ids.size() * P->A);
  std::vector<StreamedSplat> run;
  std::vector<float> runAttributes;
  for (size_t k = 0; k < order.size();)
  {
    size_t end = k + 1;
    while (end < order.size() && ids[order[end]] <= ids[order[end - 1]] + 1)
    {
      ++end;
    }
    const long long first = ids[order[k]];
    if (first < 0 || ids[order[end - 1]] >= P->SplatCount ||
      !this->ReadSplats(first, ids[order[end - 1]] - first + 1, run, runAttributes))
    {
      return false;
    }
    for (size_t j = k; j < end; ++j)
    {
      const size_t r = static_cast<size_t>(ids[order[j]] - first);
      splats[order[j]] = run[r];
      std::copy(runAttributes.begin() + r * P->A,
        runAttributes.begin() + (r + 1) * P->A,
        attributes.begin() + order[j] * P->A);
    }
    k = end;
  }
  return true;
}

long long SplatStream::NumberOfSplats() const
{
  return P->SplatCount;
}
const std::vector<double>& SplatStream::Origins() const
{
  return P->Origins;
}
const std::vector<double>& SplatStream::Radii() const
{
  return P->Radii;
}
const std::vector<int>& SplatStream::Levels() const
{
  return P->Levels;
}
const std::vector<double>& SplatStream::LevelQuality() const
{
  return P->LevelQuality;
}
bool SplatStream::Oriented() const
{
  return P->Oriented;
}
int SplatStream::Attributes() const
{
  return P->A;
}
const StreamStatistics& SplatStream::Statistics() const
{
  return P->Stats;
}
const std::string& SplatStream::Error() const
{
  return P->Error;
}
} // namespace pointsurfaces
