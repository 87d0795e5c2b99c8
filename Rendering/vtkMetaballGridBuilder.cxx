// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkMetaballGridBuilder.h"

#include "vtkComputeShaderProgram.h"
#include "vtkMetaballGPUCounters.h"
#include "vtkMetaballGridCS.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderTimer.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderStorageBuffer.h"
#include "vtkSmartPointer.h"

#include "psMetaball.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

vtkStandardNewMacro(vtkMetaballGridBuilder);

namespace
{
enum Pass
{
  Range = 0,
  Count = 1,
  Scan = 2,
  Add = 3,
  Scatter = 4,
  Place = 5,
  SlabPass = 6,
  PairPass = 7,
  NumberOfPasses = 8
};
const unsigned int BallGroup = 256;                        // local_size_x of the per-item passes
const unsigned int ScanBlock = 1024;                       // values per scan work group
const int StatCount = 16;                                  // uints of the statistics buffer
const size_t PlaceGroupsOffset = 9 * sizeof(unsigned int); // PLACE's indirect counts

// Binding points of glsl/vtkMetaballGridCS.glsl.
enum Binding
{
  BallsBinding = 0,
  CountsBinding = 2,
  SumsBinding = 3,
  PairVoxelsBinding = 4,
  PairBallsBinding = 5,
  HistogramBinding = 6,
  CursorBinding = 7,
  VoxelBallsBinding = 8,
  StatsBinding = 9
};

// Grows `buffer` to at least `bytes` (never shrinks: the grid is rebuilt every frame).
bool Reserve(vtkShaderStorageBuffer* buffer, size_t bytes)
{
  bytes = std::max<size_t>(bytes, 16);
  const size_t room =
    std::max(bytes, std::min(bytes + bytes / 4, vtkShaderStorageBuffer::GetMaximumSize()));
  return buffer->GetSize() >= bytes || buffer->Allocate(room);
}
// The uniforms that the passes share: the view in float, the frustum and the grid.
struct PassUniforms
{
  float WorldToView[16], ViewToClip[16], Frustum[6][4];
  int Parallel, Viewport[2], TileSize, Tiles[2], Slabs;
  float ProjectionRange[2];

  PassUniforms(const double worldToView[16],
    const double viewToClip[16],
    const pointsurfaces::PerspectiveGridGeometry& geometry,
    bool parallel,
    int width,
    int height,
    int tileSize,
    int tilesX,
    int tilesY,
    int slabs)
    : Parallel(parallel ? 1 : 0)
    , Viewport{ width, height }
    , TileSize(tileSize)
    , Tiles{ tilesX, tilesY }
    , Slabs(slabs)
    , ProjectionRange{ static_cast<float>(geometry.GetProjectionNear()),
      static_cast<float>(geometry.GetProjectionFar()) }
  {
    for (int k = 0; k < 16; ++k)
    {
      this->WorldToView[k] = static_cast<float>(worldToView[k]);
      this->ViewToClip[k] = static_cast<float>(viewToClip[k]);
    }
    for (int k = 0; k < 24; ++k)
    {
      this->Frustum[k / 4][k % 4] = static_cast<float>(geometry.GetFrustumPlanes()[k]);
    }
  }

  void Set(vtkComputeShaderProgram* p) const
  {
    p->SetUniformMatrix4x4("worldToView", this->WorldToView);
    p->SetUniformMatrix4x4("viewToClip", this->ViewToClip);
    for (int k = 0; k < 6; ++k)
    {
      p->SetUniform4f(("frustum[" + std::to_string(k) + "]").c_str(), this->Frustum[k]);
    }
    p->SetUniformi("parallelProjection", this->Parallel);
    p->SetUniform2i("viewport", this->Viewport[0], this->Viewport[1]);
    p->SetUniformi("tileSize", this->TileSize);
    p->SetUniform2i("tiles", this->Tiles[0], this->Tiles[1]);
    p->SetUniformi("slabs", this->Slabs);
    p->SetUniform2f("projectionRange", this->ProjectionRange[0], this->ProjectionRange[1]);
  }
};
} // namespace

