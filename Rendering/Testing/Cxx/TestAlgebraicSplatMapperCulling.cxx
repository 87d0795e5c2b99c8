// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Face culling by the splats' oriented normals (the actor property's
// BackfaceCulling and FrontfaceCulling): hits whose normal faces away from
// the eye (or towards it) are not there, and the ray goes on. Splats fitted
// to a unit sphere (degree 2, s = 1 and the strongly curved s = 4; the
// fitter orients their normals outward) are drawn opaque and blended, and
// each covered pixel is classed by its depth: near side (the unprojected
// point's outward normal faces the eye), far side, or grazing (|cos| < 0.1).
// - back faces culled: no far-side pixel, and wherever the unculled image
//   shows the near side, the same colour (exactly when opaque; at no more
//   than 0.2 % of the pixels when blended, where back splats within the
//   blend depth of the silhouette no longer join it);
// - front faces culled: no near-side pixel, and the far side covers the
//   sphere's outline (all but 0.2 % of the unculled pixels);
// - both culled: nothing is drawn;
// - all of this through a perspective and a parallel camera, and with a
//   non-uniformly scaled actor (an ellipsoid);
// - from inside the sphere, where every hit is a back face: culling back
//   faces leaves nothing, culling front faces changes nothing;
// - normals left unoriented (OrientNormals off): one warning, and nothing is
//   culled.
// The property's GL face culling would cut the splats' bounding faces by
// their winding: the mapper turns it off while it draws.
#include "vtkActor.h"
#include "vtkAlgebraicSplatFitter.h"
#include "vtkAlgebraicSplatMapper.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"

#include "psRenderTestSupport.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <vector>

namespace
{
struct Frame
{
  std::vector<unsigned char> Colour;
  std::vector<float> Depth;
  int Covered = 0;
};

// Per pixel: 1 near side, -1 far side, 0 grazing or empty, for the unit
// sphere scaled by `scale` (an ellipsoid, outward normal (x/a², y/b², z/c²)).
std::vector<int> Sides(vtkRenderer* ren, const Frame& f, int w, int h, const double scale[3])
{
  vtkCamera* camera = ren->GetActiveCamera();
  double eye[3], direction[3];
  camera->GetPosition(eye);
  camera->GetDirectionOfProjection(direction);
  const bool parallel = camera->GetParallelProjection() != 0;
  std::vector<int> sides(w * h, 0);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const float z = f.Depth[y * w + x];
      if (z >= 1.0f)
      {
        continue;
      }
      double p[3];
      psDisplayToWorld(ren, x + 0.5, y + 0.5, z, p);
      double facing = 0.0, len = 0.0, ray = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        const double n = p[c] / (scale[c] * scale[c]);
        const double r = parallel ? direction[c] : p[c] - eye[c];
        facing += n * r;
        len += n * n;
        ray += r * r;
      }
      const double cosine = facing / std::sqrt(len * ray);
      sides[y * w + x] = cosine < -0.1 ? 1 : (cosine > 0.1 ? -1 : 0);
    }
  }
  return sides;
}

Frame Grab(vtkRenderWindow* renWin)
{
  renWin->Render();
  const int* size = renWin->GetSize();
  Frame f;
  vtkNew<vtkUnsignedCharArray> rgb;
  renWin->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, rgb, 0);
  f.Colour.assign(rgb->GetPointer(0), rgb->GetPointer(0) + 3 * size[0] * size[1]);
  vtkNew<vtkFloatArray> z;
  renWin->GetZbufferData(0, 0, size[0] - 1, size[1] - 1, z);
  f.Depth.assign(z->GetPointer(0), z->GetPointer(0) + size[0] * size[1]);
  for (float d : f.Depth)
  {
    f.Covered += d < 1.0f ? 1 : 0;
  }
  return f;
}

// Pixels whose colour differs by more than `tolerance` or whose coverage differs.
int Differing(const Frame& a, const Frame& b, int tolerance)
{
  int count = 0;
  for (size_t i = 0; i < a.Depth.size(); ++i)
  {
    bool differ = (a.Depth[i] < 1.0f) != (b.Depth[i] < 1.0f);
    for (int c = 0; c < 3 && !differ; ++c)
    {
      differ = std::abs(int(a.Colour[3 * i + c]) - int(b.Colour[3 * i + c])) > tolerance;
    }
    count += differ ? 1 : 0;
  }
  return count;
}
} // namespace

