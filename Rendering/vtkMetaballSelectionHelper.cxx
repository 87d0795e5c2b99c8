// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psOpenGL.h"

#include "vtkMetaballSelectionHelper.h"

#include "vtkDataArray.h"
#include "vtkHardwareSelector.h"
#include "vtkMath.h"
#include "vtkMetaballCompositeFS.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "psMetaball.h"
#include "psShaderHooks.h"

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkMetaballSelectionHelper);

namespace
{
// A selection pixel that no ray hit (PickBalls); -1 is a hit without a ball.
constexpr vtkIdType NoHit = -2;
// The screen tile side of the selection grid, in pixels.
constexpr int PickTile = 8;

// The slab of a perspective grid that holds view distance d, clamped.
int SlabOf(const std::vector<double>& planes, double d)
{
  const int k =
    static_cast<int>(std::upper_bound(planes.begin(), planes.end(), d) - planes.begin());
  return std::min(std::max(k - 1, 0), static_cast<int>(planes.size()) - 2);
}

// The view-space point at view distance `distance` on the ray through the
// centre of pixel (x, y), as the ray casters cast it.
void HitPoint(const double clipToView[16],
  int width,
  int height,
  int x,
  int y,
  double distance,
  double point[3])
{
  const double ndc[2] = { (x + 0.5) / width * 2.0 - 1.0, (y + 0.5) / height * 2.0 - 1.0 };
  double ends[2][4];
  for (int e = 0; e < 2; ++e)
  {
    const double clip[4] = { ndc[0], ndc[1], e == 0 ? -1.0 : 1.0, 1.0 };
    for (int r = 0; r < 4; ++r)
    {
      ends[e][r] = clipToView[4 * r] * clip[0] + clipToView[4 * r + 1] * clip[1] +
        clipToView[4 * r + 2] * clip[2] + clipToView[4 * r + 3] * clip[3];
    }
    for (int r = 0; r < 3; ++r)
    {
      ends[e][r] /= ends[e][3];
    }
  }
  const double dz = ends[1][2] - ends[0][2];
  const double t = dz != 0.0 ? (-distance - ends[0][2]) / dz : 0.0;
  for (int r = 0; r < 3; ++r)
  {
    point[r] = ends[0][r] + t * (ends[1][r] - ends[0][r]);
  }
}
// The area's own projection: the viewport's, scaled and moved so that its
// clip-space square is the area (viewport pixels xmin, ymin, xmax, ymax).
void AreaToClip(const pointsurfaces::MetaballView& cast, const int area[4], double areaToClip[16])
{
  const int width = cast.Width, height = cast.Height;
  const int areaWidth = area[2] - area[0] + 1, areaHeight = area[3] - area[1] + 1;
  std::copy_n(cast.ViewToClip, 16, areaToClip);
  const double sx = static_cast<double>(width) / areaWidth;
  const double tx = static_cast<double>(width - 2 * area[0]) / areaWidth - 1.0;
  const double sy = static_cast<double>(height) / areaHeight;
  const double ty = static_cast<double>(height - 2 * area[1]) / areaHeight - 1.0;
  for (int c = 0; c < 4; ++c)
  {
    areaToClip[c] = sx * cast.ViewToClip[c] + tx * cast.ViewToClip[12 + c];
    areaToClip[4 + c] = sy * cast.ViewToClip[4 + c] + ty * cast.ViewToClip[12 + c];
  }
}

// The input's points to view: the cast's view without the balls' shift.
void InputToView(const pointsurfaces::MetaballView& cast, const double shift[3], double toView[16])
{
  std::copy_n(cast.WorldToView, 16, toView);
  for (int r = 0; r < 3; ++r)
  {
    for (int k = 0; k < 3; ++k)
    {
      toView[4 * r + 3] -= cast.WorldToView[4 * r + k] * shift[k];
    }
  }
}

// The balls that reach into a selection area: their input ids (ascending),
// the balls themselves in the area's view space, and a perspective grid of
// them over the area.
struct AreaBalls
{
  std::vector<unsigned> Ids;
  std::vector<double> Centres, Radii, Strengths;
  pointsurfaces::MetaballSet Set;
  pointsurfaces::PerspectiveGrid Grid;
};

// The AreaBalls of `area`; false when there is no grid to search.
bool GatherAreaBalls(const pointsurfaces::MetaballView& cast,
  const int area[4],
  const pointsurfaces::MetaballBalls& balls,
  AreaBalls& out)
{
  const pointsurfaces::MetaballSet& set = balls.Extracted.Set;
  double areaToClip[16], toView[16], planes[24];
  AreaToClip(cast, area, areaToClip);
  pointsurfaces::FrustumPlanes(areaToClip, planes);
  InputToView(cast, balls.Shift, toView);
  const auto centreInView = [&](vtkIdType i, double out[3])
  {
    const double* c = set.Centers + 3 * i;
    for (int r = 0; r < 3; ++r)
    {
      out[r] = toView[4 * r] * c[0] + toView[4 * r + 1] * c[1] + toView[4 * r + 2] * c[2] +
        toView[4 * r + 3];
    }
  };

  // The balls that the ray casters draw (a positive float radius) whose
  // support reaches into the area's frustum, ascending.
  vtkSMPThreadLocal<std::vector<unsigned>> reaching;
  vtkSMPTools::For(0,
    set.Count,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<unsigned>& ids = reaching.Local();
      for (vtkIdType i = begin; i < end; ++i)
      {
        if (!(balls.HostBalls[4 * i + 3] > 0.0f))
        {
          continue;
        }
        double c[3];
        centreInView(i, c);
        bool inside = true;
        for (int k = 0; k < 6 && inside; ++k)
        {
          const double* e = planes + 4 * k;
          inside = e[0] * c[0] + e[1] * c[1] + e[2] * c[2] + e[3] >= -set.Radii[i];
        }
        if (inside)
        {
          ids.push_back(static_cast<unsigned>(i));
        }
      }
    });
  std::vector<unsigned>& ids = out.Ids;
  for (const std::vector<unsigned>& part : reaching)
  {
    ids.insert(ids.end(), part.begin(), part.end());
  }
  std::sort(ids.begin(), ids.end());

