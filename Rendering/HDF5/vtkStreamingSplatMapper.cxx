// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkStreamingSplatMapper.h"

#include "psLocalFit.h"
#include "psSplatArena.h"
#include "psSplatLOD.h"
#include "psSplatPageCache.h"
#include "psSplatPages.h"

#include "vtkCallbackCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSplatDataModel.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iterator>
#include <map>

vtkStandardNewMacro(vtkStreamingSplatMapper);

namespace
{
// GPU bytes a splat of `degree` takes before the first upload measures it:
// position, normal, tangent and sizes (3 floats each), the coefficients in
// vec4s, and a colour when the splats are coloured by an array.
double EstimatedGPUBytes(int degree, bool colored)
{
  const int m = pointsurfaces::MonomialCount(degree);
  return 4.0 * (3 + 3 + 3 + 3) + 16.0 * ((m + 3) / 4) + (colored ? 4.0 : 0.0);
}

// Tuples [from, from + count) of `values` (`comps` values each) into `to` at tuple `at`.
template<typename T, typename Array>
void Put(Array* to,
  vtkIdType at,
  const std::vector<T>& values,
  long long from,
  long long count,
  int comps)
{
  if (count > 0)
  {
    std::memcpy(to->GetPointer(at * comps),
      values.data() + static_cast<size_t>(from) * comps,
      sizeof(T) * count * comps);
  }
}

// The same for an attribute, in its array's type.
void PutAttribute(vtkDataArray* to,
  vtkIdType at,
  const std::vector<float>& values,
  long long from,
  long long count,
  int comps)
{
  if (auto* typed = vtkFloatArray::FastDownCast(to))
  {
    Put(typed, at, values, from, count, comps);
    return;
  }
  for (long long k = 0; k < count; ++k)
  {
    for (int c = 0; c < comps; ++c)
    {
      to->SetComponent(at + k, c, values[static_cast<size_t>(comps) * (from + k) + c]);
    }
  }
}

// The arrays of the splat data model (and the file's attributes) in `out`,
// `n` rows each, for pages to be written into.
struct Columns
{
  vtkDoubleArray* Origin = nullptr;
  vtkFloatArray *Normal = nullptr, *Tangent = nullptr, *Size = nullptr, *Coeffs = nullptr;
  vtkFloatArray *Radius = nullptr, *Deviation = nullptr, *Nominal = nullptr, *Tolerance = nullptr;
  vtkIntArray* LOD = nullptr;
  std::vector<vtkDataArray*> Attributes; // null: named like a model array, left out
  std::vector<int> Components;
  int M = 0;

  Columns() = default;
  Columns(const pointsurfaces::SplatFileInfo& info, vtkIdType n, vtkPolyData* out)
    : Components(info.AttributeComponents)
    , M(pointsurfaces::MonomialCount(info.Degree))
  {
    out->Initialize();
    auto make = [&](const char* name, int comps)
    {
      vtkNew<vtkFloatArray> a;
      a->SetName(name);
      a->SetNumberOfComponents(comps);
      a->SetNumberOfTuples(n);
      out->GetPointData()->AddArray(a);
      return a.GetPointer();
    };
    vtkNew<vtkDoubleArray> origin;
    origin->SetNumberOfComponents(3);
    origin->SetNumberOfTuples(n);
    this->Origin = origin;
    this->Normal = make(vtkSplatDataModel::NormalName(), 3);
    this->Tangent = make(vtkSplatDataModel::TangentName(), 3);
    this->Size = make(vtkSplatDataModel::FeatureSizeName(), 1);
    this->Coeffs = make(vtkSplatDataModel::CoefficientsName(), this->M);
    this->Radius = make(vtkSplatDataModel::RadiusName(), 1);
    this->Deviation = make(vtkSplatDataModel::MaxDeviationName(), 1);
    this->Nominal = make(vtkSplatDataModel::NominalRadiusName(), 1);
    this->Tolerance = make(vtkSplatDataModel::ToleranceName(), 1);
    vtkNew<vtkIntArray> lod;
    lod->SetName(vtkSplatDataModel::LODName());
    lod->SetNumberOfTuples(n);
    out->GetPointData()->AddArray(lod);
    this->LOD = lod;
    for (size_t a = 0; a < info.AttributeNames.size(); ++a)
    {
      const char* name = info.AttributeNames[a].c_str();
      if (out->GetPointData()->HasArray(name))
      {
        this->Attributes.push_back(nullptr);
        continue;
      }
      vtkSmartPointer<vtkDataArray> array;
      array.TakeReference(vtkDataArray::CreateDataArray(info.AttributeType(a)));
      array->SetName(name);
      array->SetNumberOfComponents(info.AttributeComponents[a]);
      array->SetNumberOfTuples(n);
      out->GetPointData()->AddArray(array);
      this->Attributes.push_back(array);
    }
    vtkNew<vtkPoints> points;
    points->SetData(origin);
    out->SetPoints(points);
    vtkSplatDataModel::AddVertexCells(out);
    vtkSplatDataModel::AddSetFields(out, info.Degree, info.Pages.LevelQuality, info.Oriented);
  }