struct vtkMetaballGridBuilder::Internals
{
  vtkOpenGLRenderTimer Timer; // the build's GPU time, read a build late
  vtkNew<vtkComputeShaderProgram> Programs[NumberOfPasses];
  vtkNew<vtkShaderStorageBuffer> Counts, PairVoxels, PairBalls, Histogram, Cursor, VoxelBalls;
  vtkNew<vtkMetaballGPUCounters> StatRing; // a ring of statistics buffers, read through fences
  vtkShaderStorageBuffer* Stats = nullptr; // the current build's
  vtkIdType Balls = 0;                     // the current build's ball count
  long long CountedWaits = 0;              // StatRing's waits already counted
  unsigned int MaxGroups = 0;              // GL_MAX_COMPUTE_WORK_GROUP_COUNT in x
  std::vector<vtkSmartPointer<vtkShaderStorageBuffer>> Sums; // one per scan level

  vtkComputeShaderProgram* Use(vtkOpenGLRenderWindow* renWin, int pass)
  {
    vtkComputeShaderProgram* p = this->Programs[pass];
    return p->ReadyPass(renWin, "vtkMetaballGridCS", vtkMetaballGridCS, pass) ? p : nullptr;
  }

  // Exclusive scan of `n` uints of `values` in place, over as many levels as needed.
  bool ExclusiveScan(vtkOpenGLRenderWindow* renWin,
    vtkShaderStorageBuffer* values,
    size_t n,
    size_t level,
    bool recordMax)
  {
    const size_t groups = (n + ScanBlock - 1) / ScanBlock;
    if (this->Sums.size() <= level)
    {
      this->Sums.push_back(vtkSmartPointer<vtkShaderStorageBuffer>::New());
    }
    vtkShaderStorageBuffer* sums = this->Sums[level];
    if (!Reserve(sums, (groups + 1) * sizeof(unsigned int)))
    {
      return false;
    }
    vtkComputeShaderProgram* scan = this->Use(renWin, Scan);
    if (!scan)
    {
      return false;
    }
    values->BindBase(CountsBinding);
    sums->BindBase(SumsBinding);
    if (this->Stats)
    {
      this->Stats->BindBase(StatsBinding);
    }
    scan->SetUniformui("count", static_cast<unsigned int>(n));
    scan->SetUniformi("recordMax", recordMax ? 1 : 0);
    if (!scan->Dispatch(static_cast<unsigned int>(groups)))
    {
      return false;
    }
    if (groups > 1)
    {
      if (!this->ExclusiveScan(renWin, sums, groups, level + 1, false))
      {
        return false;
      }
      vtkComputeShaderProgram* add = this->Use(renWin, Add);
      if (!add)
      {
        return false;
      }
      values->BindBase(CountsBinding);
      sums->BindBase(SumsBinding);
      add->SetUniformui("count", static_cast<unsigned int>(n));
      if (!add->Dispatch(vtkComputeShaderProgram::GroupCount(n, BallGroup)))
      {
        return false;
      }
    }
    return true;
  }

