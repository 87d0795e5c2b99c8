// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// vtkStreamingSplatMapper on a fitted sphere written as a splat file (three
// levels, pages of 128 splats, a colour array), against
// vtkAlgebraicSplatMapper drawing the whole file (vtkSplatFileReader):
// - without a budget, reading before it draws: the same picture, coloured
//   by the file's array;
// - with its loading thread: the first render returns without waiting, and
//   rendering until Loading is false ends on the same picture; under an
//   interactor's event loop (x11 variant), the mapper's own timer renders
//   until every page is drawn (RenderWhileLoading);
// - a budget that holds the coarsest level and little more: at most the
//   budget in memory, fewer splats, and no holes (the coarse splats keep
//   their size): the sphere covers as many pixels as the whole file;
// - with a PixelError, the splats drawn are those the view wants, also
//   after a close view left finer levels in memory;
// - a close view within a budget of a third of the file: only pages in
//   view are loaded, and the picture is the whole file's; with shadows, the
//   light's view loads nothing of its own;
// - IncrementalUpload along an orbit within that budget: the same splats
//   and picture as gathering the resident set on each arrival, in the
//   budget's rows, uploading what arrives; picking picks rows in use only;
// - the bounds are the file's before anything is drawn;
// - a budget smaller than one page (a warning, nothing drawn), a truncated
//   file (one error naming it) and no FileName (one error): no crash.
#include "psIOTestSupport.h"
#include "psSplatFileTestSupport.h"

#include "vtkActor.h"
#include "vtkAlgebraicSplatMapper.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkHardwareSelector.h"
#include "vtkLight.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkSplatDataModel.h"
#include "vtkSplatFileReader.h"
#include "vtkStreamingSplatMapper.h"
#include "vtkXRenderWindowInteractor.h"

#include <cstdlib>

using namespace pointsurfaces_test;

namespace
{
constexpr int Size = 240;
const double Background[3] = { 0.1, 0.2, 0.3 };

struct Scene
{
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkActor> Actor;
  Scene(vtkMapper* mapper, double zoom)
  {
    this->Actor->SetMapper(mapper);
    this->Renderer->AddActor(this->Actor);
    this->Renderer->SetBackground(Background[0], Background[1], Background[2]);
    this->Window->SetSize(Size, Size);
    this->Window->SetMultiSamples(0);
    this->Window->AddRenderer(this->Renderer);
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetPosition(0, 0, 6);
    camera->SetFocalPoint(0.3, 0.3, 0.8);
    camera->SetViewUp(0, 1, 0);
    camera->Zoom(zoom);
    camera->SetClippingRange(1.0, 20.0);
  }
  std::vector<unsigned char> Pixels()
  {
    this->Window->Render();
    vtkNew<vtkUnsignedCharArray> rgb;
    this->Window->GetPixelData(0, 0, Size - 1, Size - 1, 0, rgb);
    return std::vector<unsigned char>(rgb->GetPointer(0), rgb->GetPointer(0) + 3 * Size * Size);
  }
};

// Share of pixels whose colour differs by more than 8 in some channel.
double Differ(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b)
{
  long long n = 0;
  for (size_t k = 0; k < a.size(); k += 3)
  {
    bool d = false;
    for (int c = 0; c < 3; ++c)
    {
      d = d || std::abs(int(a[k + c]) - int(b[k + c])) > 8;
    }
    n += d ? 1 : 0;
  }
  return static_cast<double>(n) / (a.size() / 3);
}

// Pixels that are not the background.
long long Covered(const std::vector<unsigned char>& a)
{
  long long n = 0;
  for (size_t k = 0; k < a.size(); k += 3)
  {
    bool fg = false;
    for (int c = 0; c < 3; ++c)
    {
      fg = fg || std::abs(int(a[k + c]) - int(255.0 * Background[c] + 0.5)) > 2;
    }
    n += fg ? 1 : 0;
  }
  return n;
}

void ColourBy(vtkMapper* mapper)
{
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray("Colour");
  mapper->SetColorModeToDirectScalars();
  mapper->ScalarVisibilityOn();
}

// The whole file through vtkSplatFileReader and vtkAlgebraicSplatMapper.
std::vector<unsigned char> Reference(const std::string& path, double zoom)
{
  vtkNew<vtkSplatFileReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetMemoryBudget(0.0);
  vtkNew<vtkAlgebraicSplatMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort());
  ColourBy(mapper);
  Scene scene(mapper, zoom);
  return scene.Pixels();
}