  // Those balls in view space, binned into a perspective grid over the area.
  const size_t count = ids.size();
  std::vector<double>& centres = out.Centres;
  std::vector<double>& radii = out.Radii;
  std::vector<double>& strengths = out.Strengths;
  centres.resize(3 * count);
  radii.resize(count);
  strengths.resize(set.Strengths ? count : 0);
  for (size_t k = 0; k < count; ++k)
  {
    centreInView(ids[k], &centres[3 * k]);
    radii[k] = set.Radii[ids[k]];
    if (set.Strengths)
    {
      strengths[k] = set.Strengths[ids[k]];
    }
  }
  pointsurfaces::MetaballSet& nearby = out.Set;
  nearby = set;
  nearby.Centers = centres.data();
  nearby.Radii = radii.data();
  nearby.Strengths = set.Strengths ? strengths.data() : nullptr;
  nearby.Count = static_cast<long long>(count);
  pointsurfaces::GridView grid;
  for (int k = 0; k < 16; ++k)
  {
    grid.WorldToView[k] = k % 5 == 0 ? 1.0 : 0.0;
    grid.ViewToClip[k] = areaToClip[k];
  }
  grid.Parallel = cast.Parallel;
  grid.Width = area[2] - area[0] + 1;
  grid.Height = area[3] - area[1] + 1;
  grid.TileSize = PickTile;
  grid.Slabs = 16;
  out.Grid = pointsurfaces::BuildPerspectiveGrid(nearby, grid);
  return out.Grid.SlabPlanes.size() >= 2;
}

} // namespace

//------------------------------------------------------------------------------
vtkMetaballSelectionHelper::vtkMetaballSelectionHelper() = default;

//------------------------------------------------------------------------------
vtkMetaballSelectionHelper::~vtkMetaballSelectionHelper() = default;

