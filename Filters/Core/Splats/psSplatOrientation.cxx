// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psSplatOrientation.h"

#include "psPointIndex.h"
#include "psPolynomial.h"

#include "vtkMath.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <utility>

namespace pointsurfaces
{
namespace
{
constexpr double Decisive = OrientationDecisive;
constexpr double OpenSheet = OrientationOpenSheet;
// A splat whose visible views face it, summed as |n.u| over the views, reach
// SeenEnough, and agree on its side by Unanimous of that sum, is a seed of
// its closed part's orientation.
constexpr double SeenEnough = 1.0;
constexpr double Unanimous = 0.8;
// Views steeper than this (|n.u|) vote; grazing ones do not.
constexpr double Facing = 0.2;
// The largest side of a view's depth image, in pixels.
constexpr int LargestImage = 1024;
// The depth images' pixel, in median disc radii, and the coarsest that
// still votes.
constexpr double PixelRadii = 0.5;
constexpr double CoarsestPixel = 2.0;

// The splats as the views see them: which take part, their origins (from
// the mean of the valid ones, so that the depths, stored as floats, keep
// their digits far from the coordinates' origin), normals, radii, depth
// slacks (half a spacing) and the median radius.
struct ViewedSplats
{
  long long N = 0;
  std::vector<char> Valid;
  std::vector<double> Origins, Normals, Slacks;
  const double* Radii = nullptr;
  double Median = 0.0;

  // False when no splat takes part or the median radius is not positive.
  bool Gather(const std::vector<Splat*>& splats, const std::vector<double>& radii)
  {
    const long long n = static_cast<long long>(splats.size());
    this->N = n;
    this->Radii = radii.data();
    this->Valid.assign(static_cast<size_t>(n), 0);
    std::vector<double> sorted;
    double centre[3] = { 0.0, 0.0, 0.0 };
    long long count = 0;
    for (long long i = 0; i < n; ++i)
    {
      const LocalFrame& f = splats[i]->Frame;
      this->Valid[i] = std::isfinite(vtkMath::Dot(f.Origin, f.Origin)) &&
        std::isfinite(vtkMath::Dot(f.Normal, f.Normal)) && std::isfinite(radii[i]) &&
        radii[i] >= 0.0;
      if (this->Valid[i])
      {
        sorted.push_back(radii[i]);
        for (int c = 0; c < 3; ++c)
        {
          centre[c] += f.Origin[c];
        }
        ++count;
      }
    }
    if (count == 0)
    {
      return false;
    }
    std::nth_element(sorted.begin(), sorted.begin() + count / 2, sorted.end());
    this->Median = sorted[count / 2];
    if (!(this->Median > 0.0))
    {
      return false;
    }
    for (double& c : centre)
    {
      c /= static_cast<double>(count);
    }
    this->Origins.assign(3 * static_cast<size_t>(n), 0.0);
    this->Normals.assign(3 * static_cast<size_t>(n), 0.0);
    this->Slacks.assign(static_cast<size_t>(n), 0.0);
    for (long long i = 0; i < n; ++i)
    {
      if (!this->Valid[i])
      {
        continue;
      }
      const LocalFrame& f = splats[i]->Frame;
      for (int c = 0; c < 3; ++c)
      {
        this->Origins[3 * i + c] = f.Origin[c] - centre[c];
        this->Normals[3 * i + c] = f.Normal[c];
      }
      this->Slacks[i] = 0.5 * (splats[i]->Spacing > 0.0 ? splats[i]->Spacing : radii[i]);
    }
    return true;
  }
};

// One end of each of the 13 axes of a cube's neighbours (its first non-zero
// component positive).
std::vector<std::array<double, 3>> ViewAxes()
{
  std::vector<std::array<double, 3>> axes;
  for (int i = -1; i <= 1; ++i)
  {
    for (int j = -1; j <= 1; ++j)
    {
      for (int k = -1; k <= 1; ++k)
      {
        if (i > 0 || (i == 0 && (j > 0 || (j == 0 && k > 0))))
        {
          const double length = std::sqrt(double(i * i + j * j + k * k));
          axes.push_back({ i / length, j / length, k / length });
        }
      }
    }
  }
  return axes;
}

// The depth images of the splats along one axis u: the nearest and the
// farthest depth per pixel, seen in parallel projection. Its buffers are
// kept from one axis to the next of a thread.
class AxisImage
{
public:
  explicit AxisImage(const ViewedSplats* splats = nullptr)
    : S(splats)
  {
  }