vtkSmartPointer<vtkStreamingSplatMapper> Streaming(const std::string& path,
  double budget,
  bool asynchronous)
{
  auto mapper = vtkSmartPointer<vtkStreamingSplatMapper>::New();
  mapper->SetFileName(path.c_str());
  mapper->SetMemoryBudget(budget);
  mapper->SetAsynchronous(asynchronous);
  ColourBy(mapper);
  return mapper;
}

// The streaming mapper, with which of its rows hold a splat in view.
class RowProbe : public vtkStreamingSplatMapper
{
public:
  static RowProbe* New();
  vtkTypeMacro(RowProbe, vtkStreamingSplatMapper);
  bool InUse(vtkIdType row) const
  {
    return row >= 0 && row < static_cast<vtkIdType>(this->RowsInUse.size()) &&
      this->RowsInUse[row] != 0;
  }
};
vtkStandardNewMacro(RowProbe);

struct Messages
{
  vtkNew<vtkTest::ErrorObserver> Observer;
  vtkNew<vtkCallbackCommand> Errors, Warnings;
  explicit Messages(vtkObject* o)
  {
    this->Errors->SetCallback(CountError);
    this->Warnings->SetCallback(CountWarning);
    o->AddObserver(vtkCommand::ErrorEvent, this->Observer);
    o->AddObserver(vtkCommand::WarningEvent, this->Observer);
    o->AddObserver(vtkCommand::ErrorEvent, this->Errors);
    o->AddObserver(vtkCommand::WarningEvent, this->Warnings);
  }
};
} // namespace