  // Rows [from, from + count) of `block` into rows [row, row + count).
  void Write(const pointsurfaces::SplatColumns& block,
    long long from,
    vtkIdType row,
    long long count)
  {
    Put(this->Origin, row, block.Origin, from, count, 3);
    Put(this->Normal, row, block.Normal, from, count, 3);
    Put(this->Tangent, row, block.Tangent, from, count, 3);
    Put(this->Size, row, block.FeatureSize, from, count, 1);
    Put(this->Coeffs, row, block.Coefficients, from, count, this->M);
    Put(this->Radius, row, block.Radius, from, count, 1);
    Put(this->Deviation, row, block.MaxDeviation, from, count, 1);
    Put(this->Nominal, row, block.NominalRadius, from, count, 1);
    Put(this->Tolerance, row, block.Tolerance, from, count, 1);
    Put(this->LOD, row, block.LOD, from, count, 1);
    for (size_t a = 0; a < this->Attributes.size(); ++a)
    {
      if (this->Attributes[a])
      {
        PutAttribute(
          this->Attributes[a], row, block.Attributes[a], from, count, this->Components[a]);
      }
    }
  }

  // Tell the pipeline (and the mapper's colours) that rows were written.
  void Modified()
  {
    for (vtkDataArray* a : { static_cast<vtkDataArray*>(this->Origin),
           static_cast<vtkDataArray*>(this->Normal),
           static_cast<vtkDataArray*>(this->Tangent),
           static_cast<vtkDataArray*>(this->Size),
           static_cast<vtkDataArray*>(this->Coeffs),
           static_cast<vtkDataArray*>(this->Radius),
           static_cast<vtkDataArray*>(this->Deviation),
           static_cast<vtkDataArray*>(this->Nominal),
           static_cast<vtkDataArray*>(this->Tolerance),
           static_cast<vtkDataArray*>(this->LOD) })
    {
      a->Modified();
    }
    for (vtkDataArray* a : this->Attributes)
    {
      if (a)
      {
        a->Modified();
      }
    }
  }
};

// The resident pages as the splat data model, in the file's order, with
// the file's page octree re-indexed to them: each page's range is what is
// in memory of it, and OctreeNodePresentLevels how many levels that is.
// (IncrementalUpload off: each arrival gathers and uploads them all.)
void Gather(const std::vector<pointsurfaces::ResidentPage>& pages,
  const pointsurfaces::SplatFileInfo& info,
  vtkPolyData* out)
{
  long long n = 0;
  for (const pointsurfaces::ResidentPage& page : pages)
  {
    n += page.Splats;
  }
  Columns columns(info, n, out);

  // The page octree, its leaves re-indexed to what is resident.
  pointsurfaces::Octree tree = info.Pages.Tree;
  const int L = tree.Levels;
  const size_t nodes = tree.Nodes.size();
  std::vector<long long> present(nodes, 0);
  tree.PresentLevels.assign(nodes, 0);
  for (const pointsurfaces::ResidentPage& page : pages)
  {
    present[page.Node] = page.Splats;
    tree.PresentLevels[page.Node] = page.Levels;
  }
  std::vector<int> leaves;
  for (size_t id = 0; id < nodes; ++id)
  {
    if (tree.Nodes[id].ChildCount == 0)
    {
      leaves.push_back(static_cast<int>(id));
    }
  }
  std::sort(leaves.begin(),
    leaves.end(),
    [&info](int a, int b)
    { return info.Pages.Tree.Nodes[a].Begin < info.Pages.Tree.Nodes[b].Begin; });
  long long at = 0;
  for (int id : leaves)
  {
    pointsurfaces::OctreeNode& node = tree.Nodes[id];
    const long long fileBegin = node.Begin;
    node.Begin = at;
    node.End = at + present[id];
    for (int l = 0; l < L; ++l)
    {
      long long& end = tree.LevelEnds[static_cast<size_t>(id) * L + l];
      end = at + std::min(end - fileBegin, present[id]);
    }
    at = node.End;
  }
  // Inner nodes: their children's span (children come after their parent).
  for (size_t k = nodes; k-- > 0;)
  {
    pointsurfaces::OctreeNode& node = tree.Nodes[k];
    if (node.ChildCount == 0)
    {
      continue;
    }
    node.Begin = tree.Nodes[node.FirstChild].Begin;
    node.End = tree.Nodes[node.FirstChild].End;
    int levels = L;
    for (int c = 0; c < node.ChildCount; ++c)
    {
      const pointsurfaces::OctreeNode& child = tree.Nodes[node.FirstChild + c];
      node.Begin = std::min(node.Begin, child.Begin);
      node.End = std::max(node.End, child.End);
      levels = std::min(levels, tree.PresentLevels[node.FirstChild + c]);
    }
    std::fill_n(tree.LevelEnds.begin() + k * L, L, node.End);
    tree.PresentLevels[k] = levels;
  }

  vtkIdType row = 0;
  for (const pointsurfaces::ResidentPage& page : pages)
  {
    for (const auto& block : page.Blocks)
    {
      columns.Write(*block, 0, row, block->Count);
      row += block->Count;
    }
  }
  if (n > 0)
  {
    vtkSplatDataModel::AddOctree(out, tree);
  }
}
} // namespace

