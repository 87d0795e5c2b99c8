// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSplatDataModel.h"

#include "psPolynomial.h"
#include "psRealArrayView.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

vtkStandardNewMacro(vtkSplatDataModel);

//------------------------------------------------------------------------------
void vtkSplatDataModel::AddVertexCells(vtkPolyData* pd)
{
  const vtkIdType n = pd->GetNumberOfPoints();
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(n);
  std::iota(connectivity->GetPointer(0), connectivity->GetPointer(0) + n, vtkIdType(0));
  vtkNew<vtkCellArray> verts;
  verts->SetData(1, connectivity);
  pd->SetVerts(verts);
}

//------------------------------------------------------------------------------
void vtkSplatDataModel::AddSetFields(vtkPolyData* pd,
  int degree,
  const std::vector<double>& levelQuality,
  bool oriented)
{
  vtkFieldData* fd = pd->GetFieldData();
  vtkNew<vtkIntArray> degreeArray;
  degreeArray->SetName(DegreeName());
  degreeArray->InsertNextValue(degree);
  fd->AddArray(degreeArray);
  vtkNew<vtkDoubleArray> levels;
  levels->SetName(LODQualityName());
  for (double s : levelQuality)
  {
    levels->InsertNextValue(s);
  }
  fd->AddArray(levels);
  vtkNew<vtkIdTypeArray> orientedArray;
  orientedArray->SetName(NormalsOrientedName());
  orientedArray->InsertNextValue(oriented ? 1 : 0);
  fd->AddArray(orientedArray);
}

//------------------------------------------------------------------------------
bool vtkSplatDataModel::ComputeSplatBounds(vtkPolyData* pd, double bounds[6])
{
  vtkMath::UninitializeBounds(bounds);
  const int degree = GetSplatDegree(pd);
  if (degree < 0)
  {
    return false;
  }
  vtkPointData* pdata = pd->GetPointData();
  vtkDataArray* normal = pdata->GetArray(NormalName());
  vtkDataArray* size = pdata->GetArray(FeatureSizeName());
  vtkDataArray* coeffs = pdata->GetArray(CoefficientsName());
  vtkDataArray* radius = pdata->GetArray(RadiusName());
  const int m = pointsurfaces::MonomialCount(degree);
  double lo[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
  double hi[3] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  bool any = false;
  double c[15];
  const vtkIdType count = pd->GetNumberOfPoints();
  // (GetSplatDegree checked their shapes.)
  const pointsurfaces::RealArrayView points(pd->GetPoints()->GetData(), count),
    normals(normal, count), sizes(size, count), radii(radius, count), coefficients(coeffs, count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    const double o[3] = { points(i, 0), points(i, 1), points(i, 2) };
    const double n[3] = { normals(i, 0), normals(i, 1), normals(i, 2) };
    const double h = sizes(i, 0), r = radii(i, 0);
    for (int k = 0; k < m; ++k)
    {
      c[k] = coefficients(i, k);
    }
    double glo, ghi;
    if (!(h > 0.0) || !(r > 0.0) || !std::isfinite(h * r) ||
      !pointsurfaces::HeightRange(c, degree, r / h, glo, ghi) || !std::isfinite(glo + ghi))
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      // A disc's extent along an axis is R sqrt(1 - n_a^2); the patch rises
      // from it by g h along n.
      const double disc = r * std::sqrt(std::max(0.0, 1.0 - n[a] * n[a]));
      const double e0 = n[a] * glo * h, e1 = n[a] * ghi * h;
      lo[a] = std::min(lo[a], o[a] + std::min(e0, e1) - disc);
      hi[a] = std::max(hi[a], o[a] + std::max(e0, e1) + disc);
    }
    any = true;
  }
  if (any)
  {
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = lo[a];
      bounds[2 * a + 1] = hi[a];
    }
  }
  return any;
}

//------------------------------------------------------------------------------
int vtkSplatDataModel::GetSplatDegree(vtkPolyData* pd)
{
  if (!pd || pd->GetNumberOfPoints() == 0)
  {
    return -1;
  }
  vtkDataArray* degreeArray = pd->GetFieldData()->GetArray(DegreeName());
  const int degree = degreeArray ? static_cast<int>(degreeArray->GetTuple1(0)) : -1;
  if (degree < 1 || degree > pointsurfaces::MaximumDegree)
  {
    return -1;
  }
  const vtkIdType n = pd->GetNumberOfPoints();
  const std::pair<const char*, int> arrays[] = { { NormalName(), 3 },
    { TangentName(), 3 },
    { FeatureSizeName(), 1 },
    { RadiusName(), 1 },
    { CoefficientsName(), pointsurfaces::MonomialCount(degree) } };
  for (const auto& a : arrays)
  {
    vtkDataArray* array = pd->GetPointData()->GetArray(a.first);
    if (!array || array->GetNumberOfComponents() != a.second || array->GetNumberOfTuples() != n)
    {
      return -1;
    }
  }
  return degree;
}

