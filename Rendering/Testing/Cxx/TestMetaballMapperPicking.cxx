// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkHardwareSelector on metaballs selects the ball that dominates the
// surface at each pixel, by point id, with point and cell association alike.
// Balls 0 to 3 stand apart; balls 4 and 5 (strengths 1 and 1.8) melt into
// one blob. A 3x3 area at each ball's projected centre must select that ball
// alone, an area of background nothing; over the blob, each pixel must
// select the ball with the larger term q K(r^2 / R^2) at the reference ray's
// hit (pointsurfaces::CastRay), near-ties left out. A cube in front of ball
// 3 hides it, one behind ball 2 does not. Then the actor is moved, turned
// and scaled, and each centre picked again. All with the automatic ray
// caster, then with the GPU one.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkFloatArray.h"
#include "vtkHardwareSelector.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkMatrix4x4.h"
#include "vtkMetaballMapper.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkSmartPointer.h"

#include "psMetaball.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <set>

namespace
{
// The ids selected on `prop` in [x - h, x + h] x [y - h, y + h]; `others`
// counts the selected nodes of other props.
std::set<vtkIdType> Pick(vtkHardwareSelector* selector,
  vtkProp* prop,
  int x,
  int y,
  int h,
  int& others)
{
  selector->SetArea(x - h, y - h, x + h, y + h);
  vtkSmartPointer<vtkSelection> selection;
  selection.TakeReference(selector->Select());
  std::set<vtkIdType> ids;
  for (unsigned int k = 0; selection && k < selection->GetNumberOfNodes(); ++k)
  {
    vtkSelectionNode* node = selection->GetNode(k);
    auto* list = vtkIdTypeArray::SafeDownCast(node->GetSelectionList());
    if (node->GetProperties()->Get(vtkSelectionNode::PROP()) != prop || !list)
    {
      ++others;
      continue;
    }
    for (vtkIdType i = 0; i < list->GetNumberOfTuples(); ++i)
    {
      ids.insert(list->GetValue(i));
    }
  }
  return ids;
}
} // namespace