struct vtkStreamingSplatMapper::Impl
{
  std::unique_ptr<pointsurfaces::SplatPageCache> Cache;
  bool CacheAsynchronous = true;
  std::string Path;     // the file the cache has open (or failed to open)
  long long Stamp = -1; // its modification time then
  bool Failed = false;  // it could not be opened or read: reported once
  long long Drawn = -1; // the cache generation gathered into Resident
  double MeasuredBytes = 0.0;
  double WarnedBudget = -1.0;
  bool WarnedInput = false;
  vtkNew<vtkPolyData> Resident;
  long long ResidentSplats = 0;

  // IncrementalUpload: Resident is an arena of rows (psSplatArena.h) into
  // which each (page, level) block that arrives is written once; the rows
  // each resident level of each page holds, by page.
  bool ArenaMode = false;
  pointsurfaces::SplatArena Arena;
  std::map<int, std::vector<std::vector<pointsurfaces::RowExtent>>> Slots;
  Columns ArenaColumns;

  // The render's upload statistics.
  double UploadSeconds = 0.0;
  vtkIdType UploadedSplats = 0;

  void Reset()
  {
    this->Resident->Initialize();
    this->ResidentSplats = 0;
    this->ArenaMode = false;
    this->Arena = pointsurfaces::SplatArena();
    this->Slots.clear();
    this->ArenaColumns = Columns();
  }
  void UpdateRows(vtkStreamingSplatMapper* mapper,
    const std::vector<pointsurfaces::ResidentPage>& pages,
    long long budgetRows,
    long long wanted);
  void BuildArena(vtkStreamingSplatMapper* mapper,
    const std::vector<pointsurfaces::ResidentPage>& pages,
    long long capacity);
  void WriteLevel(vtkStreamingSplatMapper* mapper,
    const pointsurfaces::SplatColumns& block,
    std::vector<pointsurfaces::RowExtent>& rows);
  // RenderWhileLoading: the interactor observed, and its pending timer (0: none).
  vtkWeakPointer<vtkRenderWindowInteractor> Interactor;
  vtkNew<vtkCallbackCommand> Callback;
  unsigned long Observer = 0;
  int TimerId = 0;
  void Detach()
  {
    if (this->Interactor)
    {
      this->Interactor->RemoveObserver(this->Observer);
      if (this->TimerId != 0)
      {
        this->Interactor->DestroyTimer(this->TimerId);
      }
    }
    this->Interactor = nullptr;
    this->Observer = 0;
    this->TimerId = 0;
  }
  Impl()
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback(
      [](vtkObject* caller, unsigned long, void* clientData, void* callData)
      {
        auto* impl = static_cast<Impl*>(clientData);
        if (!callData || *static_cast<int*>(callData) != impl->TimerId || impl->TimerId == 0)
        {
          return; // another timer of the interactor
        }
        impl->TimerId = 0;
        static_cast<vtkRenderWindowInteractor*>(caller)->Render();
      });
  }
  ~Impl() { this->Detach(); }
};