//------------------------------------------------------------------------------
void vtkSplatDataModel::AddOctree(vtkPolyData* pd, const pointsurfaces::Octree& tree)
{
  const vtkIdType nodes = static_cast<vtkIdType>(tree.Nodes.size());
  const int levels = tree.Levels;
  auto make = [nodes](auto array, const char* name, int components)
  {
    array->SetName(name);
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(nodes);
    return array;
  };
  vtkNew<vtkDoubleArray> bounds, sphere;
  vtkNew<vtkIdTypeArray> children, range, ends;
  make(bounds.GetPointer(), OctreeNodeBoundsName(), 6);
  make(sphere.GetPointer(), OctreeNodeSphereName(), 4);
  make(children.GetPointer(), OctreeNodeChildrenName(), 2);
  make(range.GetPointer(), OctreeNodeRangeName(), 2);
  make(ends.GetPointer(), OctreeNodeLevelEndsName(), levels);
  for (vtkIdType id = 0; id < nodes; ++id)
  {
    const pointsurfaces::OctreeNode& node = tree.Nodes[id];
    bounds->SetTypedTuple(id, node.Bounds);
    sphere->SetTypedTuple(id, node.Sphere);
    children->SetTypedComponent(id, 0, node.FirstChild);
    children->SetTypedComponent(id, 1, node.ChildCount);
    range->SetTypedComponent(id, 0, node.Begin);
    range->SetTypedComponent(id, 1, node.End);
    for (int l = 0; l < levels; ++l)
    {
      ends->SetTypedComponent(id, l, tree.LevelEnds[id * levels + l]);
    }
  }
  vtkFieldData* fd = pd->GetFieldData();
  fd->AddArray(bounds);
  fd->AddArray(sphere);
  fd->AddArray(children);
  fd->AddArray(range);
  fd->AddArray(ends);
  if (!tree.PresentLevels.empty())
  {
    vtkNew<vtkIntArray> present;
    make(present.GetPointer(), OctreeNodePresentLevelsName(), 1);
    for (vtkIdType id = 0; id < nodes; ++id)
    {
      present->SetValue(id, tree.PresentLevels[id]);
    }
    fd->AddArray(present);
  }
  else
  {
    fd->RemoveArray(OctreeNodePresentLevelsName());
  }
}

