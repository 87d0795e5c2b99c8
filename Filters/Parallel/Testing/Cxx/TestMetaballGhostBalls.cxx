// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Metaballs split across MPI ranks (run under mpiexec, any number of ranks,
// one included): 1 500 balls with radii and colours in slabs along x, one
// slab per rank. Each rank adds its ghost balls (vtkMetaballGhostBalls),
// then:
// - the field: at points inside its own balls' supports, its balls (own and
//   ghosts) give the whole set's field to 1e-12;
// - the picture: every rank renders its balls with vtkMetaballMapper under
//   one camera, rank 0 composites colour by nearest depth, as ParaView's
//   IceT does, and compares with one render of all the balls: at most 0.05 %
//   of the pixels may differ by more than 40/255. The same composite of the
//   ranks' own balls alone (the seams this filter removes) is measured too,
//   and must differ more;
// - a composite input (a multiblock of a poly data and an unstructured grid
//   holding a rank's balls, the latter with an array of its own and a copy
//   of another rank's ball flagged as a duplicate point, and an empty leaf
//   without arrays): the same structure back, the copy dropped, the same
//   ghosts, which follow the first leaf, and every leaf keeps its arrays;
// - bad input: a rank with no balls, NaN centres and zero radii take part
//   without hanging or sending them;
// - no radius array and no radius: the automatic radii follow the mean
//   nearest-neighbour spacing of all the balls (the serial one to 1e-12),
//   the same number on every rank, passed on in the field data, where the
//   mappers' rule takes it.
#include "vtkMetaballGhostBalls.h"

#include "psBallExtraction.h"
#include "psMetaball.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkMPIController.h"
#include "vtkMetaballMapper.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <vector>

namespace
{
const int Size = 240;

// The balls: centres, radius array "Radius", scalars "Value", of the ranks
// rank `rank` of `ranks` (a rank owns a slab of x), or all of them.
vtkSmartPointer<vtkPolyData> MakeBalls(int rank, int ranks, bool all)
{
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> x(-2.4, 2.4), yz(-0.9, 0.9), r(0.22, 0.42);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkFloatArray> radius, value;
  radius->SetName("Radius");
  value->SetName("Value");
  for (int i = 0; i < 1500; ++i)
  {
    const double p[3] = { x(gen), yz(gen), yz(gen) };
    const double R = r(gen);
    const int owner = std::min(ranks - 1, static_cast<int>((p[0] + 2.4) / 4.8 * ranks));
    if (all || owner == rank)
    {
      points->InsertNextPoint(p);
      radius->InsertNextValue(static_cast<float>(R));
      value->InsertNextValue(static_cast<float>(p[1] + 0.5 * p[2]));
    }
  }
  auto balls = vtkSmartPointer<vtkPolyData>::New();
  balls->SetPoints(points);
  balls->GetPointData()->AddArray(radius);
  balls->GetPointData()->SetScalars(value);
  return balls;
}

// The field of a point cloud with a "Radius" array, at x.
double Field(vtkPolyData* balls, const double x[3])
{
  const vtkIdType n = balls->GetNumberOfPoints();
  std::vector<double> c(3 * n), r(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    balls->GetPoint(i, &c[3 * i]);
    r[i] = balls->GetPointData()->GetArray("Radius")->GetComponent(i, 0);
  }
  pointsurfaces::MetaballSet set;
  set.Centers = c.data();
  set.Radii = r.data();
  set.Count = n;
  return pointsurfaces::FieldValue(set, x);
}

// Renders `balls` under the common camera: RGB and depth.
void Render(vtkPolyData* balls, vtkUnsignedCharArray* rgb, vtkFloatArray* depth)
{
  vtkNew<vtkMetaballMapper> mapper;
  mapper->SetInputDataObject(balls);
  mapper->GetField()->SetRadiusArrayName("Radius");
  mapper->SetScalarRange(-1.2, 1.2);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.15);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.6, 1.8, 6.5);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewAngle(45);
  camera->SetClippingRange(2.0, 12.0); // not from each rank's own bounds
  vtkNew<vtkRenderWindow> window;
  window->SetSize(Size, Size);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  window->Render();
  window->GetPixelData(0, 0, Size - 1, Size - 1, 0, rgb);
  window->GetZbufferData(0, 0, Size - 1, Size - 1, depth);
}