  // Each disc's centre on the image of axis `axis`, and its plane's depth
  // there and gradient; false when the image's pixels would pass
  // CoarsestPixel median radii (no votes from this axis).
  bool Project(const double axis[3]);
  // The discs into the nearest and farthest depth images.
  void Draw();
  // Whether each splat is seen from the + end (bit 0) and the - end (bit 1).
  void See(unsigned char* sight) const;

private:
  int Column(double value) const
  {
    return std::min(
      this->Width - 1, std::max(0, static_cast<int>((value - this->Lo[0]) / this->Pixel)));
  }
  int Row(double value) const
  {
    return std::min(
      this->Height - 1, std::max(0, static_cast<int>((value - this->Lo[1]) / this->Pixel)));
  }
  // Splat i's depth at its own centre's pixel (x, y): its plane's at the
  // pixel's centre, where its disc reaches that far, else its centre's.
  double OwnDepth(long long i, int x, int y) const
  {
    const double ga = this->Gradient[2 * i], gb = this->Gradient[2 * i + 1];
    const double da = this->Lo[0] + (x + 0.5) * this->Pixel - this->A[i];
    const double db = this->Lo[1] + (y + 0.5) * this->Pixel - this->B[i];
    const double dt = ga * da + gb * db;
    const double t0 = -vtkMath::Dot(&this->S->Origins[3 * i], this->U);
    const double r = this->S->Radii[i];
    return da * da + db * db + dt * dt <= r * r ? t0 + dt : t0;
  }

