// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Frame times of the splat and metaball mappers against their peers, in C++
// so that it runs where no Python with VTK does (the GPU bundle of
// scripts/gpu-bundle.sh): one window, one process, every method on the same
// input and camera.
//
// - Splats: N points sampled uniformly by area (seeded) on a mesh's
//   triangles, fitted by vtkAlgebraicSplatFitter, drawn opaque and blended,
//   each without anti-aliasing and with adaptive 2 x 2 and 3 x 3; the peers
//   vtkPointGaussianMapper (opaque sphere sprites) and vtkOpenGLSphereMapper
//   draw all N points at 1.5 mean spacings.
// - Metaballs: N balls uniform in a cube, radius two mean spacings, every
//   frame dynamic (the points are marked modified, so they are uploaded and
//   the grid rebuilt); the grid build and ray cast times are the mapper's
//   GPU timer queries, and upload_ms the wall time of the last frame's
//   upload of the balls; a second row draws them with LevelOfDetailPixels 2
//   and counts the read-backs of its frames. The peer: vtkOpenGLSphereMapper on the same balls at
//   the radius of a lone ball's surface.
//
// - Paging (--paging C, with PointSurfaces::RenderingHDF5): the fitted
//   splats (three levels) and their N points tiled C times in a grid of
//   copies, the splats written as a splat file; vtkStreamingSplatMapper
//   draws the file within --budget MB (LODPixelError 1) while the camera
//   orbits the grid, the peer vtkPointGaussianMapper draws all C x N points
//   from memory on the same orbit. Reported: the median orbit frame, the
//   seconds to the first non-empty picture (in the note), the file's size
//   per input point. A copy of the 1M-point Bunny tiled 100 times is the
//   issue's 10^8 points; the file is deleted afterwards.
//
// A frame is Render() plus a one-pixel depth read-back (which waits for the
// GPU); the median over the frames is reported. CSV goes to stdout and
// <out>/render.csv, a picture of each scene to <out>/*.png, and the EGL
// platform and GL renderer are printed first.
//
// Usage: BenchRender [--smoke] [--size WxH] [--frames N] [--points N]
//                    [--balls N,N,...] [--degree D] [--quality s]
//                    [--paging C] [--budget MB] [--out DIR] mesh.vtp
#include "psMetaball.h"
#include "vtkAlgebraicSplatFitter.h"
#include "vtkAlgebraicSplatMapper.h"
#include "vtkBenchSphereSpriteFS.h"
#include "vtkEGLHeadlessRenderWindow.h"
#include "vtkMetaballField.h"
#include "vtkMetaballMapper.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLSphereMapper.h"
#include "vtkPNGWriter.h"
#include "vtkPointGaussianMapper.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStaticPointLocator.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLPolyDataReader.h"
#ifdef POINTSURFACES_BENCH_PAGING
#include "vtkAppendPolyData.h"
#include "vtkSplatFileWriter.h"
#include "vtkStreamingSplatMapper.h"
#include <cstdio> // For std::remove
#include <thread> // For the first picture's wait
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
struct Options
{
  bool Smoke = false;
  int Width = 1920;
  int Height = 1080;
  int Frames = 20;
  long long Points = 1000000;
  std::vector<long long> Balls{ 100000, 1000000, 10000000 };
  int Degree = 2;
  double Quality = 1.0;
  int PagingCopies = 0; // 0: no paging scene
  double PagingBudget = 2048.0;
  std::string Out = ".";
  std::string Mesh;
};

struct Row
{
  std::string Scene, Method, Setting;
  long long Primitives = 0;
  double FrameMs = 0.0, GridMs = -1.0, CastMs = -1.0, UploadMs = -1.0, FitSeconds = -1.0;
  std::string Note;
};

std::string Fixed(double value, int digits)
{
  if (value < 0.0)
  {
    return "";
  }
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << value;
  return s.str();
}