int TestStreamingSplatMapper(int, char*[])
{
  // The file: a fitted unit sphere, coloured by position.
  const std::string path = psScratchPath("TestStreamingSplatMapper.psplat");
  const vtkIdType total = psWriteSphereSplatFile(path, 20000, 255.0, 128);

  const std::vector<unsigned char> whole = Reference(path, 1.0);
  const long long wholeCover = Covered(whole);
  Check(wholeCover > Size * Size / 10, "the reference draws the sphere");

  // Bounds before anything is drawn.
  {
    auto mapper = Streaming(path, 0.0, true);
    const double* b = mapper->GetBounds();
    Check(b[0] <= -0.99 && b[1] >= 0.99 && b[2] <= -0.99 && b[3] >= 0.99 && b[4] <= -0.99 &&
        b[5] >= 0.99 && b[1] < 1.5,
      "the bounds are the file's before a render");
  }

  // Synchronous, no budget: the reference picture.
  std::vector<unsigned char> synchronous;
  {
    auto mapper = Streaming(path, 0.0, false);
    Scene scene(mapper, 1.0);
    synchronous = scene.Pixels();
    std::cout << "synchronous: " << mapper->GetNumberOfResidentSplats() << " of "
              << mapper->GetNumberOfSplats() << " splats, " << mapper->GetBytesPerSplat()
              << " GPU bytes each, differs from the reference at "
              << 100 * Differ(synchronous, whole) << " % of the pixels\n";
    Check(mapper->GetNumberOfSplats() == total, "the mapper counts the file's splats");
    Check(Differ(synchronous, whole) < 0.005, "without a budget, the whole file's picture");
  }

  // Asynchronous: render until nothing is loading.
  {
    auto mapper = Streaming(path, 0.0, true);
    Scene scene(mapper, 1.0);
    scene.Pixels();
    const vtkIdType first = mapper->GetNumberOfResidentSplats();
    int renders = 1;
    std::vector<unsigned char> last;
    while (true)
    {
      const bool loading = mapper->GetLoading();
      Check(mapper->WaitForPages(60.0), "WaitForPages returns");
      last = scene.Pixels();
      ++renders;
      if (!loading || renders > 100)
      {
        break;
      }
    }
    std::cout << "asynchronous: first render " << first << " splats, " << renders << " renders to "
              << mapper->GetNumberOfResidentSplats() << "\n";
    Check(first < total || renders == 2, "the first render does not wait for every page");
    Check(mapper->GetNumberOfResidentSplats() == total && Differ(last, synchronous) < 0.001,
      "the loading thread ends on the whole picture");
  }

  // Asynchronous with RenderWait (batch jobs): the first render waits for its pages.
  {
    auto mapper = Streaming(path, 0.0, true);
    mapper->SetRenderWait(60.0);
    Scene scene(mapper, 1.0);
    const std::vector<unsigned char> first = scene.Pixels();
    std::cout << "asynchronous, RenderWait 60 s: the first render draws "
              << mapper->GetNumberOfResidentSplats() << " splats\n";
    Check(mapper->GetNumberOfResidentSplats() == total && Differ(first, synchronous) < 0.001,
      "with RenderWait, the first render is the whole picture");
  }

  // RenderWhileLoading, under an interactor's event loop (an X window: the
  // x11 variant of this test): the mapper's own timer renders until every
  // page is drawn, with no render asked for by the program after the first.
  const char* windowKind = std::getenv("POINTSURFACES_RENDER_WINDOW");
  if (windowKind && std::string(windowKind) == "x11" && std::getenv("DISPLAY"))
  {
    auto mapper = Streaming(path, 0.0, true);
    mapper->SetLoadingRenderInterval(20);
    Scene scene(mapper, 1.0);
    // An X interactor as such: the test driver's object factory would give
    // vtkTestingInteractor, whose Start() compares images instead of
    // running an event loop.
    vtkNew<vtkXRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(scene.Window);
    int renders = 0;
    vtkIdType first = -1;
    bool timedOut = false;
    vtkNew<vtkCallbackCommand> onRender;
    struct Loop
    {
      vtkStreamingSplatMapper* Mapper;
      vtkRenderWindowInteractor* Interactor;
      int* Renders;
      vtkIdType* First;
    } loop{ mapper, interactor, &renders, &first };
    onRender->SetClientData(&loop);
    onRender->SetCallback(
      [](vtkObject*, unsigned long, void* data, void*)
      {
        auto* l = static_cast<Loop*>(data);
        if (++*l->Renders == 1)
        {
          *l->First = l->Mapper->GetNumberOfResidentSplats();
        }
        if (!l->Mapper->GetLoading())
        {
          l->Interactor->TerminateApp();
        }
      });
    // The window mapped and its first exposures drawn with the actor
    // hidden, so that the renders counted below are the program's first
    // and the mapper's timer's, not the X server's.
    scene.Actor->VisibilityOff();
    interactor->Initialize();
    for (int k = 0; k < 10; ++k)
    {
      interactor->ProcessEvents();
    }
    scene.Actor->VisibilityOn();
    scene.Window->AddObserver(vtkCommand::EndEvent, onRender);
    // A guard: a loop that never ends fails instead of hanging.
    vtkNew<vtkCallbackCommand> onGuard;
    const int guard = interactor->CreateOneShotTimer(60000);
    int mapperTimers = 0; // timer events that are not the guard's: the mapper's
    struct Guard
    {
      bool* TimedOut;
      int Id;
      vtkRenderWindowInteractor* Interactor;
      int* Others;
    } g{ &timedOut, guard, interactor, &mapperTimers };
    onGuard->SetClientData(&g);
    onGuard->SetCallback(
      [](vtkObject*, unsigned long, void* data, void* callData)
      {
        auto* gd = static_cast<Guard*>(data);
        if (callData && *static_cast<int*>(callData) == gd->Id)
        {
          *gd->TimedOut = true;
          gd->Interactor->TerminateApp();
        }
        else
        {
          ++*gd->Others;
        }
      });
    interactor->AddObserver(vtkCommand::TimerEvent, onGuard);
    scene.Window->Render();
    if (mapper->GetLoading())
    {
      interactor->Start();
    }
    std::cout << "render while loading: first render " << first << " splats, " << renders
              << " renders (" << mapperTimers << " on the mapper's timer) to "
              << mapper->GetNumberOfResidentSplats() << (timedOut ? " (timed out)" : "") << "\n";
    Check(!timedOut && mapper->GetNumberOfResidentSplats() == total && !mapper->GetLoading(),
      "the mapper's own timer renders until every page is drawn");
    Check(first < total ? mapperTimers >= 1 : true, "renders came from the mapper's timer");
    interactor->DestroyTimer(guard);
  }

  // A budget of the coarsest level and a little more: no holes.
  {
    auto probe = Streaming(path, 0.0, false);
    Scene s(probe, 1.0);
    s.Pixels();
    const double perSplat = probe->GetBytesPerSplat();
    vtkNew<vtkSplatFileReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkDataArray* lod = reader->GetOutput()->GetPointData()->GetArray(vtkSplatDataModel::LODName());
    long long coarse = 0;
    for (vtkIdType i = 0; lod && i < lod->GetNumberOfTuples(); ++i)
    {
      coarse += lod->GetTuple1(i) == 0 ? 1 : 0;
    }
    const double budget = (coarse + 200) * perSplat / 1e6;
    auto mapper = Streaming(path, budget, false);
    Scene scene(mapper, 1.0);
    const std::vector<unsigned char> pixels = scene.Pixels();
    const vtkIdType resident = mapper->GetNumberOfResidentSplats();
    std::cout << "budget " << budget << " MB (" << coarse << " level-0 splats): " << resident
              << " resident, covering " << Covered(pixels) << " pixels of " << wholeCover << "\n";
    Check(resident >= coarse && resident * perSplat <= budget * 1e6 + 1 && resident < total,
      "a coarse budget: level 0 everywhere, within the budget");
    Check(Covered(pixels) >= 0.99 * wholeCover && Covered(pixels) <= 1.01 * wholeCover,
      "the coarsest levels cover the sphere without holes");
  }

  // With a PixelError, the splats drawn are the levels the view wants
  // (SelectPages, from the file's mean splat scale per page): before and
  // after a close view that loaded finer levels of the pages in view. The
  // mapper's level choice once took its scale from the resident splats
  // only, and drew 450 and 504 of the 530 wanted at PixelError 32: coarser
  // than what was loaded for the view.
  for (const double pixelError : { 0.5, 32.0, 64.0 })
  {
    auto mapper = Streaming(path, 0.0, false);
    mapper->SetLODPixelError(pixelError);
    Scene scene(mapper, 1.0);
    scene.Pixels();
    const vtkIdType farWanted = mapper->GetNumberOfWantedSplats();
    const vtkIdType farDrawn = mapper->GetNumberOfRenderedSplats();
    scene.Renderer->GetActiveCamera()->Zoom(4.0);
    scene.Pixels();
    const vtkIdType closeResident = mapper->GetNumberOfResidentSplats();
    scene.Renderer->GetActiveCamera()->Zoom(0.25);
    scene.Pixels();
    std::cout << "PixelError " << pixelError << ": far view wants " << farWanted << ", draws "
              << farDrawn << "; after a close view (" << closeResident << " resident) wants "
              << mapper->GetNumberOfWantedSplats() << ", draws "
              << mapper->GetNumberOfRenderedSplats() << "\n";
    Check(farDrawn == farWanted && mapper->GetNumberOfRenderedSplats() == farWanted &&
        mapper->GetNumberOfWantedSplats() == farWanted,
      "the levels drawn are the levels the view wants, before and after a close view");
    Check(pixelError > 1.0 ? closeResident > farWanted : farWanted == total,
      "a PixelError leaves finer levels for closer views");
  }

  // A close view within a third of the file: only the pages in view.
  {
    const std::vector<unsigned char> close = Reference(path, 4.0);
    auto probe = Streaming(path, 0.0, false);
    Scene s(probe, 1.0);
    s.Pixels();
    const double budget = total * probe->GetBytesPerSplat() / 3.0 / 1e6;
    auto mapper = Streaming(path, budget, false);
    Scene scene(mapper, 4.0);
    const std::vector<unsigned char> pixels = scene.Pixels();
    std::cout << "close view within " << budget << " MB: " << mapper->GetNumberOfResidentSplats()
              << " of " << total << " splats, differs at " << 100 * Differ(pixels, close)
              << " % of the pixels\n";
    Check(mapper->GetNumberOfResidentSplats() < total / 3 + 1 &&
        mapper->GetNumberOfResidentSplats() == mapper->GetNumberOfWantedSplats(),
      "a close view loads only what it wants, within the budget");
    Check(Differ(pixels, close) < 0.005, "the close view is the whole file's");

    // With shadows: the light's view (vtkShadowMapBakerPass) loads nothing of its own.
    const vtkIdType resident = mapper->GetNumberOfResidentSplats();
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetPosition(5, 0, 0);
    light->SetFocalPoint(0, 0, 0);
    scene.Renderer->AddLight(light);
    psUseShadowMapPasses(scene.Renderer);
    const std::vector<unsigned char> shadowed = scene.Pixels();
    Check(mapper->GetNumberOfResidentSplats() == resident && Covered(shadowed) > 0,
      "with shadows, the pages of the camera's view only");
  }

  // IncrementalUpload along an orbit, close to the sphere within a third of
  // the file, so that pages come and go: the same pages, splats and picture
  // as gathering and uploading the resident set on each arrival, in no more
  // rows than the budget holds, uploading less; hardware picking (which
  // draws every row) picks only rows that hold a resident splat.
  for (const double pixelError : { 0.0, 8.0 })
  {
    auto probe = Streaming(path, 0.0, false);
    Scene s(probe, 1.0);
    s.Pixels();
    const double perSplat = probe->GetBytesPerSplat();
    const double budget = total * perSplat / 3.0 / 1e6;
    vtkNew<RowProbe> incremental;
    incremental->SetFileName(path.c_str());
    incremental->SetMemoryBudget(budget);
    incremental->AsynchronousOff();
    incremental->SetLODPixelError(pixelError);
    ColourBy(incremental);
    auto gathered = Streaming(path, budget, false);
    gathered->IncrementalUploadOff();
    gathered->SetLODPixelError(pixelError);
    Scene a(incremental, 2.5), b(gathered, 2.5);
    long long uploaded = 0, uploadedGathered = 0, arrivals = 0, partial = 0;
    double worst = 0.0;
    bool same = true, withinBudget = true;
    for (int step = 0; step < 12; ++step)
    {
      for (Scene* scene : { &a, &b })
      {
        scene->Renderer->GetActiveCamera()->Azimuth(30.0);
        scene->Renderer->GetActiveCamera()->Elevation(step % 2 ? 15.0 : -15.0);
        scene->Renderer->GetActiveCamera()->OrthogonalizeViewUp();
      }
      const std::vector<unsigned char> pa = a.Pixels(), pb = b.Pixels();
      worst = std::max(worst, Differ(pa, pb));
      same = same &&
        incremental->GetNumberOfResidentSplats() == gathered->GetNumberOfResidentSplats() &&
        incremental->GetNumberOfRenderedSplats() == gathered->GetNumberOfRenderedSplats();
      withinBudget =
        withinBudget && incremental->GetNumberOfAllocatedSplats() * perSplat <= budget * 1e6 + 1;
      const vtkIdType up = incremental->GetNumberOfUploadedSplats();
      uploaded += up;
      uploadedGathered += gathered->GetNumberOfUploadedSplats();
      arrivals += gathered->GetNumberOfUploadedSplats() > 0 ? 1 : 0;
      partial += up > 0 && up < incremental->GetNumberOfResidentSplats() ? 1 : 0;
    }
    std::cout << "orbit within " << budget << " MB, PixelError " << pixelError << ": "
              << incremental->GetNumberOfResidentSplats() << " resident in "
              << incremental->GetNumberOfAllocatedSplats() << " rows; uploaded " << uploaded
              << " splats against " << uploadedGathered << " gathered, " << partial << " of "
              << arrivals << " arrivals uploaded less than the resident set; pictures differ at "
              << 100 * worst << " % of the pixels at most\n";
    Check(same && worst < 0.0005,
      "incremental uploads: the same splats and picture as gathering the resident set");
    Check(withinBudget, "incremental uploads: no more rows than the budget holds");
    Check(arrivals >= 3 && partial >= arrivals / 2 && uploaded < uploadedGathered,
      "incremental uploads: arrivals upload what arrives, not the resident set");

    vtkNew<vtkHardwareSelector> selector;
    selector->SetRenderer(a.Renderer);
    selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_POINTS);
    selector->SetArea(0, 0, Size - 1, Size - 1);
    vtkSmartPointer<vtkSelection> selection;
    selection.TakeReference(selector->Select());
    vtkDataArray* ids = selection && selection->GetNumberOfNodes() == 1
      ? vtkDataArray::SafeDownCast(selection->GetNode(0)->GetSelectionList())
      : nullptr;
    vtkIdType picked = ids ? ids->GetNumberOfTuples() : 0, free = 0;
    for (vtkIdType k = 0; k < picked; ++k)
    {
      free += incremental->InUse(static_cast<vtkIdType>(ids->GetTuple1(k))) ? 0 : 1;
    }
    std::cout << "  picking: " << picked << " splats picked, " << free << " from free rows\n";
    Check(picked > 0 && free == 0, "picking the incremental rows picks resident splats only");
  }

  // A budget below one page: a warning, nothing drawn.
  {
    auto mapper = Streaming(path, 1e-6, false);
    Messages messages(mapper);
    const int before = Warnings;
    Scene scene(mapper, 1.0);
    const std::vector<unsigned char> pixels = scene.Pixels();
    scene.Pixels();
    Check(Warnings - before == 1 &&
        messages.Observer->GetWarningMessage().find("MemoryBudget") != std::string::npos,
      "one warning for a budget below one page (got '" + messages.Observer->GetWarningMessage() +
        "')");
    Check(Covered(pixels) == 0, "nothing drawn within a budget below one page");
  }

  // A truncated file; no file name.
  {
    const std::string bytes = Slurp(path);
    const std::string cut = Write(
      psScratchPath("TestStreamingSplatMapper-cut.psplat"), bytes.substr(0, bytes.size() / 3));
    auto mapper = Streaming(cut, 0.0, true);
    Messages messages(mapper);
    const int before = Errors;
    Scene scene(mapper, 1.0);
    const std::vector<unsigned char> pixels = scene.Pixels();
    scene.Pixels();
    Check(
      Errors - before == 1 && messages.Observer->GetErrorMessage().find(cut) != std::string::npos,
      "one error naming a truncated file (got '" + messages.Observer->GetErrorMessage() + "')");
    Check(Covered(pixels) == 0, "nothing drawn from a truncated file");
    Check(!mapper->GetLoading() && !mapper->WaitForPages(1.0),
      "a truncated file: nothing loading, WaitForPages says so");
    std::remove(cut.c_str());

    vtkNew<vtkStreamingSplatMapper> empty;
    Messages none(empty);
    const int before2 = Errors;
    Scene scene2(empty, 1.0);
    scene2.Pixels();
    Check(Errors - before2 == 1, "one error without a FileName");
  }
  std::remove(path.c_str());
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