//------------------------------------------------------------------------------
void vtkStreamingSplatMapper::Impl::WriteLevel(vtkStreamingSplatMapper* mapper,
  const pointsurfaces::SplatColumns& block,
  std::vector<pointsurfaces::RowExtent>& rows)
{
  // Every free row the arena holds covers what the cache keeps (UpdateRows).
  if (!this->Arena.Allocate(block.Count, rows))
  {
    return;
  }
  long long from = 0;
  for (const pointsurfaces::RowExtent& extent : rows)
  {
    this->ArenaColumns.Write(block, from, static_cast<vtkIdType>(extent.Begin), extent.Size());
    std::fill(mapper->RowsInUse.begin() + extent.Begin, mapper->RowsInUse.begin() + extent.End, 1);
    mapper->ChangedRows.emplace_back(extent.Begin, extent.End);
    from += extent.Size();
  }
}

//------------------------------------------------------------------------------
void vtkStreamingSplatMapper::Impl::BuildArena(vtkStreamingSplatMapper* mapper,
  const std::vector<pointsurfaces::ResidentPage>& pages,
  long long capacity)
{
  const pointsurfaces::SplatFileInfo& info = this->Cache->Info();
  this->ArenaColumns = Columns(info, static_cast<vtkIdType>(capacity), this->Resident);
  this->Arena = pointsurfaces::SplatArena(capacity);
  this->Slots.clear();
  mapper->RowsInUse.assign(static_cast<size_t>(capacity), 0);
  for (const pointsurfaces::ResidentPage& page : pages)
  {
    std::vector<std::vector<pointsurfaces::RowExtent>>& levels = this->Slots[page.Node];
    for (int l = 0; l < page.Levels; ++l)
    {
      levels.emplace_back();
      this->WriteLevel(mapper, *page.Blocks[l], levels.back());
    }
  }
  // New arrays: the next build uploads every row.
  mapper->ChangedRows.clear();
  mapper->RowUpdatePending = false;
  this->ArenaMode = true;
}