//------------------------------------------------------------------------------
vtkSplatDataModel::OctreeStatus vtkSplatDataModel::GetOctree(vtkPolyData* pd,
  pointsurfaces::Octree& tree,
  std::vector<double>& levelQuality)
{
  tree = pointsurfaces::Octree();
  levelQuality.clear();
  if (!pd)
  {
    return NoOctree;
  }
  vtkFieldData* fd = pd->GetFieldData();
  vtkDataArray* bounds = fd->GetArray(OctreeNodeBoundsName());
  vtkDataArray* sphere = fd->GetArray(OctreeNodeSphereName());
  vtkDataArray* children = fd->GetArray(OctreeNodeChildrenName());
  vtkDataArray* range = fd->GetArray(OctreeNodeRangeName());
  vtkDataArray* ends = fd->GetArray(OctreeNodeLevelEndsName());
  vtkDataArray* quality = fd->GetArray(LODQualityName());
  vtkDataArray* present = fd->GetArray(OctreeNodePresentLevelsName());
  vtkDataArray* radius = pd->GetPointData()->GetArray(RadiusName());
  vtkDataArray* lod = pd->GetPointData()->GetArray(LODName());
  const vtkIdType count = sphere ? sphere->GetNumberOfTuples() : 0;
  if (!count || !children || !range || !ends || !quality || !radius || !lod ||
    sphere->GetNumberOfComponents() != 4 || children->GetNumberOfComponents() != 2 ||
    range->GetNumberOfComponents() != 2 || children->GetNumberOfTuples() != count ||
    range->GetNumberOfTuples() != count || ends->GetNumberOfTuples() != count ||
    ends->GetNumberOfComponents() != quality->GetNumberOfTuples() ||
    (bounds && (bounds->GetNumberOfComponents() != 6 || bounds->GetNumberOfTuples() != count)) ||
    (present && (present->GetNumberOfComponents() != 1 || present->GetNumberOfTuples() != count)))
  {
    return NoOctree;
  }
  const vtkIdType n = pd->GetNumberOfPoints();
  const pointsurfaces::RealArrayView points(pd->GetPoints()->GetData(), n);
  const pointsurfaces::RealArrayView level(lod, n);
  if (!points.Present() || !level.Present())
  {
    return NoOctree;
  }
  // The root's sphere must still hold every splat (a transform moves the
  // points and leaves the octree behind).
  {
    double root[4];
    sphere->GetTuple(0, root);
    const double r2 = root[3] * root[3] * (1.0 + 1e-6) + 1e-300;
    for (vtkIdType i = 0; i < n; ++i)
    {
      const double p[3] = { points(i, 0), points(i, 1), points(i, 2) };
      if (vtkMath::Distance2BetweenPoints(p, root) > r2)
      {
        return MovedSplats;
      }
    }
  }
  // Every range must index the splats (a split, threshold or merge leaves
  // ranges that no longer do).
  const int levels = ends->GetNumberOfComponents();
  bool valid = static_cast<vtkIdType>(range->GetComponent(0, 0)) == 0 &&
    static_cast<vtkIdType>(range->GetComponent(0, 1)) == n;
  for (vtkIdType i = 0; i < count && valid; ++i)
  {
    const double begin = range->GetComponent(i, 0), end = range->GetComponent(i, 1);
    const double first = children->GetComponent(i, 0), number = children->GetComponent(i, 1);
    valid = begin >= 0 && begin <= end && end <= n && number >= 0 &&
      (number == 0 || (first > i && first + number <= count));
    for (int l = 0; l < levels && valid; ++l)
    {
      const double e = ends->GetComponent(i, l);
      valid = e >= begin && e <= end;
    }
    if (present && valid)
    {
      const double p = present->GetTuple1(i);
      valid = p >= 0 && p <= levels;
    }
  }
  for (vtkIdType k = 0; k < n && valid; ++k)
  {
    valid = level(k, 0) >= 0 && level(k, 0) < levels;
  }
  if (!valid)
  {
    return StaleIndex;
  }
  tree.Levels = levels;
  tree.Nodes.resize(count);
  tree.LevelEnds.resize(static_cast<size_t>(count) * levels);
  if (present)
  {
    tree.PresentLevels.resize(count);
  }
  for (vtkIdType i = 0; i < count; ++i)
  {
    pointsurfaces::OctreeNode& node = tree.Nodes[i];
    sphere->GetTuple(i, node.Sphere);
    if (bounds)
    {
      bounds->GetTuple(i, node.Bounds);
    }
    node.FirstChild = static_cast<int>(children->GetComponent(i, 0));
    node.ChildCount = static_cast<int>(children->GetComponent(i, 1));
    node.Begin = static_cast<long long>(range->GetComponent(i, 0));
    node.End = static_cast<long long>(range->GetComponent(i, 1));
    for (int l = 0; l < levels; ++l)
    {
      tree.LevelEnds[i * levels + l] = static_cast<long long>(ends->GetComponent(i, l));
    }
    if (present)
    {
      tree.PresentLevels[i] = static_cast<int>(present->GetTuple1(i));
    }
  }
  // Every leaf must still hold its own splats, in level order: splats
  // reordered within the set (a sort, a shuffle, a redistribution that
  // kept the count) leave ranges that look valid but index other splats.
  for (vtkIdType i = 0; i < count; ++i)
  {
    const pointsurfaces::OctreeNode& node = tree.Nodes[i];
    if (node.ChildCount != 0)
    {
      continue;
    }
    const double r2 = node.Sphere[3] * node.Sphere[3] * (1.0 + 1e-6) + 1e-300;
    const long long* leafEnds = &tree.LevelEnds[static_cast<size_t>(i) * levels];
    for (long long k = node.Begin; k < node.End; ++k)
    {
      const double p[3] = { points(k, 0), points(k, 1), points(k, 2) };
      const int l = static_cast<int>(level(k, 0));
      const long long first = l > 0 ? leafEnds[l - 1] : node.Begin;
      if (vtkMath::Distance2BetweenPoints(p, node.Sphere) > r2 || k < first || k >= leafEnds[l])
      {
        tree = pointsurfaces::Octree();
        return StaleIndex;
      }
    }
  }
  for (int l = 0; l < levels; ++l)
  {
    levelQuality.push_back(quality->GetTuple1(l));
  }
  return ValidOctree;
}