// The median time of `frames` frames, each Render() plus a one-pixel depth
// read-back, with `before` run ahead of each.
double MedianFrameMs(vtkRenderWindow* window, int frames, const std::function<void()>& before)
{
  std::vector<double> times;
  for (int k = 0; k < frames; ++k)
  {
    if (before)
    {
      before();
    }
    const auto t0 = std::chrono::steady_clock::now();
    window->Render();
    float depth = 0.0f;
    window->GetZbufferData(0, 0, 0, 0, &depth);
    times.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(times.begin(), times.end());
  return times.empty() ? 0.0 : times[times.size() / 2];
}

void WritePicture(vtkRenderWindow* window, const std::string& file)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(file.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
}

// `n` points uniformly by area on the triangles of `mesh`, with vertex cells.
vtkSmartPointer<vtkPolyData> SampleSurface(vtkPolyData* mesh, long long n, unsigned seed)
{
  std::vector<vtkIdType> triangles;
  std::vector<double> cumulative;
  double total = 0.0;
  vtkCellArray* polys = mesh->GetPolys();
  vtkNew<vtkIdList> cell;
  for (polys->InitTraversal(); polys->GetNextCell(cell);)
  {
    if (cell->GetNumberOfIds() != 3)
    {
      continue;
    }
    double a[3], b[3], c[3], u[3], v[3], w[3];
    mesh->GetPoint(cell->GetId(0), a);
    mesh->GetPoint(cell->GetId(1), b);
    mesh->GetPoint(cell->GetId(2), c);
    for (int k = 0; k < 3; ++k)
    {
      u[k] = b[k] - a[k];
      v[k] = c[k] - a[k];
    }
    w[0] = u[1] * v[2] - u[2] * v[1];
    w[1] = u[2] * v[0] - u[0] * v[2];
    w[2] = u[0] * v[1] - u[1] * v[0];
    total += 0.5 * std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    triangles.insert(triangles.end(), { cell->GetId(0), cell->GetId(1), cell->GetId(2) });
    cumulative.push_back(total);
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  if (cumulative.empty() || total <= 0.0)
  {
    out->SetPoints(points);
    return out;
  }
  points->SetNumberOfPoints(n);
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (long long i = 0; i < n; ++i)
  {
    const size_t t = std::min(
      static_cast<size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), uni(gen) * total) -
        cumulative.begin()),
      cumulative.size() - 1);
    const double r1 = std::sqrt(uni(gen)), r2 = uni(gen);
    double a[3], b[3], c[3], p[3];
    mesh->GetPoint(triangles[3 * t], a);
    mesh->GetPoint(triangles[3 * t + 1], b);
    mesh->GetPoint(triangles[3 * t + 2], c);
    for (int k = 0; k < 3; ++k)
    {
      p[k] = (1 - r1) * a[k] + r1 * (1 - r2) * b[k] + r1 * r2 * c[k];
    }
    points->SetPoint(i, p);
  }
  out->SetPoints(points);
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < n; ++i)
  {
    verts->InsertNextCell(1, &i);
  }
  out->SetVerts(verts);
  return out;
}

// The mean distance to the nearest other point, over up to 2000 samples.
double MeanSpacing(vtkPolyData* cloud)
{
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(cloud);
  locator->BuildLocator();
  vtkNew<vtkIdList> ids;
  const vtkIdType n = cloud->GetNumberOfPoints();
  const vtkIdType step = std::max<vtkIdType>(1, n / 2000);
  double sum = 0.0;
  int count = 0;
  for (vtkIdType i = 0; i < n; i += step)
  {
    double p[3], q[3];
    cloud->GetPoint(i, p);
    locator->FindClosestNPoints(2, p, ids);
    if (ids->GetNumberOfIds() < 2)
    {
      continue;
    }
    cloud->GetPoint(ids->GetId(1), q);
    sum += std::sqrt(vtkMath::Distance2BetweenPoints(p, q));
    ++count;
  }
  return count ? sum / count : 1.0;
}

void Material(vtkActor* actor)
{
  vtkProperty* p = actor->GetProperty();
  p->SetColor(0.85, 0.75, 0.6);
  p->SetAmbient(0.15);
  p->SetDiffuse(0.85);
}

