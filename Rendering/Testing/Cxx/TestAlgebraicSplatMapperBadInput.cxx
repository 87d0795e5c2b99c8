// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The splat mapper on bad input and at extreme coordinates:
// - a unit sphere's splats offset to 1e7: the positions keep their precision
//   on the GPU (they are uploaded relative to the data's centre), so the
//   silhouette covers the same pixels as at the origin, and the depth error
//   stays within 1e-3 of the radius;
// - splats with NaN positions, NaN coefficients, zero radii, zero feature
//   sizes and zero normals mixed into a valid set: they are counted, a
//   warning names them, the others are drawn, and GL reports no error;
// - half the splats with the whole set's octree (a subset or a split between
//   ParaView's ranks): the stale octree is replaced by one of the mapper's
//   own, without a warning or a crash;
// - a fragment shader that does not compile (a broken replacement in the
//   actor's shader property): one error over two frames, nothing drawn and
//   no crash (VTK's UpdateShaders would reuse the null program), and the
//   splats back once the replacement is removed;
// - a template without a hook that the mapper fills in: one error naming
//   it, nothing drawn, and the splats back once the template is whole;
// - an empty input and an input that is not a splat set: nothing is drawn
//   and no GL error, with an error message for the latter.
#include "psOpenGL.h"
#include "vtkActor.h"
#include "vtkAlgebraicSplatFitter.h"
#include "vtkAlgebraicSplatMapper.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkLogger.h"
#include "vtkMaskPoints.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkShaderProperty.h"
#include "vtkSplatDataModel.h"
#include "vtkStringOutputWindow.h"
#include "vtkTransform.h"
#include "vtkTransformFilter.h"

#include "psRenderTestSupport.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>

namespace
{
int Warnings = 0;
int Errors = 0;
std::string Messages; // the errors' and warnings' text
void Count(vtkObject*, unsigned long event, void*, void* text)
{
  (event == vtkCommand::WarningEvent ? Warnings : Errors)++;
  Messages += text ? static_cast<const char*>(text) : "";
}

// Covered pixels and the largest depth error against a unit sphere at `centre`.
void Measure(vtkRenderWindow* renWin,
  vtkRenderer* ren,
  const double centre[3],
  int& covered,
  double& worst)
{
  const int* size = renWin->GetSize();
  vtkNew<vtkFloatArray> z;
  renWin->GetZbufferData(0, 0, size[0] - 1, size[1] - 1, z);
  covered = 0;
  worst = 0.0;
  for (int y = 0; y < size[1]; ++y)
  {
    for (int x = 0; x < size[0]; ++x)
    {
      const float depth = z->GetValue(y * size[0] + x);
      if (depth >= 1.0f)
      {
        continue;
      }
      ++covered;
      double w[3];
      psDisplayToWorld(ren, x + 0.5, y + 0.5, depth, w);
      double r2 = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        const double d = w[c] - centre[c];
        r2 += d * d;
      }
      worst = std::max(worst, std::abs(std::sqrt(r2) - 1.0));
    }
  }
}
} // namespace