  // Scatters the (voxel, ball) pairs and counts them per voxel, scans the
  // counts into offsets, and places each pair after its voxel's earlier ones
  // (a counting sort); the ranges and each ball's first pair are in place.
  bool SortPairs(vtkOpenGLRenderWindow* renWin,
    const PassUniforms& common,
    size_t n,
    size_t voxels,
    size_t capacity)
  {
    // Scatter the pairs and count them per voxel; scan the counts into offsets.
    bool ok = Reserve(this->PairVoxels, capacity * sizeof(unsigned int)) &&
      Reserve(this->PairBalls, capacity * sizeof(unsigned int)) &&
      Reserve(this->Histogram, (voxels + 1) * sizeof(unsigned int)) &&
      Reserve(this->Cursor, voxels * sizeof(unsigned int)) &&
      Reserve(this->VoxelBalls, capacity * sizeof(unsigned int));
    if (ok)
    {
      this->Histogram->Fill(0, (voxels + 1) * sizeof(unsigned int));
    }
    vtkComputeShaderProgram* scatter = ok ? this->Use(renWin, Scatter) : nullptr;
    ok = scatter != nullptr;
    if (ok)
    {
      common.Set(scatter);
      scatter->SetUniformui("count", static_cast<unsigned int>(n));
      scatter->SetUniformui("capacity", static_cast<unsigned int>(capacity));
      this->Counts->BindBase(CountsBinding);
      this->PairVoxels->BindBase(PairVoxelsBinding);
      this->PairBalls->BindBase(PairBallsBinding);
      this->Histogram->BindBase(HistogramBinding);
      this->Stats->BindBase(StatsBinding); // the slab range
      ok =
        scatter->Dispatch(vtkComputeShaderProgram::GroupCount(std::max<size_t>(n, 1), BallGroup));
    }
    ok = ok && this->ExclusiveScan(renWin, this->Histogram, voxels + 1, 0, true);

    // Counting sort: each pair takes the next place of its voxel, in as
    // many work groups as PAIRS wrote.
    if (ok)
    {
      glBindBuffer(GL_COPY_READ_BUFFER, this->Histogram->GetHandle());
      glBindBuffer(GL_COPY_WRITE_BUFFER, this->Cursor->GetHandle());
      glCopyBufferSubData(
        GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, voxels * sizeof(unsigned int));
      glBindBuffer(GL_COPY_READ_BUFFER, 0);
      glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
      vtkComputeShaderProgram* place = this->Use(renWin, Place);
      ok = place != nullptr;
      if (ok)
      {
        this->PairVoxels->BindBase(PairVoxelsBinding);
        this->PairBalls->BindBase(PairBallsBinding);
        this->Cursor->BindBase(CursorBinding);
        this->VoxelBalls->BindBase(VoxelBallsBinding);
        this->Stats->BindBase(StatsBinding);
        place->DispatchIndirect(this->Stats->GetHandle(), PlaceGroupsOffset);
      }
    }
    return ok;
  }

  // The slab range into stats[5..6]: `fixed` when its second value is the
  // larger, else the nearest and farthest view distance that the balls in the
  // frustum reach (the range pass).
  bool SlabRange(vtkOpenGLRenderWindow* renWin,
    const PassUniforms& common,
    size_t n,
    const double fixed[2])
  {
    const bool follow = !(fixed[1] > fixed[0]);
    bool ok = true;
    if (follow)
    {
      vtkComputeShaderProgram* range = this->Use(renWin, Range);
      ok = range != nullptr;
      if (ok)
      {
        common.Set(range);
        range->SetUniformui("count", static_cast<unsigned int>(n));
        ok =
          range->Dispatch(vtkComputeShaderProgram::GroupCount(std::max<size_t>(n, 1), BallGroup));
      }
    }
    vtkComputeShaderProgram* slabs = ok ? this->Use(renWin, SlabPass) : nullptr;
    ok = slabs != nullptr;
    if (ok)
    {
      common.Set(slabs);
      slabs->SetUniform2f("fixedRange",
        static_cast<float>(follow ? 0.0 : fixed[0]),
        static_cast<float>(follow ? 0.0 : fixed[1]));
      ok = slabs->Dispatch(1);
    }
    return ok;
  }

  // The pair count from the scanned counts, the pairs placed (at most
  // `capacity`) and the pair pass's work groups, into stats[7..11].
  bool PairCount(vtkOpenGLRenderWindow* renWin, size_t n, size_t capacity)
  {
    vtkComputeShaderProgram* pairs = this->Use(renWin, PairPass);
    if (!pairs)
    {
      return false;
    }
    this->Counts->BindBase(CountsBinding);
    this->Stats->BindBase(StatsBinding);
    pairs->SetUniformui("count", static_cast<unsigned int>(n));
    pairs->SetUniformui("capacity", static_cast<unsigned int>(capacity));
    if (this->MaxGroups == 0)
    {
      this->MaxGroups =
        static_cast<unsigned int>(vtkComputeShaderProgram::GetMaxWorkGroupCount(renWin));
    }
    pairs->SetUniformui("maxGroups", this->MaxGroups);
    return pairs->Dispatch(1);
  }
};