  const ViewedSplats* S;
  double U[3] = { 0.0, 0.0, 1.0 };
  std::vector<double> A, B, Gradient;
  std::vector<float> Near, Far;
  double Lo[2] = { 0.0, 0.0 }, Hi[2] = { 0.0, 0.0 };
  double Pixel = 1.0;
  int Width = 1, Height = 1;
};

//------------------------------------------------------------------------------
bool AxisImage::Project(const double axis[3])
{
  const double* u = axis;
  std::copy(axis, axis + 3, this->U);
  const long long n = this->S->N;
  this->A.resize(static_cast<size_t>(n));
  this->B.resize(static_cast<size_t>(n));
  this->Gradient.resize(2 * static_cast<size_t>(n));
  // The image plane's axes a and b.
  const int least = std::abs(u[0]) < std::abs(u[1]) ? (std::abs(u[0]) < std::abs(u[2]) ? 0 : 2)
                                                    : (std::abs(u[1]) < std::abs(u[2]) ? 1 : 2);
  double e[3] = { 0.0, 0.0, 0.0 };
  e[least] = 1.0;
  double a[3], b[3];
  vtkMath::Cross(u, e, a);
  vtkMath::Normalize(a);
  vtkMath::Cross(u, a, b);
  // Each disc's centre on the image, and its plane's depth t (along
  // -u) there and its gradient: t = -o.u + ga da + gb db.
  this->Lo[0] = this->Lo[1] = std::numeric_limits<double>::max();
  this->Hi[0] = this->Hi[1] = -std::numeric_limits<double>::max();
  for (long long i = 0; i < n; ++i)
  {
    if (!this->S->Valid[i])
    {
      continue;
    }
    const double* o = &this->S->Origins[3 * i];
    const double* m = &this->S->Normals[3 * i];
    this->A[i] = vtkMath::Dot(o, a);
    this->B[i] = vtkMath::Dot(o, b);
    const double nu = vtkMath::Dot(m, u);
    const bool steep = std::abs(nu) > 1e-6;
    this->Gradient[2 * i] = steep ? vtkMath::Dot(m, a) / nu : 0.0;
    this->Gradient[2 * i + 1] = steep ? vtkMath::Dot(m, b) / nu : 0.0;
    this->Lo[0] = std::min(this->Lo[0], this->A[i] - this->S->Radii[i]);
    this->Hi[0] = std::max(this->Hi[0], this->A[i] + this->S->Radii[i]);
    this->Lo[1] = std::min(this->Lo[1], this->B[i] - this->S->Radii[i]);
    this->Hi[1] = std::max(this->Hi[1], this->B[i] + this->S->Radii[i]);
  }
  this->Pixel = std::max({ PixelRadii * this->S->Median,
    (this->Hi[0] - this->Lo[0]) / LargestImage,
    (this->Hi[1] - this->Lo[1]) / LargestImage });
  if (!(this->Pixel <= CoarsestPixel * this->S->Median))
  {
    return false;
  }
  this->Width = static_cast<int>((this->Hi[0] - this->Lo[0]) / this->Pixel) + 1;
  this->Height = static_cast<int>((this->Hi[1] - this->Lo[1]) / this->Pixel) + 1;
  const size_t pixels = static_cast<size_t>(this->Width) * this->Height;
  this->Near.assign(pixels, std::numeric_limits<float>::max());
  this->Far.assign(pixels, -std::numeric_limits<float>::max());
  return true;
}

//------------------------------------------------------------------------------
void AxisImage::Draw()
{
  const double* u = this->U;
  const long long n = this->S->N;
  for (long long i = 0; i < n; ++i)
  {
    if (!this->S->Valid[i] || !(std::abs(vtkMath::Dot(&this->S->Normals[3 * i], u)) > 1e-6))
    {
      continue; // seen edge on
    }
    const double t0 = -vtkMath::Dot(&this->S->Origins[3 * i], u), ga = this->Gradient[2 * i],
                 gb = this->Gradient[2 * i + 1], r2 = this->S->Radii[i] * this->S->Radii[i];
    const double ca = this->A[i], cb = this->B[i];
    // Row by row, the pixels whose rays meet the plane within the
    // disc: at (da, db) from the centre the ray meets it at depth
    // t0 + dt, dt = ga da + gb db, da a + db b - dt u from the
    // centre, inside where da^2 + db^2 + dt^2 <= r^2: an interval
    // of da, (-ga gb db +- sqrt(D)) / (1 + ga^2) with
    // D = (1 + ga^2) r^2 - (1 + ga^2 + gb^2) db^2.
    const double qa = 1.0 + ga * ga;
    for (int y = this->Row(cb - this->S->Radii[i]), y1 = this->Row(cb + this->S->Radii[i]); y <= y1;
         ++y)
    {
      const double db = this->Lo[1] + (y + 0.5) * this->Pixel - cb;
      const double discriminant = qa * r2 - (qa + gb * gb) * db * db;
      if (!(discriminant >= 0.0))
      {
        continue;
      }
      const double root = std::sqrt(discriminant), middle = -ga * gb * db;
      const double first = ca + (middle - root) / qa - this->Lo[0];
      const double last = ca + (middle + root) / qa - this->Lo[0];
      const int x0 = std::max(0, static_cast<int>(std::ceil(first / this->Pixel - 0.5)));
      const int x1 =
        std::min(this->Width - 1, static_cast<int>(std::floor(last / this->Pixel - 0.5)));
      float* nearRow = this->Near.data() + static_cast<size_t>(y) * this->Width;
      float* farRow = this->Far.data() + static_cast<size_t>(y) * this->Width;
      for (int x = x0; x <= x1; ++x)
      {
        const float t =
          static_cast<float>(t0 + ga * (this->Lo[0] + (x + 0.5) * this->Pixel - ca) + gb * db);
        nearRow[x] = std::min(nearRow[x], t);
        farRow[x] = std::max(farRow[x], t);
      }
    }
    // A disc that misses its own pixel's centre still hides it, at
    // its centre's depth.
    const int x = this->Column(ca), y = this->Row(cb);
    const float t = static_cast<float>(this->OwnDepth(i, x, y));
    const size_t p = static_cast<size_t>(y) * this->Width + x;
    this->Near[p] = std::min(this->Near[p], t);
    this->Far[p] = std::max(this->Far[p], t);
  }
}

//------------------------------------------------------------------------------
void AxisImage::See(unsigned char* sight) const
{
  const double* u = this->U;
  const long long n = this->S->N;
  for (long long i = 0; i < n; ++i)
  {
    if (!this->S->Valid[i] || !(std::abs(vtkMath::Dot(&this->S->Normals[3 * i], u)) > Facing))
    {
      continue;
    }
    const int x = this->Column(this->A[i]), y = this->Row(this->B[i]);
    const double t = this->OwnDepth(i, x, y);
    const size_t p = static_cast<size_t>(y) * this->Width + x;
    // Seen from the + end (nearest depth) and from the - end (farthest).
    sight[i] = static_cast<unsigned char>((t <= this->Near[p] + this->S->Slacks[i] ? 1 : 0) |
      (t >= this->Far[p] - this->S->Slacks[i] ? 2 : 0));
  }
}

// How the splats are seen from outside: from each of the 26 directions of a
// cube's neighbours (13 axes, each seen from both ends), the discs are
// drawn in parallel projection into a depth image (pixels of PixelRadii
// median radii, coarser where the image would pass LargestImage; the
// nearest and the farthest depth per pixel serve the two ends). A splat
// whose own depth at its centre's pixel (its plane's there, or its centre's
// where its disc misses the pixel's centre) lies within half its spacing of
// the nearest is visible from that end; it faces the view when n.u > 0 for
// the direction u towards the viewer. votes[i] sums n.u and seen[i] |n.u|
// over the views that see splat i steeper than Facing. An axis whose
// pixels would pass CoarsestPixel median radii gives no votes (the scene
// is too large against its discs to tell them apart), and splats with a
// non-finite origin, normal or radius take no part.
void VisibilityVotes(const std::vector<Splat*>& splats,
  const std::vector<double>& radii,
  std::vector<double>& votes,
  std::vector<double>& seen)
{
  const long long n = static_cast<long long>(splats.size());
  votes.assign(static_cast<size_t>(n), 0.0);
  seen.assign(static_cast<size_t>(n), 0.0);
  ViewedSplats viewed;
  if (!viewed.Gather(splats, radii))
  {
    return;
  }
  const std::vector<std::array<double, 3>> axes = ViewAxes();
  // What each axis sees of each splat: bit 0 from its + end, bit 1 from its
  // - end; summed in the axes' order below, so that the votes do not
  // depend on the threads.
  const size_t axisCount = axes.size();
  std::vector<unsigned char> sights(axisCount * static_cast<size_t>(n), 0);
  vtkSMPThreadLocal<AxisImage> images(AxisImage{ &viewed });
  vtkSMPTools::For(0,
    static_cast<vtkIdType>(axisCount),
    1,
    [&](vtkIdType begin, vtkIdType end)
    {
      AxisImage& image = images.Local();
      for (vtkIdType axis = begin; axis < end; ++axis)
      {
        if (image.Project(axes[axis].data()))
        {
          image.Draw();
          image.See(sights.data() + static_cast<size_t>(axis) * n);
        }
      }
    });
  for (size_t axis = 0; axis < axisCount; ++axis)
  {
    const unsigned char* sight = sights.data() + axis * static_cast<size_t>(n);
    for (long long i = 0; i < n; ++i)
    {
      if (sight[i])
      {
        const double nu = vtkMath::Dot(&viewed.Normals[3 * i], axes[axis].data());
        const int ends = (sight[i] & 1) + (sight[i] >> 1);
        votes[i] += ((sight[i] & 1) ? nu : 0.0) - ((sight[i] & 2) ? nu : 0.0);
        seen[i] += ends * std::abs(nu);
      }
    }
  }
}
} // namespace

void FlipSplat(Splat& splat)
{
  LocalFrame& f = splat.Frame;
  for (int c = 0; c < 3; ++c)
  {
    f.Normal[c] = -f.Normal[c];
    f.Bitangent[c] = -f.Bitangent[c];
  }
  // (u, v, w) -> (u, -v, -w): the monomial u^(d-j) v^j changes sign with j,
  // and the whole of g with w.
  int k = 0;
  for (int d = 0; d <= MaximumDegree; ++d)
  {
    for (int j = 0; j <= d; ++j, ++k)
    {
      splat.Fit.Coefficients[k] *= (j % 2 == 0) ? -1.0 : 1.0;
    }
  }
}

namespace
{
// One OrientSplats call: the splats' k-nearest-neighbour graph with its
// edges cheapest first, the spanning trees over it, and the state of the
// propagation (which splats are reached, which turned, how each is seen
// from outside).
class Orientation
{
public:
  Orientation(const std::vector<Splat*>& splats, const std::vector<double>* radii)
    : Splats(splats)
    , N(static_cast<long long>(splats.size()))
    , Radii(radii)
    , XYZ(3 * splats.size())
    , Root(splats.size())
    , Tree(splats.size())
    , Done(splats.size(), 0)
    , Turned(splats.size(), 0)
  {
    for (long long i = 0; i < this->N; ++i)
    {
      std::copy(splats[i]->Frame.Origin, splats[i]->Frame.Origin + 3, &this->XYZ[3 * i]);
    }
  }