//------------------------------------------------------------------------------
void vtkStreamingSplatMapper::Impl::UpdateRows(vtkStreamingSplatMapper* mapper,
  const std::vector<pointsurfaces::ResidentPage>& pages,
  long long budgetRows,
  long long wanted)
{
  long long needed = 0;
  for (const pointsurfaces::ResidentPage& page : pages)
  {
    needed += page.Splats;
  }
  this->ResidentSplats = needed;
  if (!this->ArenaMode && needed == 0)
  {
    return; // nothing to hold yet
  }
  // Rows for what is resident, and for what the view wants (so that its
  // pages arriving need no larger buffers), within the budget: a larger
  // set, or a budget lowered below the rows held, makes new buffers.
  const long long capacity = this->Arena.Capacity();
  if (!this->ArenaMode || needed > capacity || (budgetRows > 0 && capacity > budgetRows))
  {
    long long rows = std::max(needed, wanted) + std::max(needed, wanted) / 4 + 4096;
    if (budgetRows > 0)
    {
      rows = std::min(rows, budgetRows);
    }
    this->BuildArena(mapper, pages, std::max(rows, needed));
    return;
  }
  std::map<int, const pointsurfaces::ResidentPage*> now;
  for (const pointsurfaces::ResidentPage& page : pages)
  {
    now[page.Node] = &page;
  }
  // What left: its rows free, drawn as nothing.
  for (auto slot = this->Slots.begin(); slot != this->Slots.end();)
  {
    auto page = now.find(slot->first);
    const size_t keep = page == now.end() ? 0 : static_cast<size_t>(page->second->Levels);
    while (slot->second.size() > keep)
    {
      for (const pointsurfaces::RowExtent& extent : slot->second.back())
      {
        this->Arena.Release(extent);
        std::fill(
          mapper->RowsInUse.begin() + extent.Begin, mapper->RowsInUse.begin() + extent.End, 0);
        mapper->ChangedRows.emplace_back(extent.Begin, extent.End);
      }
      slot->second.pop_back();
    }
    slot = slot->second.empty() ? this->Slots.erase(slot) : std::next(slot);
  }
  // What came: written into free rows.
  for (const pointsurfaces::ResidentPage& page : pages)
  {
    std::vector<std::vector<pointsurfaces::RowExtent>>& levels = this->Slots[page.Node];
    for (int l = static_cast<int>(levels.size()); l < page.Levels; ++l)
    {
      levels.emplace_back();
      this->WriteLevel(mapper, *page.Blocks[l], levels.back());
    }
  }
  this->ArenaColumns.Modified();
  mapper->RowUpdatePending = true;
}

//------------------------------------------------------------------------------
vtkStreamingSplatMapper::vtkStreamingSplatMapper()
  : P(new Impl)
{
  this->SetInputData(P->Resident);
}

vtkStreamingSplatMapper::~vtkStreamingSplatMapper() = default;

//------------------------------------------------------------------------------
double vtkStreamingSplatMapper::GetBytesPerSplat()
{
  if (P->MeasuredBytes > 0.0)
  {
    return P->MeasuredBytes;
  }
  const bool open = P->Cache && P->Cache->IsOpen();
  // Colours need an array to colour by: the file's attributes.
  const bool colored =
    this->GetScalarVisibility() && (!open || !P->Cache->Info().AttributeNames.empty());
  return EstimatedGPUBytes(open ? P->Cache->Info().Degree : 4, colored);
}

bool vtkStreamingSplatMapper::GetLoading()
{
  // Still reading, or read since the last render gathered the pages.
  return P->Cache && !P->Failed && (P->Cache->Loading() || P->Cache->Generation() != P->Drawn);
}

bool vtkStreamingSplatMapper::WaitForPages(double seconds)
{
  return P->Cache && !P->Failed && P->Cache->Wait(seconds);
}

//------------------------------------------------------------------------------
void vtkStreamingSplatMapper::ComputeBounds()
{
  // The file's header stays readable after a read error (the pages in memory are still drawn).
  if (P->Cache && !P->Cache->Info().Pages.Tree.Nodes.empty())
  {
    const double* b = P->Cache->Info().Pages.Tree.Nodes[0].Bounds;
    std::copy(b, b + 6, this->Bounds);
    return;
  }
  vtkMath::UninitializeBounds(this->Bounds);
}

double* vtkStreamingSplatMapper::GetBounds()
{
  this->OpenFile();
  this->ComputeBounds();
  return this->Bounds;
}