struct Bench
{
  Options Opt;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  std::vector<Row> Rows;
  int Errors = 0;
  std::string LastError;

  void Show(vtkActor* actor)
  {
    this->Renderer->RemoveAllViewProps();
    this->Renderer->AddActor(actor);
  }

  void Print(const Row& r, std::ostream& os) const
  {
    const double fps = r.FrameMs > 0.0 ? 1000.0 / r.FrameMs : 0.0;
    os << r.Scene << "," << r.Method << ",\"" << r.Setting << "\"," << r.Primitives << ","
       << this->Opt.Width << "," << this->Opt.Height << "," << Fixed(r.FrameMs, 2) << ","
       << Fixed(fps, 1) << "," << Fixed(r.GridMs, 3) << "," << Fixed(r.CastMs, 3) << ","
       << Fixed(r.UploadMs, 3) << "," << Fixed(r.FitSeconds, 2) << ",\"" << r.Note << "\"\n";
  }

  void Record(const Row& r)
  {
    this->Rows.push_back(r);
    this->Print(r, std::cout);
    std::cout.flush();
  }

  void Splats()
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(this->Opt.Mesh.c_str());
    reader->Update();
    vtkPolyData* mesh = reader->GetOutput();
    if (!mesh || mesh->GetNumberOfPolys() == 0)
    {
      std::cerr << "BenchRender: no triangles in " << this->Opt.Mesh << "\n";
      ++this->Errors;
      return;
    }
    vtkSmartPointer<vtkPolyData> cloud = SampleSurface(mesh, this->Opt.Points, 1);
    const double spacing = MeanSpacing(cloud);
    const auto t0 = std::chrono::steady_clock::now();
    vtkNew<vtkAlgebraicSplatFitter> fitter;
    fitter->SetInputData(cloud);
    fitter->SetDegree(this->Opt.Degree);
    fitter->SetQualityFactor(this->Opt.Quality);
    fitter->Update();
    const double fitSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    vtkPolyData* splats = fitter->GetOutput();
    std::ostringstream scene;
    scene << "splats-" << this->Opt.Points;
    this->Renderer->ResetCamera(mesh->GetBounds());

    vtkNew<vtkAlgebraicSplatMapper> mapper;
    mapper->SetInputData(splats);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    Material(actor);
    this->Show(actor);
    for (bool blended : { false, true })
    {
      for (int aa : { 1, 2, 3 })
      {
        mapper->SetBlending(blended);
        mapper->SetAntiAliasing(aa);
        Row r;
        r.Scene = scene.str();
        r.Method = "algebraic-splats";
        std::ostringstream setting;
        setting << "degree " << this->Opt.Degree << ", s = " << this->Opt.Quality << ", "
                << (blended ? "blended" : "opaque") << ", "
                << (aa > 1 ? std::to_string(aa) + "x" + std::to_string(aa) + " adaptive AA"
                           : std::string("no AA"));
        r.Setting = setting.str();
        r.Primitives = splats->GetNumberOfPoints();
        this->Window->Render(); // shaders and buffers outside the timing
        r.FrameMs = MedianFrameMs(this->Window, this->Opt.Frames, nullptr);
        r.FitSeconds = fitSeconds;
        this->Record(r);
        if (blended && aa == 2)
        {
          WritePicture(this->Window, this->Opt.Out + "/" + scene.str() + ".png");
        }
      }
    }

    // The peers over all the points.
    vtkNew<vtkPointGaussianMapper> gaussian;
    gaussian->SetInputData(cloud);
    gaussian->SetScaleFactor(1.5 * spacing);
    gaussian->SetSplatShaderCode(vtkBenchSphereSpriteFS);
    gaussian->EmissiveOff();
    vtkNew<vtkOpenGLSphereMapper> spheres;
    spheres->SetInputData(cloud);
    spheres->SetRadius(1.5 * spacing);
    const std::pair<const char*, vtkMapper*> peers[] = { { "point-gaussian", gaussian },
      { "sphere", spheres } };
    for (const auto& peer : peers)
    {
      vtkNew<vtkActor> peerActor;
      peerActor->SetMapper(peer.second);
      Material(peerActor);
      this->Show(peerActor);
      Row r;
      r.Scene = scene.str();
      r.Method = peer.first;
      r.Setting = "r = 1.5 mean spacings";
      r.Primitives = cloud->GetNumberOfPoints();
      this->Window->Render();
      r.FrameMs = MedianFrameMs(this->Window, this->Opt.Frames, nullptr);
      this->Record(r);
    }
  }