//------------------------------------------------------------------------------
void vtkMetaballSelectionHelper::Draw(vtkOpenGLRenderWindow* renWin,
  vtkHardwareSelector* selector,
  int x0,
  int y0,
  const pointsurfaces::MetaballView& view,
  unsigned long serial,
  const pointsurfaces::MetaballBalls& balls,
  const pointsurfaces::MetaballImages& images,
  vtkDataArray* ids)
{
  const int width = view.Width, height = view.Height;
  // The selector's area (window pixels) in the viewport: only it is read.
  const unsigned int* a = selector->GetArea();
  const int area[4] = { std::max(static_cast<int>(a[0]) - x0, 0),
    std::max(static_cast<int>(a[1]) - y0, 0),
    std::min(static_cast<int>(a[2]) - x0, width - 1),
    std::min(static_cast<int>(a[3]) - y0, height - 1) };
  if (area[0] > area[2] || area[1] > area[3])
  {
    return;
  }
  if (this->Serial != serial || !std::equal(area, area + 4, this->Area))
  {
    this->PickBalls(area, view, balls, images);
    this->Serial = serial;
  }
  this->PassColors(selector, area, width, height, ids);
  if (this->Image->GetWidth() != static_cast<unsigned int>(width) ||
    this->Image->GetHeight() != static_cast<unsigned int>(height) || !this->Image->GetHandle())
  {
    this->Image->SetContext(renWin);
    this->Image->Allocate2D(width, height, 4, VTK_UNSIGNED_CHAR);
  }
  pointsurfaces::UploadTexture(
    this->Image, width, height, GL_RGBA, GL_UNSIGNED_BYTE, this->Pixels.data());

  // The composite shader with lighting off writes the colours as they are
  // (nearest texels of an rgba8 image: the same bytes), with the hits' depth.
  if (!this->ReadyComposite(renWin))
  {
    return;
  }
  vtkShaderProgram* program = this->Composite->Program;
  const pointsurfaces::CompositeDepthState depthState(renWin->GetState());
  this->Image->Activate();
  images.Depth->Activate();
  program->SetUniformi("colorTexture", this->Image->GetTextureUnit());
  program->SetUniformi("depthTexture", images.Depth->GetTextureUnit());
  program->SetUniformi("shadows", 0);
  program->SetUniformf("opacity", 1.0f);
  this->Composite->Render();
  this->Image->Deactivate();
  images.Depth->Deactivate();
}

