// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMetaballGhostBalls.h"

#include "psBallExtraction.h"
#include "psMetaball.h"

#include "vtkCellArray.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMetaballGhostBalls);
vtkCxxSetObjectMacro(vtkMetaballGhostBalls, Controller, vtkMultiProcessController);

namespace
{
// The input's ghost flags: a point another process owns is not a ball of ours.
bool Duplicate(vtkUnsignedCharArray* ghosts, vtkIdType i)
{
  return ghosts && (ghosts->GetValue(i) & vtkDataSetAttributes::DUPLICATEPOINT);
}

// The point data without the ghost flags (they are made anew).
vtkSmartPointer<vtkPointData> WithoutGhostFlags(vtkPointData* pd)
{
  auto copy = vtkSmartPointer<vtkPointData>::New();
  copy->ShallowCopy(pd);
  copy->RemoveArray(vtkDataSetAttributes::GhostArrayName());
  return copy;
}

// One vertex per point.
vtkSmartPointer<vtkCellArray> Vertices(vtkIdType n)
{
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    offsets->SetValue(i, i);
    connectivity->SetValue(i, i);
  }
  offsets->SetValue(n, n);
  auto verts = vtkSmartPointer<vtkCellArray>::New();
  verts->SetData(offsets, connectivity);
  return verts;
}

// Points `keep[k]` of the sets `sets[k]`, in order, as a point cloud (one
// vertex per point) with the point arrays of the first set that gives
// points (its active attributes too). A later set's array of the same name
// and kind fills its points' tuples; where a set lacks one, its tuples stay
// zero (empty strings) and the array's name goes into `missing`. Points in
// double when any set's are. One set kept whole is shared, not copied.
vtkSmartPointer<vtkPolyData> MergePoints(const std::vector<vtkPointSet*>& sets,
  const std::vector<std::vector<vtkIdType>>& keep,
  std::set<std::string>& missing)
{
  std::vector<size_t> giving;
  vtkIdType total = 0;
  int pointType = VTK_FLOAT;
  for (size_t k = 0; k < sets.size(); ++k)
  {
    if (!keep[k].empty())
    {
      giving.push_back(k);
      total += static_cast<vtkIdType>(keep[k].size());
      if (sets[k]->GetPoints()->GetDataType() == VTK_DOUBLE)
      {
        pointType = VTK_DOUBLE;
      }
    }
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  if (giving.empty())
  {
    // No points: keep the first set's arrays, empty.
    if (!sets.empty())
    {
      out->GetPointData()->CopyAllocate(WithoutGhostFlags(sets[0]->GetPointData()), 0);
    }
    out->SetPoints(vtkNew<vtkPoints>());
    return out;
  }
  vtkPointSet* first = sets[giving[0]];
  vtkSmartPointer<vtkPointData> firstData = WithoutGhostFlags(first->GetPointData());
  if (giving.size() == 1 && total == first->GetNumberOfPoints() &&
    keep[giving[0]].back() == total - 1)
  {
    // Kept whole and in order (ids ascend): share points and arrays.
    out->SetPoints(first->GetPoints());
    out->GetPointData()->ShallowCopy(firstData);
    out->SetVerts(Vertices(total));
    return out;
  }

  vtkNew<vtkPoints> points;
  points->SetDataType(pointType);
  points->SetNumberOfPoints(total);
  vtkPointData* pd = out->GetPointData();
  for (int a = 0; a < firstData->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* from = firstData->GetAbstractArray(a);
    vtkSmartPointer<vtkAbstractArray> to =
      vtkSmartPointer<vtkAbstractArray>::Take(from->NewInstance());
    to->SetName(from->GetName());
    to->SetNumberOfComponents(from->GetNumberOfComponents());
    to->SetNumberOfTuples(total);
    if (auto* numbers = vtkDataArray::SafeDownCast(to))
    {
      numbers->Fill(0.0);
    }
    pd->AddArray(to);
  }
  for (int t = 0; t < vtkDataSetAttributes::NUM_ATTRIBUTES; ++t)
  {
    vtkAbstractArray* active = firstData->GetAbstractAttribute(t);
    if (active && active->GetName())
    {
      pd->SetActiveAttribute(active->GetName(), t);
    }
  }
  vtkIdType next = 0;
  for (size_t k : giving)
  {
    vtkPointData* source = sets[k]->GetPointData();
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* to = pd->GetAbstractArray(a);
      vtkAbstractArray* from = source->GetAbstractArray(to->GetName());
      const bool fits = from && from->GetNumberOfComponents() == to->GetNumberOfComponents() &&
        (from->IsA(to->GetClassName()) ||
          (vtkDataArray::SafeDownCast(from) && vtkDataArray::SafeDownCast(to)));
      if (!fits)
      {
        missing.insert(to->GetName());
        continue;
      }
      vtkIdType row = next;
      for (vtkIdType i : keep[k])
      {
        to->SetTuple(row++, i, from);
      }
    }
    for (vtkIdType i : keep[k])
    {
      points->SetPoint(next++, sets[k]->GetPoint(i));
    }
  }
  out->SetPoints(points);
  out->SetVerts(Vertices(total));
  return out;
}

