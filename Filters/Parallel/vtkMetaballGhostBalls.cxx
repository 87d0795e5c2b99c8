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
#include "vtkDoubleArray.h"
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
#include "vtkSMPTools.h"
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

// The field-data array of the mean spacing of all processes' balls: set to
// `spacing`, or removed when it is not positive.
void SetSpacingArray(vtkFieldData* fd, double spacing)
{
  fd->RemoveArray(pointsurfaces::MeanSpacingArrayName);
  if (spacing > 0.0)
  {
    vtkNew<vtkDoubleArray> array;
    array->SetName(pointsurfaces::MeanSpacingArrayName);
    array->SetNumberOfValues(1);
    array->SetValue(0, spacing);
    fd->AddArray(array);
  }
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
// The point-set leaves of `input`, in order (itself when it is one).
std::vector<vtkPointSet*> PointSetLeaves(vtkDataObject* input)
{
  std::vector<vtkPointSet*> leaves;
  if (vtkCompositeDataSet* composite = vtkCompositeDataSet::SafeDownCast(input))
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

  return leaves;
}

// Each leaf as a point cloud of its own balls (`own`); `received`, when
// given, follows the first non-empty one. Split across processes, each
// cloud flags what follows its own balls as ghosts.
std::vector<vtkSmartPointer<vtkPolyData>> OwnClouds(const std::vector<vtkPointSet*>& leaves,
  const std::vector<std::vector<vtkIdType>>& own,
  vtkPolyData* received,
  bool split,
  std::set<std::string>& missing,
  bool& placed)
{
  std::vector<vtkSmartPointer<vtkPolyData>> clouds;
  placed = false;
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
    cloud->GetFieldData()->PassData(leaves[k]->GetFieldData());
    if (split)
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
  return clouds;
}

// The clouds into `output`: the composite input's structure with each point
// set leaf replaced by its cloud (others passed through), or the one cloud.
void SetCloudsAsOutput(vtkDataObject* input,
  vtkDataObject* output,
  const std::vector<vtkSmartPointer<vtkPolyData>>& clouds)
{
  vtkCompositeDataSet* composite = vtkCompositeDataSet::SafeDownCast(input);
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
    vtkPolyData::SafeDownCast(output)->ShallowCopy(clouds[0]);
  }
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
double vtkMetaballGhostBalls::SpacingOfAllProcesses(const std::vector<vtkPointSet*>& leaves,
  const std::vector<std::vector<vtkIdType>>& own,
  const std::vector<pointsurfaces::RadiusSource>& sources)
{
  const pointsurfaces::NearestNeighbours& mine = this->OwnNeighbours(leaves, own, sources);
  std::vector<double> distances = mine.Distances;
  this->NearestOnAllProcesses(mine, distances);
  const int ranks = this->Controller->GetNumberOfProcesses();
  // Every process's sum and count, added in rank order on every process:
  // the same mean everywhere, to the last bit (a reduction's order may
  // differ between processes).
  const pointsurfaces::NeighbourSpacing local =
    pointsurfaces::NearestNeighbours::Spacing(distances);
  const double sums[2] = { local.Sum, static_cast<double>(local.Count) };
  std::vector<double> all(2 * static_cast<size_t>(ranks));
  this->Controller->AllGather(sums, all.data(), 2);
  double sum = 0.0, count = 0.0;
  for (int r = 0; r < ranks; ++r)
  {
    sum += all[2 * r];
    count += all[2 * r + 1];
  }
  return count > 0.0 ? sum / count : 0.0;
}

//------------------------------------------------------------------------------
const pointsurfaces::NearestNeighbours& vtkMetaballGhostBalls::OwnNeighbours(
  const std::vector<vtkPointSet*>& leaves,
  const std::vector<std::vector<vtkIdType>>& own,
  const std::vector<pointsurfaces::RadiusSource>& sources)
{
  // Our own balls of the leaves whose radii follow the spacing, each with
  // its nearest neighbour among them; measured again only when a leaf
  // changed.
  std::vector<const void*> measured;
  std::vector<vtkMTimeType> times;
  for (size_t k = 0; k < leaves.size(); ++k)
  {
    if (sources[k].Rule == pointsurfaces::RadiusRule::Spacing)
    {
      measured.push_back(leaves[k]);
      times.push_back(leaves[k]->GetMTime());
    }
  }
  if (!this->Neighbours || measured != this->SpacingLeaves || times != this->SpacingTimes)
  {
    std::vector<double> xyz;
    for (size_t k = 0; k < leaves.size(); ++k)
    {
      if (sources[k].Rule == pointsurfaces::RadiusRule::Spacing)
      {
        for (vtkIdType i : own[k])
        {
          double p[3];
          leaves[k]->GetPoint(i, p);
          xyz.insert(xyz.end(), p, p + 3);
        }
      }
    }
    this->Neighbours.reset(
      new pointsurfaces::NearestNeighbours(xyz.data(), static_cast<long long>(xyz.size() / 3)));
    this->SpacingLeaves = measured;
    this->SpacingTimes = times;
  }
  return *this->Neighbours;
}

//------------------------------------------------------------------------------
void vtkMetaballGhostBalls::NearestOnAllProcesses(const pointsurfaces::NearestNeighbours& mine,
  std::vector<double>& distances)
{
  // Points near a cut may have their nearest neighbour on another process.
  // Each process asks the others about its points whose distance to their
  // nearest here reaches that process's box (all of them when alone), and
  // keeps the nearer answer: each point then has its nearest neighbour among
  // all processes' points, as in one process. (A position held by two
  // processes counts on each, its copy not being a neighbour.)
  const int ranks = this->Controller->GetNumberOfProcesses();
  const int me = this->Controller->GetLocalProcessId();
  double box[6] = { 1.0, 0.0, 1.0, 0.0, 1.0, 0.0 }; // empty
  for (long long i = 0; i < mine.Size(); ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      const double x = mine.Point(i)[a];
      box[2 * a] = i ? std::min(box[2 * a], x) : x;
      box[2 * a + 1] = i ? std::max(box[2 * a + 1], x) : x;
    }
  }
  std::vector<double> boxes(6 * static_cast<size_t>(ranks));
  this->Controller->AllGather(box, boxes.data(), 6);
  for (int rank = 0; rank < ranks; ++rank)
  {
    // Our questions to `rank`: points whose nearest-neighbour sphere reaches its box.
    const double* b = boxes.data() + 6 * rank;
    std::vector<long long> asked;
    std::vector<double> questions;
    if (rank != me && b[0] <= b[1])
    {
      for (long long i = 0; i < mine.Size(); ++i)
      {
        const double* p = mine.Point(i);
        double d2 = 0.0;
        for (int a = 0; a < 3; ++a)
        {
          const double gap = std::max({ b[2 * a] - p[a], p[a] - b[2 * a + 1], 0.0 });
          d2 += gap * gap;
        }
        if (!(d2 > distances[i] * distances[i]))
        {
          asked.push_back(i);
          questions.insert(questions.end(), p, p + 3);
        }
      }
    }
    // Gathered on `rank`, answered there, and the answers scattered back.
    vtkIdType count = static_cast<vtkIdType>(asked.size());
    std::vector<vtkIdType> counts(ranks, 0), lengths(ranks, 0), offsets(ranks, 0);
    this->Controller->Gather(&count, counts.data(), 1, rank);
    vtkIdType total = 0;
    for (int r = 0; r < ranks; ++r)
    {
      lengths[r] = 3 * counts[r];
      offsets[r] = total;
      total += counts[r];
    }
    std::vector<double> received(3 * static_cast<size_t>(total) + 3);
    std::vector<vtkIdType> lengthOffsets(ranks, 0);
    for (int r = 0; r < ranks; ++r)
    {
      lengthOffsets[r] = 3 * offsets[r];
    }
    questions.resize(questions.size() + 3); // never empty: a valid pointer
    this->Controller->GatherV(
      questions.data(), received.data(), 3 * count, lengths.data(), lengthOffsets.data(), rank);
    std::vector<double> answers(static_cast<size_t>(total) + 1);
    if (rank == me)
    {
      vtkSMPTools::For(0,
        total,
        [&](vtkIdType begin, vtkIdType end)
        {
          for (vtkIdType q = begin; q < end; ++q)
          {
            answers[q] = mine.NearestTo(received.data() + 3 * q);
          }
        });
    }
    std::vector<double> replies(static_cast<size_t>(count) + 1);
    this->Controller->ScatterV(
      answers.data(), replies.data(), counts.data(), offsets.data(), count, rank);
    for (vtkIdType q = 0; q < count; ++q)
    {
      distances[asked[q]] = std::min(distances[asked[q]], replies[q]);
    }
  }
}