#ifdef POINTSURFACES_BENCH_PAGING
  // `copies` copies of `data` in a grid, `step` apart: points moved, arrays
  // shared, the field data of `data` kept (the splat set's degree and levels).
  static vtkSmartPointer<vtkPolyData> Tile(vtkPolyData* data, int copies, double step)
  {
    const int side = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(copies))));
    vtkNew<vtkAppendPolyData> append;
    for (int c = 0; c < copies; ++c)
    {
      const double shift[3] = {
        step * (c % side), step * ((c / side) % side), step * (c / (side * side))
      };
      vtkNew<vtkPolyData> copy;
      copy->ShallowCopy(data);
      vtkNew<vtkPoints> points;
      points->SetDataTypeToDouble();
      points->SetNumberOfPoints(data->GetNumberOfPoints());
      for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
      {
        double p[3];
        data->GetPoint(i, p);
        points->SetPoint(i, p[0] + shift[0], p[1] + shift[1], p[2] + shift[2]);
      }
      copy->SetPoints(points);
      append->AddInputData(copy);
    }
    append->Update();
    auto out = vtkSmartPointer<vtkPolyData>::New();
    out->ShallowCopy(append->GetOutput());
    out->GetFieldData()->ShallowCopy(data->GetFieldData());
    return out;
  }

  // Median orbit frame: `frames` renders, the camera turned 360 / frames
  // degrees about the focal point before each.
  double OrbitMs(int frames)
  {
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    return MedianFrameMs(this->Window,
      frames,
      [this, camera, frames]()
      {
        camera->Azimuth(360.0 / frames);
        this->Renderer->ResetCameraClippingRange();
      });
  }

  void Paging()
  {
    const int copies = this->Opt.PagingCopies;
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(this->Opt.Mesh.c_str());
    reader->Update();
    vtkPolyData* mesh = reader->GetOutput();
    if (!mesh || mesh->GetNumberOfPolys() == 0)
    {
      ++this->Errors;
      return;
    }
    vtkSmartPointer<vtkPolyData> cloud = SampleSurface(mesh, this->Opt.Points, 1);
    const double spacing = MeanSpacing(cloud);
    vtkNew<vtkAlgebraicSplatFitter> fitter;
    fitter->SetInputData(cloud);
    fitter->SetDegree(this->Opt.Degree);
    fitter->SetQualityFactor(this->Opt.Quality);
    fitter->SetNumberOfLevels(3);
    fitter->Update();
    double b[6];
    mesh->GetBounds(b);
    const double step =
      1.2 * std::max(b[1] - b[0], std::max(b[3] - b[2], b[5] - b[4])); // a gap between copies
    const std::string path = this->Opt.Out + "/paging.psplat";
    {
      vtkSmartPointer<vtkPolyData> splats = Tile(fitter->GetOutput(), copies, step);
      vtkNew<vtkSplatFileWriter> writer;
      writer->SetInputData(splats);
      writer->SetFileName(path.c_str());
      writer->Write();
    }
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    const double fileBytes = file ? static_cast<double>(file.tellg()) : 0.0;
    const long long points = static_cast<long long>(copies) * this->Opt.Points;
    std::ostringstream scene;
    scene << "paging-" << points;

    vtkNew<vtkStreamingSplatMapper> mapper;
    mapper->SetFileName(path.c_str());
    mapper->SetMemoryBudget(this->Opt.PagingBudget);
    mapper->SetLODPixelError(1.0);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    Material(actor);
    this->Show(actor);
    this->Renderer->ResetCamera(mapper->GetBounds());
    const auto t0 = std::chrono::steady_clock::now();
    this->Window->Render();
    while (mapper->GetNumberOfResidentSplats() == 0 && mapper->GetLoading() &&
      std::chrono::steady_clock::now() - t0 < std::chrono::seconds(120))
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      this->Window->Render();
    }
    float depth = 0.0f;
    this->Window->GetZbufferData(0, 0, 0, 0, &depth);
    const double firstSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    mapper->WaitForPages(120.0);
    this->Window->Render();
    Row r;
    r.Scene = scene.str();
    r.Method = "streaming-splats";
    std::ostringstream setting;
    setting << "degree " << this->Opt.Degree << ", s = " << this->Opt.Quality << ", " << copies
            << " copies, budget " << this->Opt.PagingBudget << " MB, LODPixelError 1, orbit";
    r.Setting = setting.str();
    r.Primitives = mapper->GetNumberOfSplats();
    r.FrameMs = this->OrbitMs(this->Opt.Frames);
    std::ostringstream note;
    note << "first picture " << Fixed(firstSeconds, 3) << " s; file "
         << Fixed(fileBytes / std::max(1LL, points), 2) << " bytes a point; "
         << mapper->GetNumberOfResidentSplats() << " splats resident, "
         << mapper->GetNumberOfWantedSplats() << " wanted and "
         << mapper->GetNumberOfRenderedSplats() << " drawn in the last frame";
    r.Note = note.str();
    this->Record(r);
    WritePicture(this->Window, this->Opt.Out + "/" + scene.str() + ".png");
    this->Renderer->RemoveAllViewProps();
    mapper->ReleaseGraphicsResources(this->Window);
    std::remove(path.c_str());

    // The peer: every point, in memory.
    Row g;
    g.Scene = scene.str();
    g.Method = "point-gaussian";
    g.Setting = "r = 1.5 mean spacings, all points, orbit";
    g.Primitives = points;
    try
    {
      vtkSmartPointer<vtkPolyData> all = Tile(cloud, copies, step);
      vtkNew<vtkPointGaussianMapper> gaussian;
      gaussian->SetInputData(all);
      gaussian->SetScaleFactor(1.5 * spacing);
      gaussian->SetSplatShaderCode(vtkBenchSphereSpriteFS);
      gaussian->EmissiveOff();
      vtkNew<vtkActor> peer;
      peer->SetMapper(gaussian);
      Material(peer);
      this->Show(peer);
      this->Window->Render();
      g.FrameMs = this->OrbitMs(this->Opt.Frames);
      this->Renderer->RemoveAllViewProps();
      gaussian->ReleaseGraphicsResources(this->Window);
    }
    catch (const std::bad_alloc&)
    {
      g.Note = "not run: out of host memory";
    }
    this->Record(g);
  }