//------------------------------------------------------------------------------
bool vtkStreamingSplatMapper::OpenFile()
{
  if (this->FileName.empty())
  {
    if (!P->Failed || P->Cache)
    {
      vtkErrorMacro(<< "No FileName: nothing to draw.");
    }
    P->Cache.reset();
    P->Path.clear();
    P->Failed = true;
    this->NumberOfSplats = this->NumberOfResidentSplats = this->NumberOfWantedSplats = 0;
    P->Reset();
    return false;
  }
  const long long stamp = pointsurfaces::FileModificationStamp(this->FileName);
  if (P->Cache && P->Path == this->FileName && P->Stamp == stamp &&
    P->CacheAsynchronous == this->Asynchronous)
  {
    return !P->Failed;
  }
  P->Cache = std::make_unique<pointsurfaces::SplatPageCache>(this->Asynchronous);
  P->CacheAsynchronous = this->Asynchronous;
  P->Path = this->FileName;
  P->Stamp = stamp;
  P->Drawn = -1;
  P->MeasuredBytes = 0.0;
  P->WarnedBudget = -1.0;
  std::string error;
  P->Failed = !P->Cache->Open(this->FileName, error);
  if (P->Failed)
  {
    vtkErrorMacro(<< this->FileName << ": " << error);
  }
  this->NumberOfSplats = P->Failed ? 0 : static_cast<vtkIdType>(P->Cache->Info().Splats);
  this->NumberOfResidentSplats = this->NumberOfWantedSplats = 0;
  P->Reset();
  return !P->Failed;
}

//------------------------------------------------------------------------------
void vtkStreamingSplatMapper::ReadOctree(vtkPolyData* poly)
{
  if (P->ArenaMode && P->Cache && P->Cache->IsOpen())
  {
    // The file's page octree as it is (its ranges are the file's rows, which
    // TranslateDrawRanges maps to the arena's), each page drawing no finer
    // level than it holds.
    auto nodes = std::make_unique<pointsurfaces::LODOctree>(P->Cache->Info().Pages);
    pointsurfaces::Octree& tree = nodes->Tree;
    const size_t count = tree.Nodes.size();
    tree.PresentLevels.assign(count, 0);
    for (const auto& slot : P->Slots)
    {
      tree.PresentLevels[slot.first] = static_cast<int>(slot.second.size());
    }
    for (size_t k = count; k-- > 0;)
    {
      const pointsurfaces::OctreeNode& node = tree.Nodes[k];
      if (node.ChildCount > 0)
      {
        int levels = tree.Levels;
        for (int c = 0; c < node.ChildCount; ++c)
        {
          levels = std::min(levels, tree.PresentLevels[node.FirstChild + c]);
        }
        tree.PresentLevels[k] = levels;
      }
    }
    this->SetLODNodes(std::move(nodes));
    return;
  }
  this->Superclass::ReadOctree(poly);
  pointsurfaces::LODOctree* nodes = this->GetLODNodes();
  // The file's mean scales, for the page octree only (not for one the
  // superclass built).
  if (nodes && this->LODNodesFromInput() && P->Cache && P->Cache->IsOpen())
  {
    const std::vector<double>& file = P->Cache->Info().Pages.MeanScale;
    if (file.size() == nodes->MeanScale.size())
    {
      nodes->MeanScale = file;
    }
  }
}

//------------------------------------------------------------------------------
void vtkStreamingSplatMapper::TranslateDrawRanges(std::vector<pointsurfaces::DrawRange>& ranges)
{
  if (!P->ArenaMode)
  {
    return;
  }
  // Levels 0 .. Level of each page: the rows its levels hold, adjacent ones merged.
  std::vector<pointsurfaces::DrawRange> rows;
  rows.reserve(ranges.size() * 2);
  for (const pointsurfaces::DrawRange& range : ranges)
  {
    auto slot = P->Slots.find(range.Node);
    if (slot == P->Slots.end())
    {
      continue;
    }
    const int levels = std::min(range.Level + 1, static_cast<int>(slot->second.size()));
    for (int l = 0; l < levels; ++l)
    {
      for (const pointsurfaces::RowExtent& extent : slot->second[l])
      {
        if (!rows.empty() && rows.back().End == extent.Begin &&
          rows.back().Quality == range.Quality)
        {
          rows.back().End = extent.End;
          continue;
        }
        pointsurfaces::DrawRange part = range;
        part.Begin = extent.Begin;
        part.End = extent.End;
        rows.push_back(part);
      }
    }
  }
  ranges.swap(rows);
}