int TestAlgebraicSplatMapperCulling(int, char*[])
{
  vtkSmartPointer<vtkPolyData> cloud = psFibonacciSphere(20000);

  vtkNew<vtkAlgebraicSplatFitter> fitter;
  fitter->SetInputData(cloud);
  fitter->SetDegree(2);
  vtkNew<vtkAlgebraicSplatMapper> mapper;
  mapper->SetInputConnection(fitter->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(200, 200);
  renWin->SetMultiSamples(0);
  renWin->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  auto outside = [camera](bool parallel)
  {
    camera->SetPosition(0.4, -0.6, 3.5);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(40);
    camera->SetClippingRange(1.0, 8.0);
    camera->SetParallelProjection(parallel);
    camera->SetParallelScale(1.4);
  };

  int warnings = 0;
  vtkNew<vtkCallbackCommand> onWarning;
  onWarning->SetClientData(&warnings);
  onWarning->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*) { ++*static_cast<int*>(data); });
  mapper->AddObserver(vtkCommand::WarningEvent, onWarning);

  int failures = 0;
  auto check = [&failures](bool ok, const std::string& what)
  {
    if (!ok)
    {
      std::cerr << "FAILED: " << what << "\n";
      ++failures;
    }
  };
  vtkProperty* property = actor->GetProperty();
  // A frame with the given faces culled; the property is left culling none.
  auto culled = [&](bool back, bool front)
  {
    property->SetBackfaceCulling(back);
    property->SetFrontfaceCulling(front);
    const Frame f = Grab(renWin);
    property->BackfaceCullingOff();
    property->FrontfaceCullingOff();
    return f;
  };
  struct View
  {
    const char* Name;
    bool Parallel;
    double Scale[3]; // the actor's
  };
  const View views[] = { { "perspective", false, { 1, 1, 1 } },
    { "parallel", true, { 1, 1, 1 } },
    { "actor scaled (1, 1.4, 0.6)", false, { 1, 1.4, 0.6 } } };
  for (const View& view : views)
  {
    outside(view.Parallel);
    actor->SetScale(view.Scale[0], view.Scale[1], view.Scale[2]);
    for (double s : { 1.0, 4.0 })
    {
      fitter->SetQualityFactor(s);
      fitter->OrientNormalsOn();
      for (bool blending : { false, true })
      {
        const std::string name = std::string(view.Name) +
          ", s = " + std::to_string(s).substr(0, 3) + (blending ? ", blended" : ", opaque");
        mapper->SetBlending(blending);
        const Frame all = culled(false, false);
        const Frame front = culled(true, false);
        const Frame back = culled(false, true);
        const Frame none = culled(true, true);

        const std::vector<int> sidesAll = Sides(renderer, all, 200, 200, view.Scale);
        const std::vector<int> sidesFront = Sides(renderer, front, 200, 200, view.Scale);
        const std::vector<int> sidesBack = Sides(renderer, back, 200, 200, view.Scale);
        int farInFront = 0, nearInBack = 0, changed = 0;
        for (size_t i = 0; i < sidesAll.size(); ++i)
        {
          farInFront += sidesFront[i] == -1 ? 1 : 0;
          nearInBack += sidesBack[i] == 1 ? 1 : 0;
          bool differ = false;
          for (int c = 0; c < 3 && sidesAll[i] == 1; ++c)
          {
            differ =
              differ || std::abs(int(all.Colour[3 * i + c]) - int(front.Colour[3 * i + c])) > 2;
          }
          changed += differ ? 1 : 0;
        }
        std::cout << name << ": " << fitter->GetOutput()->GetNumberOfPoints() << " splats, "
                  << all.Covered << " pixels; back faces culled: " << farInFront
                  << " far-side pixels, " << changed
                  << " near-side pixels changed; front faces culled: " << back.Covered
                  << " pixels, " << nearInBack << " on the near side; both culled: " << none.Covered
                  << " pixels\n";
        check(all.Covered > 5000, name + ": the sphere is drawn");
        check(farInFront == 0 && (blending ? changed <= 0.002 * all.Covered : changed == 0),
          name + ": culling back faces keeps the near side only, unchanged");
        check(nearInBack == 0 && back.Covered >= 0.998 * all.Covered,
          name + ": culling front faces shows the far side");
        check(none.Covered == 0, name + ": culling both sides draws nothing");
      }
    }
  }
  actor->SetScale(1, 1, 1);

  // From inside the sphere every hit is a back face: culling back faces
  // leaves nothing, culling front faces changes nothing.
  fitter->SetQualityFactor(1.0);
  camera->SetParallelProjection(false);
  camera->SetPosition(0.1, -0.05, 0.0);
  camera->SetFocalPoint(1.0, 0.0, 0.2);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(60);
  camera->SetClippingRange(0.05, 4.0);
  for (bool blending : { false, true })
  {
    mapper->SetBlending(blending);
    const Frame inside = culled(false, false);
    const Frame noBack = culled(true, false);
    const Frame noFront = culled(false, true);
    const int differ = Differing(inside, noFront, blending ? 2 : 0);
    std::cout << "inside, " << (blending ? "blended" : "opaque") << ": " << inside.Covered
              << " pixels; back faces culled: " << noBack.Covered
              << " pixels; front faces culled: " << differ << " pixels differ\n";
    check(inside.Covered > 30000 && noBack.Covered == 0 && differ <= 0.002 * inside.Covered,
      std::string("inside the sphere, ") + (blending ? "blended" : "opaque"));
  }
  outside(false);

  // Unoriented normals: a warning, and no culling.
  fitter->SetQualityFactor(1.0);
  fitter->OrientNormalsOff();
  mapper->SetBlending(false);
  const Frame all = Grab(renWin);
  property->FrontfaceCullingOn();
  const int before = warnings;
  const Frame unculled = Grab(renWin);
  Grab(renWin);
  property->FrontfaceCullingOff();
  std::cout << "unoriented: " << warnings - before << " warning(s), " << Differing(all, unculled, 0)
            << " pixels differ\n";
  check(warnings - before == 1, "unoriented normals: one warning");
  check(Differing(all, unculled, 0) == 0, "unoriented normals: nothing culled");
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