//------------------------------------------------------------------------------
double vtkMetaballGridBuilder::GetBuildTime()
{
  const double seconds = this->Impl->Timer.GetReusableElapsedSeconds();
  if (seconds > 0.0)
  {
    this->BuildTime = 1000.0 * seconds;
  }
  return this->BuildTime;
}

//------------------------------------------------------------------------------
vtkMetaballGridBuilder::vtkMetaballGridBuilder()
  : Impl(new Internals)
{
}

//------------------------------------------------------------------------------
vtkMetaballGridBuilder::~vtkMetaballGridBuilder() = default;

//------------------------------------------------------------------------------
vtkShaderStorageBuffer* vtkMetaballGridBuilder::GetVoxelOffsets()
{
  return this->Impl->Histogram;
}

//------------------------------------------------------------------------------
vtkShaderStorageBuffer* vtkMetaballGridBuilder::GetVoxelBalls()
{
  return this->Impl->VoxelBalls;
}

//------------------------------------------------------------------------------
vtkShaderStorageBuffer* vtkMetaballGridBuilder::GetGridStatistics()
{
  return this->Impl->Stats;
}

//------------------------------------------------------------------------------
bool vtkMetaballGridBuilder::ExclusiveScan(vtkOpenGLRenderWindow* renWin,
  vtkShaderStorageBuffer* values,
  size_t n)
{
  const bool ok = this->Impl->ExclusiveScan(renWin, values, n, 0, false);
  this->Impl->Programs[0]->Unbind();
  return ok;
}

//------------------------------------------------------------------------------
void vtkMetaballGridBuilder::ReservePairs(vtkIdType pairs)
{
  // Build() clamps it to the storage buffer limit of its context.
  this->PairCapacity = std::max(this->PairCapacity, pairs);
}

//------------------------------------------------------------------------------
double vtkMetaballGridBuilder::GetSlabPlane(int k)
{
  Internals& in = *this->Impl;
  if (!this->SlabPlanesKnown && in.Stats)
  {
    unsigned int bits[2] = { 0, 0 };
    if (in.Stats->Download(bits, sizeof(bits), 5 * sizeof(unsigned int)))
    {
      float range[2];
      std::memcpy(range, bits, sizeof(range));
      this->SetSlabPlanes(range[0], range[1]);
      ++this->NumberOfReadBacks;
    }
  }
  return k >= 0 && k < static_cast<int>(this->SlabPlanes.size()) ? this->SlabPlanes[k] : 0.0;
}

//------------------------------------------------------------------------------
void vtkMetaballGridBuilder::SetSlabPlanes(double nearD, double farD)
{
  this->SlabPlanes.resize(this->Slabs + 1);
  for (int k = 0; k <= this->Slabs; ++k)
  {
    this->SlabPlanes[k] = nearD + (farD - nearD) * k / this->Slabs;
  }
  this->SlabPlanes.back() = farD;
  this->SlabPlanesKnown = true;
}

//------------------------------------------------------------------------------
void vtkMetaballGridBuilder::Take(const unsigned int* stats)
{
  // The statistics of a finished build: its counts, and room for the next.
  const vtkIdType needed = stats[7], placed = stats[8];
  this->NumberOfPairs = needed;
  this->NumberOfCulledBalls = stats[2];
  this->NumberOfInvalidBalls = stats[3];
  this->MaximumBallsPerVoxel = stats[4];
  std::memcpy(this->TakenRange, stats + 5, sizeof(this->TakenRange));
  const vtkIdType most =
    static_cast<vtkIdType>(vtkShaderStorageBuffer::GetMaximumSize() / sizeof(unsigned int));
  if (placed < needed)
  {
    ++this->NumberOfOverflows;
    if (needed > most)
    {
      vtkWarningMacro(<< needed << " (voxel, ball) pairs exceed the shader storage buffer limit of "
                      << vtkShaderStorageBuffer::GetMaximumSize() << " bytes: the grid held "
                      << placed << " and balls were left out; use larger tiles or fewer slabs.");
    }
  }
  if (4 * needed > 3 * this->PairCapacity)
  {
    this->ReservePairs(std::min(needed + needed / 2, most));
  }
}