//------------------------------------------------------------------------------
int vtkMetaballGhostBalls::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkDataObject* output = vtkDataObject::GetData(outputVector, 0);
  this->NumberOfGhostBalls = 0;
  const std::vector<vtkPointSet*> leaves = PointSetLeaves(input);

  // Our own balls: every point not flagged as another process's duplicate;
  // their centres and radii only when there are others to send them to.
  const int ranks = this->Controller ? this->Controller->GetNumberOfProcesses() : 1;
  const pointsurfaces::BallRule rule = this->Field->GetRule();
  std::vector<std::vector<vtkIdType>> own(leaves.size());
  std::vector<pointsurfaces::RadiusSource> sources(leaves.size());
  for (size_t k = 0; k < leaves.size(); ++k)
  {
    vtkPointSet* leaf = leaves[k];
    auto* ghosts = vtkUnsignedCharArray::SafeDownCast(
      leaf->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName()));
    for (vtkIdType i = 0; i < leaf->GetNumberOfPoints(); ++i)
    {
      if (!Duplicate(ghosts, i))
      {
        own[k].push_back(i);
      }
    }
    if (ranks > 1)
    {
      sources[k] = pointsurfaces::ChooseRadii(leaf, rule);
    }
  }
  const double spacing = ranks > 1 ? this->SpacingOfAllProcesses(leaves, own, sources) : 0.0;
  std::vector<double> centres, radii;
  bool negative = false, reported = false;
  for (size_t k = 0; k < leaves.size() && ranks > 1; ++k)
  {
    vtkPointSet* leaf = leaves[k];
    pointsurfaces::RadiusSource& source = sources[k];
    if (source.Rule == pointsurfaces::RadiusRule::Spacing)
    {
      pointsurfaces::ApplySpacing(source, spacing, true);
    }
    if (!reported && !own[k].empty())
    {
      this->Field->ReportRadii(source);
      reported = true;
    }
    vtkDataArray* q = pointsurfaces::StrengthArray(leaf, rule);
    for (vtkIdType i : own[k])
    {
      double p[3];
      leaf->GetPoint(i, p);
      centres.insert(centres.end(), p, p + 3);
      radii.push_back(source.SupportRadius(i));
      negative = negative || (q && q->GetComponent(i, 0) < 0.0);
    }
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
    received = this->ExchangeGhosts(leaves, own, centres, radii, missing);
  }

  // Each leaf as a point cloud of its own balls; the ghosts follow the first
  // non-empty one, flagged.
  bool placed = false;
  const std::vector<vtkSmartPointer<vtkPolyData>> clouds =
    OwnClouds(leaves, own, received, ranks > 1, missing, placed);
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

  // Split across processes: every leaf carries the spacing of all the
  // processes' balls (or none, whatever the input carried), for the mappers.
  if (ranks > 1)
  {
    for (vtkPolyData* cloud : clouds)
    {
      SetSpacingArray(cloud->GetFieldData(), spacing);
    }
  }

  SetCloudsAsOutput(input, output, clouds);
  return 1;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> vtkMetaballGhostBalls::ExchangeGhosts(
  const std::vector<vtkPointSet*>& leaves,
  const std::vector<std::vector<vtkIdType>>& own,
  std::vector<double>& centres,
  std::vector<double>& radii,
  std::set<std::string>& missing)
{
  const int ranks = this->Controller->GetNumberOfProcesses();
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
  if (from.empty())
  {
    return nullptr;
  }
  vtkSmartPointer<vtkPolyData> received = MergePoints(from, all, missing);
  this->NumberOfGhostBalls = received->GetNumberOfPoints();
  return received;
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