#endif

  void Metaballs(long long n)
  {
    std::ostringstream scene;
    scene << "metaballs-" << n;
    auto balls = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPoints> points;
    points->SetDataTypeToFloat();
    try
    {
      points->SetNumberOfPoints(n);
    }
    catch (const std::bad_alloc&)
    {
      Row r;
      r.Scene = scene.str();
      r.Method = "metaballs";
      r.Note = "not run: out of host memory";
      this->Record(r);
      return;
    }
    std::mt19937_64 gen(7);
    std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
    auto* xyz = static_cast<float*>(points->GetVoidPointer(0));
    for (long long i = 0; i < 3 * n; ++i)
    {
      xyz[i] = uni(gen);
    }
    balls->SetPoints(points);
    vtkNew<vtkCellArray> verts; // the sphere peer draws vertex cells
    verts->AllocateExact(n, n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      verts->InsertNextCell(1, &i);
    }
    balls->SetVerts(verts);
    const double spacing = 2.0 / std::cbrt(static_cast<double>(n));
    const double radius = 2.0 * spacing;

    vtkNew<vtkMetaballMapper> mapper;
    mapper->SetInputDataObject(balls);
    mapper->GetField()->SetRadius(radius);
    vtkNew<vtkCallbackCommand> onError;
    onError->SetClientData(this);
    onError->SetCallback(
      [](vtkObject*, unsigned long, void* self, void* text)
      {
        auto* bench = static_cast<Bench*>(self);
        ++bench->Errors;
        bench->LastError = text ? static_cast<const char*>(text) : "";
      });
    mapper->AddObserver(vtkCommand::ErrorEvent, onError);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    Material(actor);
    this->Show(actor);
    const double box[6] = {
      -1 - radius, 1 + radius, -1 - radius, 1 + radius, -1 - radius, 1 + radius
    };
    this->Renderer->ResetCamera(box);
    const int errorsBefore = this->Errors;
    this->Window->Render();
    Row r;
    r.Scene = scene.str();
    r.Method = "metaballs";
    r.Setting = "radius 2 mean spacings, dynamic frames, defaults";
    r.Primitives = n;
    r.FrameMs = MedianFrameMs(this->Window, this->Opt.Frames, [&points]() { points->Modified(); });
    r.GridMs = mapper->GetGridBuildTime();
    r.CastMs = mapper->GetRayCastTime();
    r.UploadMs = mapper->GetUploadTime();
    if (this->Errors > errorsBefore)
    {
      // Too many balls for this GPU's buffers: reported, not a failure.
      r.Note = "not drawn: " + this->LastError;
      this->Errors = errorsBefore;
    }
    this->Record(r);
    if (r.Note.empty())
    {
      WritePicture(this->Window, this->Opt.Out + "/" + scene.str() + ".png");
    }

    // The same frames with a level of detail of 2 pixels (vtkMetaballLevelOfDetail),
    // and the read-backs they waited for (none after the first frame).
    if (r.Note.empty())
    {
      mapper->SetLevelOfDetailPixels(2.0);
      this->Window->Render();
      const vtkIdType readBacks = mapper->GetNumberOfReadBacks();
      Row l;
      l.Scene = scene.str();
      l.Method = "metaballs";
      l.Primitives = n;
      l.FrameMs =
        MedianFrameMs(this->Window, this->Opt.Frames, [&points]() { points->Modified(); });
      l.GridMs = mapper->GetGridBuildTime();
      l.CastMs = mapper->GetRayCastTime();
      l.UploadMs = mapper->GetUploadTime();
      l.Setting = "radius 2 mean spacings, dynamic frames, LevelOfDetailPixels 2 (" +
        std::to_string(mapper->GetNumberOfBallsMerged()) + " balls merged into " +
        std::to_string(mapper->GetNumberOfMergedBalls()) + "; " +
        std::to_string(mapper->GetNumberOfReadBacks() - readBacks) + " read-backs in " +
        std::to_string(this->Opt.Frames) + " frames)";
      if (this->Errors > errorsBefore)
      {
        l.Note = "not drawn: " + this->LastError;
        this->Errors = errorsBefore;
      }
      this->Record(l);
      mapper->SetLevelOfDetailPixels(0.0);
    }

    vtkNew<vtkOpenGLSphereMapper> spheres;
    spheres->SetInputData(balls);
    spheres->SetRadius(
      radius * pointsurfaces::LoneBallIsoRadius(pointsurfaces::MetaballKernel::Wyvill, 0.5));
    vtkNew<vtkActor> sphereActor;
    sphereActor->SetMapper(spheres);
    Material(sphereActor);
    this->Show(sphereActor);
    this->Window->Render();
    Row s;
    s.Scene = scene.str();
    s.Method = "sphere";
    s.Setting = "radius of a lone ball's surface";
    s.Primitives = n;
    s.FrameMs = MedianFrameMs(this->Window, this->Opt.Frames, [&points]() { points->Modified(); });
    this->Record(s);
  }
};