  // The symmetric k-nearest-neighbour graph's edges, each once, cheapest first.
  void BuildGraph(int k);
  // Orients every part from its highest splat, then regrows the closed
  // parts that their views disagree with. Returns the splats flipped.
  long long Run(long long* parts, std::vector<long long>* partOf, bool outside);

private:
  struct Edge
  {
    double Cost;
    int From, To;
    bool operator<(const Edge& other) const
    {
      return Cost < other.Cost ||
        (Cost == other.Cost && (From < other.From || (From == other.From && To < other.To)));
    }
  };

  // The cost of an edge: how far the normals turn (Hoppe's 1 - |n_i.n_j|),
  // plus how steeply the edge leaves each splat's plane (|e.n| for the unit
  // edge e). Along the surface an edge lies nearly in both planes; between
  // the two faces of a thin part it runs along their normals, which are
  // antiparallel and so turn by nothing: by angle alone such an edge was as
  // cheap as any, and the propagation crossed through the part and turned
  // one face inward (a third of Lucy's splats).
  double Cost(long long i, long long j) const;
  int Find(int i);
  // Minimum spanning trees (Kruskal's algorithm) over the edges whose ends
  // `use` accepts, with each set of `joined` splats one node from the start
  // (the seeds of a part: the tree then grows from all of them at once,
  // as Prim's algorithm would from several roots). `tree` receives each
  // splat's tree neighbours.
  template<typename Use>
  void Span(Use&& use, const std::vector<std::vector<long long>>& joined);
  void Flip(long long i)
  {
    FlipSplat(*this->Splats[i]);
    this->Turned[i] = !this->Turned[i];
  }
  // From the splats in `front` (oriented already), along the tree: each
  // splat reached takes the side of the one it is reached from, and is
  // added to `reached` when given.
  void Grow(std::vector<long long> front, std::vector<long long>* reached);
  // Which way is out, on a closed part: there the integral of (x - c).n
  // over the area is three times the enclosed volume, positive for
  // outward normals whatever c and the shape. Summed over the part's
  // splats (weighted by h squared, their share of the area) it decides,
  // unless it is too close to zero to. The seed's rule alone (the highest
  // normal points up) turned all of Lucy inward at some settings: her
  // highest splat, on a wing's tip, lies on its underside. An open sheet
  // (a range scan, whose patch may be concave towards the scanner) keeps
  // the seed's rule: a part is taken for closed when its normals nearly
  // cancel (the area-weighted sum of a closed surface's normals is zero),
  // under OpenSheet of their total.
  // Returns whether the part is closed.
  bool OrientByFlux(const std::vector<long long>& part);
  // What is seen from outside decides each side of a closed part: the
  // tree can cross between two sheets that touch (a fold of drapery, a
  // wing against a body, two parts a spacing apart), where no edge looks
  // steep, and turn a whole sheet inward that the flux, a sum over the
  // part, outweighs. The splats that the views agree on are seeds with
  // their side; where one disagrees with the tree, a tree grows again
  // from all of them at once (below), so that a sheet takes its sign
  // from its own seeds. Open sheets are seen from both sides and keep
  // theirs.
  // Records the part for regrowing when a seed disagrees with its tree.
  void CheckByViews(const std::vector<long long>& part);
  // The regrowth of the parts CheckByViews recorded.
  void Regrow();
  double Vote(long long i) const
  {
    return this->Turned[i] != this->TurnedWhenSeen[i] ? -this->Votes[i] : this->Votes[i];
  }
  bool IsSeed(long long i) const
  {
    return this->Seen[i] >= SeenEnough && std::abs(this->Votes[i]) >= Unanimous * this->Seen[i];
  }