//------------------------------------------------------------------------------
void vtkStreamingSplatMapper::ComputePositionShift(vtkPolyData* poly, double shift[3])
{
  // The file's centre, whatever is resident (the arena's free rows hold
  // stale or zero positions), so that rows written later keep the shift.
  if (P->Cache && !P->Cache->Info().Pages.Tree.Nodes.empty())
  {
    const double* b = P->Cache->Info().Pages.Tree.Nodes[0].Bounds;
    for (int k = 0; k < 3; ++k)
    {
      shift[k] = std::isfinite(b[2 * k] + b[2 * k + 1]) ? 0.5 * (b[2 * k] + b[2 * k + 1]) : 0.0;
    }
    return;
  }
  this->Superclass::ComputePositionShift(poly, shift);
}

//------------------------------------------------------------------------------
void vtkStreamingSplatMapper::BuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  const auto start = std::chrono::steady_clock::now();
  this->Superclass::BuildBufferObjects(ren, act);
  P->UploadSeconds +=
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  P->UploadedSplats += this->LastBuildRows;
}

//------------------------------------------------------------------------------
double vtkStreamingSplatMapper::GetUploadSeconds()
{
  return P->UploadSeconds;
}

vtkIdType vtkStreamingSplatMapper::GetNumberOfUploadedSplats()
{
  return P->UploadedSplats;
}

vtkIdType vtkStreamingSplatMapper::GetNumberOfAllocatedSplats()
{
  return P->ArenaMode ? static_cast<vtkIdType>(P->Arena.Capacity())
                      : P->Resident->GetNumberOfPoints();
}

//------------------------------------------------------------------------------
void vtkStreamingSplatMapper::Render(vtkRenderer* ren, vtkActor* act)
{
  this->RenderPages(ren, act);
  if (this->RenderWhileLoading && this->Asynchronous && !IsShadowMapBake(act) && this->GetLoading())
  {
    this->ScheduleRender(ren);
  }
}

//------------------------------------------------------------------------------
void vtkStreamingSplatMapper::ScheduleRender(vtkRenderer* ren)
{
  vtkRenderWindow* window = ren ? ren->GetRenderWindow() : nullptr;
  vtkRenderWindowInteractor* interactor = window ? window->GetInteractor() : nullptr;
  if (!interactor || !interactor->GetInitialized())
  {
    return;
  }
  if (interactor != P->Interactor.GetPointer())
  {
    P->Detach();
    P->Interactor = interactor;
    P->Observer = interactor->AddObserver(vtkCommand::TimerEvent, P->Callback);
  }
  if (P->TimerId == 0)
  {
    P->TimerId =
      interactor->CreateOneShotTimer(static_cast<unsigned long>(this->LoadingRenderInterval));
  }
}

