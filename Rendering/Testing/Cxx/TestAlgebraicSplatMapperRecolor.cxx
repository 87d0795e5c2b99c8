// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Colouring changes upload the colours alone: the splats' vertex buffers and
// LOD octree are built again only when the input changes. Splats fitted to a
// unit sphere carry two scalar arrays and two RGBA arrays; after each change
// the picture must equal, pixel for pixel, that of a fresh mapper set up the
// same way, and GetGeometryBuildTime() must stay put:
// - another colour array, another scalar range, another lookup table;
// - the actor's colour and opacity under scalar colouring off;
// - scalar colouring off and on again (other attributes: a rebuild is
//   allowed, the picture must still be right);
// - new values written into the colour array (and Modified());
// - the radii, the points or the poly data itself modified: the geometry is
//   built again.
// Two mappers of the same input coloured directly by the same RGBA array
// share the array (MapScalars passes it through): switching one of them to
// another array must leave the other's pixels as they were.
#include "vtkActor.h"
#include "vtkAlgebraicSplatFitter.h"
#include "vtkAlgebraicSplatMapper.h"
#include "vtkDoubleArray.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include "psRenderTestSupport.h"

#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace
{
constexpr int Size = 160;

std::vector<unsigned char> Grab(vtkRenderWindow* window)
{
  window->Render();
  vtkNew<vtkUnsignedCharArray> rgb;
  window->GetPixelData(0, 0, Size - 1, Size - 1, 0, rgb);
  const unsigned char* p = rgb->GetPointer(0);
  return std::vector<unsigned char>(p, p + 3 * Size * Size);
}

// Pixels (of the columns [x0, x1)) whose colour differs by more than 2 in a channel.
int Differing(const std::vector<unsigned char>& a,
  const std::vector<unsigned char>& b,
  int x0 = 0,
  int x1 = Size)
{
  int count = 0;
  for (int y = 0; y < Size; ++y)
  {
    for (int x = x0; x < x1; ++x)
    {
      const int k = 3 * (y * Size + x);
      bool differs = false;
      for (int c = 0; c < 3; ++c)
      {
        differs = differs || std::abs(int(a[k + c]) - int(b[k + c])) > 2;
      }
      count += differs ? 1 : 0;
    }
  }
  return count;
}

// The colour settings a test step gives a mapper, applied again to a fresh one.
using Setup = std::function<void(vtkAlgebraicSplatMapper*, vtkActor*)>;
} // namespace