// Rank 0: the share of pixels where the nearest-depth composite of every
// rank's image differs from `serial` by more than 40/255 in a channel.
double CompositeDifference(vtkMultiProcessController* c,
  vtkPolyData* balls,
  vtkUnsignedCharArray* serial)
{
  vtkNew<vtkUnsignedCharArray> rgb, allRgb;
  vtkNew<vtkFloatArray> depth, allDepth;
  Render(balls, rgb, depth);
  c->Gather(rgb, allRgb, 0);
  c->Gather(depth, allDepth, 0);
  if (c->GetLocalProcessId() != 0)
  {
    return 0.0;
  }
  const int pixels = Size * Size;
  int differ = 0;
  for (int p = 0; p < pixels; ++p)
  {
    int nearest = 0;
    for (int k = 1; k < c->GetNumberOfProcesses(); ++k)
    {
      if (allDepth->GetValue(k * pixels + p) < allDepth->GetValue(nearest * pixels + p))
      {
        nearest = k;
      }
    }
    bool bad = false;
    for (int ch = 0; ch < 3; ++ch)
    {
      const int a = allRgb->GetValue(3 * (nearest * pixels + p) + ch);
      bad = bad || std::abs(a - serial->GetValue(3 * p + ch)) > 40;
    }
    differ += bad ? 1 : 0;
  }
  return static_cast<double>(differ) / pixels;
}
} // namespace