namespace
{
int Picking(int caster)
{
  const double centres[6][3] = {
    { -3, 2, 0 }, { 3, 2, 0 }, { -3, -2, 0 }, { 0, 0, 0 }, { 2.4, -2, 0 }, { 3.4, -2, 0 }
  };
  const double strengths[6] = { 1, 1, 1, 1, 1, 1.8 }, radii[6] = { 1, 1, 1, 1, 1, 1 };
  vtkNew<vtkPoints> pts;
  vtkNew<vtkFloatArray> strength;
  strength->SetName("Strength");
  for (int i = 0; i < 6; ++i)
  {
    pts->InsertNextPoint(centres[i]);
    strength->InsertNextValue(static_cast<float>(strengths[i]));
  }
  vtkNew<vtkPolyData> balls;
  balls->SetPoints(pts);
  balls->GetPointData()->AddArray(strength);
  vtkNew<vtkMetaballMapper> mapper;
  mapper->SetInputDataObject(balls);
  mapper->SetRayCaster(caster);
  mapper->GetField()->SetStrengthArrayName("Strength");
  mapper->GetField()->SetRadius(1.0); // radii[], not the automatic spacing
  vtkNew<vtkActor> blob, front, back;
  blob->SetMapper(mapper);
  vtkNew<vtkCubeSource> cube;
  vtkNew<vtkPolyDataMapper> cubeMapper;
  cubeMapper->SetInputConnection(cube->GetOutputPort());
  front->SetMapper(cubeMapper); // drawn after the blob, in front of ball 3
  front->SetPosition(0, 0, 1.5);
  front->SetScale(0.5);
  back->SetMapper(cubeMapper); // drawn after the blob, behind ball 2
  back->SetPosition(-3, -2, -1.5);
  back->SetScale(1.6);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(blob);
  renderer->AddActor(front);
  renderer->AddActor(back);
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(300, 300);
  renWin->SetMultiSamples(0);
  renWin->AddRenderer(renderer);
  renderer->ResetCamera();
  renWin->Render();

  // Ball i's centre (through the actor's matrix) in display coordinates.
  auto project = [&](int i, double display[3])
  {
    const double c[4] = { centres[i][0], centres[i][1], centres[i][2], 1.0 };
    double w[4];
    blob->GetMatrix()->MultiplyPoint(c, w);
    renderer->SetWorldPoint(w);
    renderer->WorldToDisplay();
    renderer->GetDisplayPoint(display);
  };
  // A 3x3 area at each centre selects that ball alone (ball 3 nothing when
  // `hidden`; with cell association, the cube in front of it).
  auto pickCentres = [&](vtkHardwareSelector* selector, bool hidden)
  {
    int failures = 0;
    const bool cells = selector->GetFieldAssociation() == vtkDataObject::FIELD_ASSOCIATION_CELLS;
    for (int i = 0; i < 6; ++i)
    {
      double d[3];
      project(i, d);
      int others = 0;
      const std::set<vtkIdType> ids = Pick(selector, blob, int(d[0]), int(d[1]), 1, others);
      if ((hidden && i == 3) ? !ids.empty() || others != (cells ? 1 : 0)
                             : ids != std::set<vtkIdType>{ i } || others != 0)
      {
        std::cerr << "Ball " << i << ": " << ids.size() << " ids selected (first "
                  << (ids.empty() ? -1 : *ids.begin()) << "), " << others << " other props\n";
        ++failures;
      }
    }
    return failures;
  };

  pointsurfaces::MetaballSet set;
  set.Centers = &centres[0][0];
  set.Radii = radii;
  set.Strengths = strengths;
  set.Count = 6;
  int failures = 0;
  for (const int association :
    { vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataObject::FIELD_ASSOCIATION_CELLS })
  {
    vtkNew<vtkHardwareSelector> selector;
    selector->SetRenderer(renderer);
    selector->SetFieldAssociation(association);
    failures += pickCentres(selector, true);
    int others = 0;
    if (!Pick(selector, blob, 8, 8, 4, others).empty() || others)
    {
      std::cerr << "The background selected something\n";
      ++failures;
    }

    // Pixel by pixel over the blob of balls 4 and 5, against the reference.
    double lo[3], hi[3], eye[3];
    project(4, lo);
    project(5, hi);
    renderer->GetActiveCamera()->GetPosition(eye);
    const int x0 = int(lo[0]) - 25, x1 = int(hi[0]) + 25, y0 = int(lo[1]) - 12, y1 = y0 + 24;
    selector->SetArea(x0, y0, x1, y1);
    selector->CaptureBuffers();
    int compared = 0, wrong = 0, disagree = 0, seen[2] = { 0, 0 };
    for (int y = y0; y <= y1; ++y)
    {
      for (int x = x0; x <= x1; ++x)
      {
        const unsigned int pos[2] = { static_cast<unsigned int>(x), static_cast<unsigned int>(y) };
        const vtkHardwareSelector::PixelInformation info = selector->GetPixelInformation(pos);
        renderer->SetDisplayPoint(x + 0.5, y + 0.5, 1.0); // on the far plane
        renderer->DisplayToWorld();
        double p[4], dir[3], w[2] = { 0, 0 };
        renderer->GetWorldPoint(p);
        for (int c = 0; c < 3; ++c)
        {
          dir[c] = p[c] / p[3] - eye[c];
        }
        const pointsurfaces::RayHit hit = pointsurfaces::CastRay(set, eye, dir, 0, 1, 1e-4, 50);
        if (hit.Hit != (info.Valid && info.Prop == blob.GetPointer()))
        {
          ++disagree; // a silhouette pixel
          continue;
        }
        for (int b = 0; b < 2 && hit.Hit; ++b)
        {
          const double* c = centres[4 + b];
          const double r2 = std::pow(hit.Point[0] - c[0], 2) + std::pow(hit.Point[1] - c[1], 2) +
            std::pow(hit.Point[2] - c[2], 2);
          w[b] = r2 < 1 ? strengths[4 + b] * pointsurfaces::KernelValue(set.Kernel, r2) : 0.0;
        }
        if (hit.Hit && std::abs(w[0] - w[1]) > 1e-3 * (w[0] + w[1]))
        {
          const vtkIdType expected = w[0] > w[1] ? 4 : 5;
          ++compared;
          ++seen[expected - 4];
          wrong += info.AttributeID == expected ? 0 : 1;
        }
      }
    }
    selector->ClearBuffers();
    std::cout << "association " << association << ": " << compared << " blob pixels (" << seen[0]
              << " of ball 4, " << seen[1] << " of ball 5), " << wrong << " wrong, " << disagree
              << " hit/miss disagreements\n";
    if (wrong || seen[0] < 20 || seen[1] < 20 || disagree > compared / 10)
    {
      std::cerr << "The blob's pixels select the wrong balls\n";
      ++failures;
    }
  }

  // The actor moved, turned and scaled (the radii scale with it).
  renderer->RemoveActor(front);
  renderer->RemoveActor(back);
  blob->SetPosition(0.4, -0.3, 0.2);
  blob->RotateZ(25);
  blob->SetScale(1.2);
  renderer->ResetCamera();
  renWin->Render();
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(renderer);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_POINTS);
  failures += pickCentres(selector, false);
  return failures;
}
} // namespace

int TestMetaballMapperPicking(int, char*[])
{
  // The automatic caster (the CPU one on a software renderer, whose upload
  // keeps the host's balls) and the GPU one (whose upload does not: the
  // selection makes them when it runs).
  int failures = 0;
  for (const int caster : { vtkMetaballMapper::AUTOMATIC, vtkMetaballMapper::GPU })
  {
    const int f = Picking(caster);
    if (f)
    {
      std::cerr << "picking failed with ray caster " << caster << "\n";
    }
    failures += f;
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