int TestAlgebraicSplatMapperRecolor(int, char*[])
{
  vtkNew<vtkAlgebraicSplatFitter> fitter;
  fitter->SetInputData(psFibonacciSphere(3000));
  fitter->SetDegree(2);
  fitter->Update();
  vtkNew<vtkPolyData> splats;
  splats->ShallowCopy(fitter->GetOutput());
  const vtkIdType n = splats->GetNumberOfPoints();
  if (n < 100)
  {
    std::cerr << "The fit gave " << n << " splats\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkDoubleArray> height, across;
  height->SetName("Height");
  across->SetName("Across");
  vtkNew<vtkUnsignedCharArray> warm, cold;
  warm->SetName("Warm");
  cold->SetName("Cold");
  for (vtkUnsignedCharArray* a : { warm.GetPointer(), cold.GetPointer() })
  {
    a->SetNumberOfComponents(4);
    a->SetNumberOfTuples(n);
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    splats->GetPoint(i, p);
    height->InsertNextValue(p[2]);
    across->InsertNextValue(p[0]);
    const auto z = static_cast<unsigned char>(127.5 * (p[2] + 1.0));
    const auto x = static_cast<unsigned char>(127.5 * (p[0] + 1.0));
    const unsigned char w[4] = { 255, z, 0, 255 }, c[4] = { 0, x, 255, 255 };
    warm->SetTypedTuple(i, w);
    cold->SetTypedTuple(i, c);
  }
  for (vtkDataArray* a : { static_cast<vtkDataArray*>(height.GetPointer()),
         static_cast<vtkDataArray*>(across.GetPointer()),
         static_cast<vtkDataArray*>(warm.GetPointer()),
         static_cast<vtkDataArray*>(cold.GetPointer()) })
  {
    splats->GetPointData()->AddArray(a);
  }

  vtkNew<vtkAlgebraicSplatMapper> mapper;
  mapper->SetInputData(splats);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(Size, Size);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);

  vtkNew<vtkLookupTable> rainbow, grey;
  rainbow->SetHueRange(0.667, 0.0);
  rainbow->Build();
  grey->SetHueRange(0.0, 0.0);
  grey->SetSaturationRange(0.0, 0.0);
  grey->SetValueRange(0.2, 1.0);
  grey->Build();
  auto byArray = [&](const char* name, double lo, double hi, vtkLookupTable* lut)
  {
    return [=](vtkAlgebraicSplatMapper* m, vtkActor* a)
    {
      m->ScalarVisibilityOn();
      m->SetScalarModeToUsePointFieldData();
      m->SelectColorArray(name);
      m->SetColorModeToMapScalars();
      m->SetScalarRange(lo, hi);
      m->SetLookupTable(lut);
      a->GetProperty()->SetColor(1.0, 1.0, 1.0);
      a->GetProperty()->SetOpacity(1.0);
    };
  };
  // Coloured directly by an RGBA array.
  auto direct = [&](const char* name)
  {
    vtkLookupTable* lut = rainbow;
    return [=, &byArray](vtkAlgebraicSplatMapper* m, vtkActor* a)
    {
      byArray(name, 0.0, 1.0, lut)(m, a);
      m->SetColorModeToDirectScalars();
    };
  };
  // The actor's colour and opacity, no scalar colouring.
  auto solid = [](double r, double g, double b, double opacity)
  {
    return [=](vtkAlgebraicSplatMapper* m, vtkActor* a)
    {
      m->ScalarVisibilityOff();
      a->GetProperty()->SetColor(r, g, b);
      a->GetProperty()->SetOpacity(opacity);
    };
  };
  const Setup first = byArray("Height", -1.0, 1.0, rainbow);
  first(mapper, actor);
  window->Render();
  renderer->ResetCamera();
  const vtkMTimeType built = mapper->GetGeometryBuildTime();
  if (built == 0)
  {
    std::cerr << "No geometry build time after the first render\n";
    return EXIT_FAILURE;
  }

  int failures = 0;
  // Applies `setup`, renders, and compares with a fresh mapper set up alike.
  auto check = [&](const std::string& what, const Setup& setup, bool geometryKept)
  {
    setup(mapper, actor);
    const vtkMTimeType before = mapper->GetGeometryBuildTime();
    const std::vector<unsigned char> recoloured = Grab(window);
    const bool kept = mapper->GetGeometryBuildTime() == before;
    vtkNew<vtkAlgebraicSplatMapper> fresh;
    fresh->SetInputData(splats);
    actor->SetMapper(fresh);
    setup(fresh, actor);
    const std::vector<unsigned char> expected = Grab(window);
    actor->SetMapper(mapper);
    const int differing = Differing(recoloured, expected);
    std::cout << what << ": " << differing << " pixels differ from a fresh mapper's, geometry "
              << (kept ? "kept" : "rebuilt") << "\n";
    if (differing > 0)
    {
      std::cerr << what << ": the picture differs from a fresh mapper's\n";
      ++failures;
    }
    if (geometryKept && !kept)
    {
      std::cerr << what << ": the vertex buffers were built again\n";
      ++failures;
    }
  };
  check("another array", byArray("Across", -1.0, 1.0, rainbow), true);
  check("another range", byArray("Across", -0.5, 0.5, rainbow), true);
  check("another lookup table", byArray("Across", -0.5, 0.5, grey), true);
  check("direct RGBA", direct("Warm"), true);
  check("scalars off", solid(0.9, 0.6, 0.2, 1.0), false);
  check("actor colour", solid(0.2, 0.8, 0.4, 1.0), true);
  check("actor opacity", solid(0.2, 0.8, 0.4, 0.5), true);
  check("scalars on again", byArray("Height", -1.0, 1.0, rainbow), false);
  // New values in the colour array itself (a time step of a field over fixed
  // splats): the input's MTime moves, its geometry does not.
  check(
    "new values in place",
    [&](vtkAlgebraicSplatMapper* m, vtkActor* a)
    {
      byArray("Height", -1.0, 1.0, rainbow)(m, a);
      for (vtkIdType i = 0; i < n; ++i)
      {
        height->SetValue(i, -splats->GetPoint(i)[2]);
      }
      height->Modified();
    },
    true);

  // A splat array, the points or the poly data modified: everything is built again.
  for (vtkObject* changed :
    { static_cast<vtkObject*>(splats->GetPointData()->GetArray("SplatRadius")),
      static_cast<vtkObject*>(splats->GetPoints()),
      static_cast<vtkObject*>(splats) })
  {
    const vtkMTimeType before = mapper->GetGeometryBuildTime();
    changed->Modified();
    window->Render();
    if (mapper->GetGeometryBuildTime() == before)
    {
      std::cerr << "The " << changed->GetClassName()
                << " was modified, but the vertex buffers were not built again\n";
      ++failures;
    }
  }

  // Two mappers of one input, coloured directly by one RGBA array (passed
  // through by MapScalars): the left one switches arrays, the right one's
  // pixels stay.
  vtkNew<vtkAlgebraicSplatMapper> left, right;
  vtkNew<vtkActor> leftActor, rightActor;
  const Setup warmDirect = direct("Warm");
  for (auto pair : { std::make_pair(left.GetPointer(), leftActor.GetPointer()),
         std::make_pair(right.GetPointer(), rightActor.GetPointer()) })
  {
    pair.first->SetInputData(splats);
    pair.second->SetMapper(pair.first);
    warmDirect(pair.first, pair.second);
  }
  leftActor->SetPosition(-1.2, 0.0, 0.0);
  rightActor->SetPosition(1.2, 0.0, 0.0);
  renderer->RemoveActor(actor);
  renderer->AddActor(leftActor);
  renderer->AddActor(rightActor);
  renderer->ResetCamera();
  const std::vector<unsigned char> both = Grab(window);
  left->SelectColorArray("Cold");
  const std::vector<unsigned char> switched = Grab(window);
  const int leftChanged = Differing(both, switched, 0, Size / 2);
  const int rightChanged = Differing(both, switched, Size / 2, Size);
  std::cout << "shared RGBA array: " << leftChanged << " pixels changed on the left, "
            << rightChanged << " on the right\n";
  if (leftChanged < 100)
  {
    std::cerr << "The left mapper's new colours did not show\n";
    ++failures;
  }
  if (rightChanged > 0)
  {
    std::cerr << "The right mapper's colours changed with the left one's\n";
    ++failures;
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