int TestMetaballGhostBalls(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  vtkMultiProcessController::SetGlobalController(controller);
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  int failures = 0;
  auto check = [&](bool ok, const char* what)
  {
    if (!ok)
    {
      std::cerr << "FAILED (rank " << rank << "): " << what << "\n";
      ++failures;
    }
  };

  vtkSmartPointer<vtkPolyData> all = MakeBalls(0, 1, true);
  vtkSmartPointer<vtkPolyData> mine = MakeBalls(rank, ranks, false);
  vtkNew<vtkMetaballGhostBalls> ghosts;
  ghosts->SetInputDataObject(mine);
  ghosts->GetField()->SetRadiusArrayName("Radius");
  ghosts->Update();
  vtkPolyData* out = vtkPolyData::SafeDownCast(ghosts->GetOutputDataObject(0));
  const vtkIdType own = mine->GetNumberOfPoints();
  check(out && out->GetNumberOfPoints() == own + ghosts->GetNumberOfGhostBalls() &&
      out->GetNumberOfVerts() == out->GetNumberOfPoints(),
    "own balls and ghosts, one vertex each");
  check(out && out->GetPointData()->GetScalars() && out->GetPointData()->GetArray("Radius"),
    "point arrays kept");
  check((ranks > 1) == (ghosts->GetNumberOfGhostBalls() > 0), "ghosts exactly when split");
  auto* flags = out ? vtkUnsignedCharArray::SafeDownCast(
                        out->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName()))
                    : nullptr;
  check(ranks == 1 ||
      (flags && flags->GetValue(0) == 0 &&
        flags->GetValue(out->GetNumberOfPoints() - 1) == vtkDataSetAttributes::DUPLICATEPOINT),
    "ghosts flagged as duplicate points");

  // The field inside own supports.
  std::mt19937 gen(100 + rank);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int exact = 0, samples = 0;
  for (vtkIdType s = 0; s < 300 && own > 0; ++s)
  {
    const vtkIdType b = std::uniform_int_distribution<vtkIdType>(0, own - 1)(gen);
    double x[3];
    mine->GetPoint(b, x);
    const double R = mine->GetPointData()->GetArray("Radius")->GetComponent(b, 0);
    for (double& v : x)
    {
      v += 0.57 * R * u(gen);
    }
    const double whole = Field(all, x);
    exact += std::abs(Field(out, x) - whole) <= 1e-12 * (1.0 + std::abs(whole)) ? 1 : 0;
    ++samples;
  }
  check(exact == samples, "the whole field inside own supports");
  std::cout << "rank " << rank << ": " << own << " balls, " << ghosts->GetNumberOfGhostBalls()
            << " ghosts, field exact at " << exact << " of " << samples << " points\n";

  // The picture.
  vtkNew<vtkUnsignedCharArray> serial;
  if (rank == 0)
  {
    vtkNew<vtkFloatArray> depth;
    Render(all, serial, depth);
  }
  const double withGhosts = CompositeDifference(controller, out, serial);
  const double ownOnly = CompositeDifference(controller, mine, serial);
  if (rank == 0)
  {
    std::cout << "composite of " << ranks << " ranks against one render: " << 100 * withGhosts
              << " % of pixels differ with ghost balls, " << 100 * ownOnly << " % without\n";
    check(withGhosts <= 5e-4, "composite with ghosts matches the serial render");
    check(ranks == 1 || ownOnly > 4 * withGhosts + 1e-3, "without ghosts the seams show");
  }

  // A composite input: the first half of our balls in a poly data, the rest
  // in an unstructured grid with a flagged copy of another rank's ball.
  {
    const vtkIdType half = own / 2;
    vtkSmartPointer<vtkPolyData> firstHalf = vtkSmartPointer<vtkPolyData>::New();
    vtkSmartPointer<vtkUnstructuredGrid> rest = vtkSmartPointer<vtkUnstructuredGrid>::New();
    vtkNew<vtkPoints> p0, p1;
    p0->SetDataTypeToDouble();
    p1->SetDataTypeToDouble();
    firstHalf->SetPoints(p0);
    rest->SetPoints(p1);
    firstHalf->GetPointData()->CopyAllocate(mine->GetPointData());
    rest->GetPointData()->CopyAllocate(mine->GetPointData());
    for (vtkIdType i = 0; i < own; ++i)
    {
      vtkPointSet* to = i < half ? static_cast<vtkPointSet*>(firstHalf) : rest;
      const vtkIdType id = to->GetPoints()->InsertNextPoint(mine->GetPoint(i));
      to->GetPointData()->CopyData(mine->GetPointData(), i, id);
    }
    // A foreign ball (the next rank's first; alone, our own first) as a
    // duplicate point: dropped, with one process too (ParaView's client).
    vtkSmartPointer<vtkPolyData> other = MakeBalls((rank + 1) % ranks, ranks, false);
    const vtkIdType copy = rest->GetPoints()->InsertNextPoint(other->GetPoint(0));
    rest->GetPointData()->CopyData(other->GetPointData(), vtkIdType(0), copy);
    vtkNew<vtkUnsignedCharArray> flags2;
    flags2->SetName(vtkDataSetAttributes::GhostArrayName());
    flags2->SetNumberOfValues(rest->GetNumberOfPoints());
    flags2->FillValue(0);
    flags2->SetValue(copy, vtkDataSetAttributes::DUPLICATEPOINT);
    rest->GetPointData()->AddArray(flags2);
    vtkNew<vtkFloatArray> extra;
    extra->SetName("Extra");
    extra->SetNumberOfValues(rest->GetNumberOfPoints());
    extra->FillValue(7.0f);
    rest->GetPointData()->AddArray(extra);
    vtkNew<vtkMultiBlockDataSet> blocks;
    blocks->SetNumberOfBlocks(3);
    blocks->SetBlock(0, firstHalf);
    blocks->SetBlock(1, rest);
    blocks->SetBlock(2, vtkNew<vtkPolyData>());
    vtkNew<vtkMetaballGhostBalls> split;
    split->SetInputDataObject(blocks);
    split->GetField()->SetRadiusArrayName("Radius");
    split->Update();
    auto* result = vtkMultiBlockDataSet::SafeDownCast(split->GetOutputDataObject(0));
    auto* leaf0 = result ? vtkPolyData::SafeDownCast(result->GetBlock(0)) : nullptr;
    auto* leaf1 = result ? vtkPolyData::SafeDownCast(result->GetBlock(1)) : nullptr;
    check(leaf0 && leaf1 && result->GetNumberOfBlocks() == 3, "composite: same structure");
    check(split->GetNumberOfGhostBalls() == ghosts->GetNumberOfGhostBalls(),
      "composite: the same ghosts");
    check(leaf0 && leaf0->GetNumberOfPoints() == half + split->GetNumberOfGhostBalls(),
      "composite: ghosts follow the first leaf");
    check(leaf1 && leaf1->GetNumberOfPoints() == own - half, "composite: duplicate point dropped");
    check(leaf0 && leaf0->GetPointData()->GetArray("Radius") && leaf0->GetPointData()->GetScalars(),
      "composite: the first leaf and its ghosts keep radii and scalars");
    check(leaf1 && leaf1->GetPointData()->GetArray("Extra") &&
        leaf1->GetPointData()->GetArray("Extra")->GetComponent(0, 0) == 7.0,
      "composite: a leaf keeps an array the others lack");
    if (leaf0 && ghosts->GetNumberOfGhostBalls() > 0)
    {
      // The ghosts' radii arrived: the field inside own supports is whole
      // (each Field subtracts the threshold T = 0.5 once).
      double x[3];
      firstHalf->GetPoint(0, x);
      const double whole = Field(all, x);
      const double parts = Field(leaf0, x) + Field(leaf1, x) + 0.5;
      check(std::abs(parts - whole) <= 1e-12 * (1.0 + std::abs(whole)),
        "composite: leaves and ghosts give the whole field");
    }
  }

  // Bad input: the last rank has no balls; NaN and zero radii elsewhere.
  vtkSmartPointer<vtkPolyData> odd = MakeBalls(rank, ranks, false);
  if (rank == ranks - 1)
  {
    odd->Initialize();
  }
  else
  {
    odd->GetPoints()->SetPoint(0, std::nan(""), 0.0, 0.0);
    odd->GetPointData()->GetArray("Radius")->SetComponent(1, 0, 0.0);
  }
  vtkNew<vtkMetaballGhostBalls> again;
  again->SetInputDataObject(odd);
  again->GetField()->SetRadiusArrayName("Radius");
  again->Update();
  vtkPolyData* oddOut = vtkPolyData::SafeDownCast(again->GetOutputDataObject(0));
  check(oddOut != nullptr, "output with bad balls");
  if (rank == ranks - 1 && ranks > 1)
  {
    check(oddOut->GetNumberOfPoints() == 0, "a rank with no balls gets no ghosts");
  }
  if (oddOut && oddOut->GetNumberOfPoints() > 0)
  {
    // Nobody sent a NaN ball: the only NaN point is our own first.
    int nans = 0;
    for (vtkIdType i = 0; i < oddOut->GetNumberOfPoints(); ++i)
    {
      double p[3];
      oddOut->GetPoint(i, p);
      nans += std::isnan(p[0]) ? 1 : 0;
    }
    check(nans == 1, "NaN balls are not sent");
  }

  // No radius array and no radius: the radii follow the mean spacing, the
  // same on every rank, that of all the balls (each ball's nearest
  // neighbour sought on every rank), passed on in the field data.
  {
    vtkSmartPointer<vtkPolyData> bare = MakeBalls(rank, ranks, false);
    bare->GetPointData()->RemoveArray("Radius");
    vtkSmartPointer<vtkPolyData> whole = MakeBalls(0, 1, true);
    const double serial = pointsurfaces::MeasureSpacing(whole).Mean();
    vtkNew<vtkMetaballGhostBalls> spaced;
    spaced->SetInputDataObject(bare);
    spaced->Update();
    auto* result = vtkPolyData::SafeDownCast(spaced->GetOutputDataObject(0));
    vtkDataArray* passed =
      result ? result->GetFieldData()->GetArray(pointsurfaces::MeanSpacingArrayName) : nullptr;
    const double spacing = passed ? passed->GetComponent(0, 0) : 0.0;
    std::vector<double> spacings(ranks);
    controller->AllGather(&spacing, spacings.data(), 1);
    if (ranks > 1)
    {
      check(passed && std::abs(spacing - serial) <= 1e-12 * serial,
        "automatic radii: the spacing of all the balls");
      check(std::all_of(spacings.begin(), spacings.end(), [&](double s) { return s == spacing; }),
        "automatic radii: the same spacing on every rank");
      check(spaced->GetField()->GetRadiusRule() == vtkMetaballField::SpacingRadius &&
          spaced->GetNumberOfGhostBalls() > 0,
        "automatic radii: ghosts exchanged by the spacing rule");
      // What the mappers read: the spacing passed on, not their piece's.
      vtkNew<vtkMetaballField> field;
      const pointsurfaces::RadiusSource source = field->ChooseRadii(result);
      check(source.Rule == pointsurfaces::RadiusRule::Spacing && source.SpacingOfAllProcesses &&
          source.Radius == pointsurfaces::SpacingRadiusFactor * spacing,
        "automatic radii: the mapper's rule takes the spacing passed on");
    }
    else
    {
      check(!passed, "automatic radii: nothing passed on by one process");
    }
    if (rank == 0)
    {
      std::cout << "automatic radii: mean spacing " << spacing << " on " << ranks
                << " rank(s), serial " << serial << "\n";
    }
  }

  int total = 0;
  controller->AllReduce(&failures, &total, 1, vtkCommunicator::SUM_OP);
  controller->Finalize();
  return total == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