bool Parse(int argc, char* argv[], Options& opt)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : std::string(); };
    if (a == "--smoke")
    {
      opt.Smoke = true;
      opt.Width = 160;
      opt.Height = 90;
      opt.Frames = 2;
      opt.Points = 20000;
      opt.Balls = { 500, 2000 };
      opt.PagingCopies = 4;
      opt.PagingBudget = 1.0;
    }
    else if (a == "--size")
    {
      const std::string v = next();
      if (std::sscanf(v.c_str(), "%dx%d", &opt.Width, &opt.Height) != 2)
      {
        return false;
      }
    }
    else if (a == "--frames")
    {
      opt.Frames = std::max(1, std::atoi(next().c_str()));
    }
    else if (a == "--points")
    {
      opt.Points = std::max(100LL, std::atoll(next().c_str()));
    }
    else if (a == "--balls")
    {
      opt.Balls.clear();
      std::stringstream list(next());
      std::string item;
      while (std::getline(list, item, ','))
      {
        opt.Balls.push_back(std::max(1LL, std::atoll(item.c_str())));
      }
    }
    else if (a == "--degree")
    {
      opt.Degree = std::min(4, std::max(1, std::atoi(next().c_str())));
    }
    else if (a == "--quality")
    {
      opt.Quality = std::atof(next().c_str());
    }
    else if (a == "--paging")
    {
      opt.PagingCopies = std::max(0, std::atoi(next().c_str()));
    }
    else if (a == "--budget")
    {
      opt.PagingBudget = std::max(0.0, std::atof(next().c_str()));
    }
    else if (a == "--out")
    {
      opt.Out = next();
    }
    else if (!a.empty() && a[0] != '-')
    {
      opt.Mesh = a;
    }
    else
    {
      return false;
    }
  }
  return !opt.Mesh.empty() && opt.Width > 0 && opt.Height > 0;
}
} // namespace