// All point ids of a set.
std::vector<vtkIdType> AllIds(vtkIdType n)
{
  std::vector<vtkIdType> ids(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    ids[i] = i;
  }
  return ids;
}
} // namespace

//------------------------------------------------------------------------------
vtkMetaballGhostBalls::vtkMetaballGhostBalls()
  : Field(vtkSmartPointer<vtkMetaballField>::New())
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

//------------------------------------------------------------------------------
void vtkMetaballGhostBalls::SetField(vtkMetaballField* field)
{
  vtkMetaballField::Assign(this->Field, field, this);
}

//------------------------------------------------------------------------------
vtkMTimeType vtkMetaballGhostBalls::GetMTime()
{
  return std::max(this->Superclass::GetMTime(), this->Field->GetMTime());
}

//------------------------------------------------------------------------------
vtkMetaballGhostBalls::~vtkMetaballGhostBalls()
{
  this->SetController(nullptr);
}

//------------------------------------------------------------------------------
int vtkMetaballGhostBalls::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

//------------------------------------------------------------------------------
int vtkMetaballGhostBalls::RequestDataObject(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataObject* output = vtkDataObject::GetData(outInfo);
  if (vtkCompositeDataSet::SafeDownCast(input))
  {
    if (!output || !output->IsA(input->GetClassName()))
    {
      vtkSmartPointer<vtkDataObject> made =
        vtkSmartPointer<vtkDataObject>::Take(input->NewInstance());
      outInfo->Set(vtkDataObject::DATA_OBJECT(), made);
    }
  }
  else if (!vtkPolyData::SafeDownCast(output))
  {
    outInfo->Set(vtkDataObject::DATA_OBJECT(), vtkSmartPointer<vtkPolyData>::New());
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkMetaballGhostBalls::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkDataObject* output = vtkDataObject::GetData(outputVector, 0);
  this->NumberOfGhostBalls = 0;

  // The point-set leaves, in order.
  std::vector<vtkPointSet*> leaves;
  vtkCompositeDataSet* composite = vtkCompositeDataSet::SafeDownCast(input);
  if (composite)
  {
    vtkSmartPointer<vtkCompositeDataIterator> it =
      vtkSmartPointer<vtkCompositeDataIterator>::Take(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      if (vtkPointSet* leaf = vtkPointSet::SafeDownCast(it->GetCurrentDataObject()))
      {
        leaves.push_back(leaf);
      }
    }
  }
  else if (vtkPointSet* set = vtkPointSet::SafeDownCast(input))
  {
    leaves.push_back(set);
  }

  // Our own balls: every point not flagged as another process's duplicate;
  // their centres and radii only when there are others to send them to.
  const int ranks = this->Controller ? this->Controller->GetNumberOfProcesses() : 1;
  const pointsurfaces::BallRule rule = this->Field->GetRule();
  std::vector<std::vector<vtkIdType>> own(leaves.size());
  std::vector<double> centres, radii;
  bool negative = false, noRadii = false;
  for (size_t k = 0; k < leaves.size(); ++k)
  {
    vtkPointSet* leaf = leaves[k];
    vtkPointData* pd = leaf->GetPointData();
    auto* ghosts =
      vtkUnsignedCharArray::SafeDownCast(pd->GetArray(vtkDataSetAttributes::GhostArrayName()));
    vtkDataArray* r = pointsurfaces::RadiusArray(leaf, rule);
    vtkDataArray* q = pointsurfaces::StrengthArray(leaf, rule);
    noRadii = noRadii || (!rule.RadiusArrayName.empty() && !r && leaf->GetNumberOfPoints() > 0);
    for (vtkIdType i = 0; i < leaf->GetNumberOfPoints(); ++i)
    {
      if (Duplicate(ghosts, i))
      {
        continue;
      }
      own[k].push_back(i);
      if (ranks <= 1)
      {
        continue;
      }
      double p[3];
      leaf->GetPoint(i, p);
      centres.insert(centres.end(), p, p + 3);
      radii.push_back(pointsurfaces::SupportRadius(r, i, rule));
      negative = negative || (q && q->GetComponent(i, 0) < 0.0);
    }
  }
  if (noRadii)
  {
    vtkWarningMacro(<< "No point array \"" << rule.RadiusArrayName
                    << "\" for the radii: every ball has radius " << rule.Radius << ".");
  }
  if (negative)
  {
    vtkWarningMacro("Some balls have negative strengths: a process's field may exceed the whole "
                    "field near the cuts between processes, and the composited surface may show "
                    "seams there.");
  }

  // Received ghosts, when split across processes.
  vtkSmartPointer<vtkPolyData> received;
  std::set<std::string> missing; // point arrays some pieces lack
  if (ranks > 1)
  {
    pointsurfaces::MetaballSet balls;
    balls.Centers = centres.data();
    balls.Radii = radii.data();
    balls.Count = static_cast<long long>(radii.size());
    double box[6];
    pointsurfaces::SupportBounds(balls, box);
    std::vector<double> boxes(6 * ranks);
    this->Controller->AllGather(box, boxes.data(), 6);

    // Our balls that reach each process's box, as (leaf, point) lists.
    const int me = this->Controller->GetLocalProcessId();
    std::vector<vtkSmartPointer<vtkDataObject>> pieces;
    for (int rank = 0; rank < ranks; ++rank)
    {
      std::vector<std::vector<vtkIdType>> send(leaves.size());
      if (rank != me)
      {
        const std::vector<long long> ids =
          pointsurfaces::BallsReachingBox(balls, boxes.data() + 6 * rank);
        size_t k = 0;
        long long first = 0; // ball id of own[k][0]
        for (long long id : ids)
        {
          while (id - first >= static_cast<long long>(own[k].size()))
          {
            first += static_cast<long long>(own[k].size());
            ++k;
          }
          send[k].push_back(own[k][id - first]);
        }
      }
      vtkSmartPointer<vtkDataObject> piece = vtkSmartPointer<vtkPolyData>::New();
      if (!leaves.empty())
      {
        piece = MergePoints(leaves, send, missing);
      }
      std::vector<vtkSmartPointer<vtkDataObject>> gathered;
      this->Controller->Gather(piece, gathered, rank);
      if (rank == me)
      {
        pieces = gathered;
      }
    }
    std::vector<vtkPointSet*> from;
    std::vector<std::vector<vtkIdType>> all;
    for (vtkDataObject* piece : pieces)
    {
      vtkPointSet* set = vtkPointSet::SafeDownCast(piece);
      if (set && set->GetNumberOfPoints() > 0)
      {
        from.push_back(set);
        all.push_back(AllIds(set->GetNumberOfPoints()));
      }
    }
    if (!from.empty())
    {
      received = MergePoints(from, all, missing);
      this->NumberOfGhostBalls = received->GetNumberOfPoints();
    }
  }

  // Each leaf as a point cloud of its own balls; the ghosts follow the first
  // non-empty one, flagged.
  std::vector<vtkSmartPointer<vtkPolyData>> clouds;
  bool placed = false;
  for (size_t k = 0; k < leaves.size(); ++k)
  {
    std::vector<vtkPointSet*> sets{ leaves[k] };
    std::vector<std::vector<vtkIdType>> keep{ own[k] };
    const bool here = received && !placed && !own[k].empty();
    if (here)
    {
      sets.push_back(received);
      keep.push_back(AllIds(received->GetNumberOfPoints()));
      placed = true;
    }
    vtkSmartPointer<vtkPolyData> cloud = MergePoints(sets, keep, missing);
    if (ranks > 1)
    {
      vtkNew<vtkUnsignedCharArray> flags;
      flags->SetName(vtkDataSetAttributes::GhostArrayName());
      flags->SetNumberOfValues(cloud->GetNumberOfPoints());
      flags->FillValue(0);
      for (vtkIdType i = static_cast<vtkIdType>(own[k].size()); i < cloud->GetNumberOfPoints(); ++i)
      {
        flags->SetValue(i, vtkDataSetAttributes::DUPLICATEPOINT);
      }
      cloud->GetPointData()->AddArray(flags);
    }
    clouds.push_back(cloud);
  }
  if (received && !placed)
  {
    this->NumberOfGhostBalls = 0; // no own ball: nothing could have reached us
  }
  if (!missing.empty())
  {
    std::string names;
    for (const std::string& name : missing)
    {
      names += (names.empty() ? "\"" : ", \"") + name + "\"";
    }
    vtkWarningMacro(<< "Some balls (other leaves' or other processes') lack the point arrays "
                    << names << ": their values there are zero.");
  }

  if (composite)
  {
    vtkCompositeDataSet* out = vtkCompositeDataSet::SafeDownCast(output);
    out->CopyStructure(composite);
    vtkSmartPointer<vtkCompositeDataIterator> it =
      vtkSmartPointer<vtkCompositeDataIterator>::Take(composite->NewIterator());
    size_t k = 0;
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      vtkDataObject* leaf = it->GetCurrentDataObject();
      if (vtkPointSet::SafeDownCast(leaf))
      {
        clouds[k]->GetFieldData()->PassData(leaf->GetFieldData());
        out->SetDataSet(it, clouds[k++]);
      }
      else
      {
        out->SetDataSet(it, leaf); // not balls: passed through
      }
    }
    out->GetFieldData()->PassData(composite->GetFieldData());
  }
  else if (!clouds.empty())
  {
    clouds[0]->GetFieldData()->PassData(leaves[0]->GetFieldData());
    vtkPolyData::SafeDownCast(output)->ShallowCopy(clouds[0]);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkMetaballGhostBalls::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "Field:\n";
  this->Field->PrintSelf(os, indent.GetNextIndent());
  os << indent << "NumberOfGhostBalls: " << this->NumberOfGhostBalls << "\n";
}
