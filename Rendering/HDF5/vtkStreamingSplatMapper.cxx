// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkStreamingSplatMapper.h"

#include "psLocalFit.h"
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
#include <cmath>
#include <cstring>

vtkStandardNewMacro(vtkStreamingSplatMapper);

namespace
{
// GPU bytes a splat of `degree` takes before the first upload measures it:
// position, normal, tangent and sizes (3 floats each), the coefficients in
// vec4s, a colour.
double EstimatedGPUBytes(int degree)
{
  const int m = pointsurfaces::MonomialCount(degree);
  return 4.0 * (3 + 3 + 3 + 3) + 16.0 * ((m + 3) / 4) + 4.0;
}

// Append `count` tuples of `comps` values from `from` to `to` at tuple `at`.
template<typename T, typename Array>
void Put(Array* to, vtkIdType at, const std::vector<T>& from, long long count, int comps)
{
  if (count > 0)
  {
    std::memcpy(to->GetPointer(at * comps), from.data(), sizeof(T) * count * comps);
  }
}

// The same for an attribute, in its array's type.
void PutAttribute(vtkDataArray* to,
  vtkIdType at,
  const std::vector<float>& from,
  long long count,
  int comps)
{
  if (auto* values = vtkFloatArray::FastDownCast(to))
  {
    Put(values, at, from, count, comps);
    return;
  }
  for (long long k = 0; k < count; ++k)
  {
    for (int c = 0; c < comps; ++c)
    {
      to->SetComponent(at + k, c, from[static_cast<size_t>(comps) * k + c]);
    }
  }
}

// The resident pages as the splat data model, in the file's order, with
// the file's page octree re-indexed to them: each page's range is what is
// in memory of it, and OctreeNodePresentLevels how many levels that is.
void Gather(const std::vector<pointsurfaces::ResidentPage>& pages,
  const pointsurfaces::SplatFileInfo& info,
  vtkPolyData* out)
{
  out->Initialize();
  long long n = 0;
  for (const pointsurfaces::ResidentPage& page : pages)
  {
    n += page.Splats;
  }
  const int m = pointsurfaces::MonomialCount(info.Degree);
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
  vtkFloatArray* normal = make(vtkSplatDataModel::NormalName(), 3);
  vtkFloatArray* tangent = make(vtkSplatDataModel::TangentName(), 3);
  vtkFloatArray* size = make(vtkSplatDataModel::FeatureSizeName(), 1);
  vtkFloatArray* coeffs = make(vtkSplatDataModel::CoefficientsName(), m);
  vtkFloatArray* radius = make(vtkSplatDataModel::RadiusName(), 1);
  vtkFloatArray* deviation = make(vtkSplatDataModel::MaxDeviationName(), 1);
  vtkFloatArray* nominal = make(vtkSplatDataModel::NominalRadiusName(), 1);
  vtkFloatArray* tolerance = make(vtkSplatDataModel::ToleranceName(), 1);
  vtkNew<vtkIntArray> lod;
  lod->SetName(vtkSplatDataModel::LODName());
  lod->SetNumberOfTuples(n);
  out->GetPointData()->AddArray(lod);
  std::vector<vtkDataArray*> attributes; // null: named like a model array, left out
  for (size_t a = 0; a < info.AttributeNames.size(); ++a)
  {
    const char* name = info.AttributeNames[a].c_str();
    if (out->GetPointData()->HasArray(name))
    {
      attributes.push_back(nullptr);
      continue;
    }
    vtkSmartPointer<vtkDataArray> array;
    array.TakeReference(vtkDataArray::CreateDataArray(info.AttributeType(a)));
    array->SetName(name);
    array->SetNumberOfComponents(info.AttributeComponents[a]);
    array->SetNumberOfTuples(n);
    out->GetPointData()->AddArray(array);
    attributes.push_back(array);
  }

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
      const long long c = block->Count;
      Put(origin.GetPointer(), row, block->Origin, c, 3);
      Put(normal, row, block->Normal, c, 3);
      Put(tangent, row, block->Tangent, c, 3);
      Put(size, row, block->FeatureSize, c, 1);
      Put(coeffs, row, block->Coefficients, c, m);
      Put(radius, row, block->Radius, c, 1);
      Put(deviation, row, block->MaxDeviation, c, 1);
      Put(nominal, row, block->NominalRadius, c, 1);
      Put(tolerance, row, block->Tolerance, c, 1);
      Put(lod.GetPointer(), row, block->LOD, c, 1);
      for (size_t a = 0; a < attributes.size(); ++a)
      {
        if (attributes[a])
        {
          PutAttribute(attributes[a], row, block->Attributes[a], c, info.AttributeComponents[a]);
        }
      }
      row += c;
    }
  }
  vtkNew<vtkPoints> points;
  points->SetData(origin);
  out->SetPoints(points);
  vtkSplatDataModel::AddVertexCells(out);
  vtkSplatDataModel::AddSetFields(out, info.Degree, info.Pages.LevelQuality, info.Oriented);
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
  return EstimatedGPUBytes(P->Cache && P->Cache->IsOpen() ? P->Cache->Info().Degree : 4);
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
    P->Resident->Initialize();
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
  P->Resident->Initialize();
  return !P->Failed;
}

//------------------------------------------------------------------------------
void vtkStreamingSplatMapper::ReadOctree(vtkPolyData* poly)
{
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

  // What is in memory now.
  const long long generation = cache.Generation();
  if (generation != P->Drawn)
  {
    Gather(cache.Resident(), info, P->Resident);
    P->Drawn = generation;
  }
  this->NumberOfResidentSplats = P->Resident->GetNumberOfPoints();
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
  os << indent << "RenderWait: " << this->RenderWait << " s\n";
  os << indent << "RenderWhileLoading: " << this->RenderWhileLoading << " (every "
     << this->LoadingRenderInterval << " ms)\n";
  os << indent << "NumberOfSplats: " << this->NumberOfSplats << "\n";
  os << indent << "NumberOfResidentSplats: " << this->NumberOfResidentSplats << "\n";
  os << indent << "NumberOfWantedSplats: " << this->NumberOfWantedSplats << "\n";
}