  const std::vector<Splat*>& Splats;
  const long long N;
  const std::vector<double>* Radii;
  std::vector<double> XYZ;
  std::vector<int> Neighbours;
  int KK = 1;
  std::vector<Edge> Edges;
  std::vector<int> Root;
  std::vector<std::vector<int>> Tree;
  std::vector<char> Done, Turned;
  // The visibility votes (of every splat, computed when the first closed
  // part is reached) and which splats were turned then; the closed parts
  // where a seed disagrees with its tree, and their seeds.
  std::vector<double> Votes, Seen;
  std::vector<char> TurnedWhenSeen;
  std::vector<std::vector<long long>> RegrowParts, RegrowSeeds;
};

//------------------------------------------------------------------------------
double Orientation::Cost(long long i, long long j) const
{
  const std::vector<Splat*>& splats = this->Splats;
  const std::vector<double>& xyz = this->XYZ;
  const double* a = splats[i]->Frame.Normal;
  const double* b = splats[j]->Frame.Normal;
  const double turn = 1.0 - std::abs(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
  const double e[3] = {
    xyz[3 * j] - xyz[3 * i], xyz[3 * j + 1] - xyz[3 * i + 1], xyz[3 * j + 2] - xyz[3 * i + 2]
  };
  const double length = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
  double total = turn;
  if (length > 0.0)
  {
    total += (std::abs(e[0] * a[0] + e[1] * a[1] + e[2] * a[2]) +
               std::abs(e[0] * b[0] + e[1] * b[1] + e[2] * b[2])) /
      length;
  }
  // A NaN would break the sort's order: such an edge comes last.
  return std::isfinite(total) ? total : std::numeric_limits<double>::infinity();
}

//------------------------------------------------------------------------------
void Orientation::BuildGraph(int k)
{
  const long long n = this->N;
  const std::vector<double>& xyz = this->XYZ;
  // The k-nearest-neighbour graph, made symmetric.
  const int kk = this->KK = static_cast<int>(std::min<long long>(std::max(k, 1) + 1, n));
  std::vector<int>& neighbours = this->Neighbours;
  neighbours.assign(static_cast<size_t>(n) * kk, -1);
  {
    PointIndex index(xyz.data(), n);
    vtkSMPTools::For(0,
      n,
      [&](long long begin, long long end)
      {
        std::vector<int> ids;
        std::vector<double> d2;
        for (long long i = begin; i < end; ++i)
        {
          index.Nearest(&xyz[3 * i], kk, ids, d2);
          std::copy(ids.begin(), ids.end(), &neighbours[static_cast<size_t>(i) * kk]);
        }
      });
  }
  // The graph's edges, each once, cheapest first (ties by their ends, so
  // that the trees do not depend on the sort).
  std::vector<Edge>& edges = this->Edges;
  edges.reserve(static_cast<size_t>(n) * kk);
  for (long long i = 0; i < n; ++i)
  {
    for (int m = 0; m < kk; ++m)
    {
      const int j = neighbours[static_cast<size_t>(i) * kk + m];
      if (j >= 0 && j != i)
      {
        edges.push_back({ 0.0,
          static_cast<int>(std::min<long long>(i, j)),
          static_cast<int>(std::max<long long>(i, j)) });
      }
    }
  }
  std::sort(edges.begin(),
    edges.end(),
    [](const Edge& x, const Edge& y)
    { return x.From < y.From || (x.From == y.From && x.To < y.To); });
  edges.erase(std::unique(edges.begin(),
                edges.end(),
                [](const Edge& x, const Edge& y) { return x.From == y.From && x.To == y.To; }),
    edges.end());
  vtkSMPTools::For(0,
    static_cast<vtkIdType>(edges.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType e = begin; e < end; ++e)
      {
        edges[e].Cost = this->Cost(edges[e].From, edges[e].To);
      }
    });
  vtkSMPTools::Sort(edges.begin(), edges.end());
}

//------------------------------------------------------------------------------
int Orientation::Find(int i)
{
  std::vector<int>& root = this->Root;
  while (root[i] != i)
  {
    root[i] = root[root[i]];
    i = root[i];
  }
  return i;
  return i;
}

//------------------------------------------------------------------------------
template<typename Use>
void Orientation::Span(Use&& use, const std::vector<std::vector<long long>>& joined)
{
  std::vector<int>& root = this->Root;
  std::iota(root.begin(), root.end(), 0);
  for (auto& t : this->Tree)
  {
    t.clear();
  }
  for (const auto& set : joined)
  {
    for (const long long i : set)
    {
      root[this->Find(static_cast<int>(i))] = this->Find(static_cast<int>(set.front()));
    }
  }
  for (const Edge& e : this->Edges)
  {
    if (!use(e.From) || !use(e.To))
    {
      continue;
    }
    const int a = this->Find(e.From), b = this->Find(e.To);
    if (a != b)
    {
      root[a] = b;
      this->Tree[e.From].push_back(e.To);
      this->Tree[e.To].push_back(e.From);
    }
  }
}

//------------------------------------------------------------------------------
void Orientation::Grow(std::vector<long long> front, std::vector<long long>* reached)
{
  for (size_t f = 0; f < front.size(); ++f)
  {
    const long long from = front[f];
    for (const int to : this->Tree[from])
    {
      if (this->Done[to])
      {
        continue;
      }
      this->Done[to] = 1;
      front.push_back(to);
      if (reached)
      {
        reached->push_back(to);
      }
      const double* a = this->Splats[from]->Frame.Normal;
      const double* b = this->Splats[to]->Frame.Normal;
      if (a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < 0.0)
      {
        this->Flip(to);
      }
    }
  }
}

//------------------------------------------------------------------------------
bool Orientation::OrientByFlux(const std::vector<long long>& part)
{
  const std::vector<Splat*>& splats = this->Splats;
  const std::vector<double>& xyz = this->XYZ;
  double centre[3] = { 0.0, 0.0, 0.0 }, weight = 0.0;
  for (const long long i : part)
  {
    const double w = splats[i]->Frame.Scale * splats[i]->Frame.Scale;
    for (int c = 0; c < 3; ++c)
    {
      centre[c] += w * xyz[3 * i + c];
    }
    weight += w;
  }
  if (!(weight > 0.0) || part.size() < 4)
  {
    return false;
  }
  for (double& c : centre)
  {
    c /= weight;
  }
  double flux = 0.0, magnitude = 0.0, area[3] = { 0.0, 0.0, 0.0 };
  for (const long long i : part)
  {
    const double w = splats[i]->Frame.Scale * splats[i]->Frame.Scale;
    const double* m = splats[i]->Frame.Normal;
    double along = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      along += (xyz[3 * i + c] - centre[c]) * m[c];
      area[c] += w * m[c];
    }
    flux += w * along;
    magnitude += w * std::abs(along);
  }
  const double open = std::sqrt(area[0] * area[0] + area[1] * area[1] + area[2] * area[2]) / weight;
  if (open < OpenSheet && flux < -Decisive * magnitude)
  {
    for (const long long i : part)
    {
      this->Flip(i);
    }
  }
  return open < OpenSheet;
}

//------------------------------------------------------------------------------
void Orientation::CheckByViews(const std::vector<long long>& part)
{
  const long long n = this->N;
  if (this->Votes.empty())
  {
    // How each splat is seen from outside, with the signs it has now.
    std::vector<double> r(static_cast<size_t>(n));
    for (long long i = 0; i < n; ++i)
    {
      r[i] = this->Radii && this->Radii->size() == static_cast<size_t>(n)
        ? (*this->Radii)[i]
        : this->Splats[i]->Frame.Scale;
    }
    VisibilityVotes(this->Splats, r, this->Votes, this->Seen);
    this->TurnedWhenSeen = this->Turned;
  }
  std::vector<long long> seeds;
  bool against = false;
  for (const long long i : part)
  {
    if (this->IsSeed(i))
    {
      seeds.push_back(i);
      against = against || this->Vote(i) < 0.0;
    }
  }
  if (against)
  {
    this->RegrowParts.push_back(part);
    this->RegrowSeeds.push_back(std::move(seeds));
  }
}

//------------------------------------------------------------------------------
void Orientation::Regrow()
{
  const long long n = this->N;
  // The parts to grow again, each from its seeds with their sides.
  std::vector<char> again(static_cast<size_t>(n), 0);
  std::vector<long long> front;
  for (size_t r = 0; r < this->RegrowParts.size(); ++r)
  {
    for (const long long i : this->RegrowParts[r])
    {
      again[i] = 1;
      this->Done[i] = 0;
    }
    for (const long long i : this->RegrowSeeds[r])
    {
      if (this->Vote(i) < 0.0)
      {
        this->Flip(i);
      }
      this->Done[i] = 1;
      front.push_back(i);
    }
  }
  this->Span([&](int i) { return again[i] != 0; }, this->RegrowSeeds);
  this->Grow(front, nullptr);
}

//------------------------------------------------------------------------------
long long Orientation::Run(long long* parts, std::vector<long long>* partOf, bool outside)
{
  const long long n = this->N;
  // Seeds in order of decreasing height; one tree over each part.
  this->Span([](int) { return true; }, {});
  std::vector<long long> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(),
    order.end(),
    [&](long long a, long long b) { return this->XYZ[3 * a + 2] > this->XYZ[3 * b + 2]; });
  std::vector<long long> part;
  long long partCount = 0;
  if (partOf)
  {
    partOf->assign(static_cast<size_t>(n), -1);
  }
  for (const long long seed : order)
  {
    if (this->Done[seed])
    {
      continue;
    }
    if (parts)
    {
      ++*parts;
    }
    if (this->Splats[seed]->Frame.Normal[2] < 0.0)
    {
      this->Flip(seed);
    }
    this->Done[seed] = 1;
    part.assign(1, seed);
    this->Grow({ seed }, &part);
    if (partOf)
    {
      for (const long long i : part)
      {
        (*partOf)[i] = partCount;
      }
    }
    ++partCount;
    if (outside && this->OrientByFlux(part))
    {
      this->CheckByViews(part);
    }
  }
  if (!this->RegrowParts.empty())
  {
    this->Regrow();
  }
  long long flipped = 0;
  for (const char t : this->Turned)
  {
    flipped += t;
  }
  return flipped;
}
} // namespace

long long OrientSplats(const std::vector<Splat*>& splats,
  int k,
  long long* parts,
  const std::vector<double>* radii,
  std::vector<long long>* partOf,
  bool outside)
{
  if (parts)
  {
    *parts = 0;
  }
  if (partOf)
  {
    partOf->assign(splats.size(), -1);
  }
  if (splats.empty())
  {
    return 0;
  }
  Orientation orientation(splats, radii);
  orientation.BuildGraph(k);
  return orientation.Run(parts, partOf, outside);
}
} // namespace pointsurfaces