//------------------------------------------------------------------------------
void vtkStreamingSplatMapper::RenderPages(vtkRenderer* ren, vtkActor* act)
{
  if (!this->OpenFile())
  {
    return;
  }
  if (this->GetInput() != P->Resident.GetPointer())
  {
    if (!P->WarnedInput)
    {
      vtkWarningMacro(<< "vtkStreamingSplatMapper draws its FileName; the input set by hand is "
                         "replaced by the pages in memory.");
      P->WarnedInput = true;
    }
    this->SetInputData(P->Resident);
  }
  pointsurfaces::SplatPageCache& cache = *P->Cache;
  const pointsurfaces::SplatFileInfo& info = cache.Info();
  // The light's view of a shadow map draws what the camera's view loaded.
  if (IsShadowMapBake(act))
  {
    if (P->Resident->GetNumberOfPoints() > 0)
    {
      this->Superclass::Render(ren, act);
    }
    return;
  }

  P->UploadSeconds = 0.0;
  P->UploadedSplats = 0;

  // What this view wants, within the budget.
  pointsurfaces::LODView view;
  this->MakeLODView(ren, act, view);
  const double perSplat = this->GetBytesPerSplat();
  const double budget = this->MemoryBudget * 1e6;
  const pointsurfaces::PageSelection selection =
    pointsurfaces::SelectPages(info.Pages, perSplat, budget, &view);
  if (selection.Ranges.empty() && selection.SmallestPage > 0.0)
  {
    if (P->WarnedBudget != this->MemoryBudget)
    {
      vtkWarningMacro(<< this->FileName << ": MemoryBudget " << this->MemoryBudget
                      << " MB holds no page's coarsest level in view (the smallest needs "
                      << selection.SmallestPage / 1e6 << " MB): nothing is drawn.");
      P->WarnedBudget = this->MemoryBudget;
    }
  }
  std::vector<pointsurfaces::PageWant> wants;
  wants.reserve(selection.Ranges.size());
  for (const pointsurfaces::PageRange& range : selection.Ranges)
  {
    const double* sphere = info.Pages.Tree.Nodes[range.Node].Sphere;
    double c[3] = { sphere[0], sphere[1], sphere[2] };
    if (!view.ModelIsIdentity)
    {
      const double* m = view.ModelToWorld;
      for (int row = 0; row < 3; ++row)
      {
        c[row] = m[4 * row] * sphere[0] + m[4 * row + 1] * sphere[1] + m[4 * row + 2] * sphere[2] +
          m[4 * row + 3];
      }
    }
    pointsurfaces::PageWant want;
    want.Node = range.Node;
    want.Levels = range.Levels;
    want.Distance = std::sqrt(vtkMath::Distance2BetweenPoints(c, view.Eye));
    wants.push_back(want);
  }
  cache.Request(wants, budget > 0.0 ? std::max(1LL, static_cast<long long>(budget / perSplat)) : 0);
  if (!this->Asynchronous)
  {
    cache.Wait();
  }
  else if (this->RenderWait > 0.0)
  {
    cache.Wait(this->RenderWait);
  }
  const std::string error = cache.TakeError();
  if (!error.empty())
  {
    vtkErrorMacro(<< this->FileName << ": " << error);
    P->Failed = true;
  }
  this->NumberOfWantedSplats = static_cast<vtkIdType>(selection.Splats);

  // What is in memory now: with IncrementalUpload, the blocks that arrived
  // written into free rows of the buffers, the rows of those that left freed;
  // without, all of it gathered anew.
  const long long generation = cache.Generation();
  const long long budgetRows =
    budget > 0.0 ? std::max(1LL, static_cast<long long>(budget / perSplat)) : 0;
  if (generation != P->Drawn || P->ArenaMode != this->IncrementalUpload ||
    (P->ArenaMode && budgetRows > 0 && P->Arena.Capacity() > budgetRows))
  {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<pointsurfaces::ResidentPage> pages = cache.Resident();
    if (this->IncrementalUpload)
    {
      P->UpdateRows(this, pages, budgetRows, selection.Splats);
    }
    else
    {
      P->Reset();
      this->RowsInUse.clear();
      Gather(pages, info, P->Resident);
      P->ResidentSplats = P->Resident->GetNumberOfPoints();
    }
    P->Drawn = generation;
    P->UploadSeconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  this->NumberOfResidentSplats = static_cast<vtkIdType>(P->ResidentSplats);
  if (this->NumberOfResidentSplats == 0)
  {
    return;
  }
  this->Superclass::Render(ren, act);
  const int measured = this->GetGPUBytesPerSplat();
  if (measured > 0)
  {
    P->MeasuredBytes = measured;
  }
}

//------------------------------------------------------------------------------
void vtkStreamingSplatMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "MemoryBudget: " << this->MemoryBudget << " MB\n";
  os << indent << "Asynchronous: " << this->Asynchronous << "\n";
  os << indent << "IncrementalUpload: " << this->IncrementalUpload << "\n";
  os << indent << "RenderWait: " << this->RenderWait << " s\n";
  os << indent << "RenderWhileLoading: " << this->RenderWhileLoading << " (every "
     << this->LoadingRenderInterval << " ms)\n";
  os << indent << "NumberOfSplats: " << this->NumberOfSplats << "\n";
  os << indent << "NumberOfResidentSplats: " << this->NumberOfResidentSplats << "\n";
  os << indent << "NumberOfWantedSplats: " << this->NumberOfWantedSplats << "\n";
}