//------------------------------------------------------------------------------
bool vtkMetaballGridBuilder::Build(vtkOpenGLRenderWindow* renWin,
  vtkShaderStorageBuffer* balls,
  vtkIdType count,
  const double worldToView[16],
  const double viewToClip[16],
  bool parallel,
  int width,
  int height)
{
  Internals& in = *this->Impl;
  if (!renWin || !balls || count < 0 || width <= 0 || height <= 0)
  {
    vtkErrorMacro(<< "Build needs a window, a ball buffer and a viewport.");
    return false;
  }
  this->TilesX = (width + this->TileSize - 1) / this->TileSize;
  this->TilesY = (height + this->TileSize - 1) / this->TileSize;
  const size_t voxels = static_cast<size_t>(this->TilesX) * this->TilesY * this->Slabs;
  const size_t n = static_cast<size_t>(count);
  const size_t maxBytes = vtkShaderStorageBuffer::GetMaximumSize();
  if (n + 1 > maxBytes / (4 * sizeof(float)) || voxels + 1 > maxBytes / sizeof(unsigned int))
  {
    vtkErrorMacro(<< count << " balls or " << voxels
                  << " voxels exceed the shader storage buffer limit of " << maxBytes << " bytes.");
    return false;
  }
  in.Timer.ReusableStart();

  pointsurfaces::PerspectiveGridGeometry geometry(
    viewToClip, parallel, width, height, this->TileSize, this->Slabs);
  const PassUniforms common(worldToView,
    viewToClip,
    geometry,
    parallel,
    width,
    height,
    this->TileSize,
    this->TilesX,
    this->TilesY,
    this->Slabs);

  // This build's statistics buffer; the finished builds' statistics come in
  // (never waiting unless the GPU is a whole ring behind).
  const auto take = [this](const unsigned int* stats) { this->Take(stats); };
  in.StatRing->SetSize(StatCount);
  const float big = std::numeric_limits<float>::max();
  unsigned int initial[StatCount] = {};
  std::memcpy(&initial[0], &big, sizeof(float));
  in.StatRing->BeginFrame(take, initial);
  in.Stats = in.StatRing->GetFrameBuffer();
  this->SlabPlanesKnown = false;
  if (in.Balls > 0 && count > 2 * in.Balls)
  {
    // Many more balls than the last build: room in proportion, before the
    // counts say so.
    this->ReservePairs(
      static_cast<vtkIdType>(static_cast<double>(this->NumberOfPairs) / in.Balls * count) + count);
  }
  in.Balls = count;
  balls->BindBase(BallsBinding);
  in.Stats->BindBase(StatsBinding);

  // The slab planes: fixed, or from the balls in view, on the GPU.
  bool ok = in.SlabRange(renWin, common, n, this->SlabRange);

  // Count voxels per ball, then scan into each ball's first pair.
  ok = ok && Reserve(in.Counts, (n + 1) * sizeof(unsigned int));
  vtkComputeShaderProgram* countPass = ok ? in.Use(renWin, Count) : nullptr;
  ok = countPass != nullptr;
  if (ok)
  {
    common.Set(countPass);
    countPass->SetUniformui("count", static_cast<unsigned int>(n));
    balls->BindBase(BallsBinding);
    in.Counts->BindBase(CountsBinding);
    in.Stats->BindBase(StatsBinding);
    ok = countPass->Dispatch(vtkComputeShaderProgram::GroupCount(n + 1, BallGroup));
  }
  ok = ok && in.ExclusiveScan(renWin, in.Counts, n + 1, 0, false);
  if (ok && this->PairCapacity == 0)
  {
    // The first build has no earlier count to size the pair buffers: it
    // reads its own back, once.
    unsigned int pairs = 0;
    ok = in.Counts->Download(&pairs, sizeof(pairs), n * sizeof(unsigned int));
    ++this->NumberOfReadBacks;
    const vtkIdType needed = pairs;
    this->ReservePairs(std::max<vtkIdType>(needed + needed / 2, 1024));
  }
  // Within one storage buffer, and within the uints the shaders count in.
  const size_t capacity = std::min({ static_cast<size_t>(this->PairCapacity),
    maxBytes / sizeof(unsigned int),
    static_cast<size_t>(UINT_MAX - 1) });
  this->PairCapacity = static_cast<vtkIdType>(capacity);
  ok = ok && in.PairCount(renWin, n, capacity);
  ok = ok && in.SortPairs(renWin, common, n, voxels, capacity);
  in.Programs[0]->Unbind();
  in.Timer.ReusableStop();

  // With statistics, this build's at once, and again with room when it
  // overflowed.
  const vtkIdType overflows = this->NumberOfOverflows;
  in.StatRing->EndFrame(take, this->CollectStatistics);
  this->NumberOfReadBacks += in.StatRing->GetNumberOfWaits() - in.CountedWaits;
  in.CountedWaits = in.StatRing->GetNumberOfWaits();
  if (!ok)
  {
    vtkErrorMacro(<< "The metaball grid build failed (see the messages above).");
    return false;
  }
  if (this->CollectStatistics)
  {
    ++this->NumberOfReadBacks;
    this->SetSlabPlanes(this->TakenRange[0], this->TakenRange[1]);
    if (this->NumberOfOverflows > overflows &&
      this->NumberOfPairs <= static_cast<vtkIdType>(maxBytes / sizeof(unsigned int)))
    {
      return this->Build(renWin, balls, count, worldToView, viewToClip, parallel, width, height);
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMetaballGridBuilder::ReleaseGraphicsResources(vtkWindow* win)
{
  Internals& in = *this->Impl;
  in.Timer.ReleaseGraphicsResources();
  for (auto& p : in.Programs)
  {
    p->ReleaseGraphicsResources(win);
  }
  for (vtkShaderStorageBuffer* b : { in.Counts.GetPointer(),
         in.PairVoxels.GetPointer(),
         in.PairBalls.GetPointer(),
         in.Histogram.GetPointer(),
         in.Cursor.GetPointer(),
         in.VoxelBalls.GetPointer() })
  {
    b->ReleaseGraphicsResources(win);
  }
  in.StatRing->ReleaseGraphicsResources(win);
  in.Stats = nullptr;
  in.Balls = 0;
  in.MaxGroups = 0;
  this->PairCapacity = 0;
  this->SlabPlanesKnown = false;
  for (auto& b : in.Sums)
  {
    b->ReleaseGraphicsResources(win);
  }
  in.Sums.clear();
}

//------------------------------------------------------------------------------
void vtkMetaballGridBuilder::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TileSize: " << this->TileSize << "\n";
  os << indent << "Slabs: " << this->Slabs << "\n";
  os << indent << "SlabRange: " << this->SlabRange[0] << ", " << this->SlabRange[1] << "\n";
  os << indent << "NumberOfPairs: " << this->NumberOfPairs << "\n";
  os << indent << "MaximumBallsPerVoxel: " << this->MaximumBallsPerVoxel << "\n";
  os << indent << "CollectStatistics: " << this->CollectStatistics << "\n";
  os << indent << "PairCapacity: " << this->PairCapacity << "\n";
  os << indent << "NumberOfOverflows: " << this->NumberOfOverflows << "\n";
  os << indent << "NumberOfReadBacks: " << this->NumberOfReadBacks << "\n";
  os << indent << "BuildTime: " << this->BuildTime << " ms\n";
}