//------------------------------------------------------------------------------
bool vtkMetaballSelectionHelper::ReadyComposite(vtkOpenGLRenderWindow* renWin)
{
  if (!this->Composite)
  {
    std::string source = vtkMetaballCompositeFS;
    if (!pointsurfaces::ReplaceHook(
          source, "//VTK::Light::Dec", "#define LIGHTING_COMPLEXITY 0\n") ||
      !pointsurfaces::ReplaceHook(source, "//VTK::Light::Impl", ""))
    {
      vtkErrorMacro(<< "vtkMetaballCompositeFS lacks its //VTK::Light hooks: nothing is selected.");
      return false;
    }
    this->Composite.reset(new vtkOpenGLQuadHelper(renWin, nullptr, source.c_str(), ""));
  }
  else
  {
    renWin->GetShaderCache()->ReadyShaderProgram(this->Composite->Program);
  }
  if (!this->Composite->Program)
  {
    vtkErrorMacro(<< "The metaball selection shader did not compile.");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMetaballSelectionHelper::PassColors(vtkHardwareSelector* selector,
  const int area[4],
  int width,
  int height,
  vtkDataArray* ids)
{
  // The pass's colour per hit pixel, as vtkHardwareSelector reads it (red
  // the low byte): the prop's colour (the actor pass's prop id, the process
  // pass's process id, the composite pass's index, each plus one), or the
  // ball id, its low or high 24 bits.
  const int pass = selector->GetCurrentPass();
  const float* propColor = selector->GetPropColorValue();
  unsigned int prop = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double c = std::min(std::max(static_cast<double>(propColor[k]), 0.0), 1.0);
    prop |= static_cast<unsigned int>(vtkMath::Round(255.0 * c)) << (8 * k);
  }
  const bool low =
    pass == vtkHardwareSelector::POINT_ID_LOW24 || pass == vtkHardwareSelector::CELL_ID_LOW24;
  const bool high =
    pass == vtkHardwareSelector::POINT_ID_HIGH24 || pass == vtkHardwareSelector::CELL_ID_HIGH24;
  std::vector<unsigned char>& pixels = this->Pixels;
  pixels.assign(4 * static_cast<size_t>(width) * height, 0);
  const int areaWidth = area[2] - area[0] + 1;
  for (int y = area[1]; y <= area[3]; ++y)
  {
    for (int x = area[0]; x <= area[2]; ++x)
    {
      vtkIdType id = this->Ids[static_cast<size_t>(y - area[1]) * areaWidth + x - area[0]];
      if (id == NoHit)
      {
        continue;
      }
      if (ids && id >= 0)
      {
        id = static_cast<vtkIdType>(ids->GetComponent(id, 0));
      }
      // VTK 9.1's selector reads the id as written (the actor pass tells hits
      // from the background); a hit without a ball (id -1) writes 0.
      const long long value = std::max<long long>(id, 0);
      const unsigned int rgb = low ? static_cast<unsigned int>(value & 0xffffff)
        : high                     ? static_cast<unsigned int>((value >> 24) & 0xffffff)
                                   : prop;
      unsigned char* p = &pixels[4 * (static_cast<size_t>(y) * width + x)];
      p[0] = static_cast<unsigned char>(rgb & 0xff);
      p[1] = static_cast<unsigned char>((rgb >> 8) & 0xff);
      p[2] = static_cast<unsigned char>((rgb >> 16) & 0xff);
      p[3] = 255;
    }
  }
}

//------------------------------------------------------------------------------
void vtkMetaballSelectionHelper::PickBalls(const int area[4],
  const pointsurfaces::MetaballView& cast,
  const pointsurfaces::MetaballBalls& balls,
  const pointsurfaces::MetaballImages& images)
{
  const int width = cast.Width, height = cast.Height;
  const int areaWidth = area[2] - area[0] + 1, areaHeight = area[3] - area[1] + 1;
  this->Ids.assign(static_cast<size_t>(areaWidth) * areaHeight, NoHit);
  std::copy_n(area, 4, this->Area);

  // The hits (colour alpha: 0 where none) and their view distances.
  std::vector<unsigned char> colors(4 * static_cast<size_t>(width) * height);
  std::vector<float> hits(4 * static_cast<size_t>(width) * height);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  if (!pointsurfaces::ReadTexture(images.Color, GL_RGBA, GL_UNSIGNED_BYTE, colors.data()) ||
    !pointsurfaces::ReadTexture(images.Normal, GL_RGBA, GL_FLOAT, hits.data()))
  {
    vtkErrorMacro(<< "The ray-cast hits could not be read back: nothing is selected.");
    return;
  }
  const pointsurfaces::MetaballSet& set = balls.Extracted.Set;
  if (set.Count != balls.Count)
  {
    return;
  }

  AreaBalls near;
  if (!GatherAreaBalls(cast, area, balls, near))
  {
    return;
  }
  const pointsurfaces::MetaballSet& nearby = near.Set;
  const pointsurfaces::PerspectiveGrid& voxels = near.Grid;
  const std::vector<unsigned>& ids = near.Ids;

  // Each hit pixel's surface point against its voxel's balls, which hold
  // every ball whose support contains it (all of the area's balls where a
  // rounding error leaves the voxel empty).
  vtkSMPTools::For(0,
    areaHeight,
    [&](vtkIdType rowBegin, vtkIdType rowEnd)
    {
      for (vtkIdType row = rowBegin; row < rowEnd; ++row)
      {
        const int y = area[1] + static_cast<int>(row);
        for (int x = area[0]; x <= area[2]; ++x)
        {
          const size_t pixel = static_cast<size_t>(y) * width + x;
          if (colors[4 * pixel + 3] == 0)
          {
            continue;
          }
          const double distance = hits[4 * pixel + 3];
          double point[3];
          HitPoint(cast.ClipToView, width, height, x, y, distance, point);
          const size_t slab = SlabOf(voxels.SlabPlanes, distance);
          const size_t voxel =
            (slab * voxels.TilesY + row / PickTile) * voxels.TilesX + (x - area[0]) / PickTile;
          long long best = -1;
          if (voxel + 1 < voxels.Offsets.size() &&
            voxels.Offsets[voxel + 1] > voxels.Offsets[voxel])
          {
            const unsigned first = voxels.Offsets[voxel];
            best = pointsurfaces::DominantBall(
              nearby, point, voxels.Balls.data() + first, voxels.Offsets[voxel + 1] - first);
          }
          if (best < 0)
          {
            best = pointsurfaces::DominantBall(nearby, point);
          }
          this->Ids[static_cast<size_t>(row) * areaWidth + x - area[0]] =
            best >= 0 ? static_cast<vtkIdType>(ids[best]) : -1;
        }
      }
    });
}

//------------------------------------------------------------------------------
void vtkMetaballSelectionHelper::ReleaseGraphicsResources(vtkWindow* win)
{
  this->Image->ReleaseGraphicsResources(win);
  if (this->Composite)
  {
    this->Composite->ReleaseGraphicsResources(win);
    this->Composite.reset();
  }
  this->Serial = 0;
}

//------------------------------------------------------------------------------
void vtkMetaballSelectionHelper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Area: " << this->Area[0] << " " << this->Area[1] << " " << this->Area[2] << " "
     << this->Area[3] << "\n";
}