int TestAlgebraicSplatMapperBadInput(int, char*[])
{
  vtkSmartPointer<vtkPolyData> sphere = psFibonacciSphere(8000);
  vtkNew<vtkAlgebraicSplatFitter> fitter;
  fitter->SetInputData(sphere);
  fitter->SetDegree(2);
  fitter->Update();

  vtkNew<vtkCallbackCommand> counter;
  counter->SetCallback(Count);
  const int size = 120;
  vtkNew<vtkRenderWindow> renWin;
  renWin->SetSize(size, size);
  renWin->SetMultiSamples(0);
  vtkNew<vtkRenderer> renderer;
  renWin->AddRenderer(renderer);
  vtkNew<vtkAlgebraicSplatMapper> mapper;
  mapper->AddObserver(vtkCommand::WarningEvent, counter);
  mapper->AddObserver(vtkCommand::ErrorEvent, counter);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  int failures = 0;
  auto glOk = [&](const char* what)
  {
    static_cast<vtkOpenGLRenderWindow*>(renWin.GetPointer())->MakeCurrent();
    const GLenum e = glGetError();
    if (e != GL_NO_ERROR)
    {
      std::cerr << what << ": GL error " << e << "\n";
      ++failures;
    }
  };
  auto look = [&](const double c[3])
  {
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetFocalPoint(c[0], c[1], c[2]);
    camera->SetPosition(c[0] + 0.3, c[1] + 0.4, c[2] + 4.0);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(40);
    camera->SetClippingRange(1.0, 8.0);
  };

  // The sphere at the origin, then offset to 1e7.
  const double origin[3] = { 0, 0, 0 }, far[3] = { 1e7, -2e7, 3e7 };
  int coveredOrigin = 0, coveredFar = 0;
  double errorOrigin = 0.0, errorFar = 0.0;
  mapper->SetInputData(fitter->GetOutput());
  look(origin);
  renWin->Render();
  Measure(renWin, renderer, origin, coveredOrigin, errorOrigin);
  vtkNew<vtkTransform> move;
  move->Translate(far);
  vtkNew<vtkTransformFilter> moved;
  moved->SetTransform(move);
  moved->SetInputData(fitter->GetOutput());
  moved->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  moved->TransformAllInputVectorsOn();
  moved->Update();
  mapper->SetInputData(vtkPolyData::SafeDownCast(moved->GetOutput()));
  look(far);
  renWin->Render();
  Measure(renWin, renderer, far, coveredFar, errorFar);
  glOk("offset 1e7");
  std::cout << "origin: " << coveredOrigin << " pixels, depth error " << errorOrigin
            << "; at 1e7: " << coveredFar << " pixels, depth error " << errorFar << "\n";
  if (coveredOrigin < 3000 || std::abs(coveredFar - coveredOrigin) > coveredOrigin / 100 ||
    !(errorFar < 1e-3))
  {
    std::cerr << "the splats lose their precision at 1e7\n";
    ++failures;
  }

  // Invalid splats among valid ones.
  vtkNew<vtkPolyData> broken;
  broken->DeepCopy(fitter->GetOutput());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  vtkPointData* pd = broken->GetPointData();
  broken->GetPoints()->SetPoint(0, nan, 0, 0);
  pd->GetArray(vtkSplatDataModel::CoefficientsName())->SetComponent(1, 2, nan);
  pd->GetArray(vtkSplatDataModel::RadiusName())->SetTuple1(2, 0.0);
  pd->GetArray(vtkSplatDataModel::FeatureSizeName())->SetTuple1(3, 0.0);
  const double zero[3] = { 0, 0, 0 };
  pd->GetArray(vtkSplatDataModel::NormalName())->SetTuple(4, zero);
  Warnings = Errors = 0;
  mapper->SetInputData(broken);
  look(origin);
  renWin->Render();
  int covered = 0;
  double error = 0.0;
  Measure(renWin, renderer, origin, covered, error);
  glOk("invalid splats");
  std::cout << mapper->GetNumberOfInvalidSplats() << " invalid splats, " << Warnings
            << " warnings, " << covered << " pixels\n";
  if (mapper->GetNumberOfInvalidSplats() != 5 || Warnings != 1 || covered < coveredOrigin * 9 / 10)
  {
    std::cerr << "invalid splats are not skipped as they should be\n";
    ++failures;
  }

  // Every other splat, the octree's field data passed along unchanged (as a
  // subset, threshold or ParaView's split between ranks leaves it): the
  // octree's ranges no longer index the splats. The mapper builds its own
  // over them (TestAlgebraicSplatMapperLOD checks its LOD): no warning, the
  // splats drawn, no crash.
  {
    vtkNew<vtkMaskPoints> half;
    half->SetInputConnection(fitter->GetOutputPort());
    half->SetOnRatio(2);
    half->GenerateVerticesOn();
    half->SingleVertexPerCellOn();
    half->Update();
    mapper->SetInputConnection(half->GetOutputPort());
    look(origin);
    Warnings = Errors = 0;
    renWin->Render();
    glOk("a subset with the whole set's octree");
    int coveredHalf = 0;
    Measure(renWin, renderer, origin, coveredHalf, error);
    std::cout << "half the splats with the whole octree: " << coveredHalf << " pixels, " << Warnings
              << " warnings, " << Errors << " errors\n";
    if (Warnings != 0 || Errors != 0 || coveredHalf < coveredOrigin / 2 ||
      half->GetOutput()->GetFieldData()->GetArray("OctreeNodeRange") == nullptr)
    {
      std::cerr << "a stale octree (subset) is not replaced as it should be\n";
      ++failures;
    }
    // A level outside SplatLODQuality: no octree can be built, one warning,
    // every splat drawn.
    vtkNew<vtkPolyData> badLevel;
    badLevel->DeepCopy(half->GetOutput());
    vtkDataArray* lod = badLevel->GetPointData()->GetArray("SplatLOD");
    if (lod && lod->GetNumberOfTuples() > 0)
    {
      lod->SetComponent(0, 0, 99.0);
    }
    mapper->SetInputData(badLevel);
    Warnings = Errors = 0;
    renWin->Render();
    glOk("a subset with a level outside the set's");
    int coveredBad = 0;
    Measure(renWin, renderer, origin, coveredBad, error);
    std::cout << "and a level outside the set's: " << coveredBad << " pixels, " << Warnings
              << " warnings, " << Errors << " errors\n";
    if (!lod || Warnings != 1 || Errors != 0 || coveredBad < coveredHalf * 9 / 10)
    {
      std::cerr << "a stale octree without valid levels does not warn and draw everything\n";
      ++failures;
    }
    mapper->SetInputData(nullptr);
  }

  // A shader that does not compile (a broken replacement in the actor's
  // shader property): one error over two frames, nothing drawn, no crash;
  // then the replacement removed, the splats come back.
  {
    mapper->SetInputConnection(fitter->GetOutputPort());
    look(origin);
    actor->GetShaderProperty()->AddFragmentShaderReplacement(
      "//VTK::Light::Impl", true, "this is not GLSL;\n", false);
    // The compiler's own report goes to a string, not to the test's output
    // (nor to the logger's standard error).
    vtkSmartPointer<vtkOutputWindow> console = vtkOutputWindow::GetInstance();
    vtkNew<vtkStringOutputWindow> quiet;
    vtkOutputWindow::SetInstance(quiet);
    const vtkLogger::Verbosity verbosity = vtkLogger::GetCurrentVerbosityCutoff();
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    Errors = 0;
    Messages.clear();
    renWin->Render();
    renWin->Render();
    int coveredBroken = 0;
    Measure(renWin, renderer, origin, coveredBroken, error);
    const int brokenErrors = Errors;
    actor->GetShaderProperty()->ClearAllFragmentShaderReplacements();
    renWin->Render();
    vtkOutputWindow::SetInstance(console);
    vtkLogger::SetStderrVerbosity(verbosity);
    glOk("a shader that does not compile");
    int coveredFixed = 0;
    Measure(renWin, renderer, origin, coveredFixed, error);
    std::cout << "broken shader: " << brokenErrors << " errors, " << coveredBroken
              << " pixels; fixed: " << coveredFixed << " pixels\n";
    if (brokenErrors != 1 || coveredBroken != 0 || coveredFixed < coveredOrigin / 2)
    {
      std::cerr << "a shader compile failure is not handled; the mapper said:\n"
                << Messages.substr(0, 4000) << "\n";
      ++failures;
    }
    mapper->SetInputData(nullptr);
  }

  // A template that lacks a hook the mapper fills in (a replacement run
  // before the mapper's takes //VTK::Depth::Impl away): the shader would
  // compile without the splat code, so the mapper names the missing hook
  // in one error and draws nothing; without the replacement, it draws again.
  {
    mapper->SetInputConnection(fitter->GetOutputPort());
    look(origin);
    actor->GetShaderProperty()->AddFragmentShaderReplacement(
      "//VTK::Depth::Impl", true, "// no depth hook\n", false);
    Errors = 0;
    Messages.clear();
    renWin->Render();
    renWin->Render();
    int coveredHookless = 0;
    Measure(renWin, renderer, origin, coveredHookless, error);
    const int hookErrors = Errors;
    const bool named = Messages.find("//VTK::Depth::Impl") != std::string::npos;
    actor->GetShaderProperty()->ClearAllFragmentShaderReplacements();
    renWin->Render();
    glOk("a template without a hook");
    int coveredBack = 0;
    Measure(renWin, renderer, origin, coveredBack, error);
    std::cout << "missing hook: " << hookErrors << " errors (hook named: " << named << "), "
              << coveredHookless << " pixels; restored: " << coveredBack << " pixels\n";
    if (hookErrors != 1 || !named || coveredHookless != 0 || coveredBack < coveredOrigin / 2)
    {
      std::cerr << "a missing shader hook is not reported\n";
      ++failures;
    }
    mapper->SetInputData(nullptr);
  }

  // Empty input, then points that are not splats.
  Warnings = Errors = 0;
  vtkNew<vtkPolyData> empty;
  mapper->SetInputData(empty);
  renWin->Render();
  glOk("empty input");
  Measure(renWin, renderer, origin, covered, error);
  const int emptyErrors = Errors;
  mapper->SetInputData(sphere);
  renWin->Render();
  glOk("not a splat set");
  int coveredPlain = 0;
  Measure(renWin, renderer, origin, coveredPlain, error);
  std::cout << "empty: " << covered << " pixels, " << emptyErrors
            << " errors; plain points: " << coveredPlain << " pixels, " << Errors - emptyErrors
            << " errors\n";
  if (covered != 0 || emptyErrors != 0 || coveredPlain != 0 || Errors - emptyErrors != 1)
  {
    std::cerr << "empty or non-splat input is not handled\n";
    ++failures;
  }
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