int main(int argc, char* argv[])
{
  Bench bench;
  if (!Parse(argc, argv, bench.Opt))
  {
    std::cerr << "usage: BenchRender [--smoke] [--size WxH] [--frames N] [--points N] "
                 "[--balls N,N,...] [--degree D] [--quality s] [--paging C] [--budget MB] "
                 "[--out DIR] mesh.vtp\n";
    return EXIT_FAILURE;
  }
  bench.Window->SetSize(bench.Opt.Width, bench.Opt.Height);
  bench.Window->SetMultiSamples(0);
  bench.Window->SetOffScreenRendering(1);
  bench.Window->AddRenderer(bench.Renderer);
  bench.Renderer->SetBackground(1.0, 1.0, 1.0);
  bench.Window->Render();
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(bench.Window);
  if (auto* egl = vtkEGLHeadlessRenderWindow::SafeDownCast(bench.Window))
  {
    std::cout << "# window: vtkEGLHeadlessRenderWindow, EGL platform " << egl->GetPlatformName()
              << ", GL renderer " << egl->GetRendererName() << "\n";
  }
  else
  {
    std::cout << "# window: " << bench.Window->GetClassName() << "\n";
  }
  if (gl && gl->ReportCapabilities())
  {
    std::string caps = gl->ReportCapabilities();
    caps = caps.substr(0, caps.find('\n', caps.find("OpenGL version")));
    for (size_t at = caps.find('\n'); at != std::string::npos; at = caps.find('\n', at + 3))
    {
      caps.replace(at, 1, "\n# ");
    }
    std::cout << "# " << caps << "\n";
  }
  const char* header = "scene,method,setting,primitives,width,height,frame_ms,fps,grid_gpu_ms,"
                       "cast_gpu_ms,upload_ms,fit_s,note\n";
  std::cout << header;
  bench.Splats();
  for (long long n : bench.Opt.Balls)
  {
    bench.Metaballs(n);
  }
#ifdef POINTSURFACES_BENCH_PAGING
  if (bench.Opt.PagingCopies > 0)
  {
    bench.Paging();
  }
#else
  if (bench.Opt.PagingCopies > 0)
  {
    std::cout << "# paging: not built (PointSurfaces::RenderingHDF5 is missing)\n";
  }
#endif
  std::ofstream csv(bench.Opt.Out + "/render.csv");
  csv << header;
  for (const Row& r : bench.Rows)
  {
    bench.Print(r, csv);
  }
  return bench.Errors == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
