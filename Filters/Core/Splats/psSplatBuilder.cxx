// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psSplatBuilder.h"

#include "psPointIndex.h"
#include "psPolynomial.h"
#include "psSplatBound.h"
#include "psSplatSelection.h"

#include "vtkMath.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <random>

#if defined(__GLIBC__)
#include <malloc.h> // For malloc_trim
#endif

namespace pointsurfaces
{
namespace
{
// How far inside its disc a bounded splat's claims stay, in point spacings.
constexpr double ClaimMargin = 0.5;
// The first disc radius a bound tries, in point spacings (see `bound`).
constexpr double FirstTrial = 4.0;
// The narrowest Gaussian weight of a bounded splat's second fit, in point spacings.
constexpr double NarrowestWeight = 1.5;
// A disc the bound kept to at least this share of its nominal radius is
// whole: Widen tries it wider.
constexpr double WholeDisc = 0.9;
// A wider fit is kept only where it draws what the narrower one drew: over
// the narrower disc's points the two patches stay within this share of the
// error bound of each other (or two noise scales), and their normals within
// WidenAngle degrees (or the angle of two noise scales over the narrower h:
// on a noisy sample the narrower fit's normals carry the noise, and Lucy
// resampled to 4M points kept 2.9 times fewer splats with the noise term
// than without, at a masked SSIM of 0.931 against 0.853)
// (a bound on the points' deviation alone let wide patches flatten folds
// shallower than the bound, which shading shows: on Lucy resampled to 200k
// points, masked SSIM 0.898 against 0.931 at one scale; 10 degrees gave
// 0.918, 5 degrees 0.928, 3 degrees 0.933 with 14 % fewer splats only).
constexpr double WidenDistance = 0.5;
// A wide fit is made on at most this many times NumberOfNeighbors of its
// neighbours, the nearest WideFitNearest of them whole (see BuildAt).
constexpr int WideFitNeighbors = 8;
constexpr int WideFitNearest = 16;
// A wide neighbourhood (the plane, h and fit points of scale m: the
// max(NumberOfNeighbors, FeatureSizeNeighbors + 1) m^2 nearest points, 10 240
// at the fitter's defaults and m = 16) is found in a subsample of the points
// (every 4th, 16th or 64th, picked by a hash of the point's id, each
// subsample within the next denser one), the sparsest that still gives it
// SubsampleNeighbors points (BuildParameters::SubsampleWideFits); the
// WideFitNearest nearest stay whole (the spacing comes from them), and the
// bound still sees every point. The ordered k-nearest searches of the wide
// gathers took a third of the fit time at 1M points, more at 10M.
constexpr int SubsampleRatios[] = { 64, 16, 4 };
constexpr int SubsampleNeighbors = 256;
constexpr double WidenAngle = 5.0;

// The point of `s`'s patch over p (along the splat's normal) and the
// patch's unit normal there, in world coordinates.
void PatchAt(const Splat& s, const double p[3], double at[3], double normal[3])
{
  const LocalFrame& f = s.Frame;
  double uvh[3];
  ToLocal(f, p, uvh);
  double du = 0.0, dv = 0.0;
  const double g = EvaluateWithGradient(s.Fit.Coefficients, s.Fit.Degree, uvh[0], uvh[1], du, dv);
  for (int k = 0; k < 3; ++k)
  {
    at[k] =
      f.Origin[k] + f.Scale * (uvh[0] * f.Tangent[k] + uvh[1] * f.Bitangent[k] + g * f.Normal[k]);
    normal[k] = f.Normal[k] - du * f.Tangent[k] - dv * f.Bitangent[k];
  }
  vtkMath::Normalize(normal);
}

// Whether `wide` draws what `narrow` draws over the points `cover` (at most
// 64 of them, evenly picked): patches within `distance`, normals within
// `angle` degrees.
bool SameSurface(const Splat& narrow,
  const Splat& wide,
  const PointIndex& index,
  const std::vector<int>& cover,
  double distance,
  double angle)
{
  const double cosAngle = std::cos(vtkMath::RadiansFromDegrees(angle));
  const size_t step = std::max<size_t>(1, cover.size() / 64);
  for (size_t j = 0; j < cover.size(); j += step)
  {
    const double* p = index.Point(cover[j]);
    double a[3], b[3], na[3], nb[3];
    PatchAt(narrow, p, a, na);
    PatchAt(wide, p, b, nb);
    if (vtkMath::Distance2BetweenPoints(a, b) > distance * distance ||
      std::abs(vtkMath::Dot(na, nb)) < cosAngle)
    {
      return false;
    }
  }
  return true;
}

struct Position
{
  double Q[3];
  long long Source;
  int Level;
  double S;
};

// The neighbour coordinates of q, gathered contiguously.
void Gather(const PointIndex& index,
  const double q[3],
  int k,
  std::vector<int>& ids,
  std::vector<double>& d2,
  std::vector<double>& coords)
{
  index.Nearest(q, k, ids, d2);
  coords.resize(3 * ids.size());
  for (size_t j = 0; j < ids.size(); ++j)
  {
    const double* p = index.Point(ids[j]);
    coords[3 * j] = p[0];
    coords[3 * j + 1] = p[1];
    coords[3 * j + 2] = p[2];
  }
}

double MeanSpacing(const PointIndex& index, unsigned int seed)
{
  const long long n = index.Size();
  std::mt19937 gen(seed);
  std::vector<int> ids;
  std::vector<double> d2;
  double sum = 0.0;
  int count = 0;
  for (int t = 0; t < 200 && n > 1; ++t)
  {
    const long long i = static_cast<long long>(gen() % static_cast<unsigned long long>(n));
    index.Nearest(index.Point(i), 7, ids, d2);
    for (size_t j = 1; j < d2.size(); ++j)
    {
      sum += std::sqrt(d2[j]);
      ++count;
    }
  }
  return count ? sum / count : 0.0;
}
// LOP's kernel theta(r) = exp(-r^2 / (h / 4)^2), as a function of r^2, over
// the support radius h.
struct LOPKernel
{
  double H, H2;

  double Theta(double r2) const { return std::exp(-r2 / this->H2); }

  // WLOP's density weight of each of the `count` points `q` (3 values each):
  // 1 + the sum of theta over their neighbours in `index` (themselves excluded).
  std::vector<double> Densities(const PointIndex& index, const double* q, long long count) const
  {
    std::vector<double> weights(static_cast<size_t>(count), 1.0);
    vtkSMPTools::For(0,
      count,
      [&](long long begin, long long end)
      {
        std::vector<int> ids;
        std::vector<double> d2;
        for (long long k = begin; k < end; ++k)
        {
          index.Within(q + 3 * k, this->H, ids, d2);
          double sum = 1.0;
          for (double e : d2)
          {
            sum += e > 0.0 ? this->Theta(e) : 0.0;
          }
          weights[k] = sum;
        }
      });
    return weights;
  }
};
} // namespace

int LocallyOptimalProjection(const double* p,
  long long n,
  std::vector<double>& x,
  bool weighted,
  int iterations,
  double h,
  double mu)
{
  const long long m = static_cast<long long>(x.size() / 3);
  if (n == 0 || m == 0)
  {
    return 0;
  }
  PointIndex data(p, n);
  if (!(h > 0.0))
  {
    // Area from the input spacing, then the support of m evenly spread samples.
    const double spacing = MeanSpacing(data, 7u);
    h = 4.0 * std::sqrt(static_cast<double>(n) * spacing * spacing / static_cast<double>(m));
  }
  const LOPKernel kernel{ h, (h / 4.0) * (h / 4.0) };
  auto theta = [&kernel](double r2) { return kernel.Theta(r2); };
  // WLOP's density weights of the input points, once.
  const std::vector<double> v =
    weighted ? kernel.Densities(data, p, n) : std::vector<double>(static_cast<size_t>(n), 1.0);

  std::vector<double> next(x.size());
  int step = 0;
  for (; step < iterations; ++step)
  {
    PointIndex samples(x.data(), m);
    const std::vector<double> w = weighted ? kernel.Densities(samples, x.data(), m)
                                           : std::vector<double>(static_cast<size_t>(m), 1.0);
    std::vector<double> moved(static_cast<size_t>(m), 0.0);
    vtkSMPTools::For(0,
      m,
      [&](long long begin, long long end)
      {
        std::vector<int> ids;
        std::vector<double> d2;
        for (long long i = begin; i < end; ++i)
        {
          const double* xi = &x[3 * i];
          // Attraction to the data.
          double attract[3] = { 0, 0, 0 }, asum = 0.0;
          data.Within(xi, h, ids, d2);
          for (size_t j = 0; j < ids.size(); ++j)
          {
            const double r = std::max(std::sqrt(d2[j]), 1e-12 * h);
            const double a = theta(d2[j]) / r / v[ids[j]];
            const double* pj = data.Point(ids[j]);
            for (int c = 0; c < 3; ++c)
            {
              attract[c] += a * pj[c];
            }
            asum += a;
          }
          // Repulsion from the other samples.
          double repel[3] = { 0, 0, 0 }, rsum = 0.0;
          samples.Within(xi, h, ids, d2);
          for (size_t j = 0; j < ids.size(); ++j)
          {
            if (ids[j] == i || d2[j] <= 0.0)
            {
              continue;
            }
            const double r = std::sqrt(d2[j]);
            // LOP: eta = 1/(3 r^3), |eta'| = 1/r^4; WLOP: eta = -r, |eta'| = 1.
            const double deta = weighted ? w[ids[j]] : 1.0 / (d2[j] * d2[j]);
            const double b = theta(d2[j]) * deta / r;
            const double* xj = &x[3 * ids[j]];
            for (int c = 0; c < 3; ++c)
            {
              repel[c] += b * (xi[c] - xj[c]);
            }
            rsum += b;
          }
          double shift2 = 0.0;
          for (int c = 0; c < 3; ++c)
          {
            double value = asum > 0.0 ? attract[c] / asum : xi[c];
            if (rsum > 0.0)
            {
              value += mu * repel[c] / rsum;
            }
            next[3 * i + c] = value;
            shift2 += (value - xi[c]) * (value - xi[c]);
          }
          moved[i] = shift2;
        }
      });
    x.swap(next);
    const double largest = *std::max_element(moved.begin(), moved.end());
    if (largest < (1e-4 * h) * (1e-4 * h))
    {
      ++step;
      break;
    }
  }
  return step;
}

namespace
{
// One BuildSplats call: the index, the parameters as clamped to the input,
// and what the selection hands to the fits. Its steps are the phases that
// BuildSplats names: positions (all, by quality level, or LOP), fits,
// radii (for a fixed count), bounds, and the result.
class SplatBuild
{
public:
  SplatBuild(const double* xyz,
    long long n,
    const double* normals,
    const BuildParameters& params,
    const std::function<void(double)>& progress,
    const std::atomic<bool>* abort,
    ChunkContext* chunk,
    std::unique_ptr<PointIndex> given = nullptr);

  BuildResult Run();

private:
  // What the selection computed for each chosen point, reused by its fit:
  // its neighbours (and, error-bounded, its fitted splat and cover).
  struct ChosenPoint
  {
    LocalFrame Plane;
    std::vector<int> Neighbours;
    std::unique_ptr<BuiltSplat> Built;
    std::vector<int> Cover;
    std::vector<double> Rho;
  };

  void Report(double f) const
  {
    if (this->Progress)
    {
      this->Progress(f);
    }
  }
  bool Aborted() const { return this->Abort && this->Abort->load(); }
  // Each point's PCA normal from its NormalNeighbors nearest, for the bounds' normal test.
  void EstimateNormals();
  // The neighbours of point i and its plane with h (Normal and Scale).
  // At `scale` m, m^2 times the neighbours (h about m times as wide).
  // `whole` (when given) tells whether `ids` are all the points within
  // their last distance: false when a wide neighbourhood came from a
  // subsample (see SubsampleRatios).
  bool PlaneOf(long long i,
    LocalFrame& frame,
    std::vector<int>& ids,
    std::vector<double>& d2,
    std::vector<double>& coords,
    double scale = 1.0,
    bool* whole = nullptr) const;
  // `base` with its MaximumDeviation in local spacings around q (from the
  // unit of BuildParameters::Tolerance): `coords` are q's nearest points,
  // `plane` their plane with h (found here when null and needed). `noise`,
  // when given, receives the NoiseScale it measured (-1 when it measured none).
  SplatFitParameters LocalFit(const double* q,
    const std::vector<double>& coords,
    const SplatFitParameters& base,
    const LocalFrame* plane,
    double* noise = nullptr) const;
  // Point i's splat fitted with `local` on the neighbours `ids` (planes and
  // cover in `c`), bounded, and refitted narrower where the bound cut it
  // well inside; null when the fit fails. `whole`: as PlaneOf's.
  std::unique_ptr<BuiltSplat> BuildAt(long long i,
    ChosenPoint& c,
    const SplatFitParameters& local,
    const std::vector<int>& ids,
    const std::vector<double>& d2,
    const std::vector<double>& coords,
    std::vector<double>& w,
    bool whole = true);
  // While the bound leaves `b` (fitted at scale `first`) whole, point i's
  // fit at 2, 4, ... times that scale, the last at MaximumFeatureScale,
  // kept (with its cover in `c`) when its disc reaches farther.
  void Widen(long long i,
    ChosenPoint& c,
    std::unique_ptr<BuiltSplat>& b,
    const SplatFitParameters& local,
    double noise,
    double first);
  // The scale of point i's first fit: 1, or wider where the neighbourhood
  // `coords` (plane `plane`) is noisy beside its h (FeatureNoiseFactor).
  double FirstScale(const std::vector<double>& coords, const LocalFrame& plane) const;
  // Bound a fitted splat of nominal radius `radius` and measure its deviation
  // against the points around it; returns the covered point ids with their
  // in-plane distances.
  // `nearest` (ids, sorted by distance, and their squared distances from the
  // splat's point `from`), when they reach far enough, stand in for a
  // search of the index. Otherwise the search is made around `from` and
  // kept: a second bound of the same point (the narrow refit below) whose
  // disc it reaches uses it again.
  void Bound(BuiltSplat& b,
    double tolerance,
    std::vector<int>* cover,
    std::vector<double>* rho,
    const std::vector<int>* nearest = nullptr,
    const std::vector<double>* nearestD2 = nullptr,
    const double* from = nullptr) const;
  // A splat whose own point lies farther off its patch than its disc is
  // wide (a bound under the noise cut the disc to less than that point's
  // noise) reaches as far as that point, within its nominal radius, and
  // its deviation is measured again over the points the wider disc covers.
  void HoldSource(BuiltSplat& b) const;
  // The selection's FrameFunction: point i's plane, and, error-bounded, its
  // fitted and bounded splat, kept for its fit.
  bool FrameOf(long long i, LocalFrame& frame);
  // A bounded splat cut well inside its nominal disc, fitted again with
  // narrower weights; the fit that reaches farther is kept in `b`.
  void NarrowRefit(long long i,
    ChosenPoint& c,
    std::unique_ptr<BuiltSplat>& b,
    const SplatFitParameters& local,
    const std::vector<int>& ids,
    const std::vector<double>& d2,
    const double* fitCoords,
    int fitCount,
    std::vector<double>& w,
    bool whole);
  // The selection's CoverFunction: the points chosen point i covers at s.
  void CoverOf(long long i, double s, std::vector<int>& out) const;
  // How far from its centre (in its plane) a bounded splat claims points at s.
  double ClaimLimit(const BuiltSplat& b, double s) const;
  // A bounded chosen point's cover cut to what its claims at this level
  // and finer ones can reach, its storage released.
  void KeepClaimable(ChosenPoint& c) const;
  // The median h of a sample of 64 points.
  double MedianScale() const;
  // A streaming fit's halo point (see ChunkContext).
  bool IsHalo(long long i) const { return Chunk && Chunk->Halo && Chunk->Halo[i]; }
  // The halo points that the points `chosen` cover at s, each once.
  void ClaimHalo(const std::vector<long long>& chosen, double s, std::vector<long long>& out) const;
  // 1. Positions: every point, the points chosen by quality level, or LOP's.
  void AllPositions(std::vector<Position>& positions, BuildResult& result) const;
  void QualityPositions(std::vector<Position>& positions, BuildResult& result);
  void LOPPositions(std::vector<Position>& positions, BuildResult& result) const;
  // 2. Fits, in parallel; each position is fitted once. Positions [first,
  // last) only; each chosen point's record is released as its splat moves
  // out.
  void Fit(const std::vector<Position>& positions,
    std::vector<BuiltSplat>& built,
    std::vector<char>& ok,
    long long first,
    long long last);
  // [Bolla 2010] 3.3.2: for a fixed count, the radius follows the spacing of the decimated set.
  void FixedCountRadii(const std::vector<Position>& positions,
    std::vector<BuiltSplat>& built) const;

  const double* xyz;
  const long long n;
  const double* normals;
  const BuildParameters& params;
  const std::function<void(double)>& Progress;
  const std::atomic<bool>* Abort;
  ChunkContext* Chunk;
  // The subsamples of SubsampleRatios (sparsest first): their points' ids,
  // coordinates and index; absent where they would hold too few points.
  struct Subsample
  {
    int Ratio = 1;
    std::vector<int> Ids;
    std::vector<double> XYZ;
    std::unique_ptr<PointIndex> Index;
  };
  std::vector<Subsample> subsamples;
  // The index of every point, built beside the subsamples' (a 10M-point
  // index takes seconds on one core), or `given` (ToleranceUnit::Automatic
  // builds it first, to measure the sample's noise).
  std::unique_ptr<PointIndex> BuildIndexes(std::unique_ptr<PointIndex> given);
  std::unique_ptr<PointIndex> indexStorage;
  const PointIndex& index;
  SplatFitParameters fit;
  int kAll;
  bool bounded;
  const double* pointNormals = nullptr;
  std::vector<double> estimated;
  unsigned long long buildId;
  std::vector<std::unique_ptr<ChosenPoint>> chosenOf;
  // The level being selected. A coarser level is drawn where its splats are
  // smaller on screen: its tolerance grows with its s, so that its discs can
  // be as coarse.
  double levelS;
  int levelIndex = 0;
  SplatFitParameters levelFit;
};

//------------------------------------------------------------------------------
SplatBuild::SplatBuild(const double* xyz_,
  long long n_,
  const double* normals_,
  const BuildParameters& params_,
  const std::function<void(double)>& progress,
  const std::atomic<bool>* abort,
  ChunkContext* chunk_,
  std::unique_ptr<PointIndex> given)
  : xyz(xyz_)
  , n(n_)
  , normals(normals_)
  , params(params_)
  , Progress(progress)
  , Abort(abort)
  , Chunk(chunk_)
  , indexStorage(this->BuildIndexes(std::move(given)))
  , index(*indexStorage)
  , fit(params_.Fit)
  , chosenOf(static_cast<size_t>(n_))
  , levelS(params_.Quality)
{
  fit.NumberOfNeighbors = static_cast<int>(std::min<long long>(fit.NumberOfNeighbors, n));
  fit.FeatureSizeNeighbors = static_cast<int>(std::min<long long>(fit.FeatureSizeNeighbors, n - 1));
  kAll = std::max(fit.NumberOfNeighbors, fit.FeatureSizeNeighbors + 1);
  bounded = fit.MaximumDeviation > 0.0;
  levelFit = fit;
  // The bounds' normal test (see BoundParameters::NormalAngle): each point's
  // normal, the input's or the PCA normal of its NormalNeighbors nearest.
  if (bounded && params.NormalAngle < 90.0)
  {
    pointNormals = normals;
    if (!normals && params.EstimateNormals)
    {
      this->EstimateNormals();
    }
  }
  // Tells this call's cached searches (see Bound) from an earlier call's.
  static std::atomic<unsigned long long> builds{ 0 };
  buildId = ++builds;
}

//------------------------------------------------------------------------------
std::unique_ptr<PointIndex> SplatBuild::BuildIndexes(std::unique_ptr<PointIndex> given)
{
  // Subsamples serve the wide fits of bounded Quality selection only. The
  // widest gather asks max(NumberOfNeighbors, FeatureSizeNeighbors + 1) m^2
  // points at m = MaximumFeatureScale; a subsample too sparse even for that,
  // or too small to hold it, is left out.
  const SplatFitParameters& f = params.Fit;
  const double widest = std::min<double>(static_cast<double>(n),
                          std::max(f.NumberOfNeighbors, f.FeatureSizeNeighbors + 1)) *
    params.MaximumFeatureScale * params.MaximumFeatureScale;
  const bool subsample = f.MaximumDeviation > 0.0 && params.MaximumFeatureScale >= 2.0 &&
    params.SubsampleWideFits && !params.KeepWeights && params.Select == Selection::Quality;
  const int top = SubsampleRatios[0];
  std::vector<unsigned char> slot;
  for (int ratio : SubsampleRatios)
  {
    if (!subsample || widest / ratio < SubsampleNeighbors || n / ratio < 4 * SubsampleNeighbors)
    {
      continue;
    }
    if (slot.empty())
    {
      slot.resize(static_cast<size_t>(n));
      vtkSMPTools::For(0,
        n,
        [&](long long begin, long long end)
        {
          for (long long i = begin; i < end; ++i)
          {
            // splitmix64: a point's slot does not depend on its neighbours'
            // ids, so a scan's order (lines, tiles) leaves no pattern in a
            // subsample; each subsample holds the sparser ones.
            unsigned long long z = static_cast<unsigned long long>(i) + 0x9e3779b97f4a7c15ULL;
            z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
            z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
            slot[i] = static_cast<unsigned char>((z ^ (z >> 31)) % top);
          }
        });
    }
    Subsample sub;
    sub.Ratio = ratio;
    const unsigned char below = static_cast<unsigned char>(top / ratio);
    for (long long i = 0; i < n; ++i)
    {
      if (slot[i] < below)
      {
        sub.Ids.push_back(static_cast<int>(i));
        sub.XYZ.insert(sub.XYZ.end(), xyz + 3 * i, xyz + 3 * i + 3);
      }
    }
    subsamples.push_back(std::move(sub));
  }
  // Every index at once: the whole one on one thread, the subsamples'
  // (a third of its points together) on the others.
  std::unique_ptr<PointIndex> whole;
  vtkSMPTools::For(0,
    static_cast<long long>(subsamples.size()) + 1,
    1,
    [&](long long begin, long long end)
    {
      for (long long k = begin; k < end; ++k)
      {
        if (k == 0)
        {
          whole = given ? std::move(given) : std::make_unique<PointIndex>(xyz, n);
        }
        else
        {
          Subsample& sub = subsamples[static_cast<size_t>(k - 1)];
          sub.Index =
            std::make_unique<PointIndex>(sub.XYZ.data(), static_cast<long long>(sub.Ids.size()));
        }
      }
    });
  return whole;
}

//------------------------------------------------------------------------------
void SplatBuild::EstimateNormals()
{
  estimated.assign(static_cast<size_t>(3 * n), 0.0);
  vtkSMPTools::For(0,
    n,
    [&](long long begin, long long end)
    {
      std::vector<int> ids;
      std::vector<double> d2, coords;
      for (long long i = begin; i < end; ++i)
      {
        Gather(index, index.Point(i), NormalNeighbors, ids, d2, coords);
        LocalFrame plane;
        if (FitReferencePlane(
              coords.data(), nullptr, static_cast<int>(ids.size()), plane, nullptr) ==
          FitStatus::Ok)
        {
          std::copy(plane.Normal, plane.Normal + 3, &estimated[static_cast<size_t>(3 * i)]);
        }
      }
    });
  pointNormals = estimated.data();
}

//------------------------------------------------------------------------------
bool SplatBuild::PlaneOf(long long i,
  LocalFrame& frame,
  std::vector<int>& ids,
  std::vector<double>& d2,
  std::vector<double>& coords,
  double scale,
  bool* whole) const
{
  const double grow = scale * scale;
  const int fitCount = static_cast<int>(
    std::min<double>(static_cast<double>(n), std::round(fit.NumberOfNeighbors * grow)));
  const int featureCount = static_cast<int>(
    std::min<double>(static_cast<double>(n - 1), std::round(fit.FeatureSizeNeighbors * grow)));
  if (whole)
  {
    *whole = true;
  }
  // The sparsest subsample that holds SubsampleNeighbors of the points
  // gathered.
  const int gathered = std::max(fitCount, featureCount + 1);
  const Subsample* sub = nullptr;
  if (scale > 1.0)
  {
    for (const Subsample& candidate : subsamples)
    {
      if (gathered / candidate.Ratio >= SubsampleNeighbors)
      {
        sub = &candidate;
        break;
      }
    }
  }
  const double* q = index.Point(i);
  if (!sub)
  {
    Gather(index, q, gathered, ids, d2, coords);
    const int m = std::min(fitCount, static_cast<int>(ids.size()));
    if (FitReferencePlane(coords.data(), nullptr, m, frame, normals ? normals + 3 * i : nullptr) !=
      FitStatus::Ok)
    {
      return false;
    }
    frame.Scale = FeatureSize(q, frame, coords.data(), static_cast<int>(ids.size()), featureCount);
    return frame.Scale > 0.0;
  }
  // The plane and h from the subsample alone; the fit's neighbours are the
  // WideFitNearest nearest points, then the subsample's points beyond them.
  thread_local std::vector<int> subIds;
  thread_local std::vector<double> subD2, subCoords;
  const int r = sub->Ratio;
  Gather(*sub->Index, q, gathered / r + 1, subIds, subD2, subCoords);
  const int m = std::min(std::max(fitCount / r, 3), static_cast<int>(subIds.size()));
  if (FitReferencePlane(subCoords.data(), nullptr, m, frame, normals ? normals + 3 * i : nullptr) !=
    FitStatus::Ok)
  {
    return false;
  }
  frame.Scale = FeatureSize(
    q, frame, subCoords.data(), static_cast<int>(subIds.size()), std::max(1, featureCount / r));
  if (!(frame.Scale > 0.0))
  {
    return false;
  }
  // As on every point, the fit reaches as far as its fitCount nearest.
  Gather(index, q, WideFitNearest, ids, d2, coords);
  const double edge = d2.empty() ? 0.0 : d2.back();
  for (size_t j = 0; j < std::min<size_t>(subIds.size(), fitCount / r + 1); ++j)
  {
    if (subD2[j] > edge)
    {
      ids.push_back(sub->Ids[subIds[j]]);
      d2.push_back(subD2[j]);
      coords.insert(coords.end(), &subCoords[3 * j], &subCoords[3 * j] + 3);
    }
  }
  if (whole)
  {
    *whole = false;
  }
  return true;
}

//------------------------------------------------------------------------------
SplatFitParameters SplatBuild::LocalFit(const double* q,
  const std::vector<double>& coords,
  const SplatFitParameters& base,
  const LocalFrame* plane,
  double* noise) const
{
  SplatFitParameters local = base;
  if (noise)
  {
    *noise = -1.0;
  }
  if (params.Tolerance == ToleranceUnit::Spacing || !(base.MaximumDeviation > 0.0))
  {
    return local;
  }
  const int count = static_cast<int>(coords.size() / 3);
  const double spacing = LocalSpacing(q, coords.data(), count);
  if (!(spacing > 0.0))
  {
    return local;
  }
  if (params.Tolerance == ToleranceUnit::Absolute)
  {
    local.MaximumDeviation = base.MaximumDeviation / spacing;
    return local;
  }
  LocalFrame found;
  if (!plane)
  {
    const int m = std::min(fit.NumberOfNeighbors, count);
    if (FitReferencePlane(coords.data(), nullptr, m, found, nullptr) != FitStatus::Ok)
    {
      return local;
    }
    found.Scale = FeatureSize(q, found, coords.data(), count, fit.FeatureSizeNeighbors);
    plane = &found;
  }
  const double measured = NoiseScale(coords.data(), count, *plane, fit.NumberOfNeighbors);
  if (noise)
  {
    *noise = measured;
  }
  local.MaximumDeviation = std::max(base.MaximumDeviation, params.NoiseFactor * measured / spacing);
  return local;
}

//------------------------------------------------------------------------------
void SplatBuild::Bound(BuiltSplat& b,
  double tolerance,
  std::vector<int>* cover,
  std::vector<double>* rho,
  const std::vector<int>* nearest,
  const std::vector<double>* nearestD2,
  const double* from) const
{
  thread_local std::vector<int> found;
  thread_local std::vector<double> d2, coords, nrm;
  thread_local std::vector<int> local;
  thread_local const double* foundFrom = nullptr;
  thread_local double foundRadius = 0.0;
  thread_local unsigned long long foundBuild = 0;
  const Splat& sp = b.Fitted;
  BoundParameters bp;
  bp.Spacing = sp.Spacing;
  bp.Tolerance = tolerance * sp.Spacing;
  bp.MaximumReach = std::max(bp.MaximumReach, 2.0 * tolerance); // a looser patch may stray farther
  bp.MeasureOnly = !bounded;
  bp.NormalAngle = params.NormalAngle;
  // BoundSplat's own fallback when the spacing is unknown: h.
  const double spacing = sp.Spacing > 0.0 ? sp.Spacing : sp.Frame.Scale;
  const double offset =
    from ? std::sqrt(vtkMath::Distance2BetweenPoints(from, sp.Frame.Origin)) : 0.0;
  // A bound looks at every point within BoundSearchRadius of the disc, so
  // its cost grows with the nominal radius, while the discs the bound
  // cuts end up near their s = 1 size at any s. The disc therefore grows:
  // first to FirstTrial spacings, doubling while the bound leaves it
  // whole, up to the nominal radius; the first trial the bound cuts is the
  // disc. At s = 1 (a nominal radius under FirstTrial spacings) there is
  // one trial, the nominal radius.
  const double nominal = b.Radius;
  double trial = bounded ? std::min(nominal, FirstTrial * spacing) : nominal;
  const std::vector<int>* candidates = nullptr; // whose points `coords` holds
  SplatBound sb;
  for (;;)
  {
    const double search = BoundSearchRadius(trial, spacing);
    const std::vector<int>* next = &found;
    bool searched = false;
    if (nearest && !nearest->empty() && std::sqrt(nearestD2->back()) >= search + offset)
    {
      next = nearest; // a superset of the points within `search` of the origin
    }
    else if (from)
    {
      // A superset of the points within `search` of the origin.
      if (from != foundFrom || foundBuild != buildId || foundRadius < search + offset)
      {
        foundFrom = nullptr;
        foundRadius = search + 2.0 * offset + 0.25 * sp.Spacing;
        index.Within(from, foundRadius, found, d2, false);
        foundFrom = from;
        foundBuild = buildId;
        searched = true;
      }
    }
    else
    {
      foundFrom = nullptr;
      index.Within(sp.Frame.Origin, search, found, d2, false);
      searched = true;
    }
    // The candidates' coordinates (and normals), gathered again only when
    // the candidates changed: a larger trial often reuses the last ones.
    if (next != candidates || searched)
    {
      candidates = next;
      const std::vector<int>& ids = *candidates;
      coords.resize(3 * ids.size());
      nrm.resize(pointNormals ? 3 * ids.size() : 0);
      for (size_t j = 0; j < ids.size(); ++j)
      {
        std::copy(index.Point(ids[j]), index.Point(ids[j]) + 3, &coords[3 * j]);
        if (pointNormals)
        {
          const double* m = pointNormals + 3 * static_cast<size_t>(ids[j]);
          std::copy(m, m + 3, &nrm[3 * j]);
        }
      }
    }
    const std::vector<int>& ids = *candidates;
    sb = BoundSplat(sp,
      trial,
      coords.data(),
      static_cast<int>(ids.size()),
      bp,
      &local,
      rho,
      pointNormals ? nrm.data() : nullptr);
    if (sb.Radius < trial || !(trial < nominal))
    {
      break;
    }
    trial = std::min(nominal, 2.0 * trial);
  }
  const std::vector<int>& ids = *candidates;
  b.NominalRadius = nominal;
  b.Radius = sb.Radius;
  b.MaxDeviation = sb.MaxDeviation;
  b.Bounded = true;
  if (cover)
  {
    cover->resize(local.size());
    for (size_t j = 0; j < local.size(); ++j)
    {
      (*cover)[j] = ids[local[j]];
    }
  }
}

//------------------------------------------------------------------------------
bool SplatBuild::FrameOf(long long i, LocalFrame& frame)
{
  thread_local std::vector<int> ids;
  thread_local std::vector<double> d2, coords, w;
  auto c = std::make_unique<ChosenPoint>();
  if (!this->PlaneOf(i, c->Plane, ids, d2, coords))
  {
    return false;
  }
  frame = c->Plane;
  if (bounded)
  {
    double noise = -1.0;
    const SplatFitParameters local =
      this->LocalFit(index.Point(i), coords, levelFit, &c->Plane, &noise);
    const bool widen = params.MaximumFeatureScale >= 2.0;
    // The noise LocalFit measured (ToleranceUnit Noise), or measured here.
    if (widen && noise < 0.0)
    {
      noise = NoiseScale(
        coords.data(), static_cast<int>(coords.size() / 3), c->Plane, fit.NumberOfNeighbors);
    }
    double first = widen ? this->FirstScale(coords, c->Plane) : 1.0;
    std::unique_ptr<BuiltSplat> b;
    if (first > 1.0)
    {
      // The first fit as wide as the noise asks; where it fails, or the
      // bound cuts it inside the k-nearest fit's disc (a fold narrower than
      // the noise width), the k-nearest fit after all.
      const LocalFrame nearest = c->Plane;
      const double nearestRadius = params.RadiusScale * levelS * nearest.Scale +
        ClaimMargin *
          LocalSpacing(index.Point(i), coords.data(), static_cast<int>(coords.size() / 3));
      SplatFitParameters start = local;
      start.NumberOfNeighbors = static_cast<int>(std::round(fit.NumberOfNeighbors * first * first));
      bool whole = true;
      if (this->PlaneOf(i, c->Plane, ids, d2, coords, first, &whole))
      {
        b = this->BuildAt(i, *c, start, ids, d2, coords, w, whole);
      }
      if (!b || b->Radius < nearestRadius)
      {
        b.reset();
        first = 1.0;
        if (!this->PlaneOf(i, c->Plane, ids, d2, coords))
        {
          return false;
        }
      }
    }
    if (!b)
    {
      b = this->BuildAt(i, *c, local, ids, d2, coords, w);
    }
    if (!b)
    {
      return false;
    }
    if (widen)
    {
      this->Widen(i, *c, b, local, noise, first);
    }
    frame = b->Fitted.Frame;
    c->Built = std::move(b);
    this->KeepClaimable(*c);
  }
  else
  {
    c->Neighbours = ids;
  }
  chosenOf[i] = std::move(c);
  return true;
}

//------------------------------------------------------------------------------
std::unique_ptr<BuiltSplat> SplatBuild::BuildAt(long long i,
  ChosenPoint& c,
  const SplatFitParameters& local,
  const std::vector<int>& ids,
  const std::vector<double>& d2,
  const std::vector<double>& coords,
  std::vector<double>& w,
  bool whole)
{
  // A wide fit (Widen, FeatureNoiseFactor) on every one of its k m^2
  // neighbours cost most of the fit time; its patch is as well determined
  // by WideFitNeighbors times k of them: the nearest WideFitNearest whole
  // (the spacing comes from them), then evenly picked by distance.
  thread_local std::vector<double> thinned;
  const double* fitCoords = coords.data();
  int fitCount = static_cast<int>(ids.size());
  SplatFitParameters fitted = local;
  const int used = std::min(fitCount, local.NumberOfNeighbors);
  const int most = WideFitNeighbors * fit.NumberOfNeighbors;
  if (!params.KeepWeights && used > most && most > WideFitNearest)
  {
    thinned.assign(coords.begin(), coords.begin() + 3 * WideFitNearest);
    const double stride = static_cast<double>(used - WideFitNearest) / (most - WideFitNearest);
    for (int k = 0; k < most - WideFitNearest; ++k)
    {
      const size_t j = static_cast<size_t>(WideFitNearest + k * stride);
      thinned.insert(thinned.end(), coords.begin() + 3 * j, coords.begin() + 3 * j + 3);
    }
    fitCoords = thinned.data();
    fitCount = most;
    fitted.NumberOfNeighbors = most;
  }
  auto b = std::make_unique<BuiltSplat>();
  b->Fitted = FitSplat(index.Point(i),
    fitCoords,
    fitCount,
    fitted,
    normals ? normals + 3 * i : nullptr,
    params.KeepWeights ? &w : nullptr,
    &c.Plane);
  if (b->Fitted.Fit.Degree <= 0)
  {
    return nullptr;
  }
  b->Level = levelIndex;
  b->Source = i;
  b->Tolerance = local.MaximumDeviation;
  // The disc reaches half a spacing past what it claims, so that the
  // discs of neighbouring claims overlap (see cover below).
  b->Radius = params.RadiusScale * levelS * b->Fitted.Frame.Scale + ClaimMargin * b->Fitted.Spacing;
  if (params.KeepWeights)
  {
    b->Ids.assign(ids.begin(), ids.begin() + w.size());
    b->Weights.assign(w.begin(), w.end());
  }
  // A subsample's neighbours are no superset of the disc's points: the bound
  // then searches the index.
  this->Bound(*b,
    local.MaximumDeviation,
    &c.Cover,
    &c.Rho,
    whole ? &ids : nullptr,
    whole ? &d2 : nullptr,
    index.Point(i));
  this->NarrowRefit(i, c, b, fitted, ids, d2, fitCoords, fitCount, w, whole);
  return b;
}

//------------------------------------------------------------------------------
void SplatBuild::Widen(long long i,
  ChosenPoint& c,
  std::unique_ptr<BuiltSplat>& b,
  const SplatFitParameters& local,
  double noise,
  double first)
{
  thread_local std::vector<int> ids;
  thread_local std::vector<double> d2, coords, w;
  // Doublings from the first scale, the last one landing on
  // MaximumFeatureScale exactly (from a first scale of 2.9 and at most 16:
  // 5.8, 11.6, 16; doubling alone would stop at 11.6).
  const double widest = params.MaximumFeatureScale;
  for (double m = std::min(2.0 * first, widest); m > first * (1.0 + 1e-9);
       first = m, m = std::min(2.0 * m, widest))
  {
    // Only a disc that the bound left (nearly) whole is tried wider: one it
    // cut found the surface's feature size already.
    if (b->Radius < WholeDisc * b->NominalRadius)
    {
      return;
    }
    ChosenPoint wide;
    bool whole = true;
    if (!this->PlaneOf(i, wide.Plane, ids, d2, coords, m, &whole))
    {
      return;
    }
    SplatFitParameters wider = local;
    wider.NumberOfNeighbors = static_cast<int>(std::round(fit.NumberOfNeighbors * m * m));
    std::unique_ptr<BuiltSplat> candidate =
      this->BuildAt(i, wide, wider, ids, d2, coords, w, whole);
    if (!candidate || !(candidate->Radius > b->Radius) ||
      !SameSurface(b->Fitted,
        candidate->Fitted,
        index,
        c.Cover,
        std::max(WidenDistance * local.MaximumDeviation * b->Fitted.Spacing, 2.0 * noise),
        std::max(
          WidenAngle, vtkMath::DegreesFromRadians(std::atan(2.0 * noise / b->Fitted.Frame.Scale)))))
    {
      return;
    }
    b = std::move(candidate);
    c.Plane = wide.Plane;
    c.Cover.swap(wide.Cover);
    c.Rho.swap(wide.Rho);
  }
}

//------------------------------------------------------------------------------
double SplatBuild::FirstScale(const std::vector<double>& coords, const LocalFrame& plane) const
{
  // A fit over fewer than FeatureNoiseFactor noise scales follows the
  // noise, and on a sample denser than the noise each doubling from the
  // k-nearest h is one more chance for Widen's same-surface test to stop at
  // a splat of the sampling's size (half the fits at any density on Lucy
  // resampled with noise): the first fit starts as wide as the noise needs,
  // in world units. Only the noise that differs from a point to its nearest
  // neighbour counts: relief that a sparse sample leaves to the quadric
  // would otherwise widen it too (Lucy at 200 000 points lost 0.013 of
  // masked SSIM with NoiseScale at factor 16).
  if (!(params.FeatureNoiseFactor > 0.0) || !(plane.Scale > 0.0))
  {
    return 1.0;
  }
  const double sigma = UncorrelatedNoiseScale(
    coords.data(), static_cast<int>(coords.size() / 3), plane, fit.NumberOfNeighbors);
  const double first =
    std::min(params.MaximumFeatureScale, params.FeatureNoiseFactor * sigma / plane.Scale);
  // Within a quarter of the k-nearest h, the k-nearest fit.
  return first >= 1.25 ? first : 1.0;
}

//------------------------------------------------------------------------------
void SplatBuild::NarrowRefit(long long i,
  ChosenPoint& c,
  std::unique_ptr<BuiltSplat>& b,
  const SplatFitParameters& local,
  const std::vector<int>& ids,
  const std::vector<double>& d2,
  const double* fitCoords,
  int fitCount,
  std::vector<double>& w,
  bool whole)
{
  // Where the surface bent away well inside the disc, the patch averaged
  // over more than it may cover: fit again with weights that reach no
  // farther than the bounded disc, and keep the fit that reaches farther.
  // The weights stay at least NarrowestWeight spacings wide: narrower,
  // too few points carry a cubic, whose patch then bulges over creases
  // (at h of two spacings, about the default, they narrow to 0.75 at
  // most; at h of four, to 0.375).
  const double nominalRadius = b->NominalRadius;
  const double narrowScale = std::max({ 0.35,
    b->Radius / nominalRadius,
    NarrowestWeight * b->Fitted.Spacing / (local.WeightScale * b->Fitted.Frame.Scale) });
  if (b->Radius < 0.6 * nominalRadius && narrowScale < 0.9)
  {
    SplatFitParameters narrow = local;
    narrow.WeightScale *= narrowScale;
    auto n2 = std::make_unique<BuiltSplat>(*b);
    n2->Fitted = FitSplat(index.Point(i),
      fitCoords,
      fitCount,
      narrow,
      normals ? normals + 3 * i : nullptr,
      params.KeepWeights ? &w : nullptr,
      &c.Plane);
    if (n2->Fitted.Fit.Degree > 0)
    {
      n2->Radius = nominalRadius;
      std::vector<int> cover2;
      std::vector<double> rho2;
      this->Bound(*n2,
        local.MaximumDeviation,
        &cover2,
        &rho2,
        whole ? &ids : nullptr,
        whole ? &d2 : nullptr,
        index.Point(i));
      if (n2->Radius > b->Radius)
      {
        if (params.KeepWeights)
        {
          n2->Ids.assign(ids.begin(), ids.begin() + w.size());
          n2->Weights.assign(w.begin(), w.end());
        }
        b = std::move(n2);
        c.Cover.swap(cover2);
        c.Rho.swap(rho2);
      }
    }
  }
}

//------------------------------------------------------------------------------
void SplatBuild::HoldSource(BuiltSplat& b) const
{
  // Every chosen point is claimed by its own splat, so no other splat is
  // made for it; a point that its own disc leaves off (on Bunny samples
  // with noise of a spacing at the default half-spacing bound, 2 points of
  // 200 000 lay 1.25 times the radius off their own patch, right over its
  // centre) would be covered by none. The margin keeps it on the disc
  // through the rounding of a metric that measures it again.
  if (b.Source < 0 || !(b.Radius > 0.0))
  {
    return;
  }
  const Splat& sp = b.Fitted;
  double inPlane2 = 0.0;
  const double off = std::abs(
    PatchOffset(sp.Frame, sp.Fit.Coefficients, sp.Fit.Degree, index.Point(b.Source), inPlane2));
  const double reach = (1.0 + 1e-6) * std::max(off, std::sqrt(inPlane2));
  if (!(reach > b.Radius) || reach > b.NominalRadius)
  {
    return;
  }
  b.Radius = reach;
  // The bound's deviation is over the points it covers, those within the
  // tolerance (the source, farther off, is not one of them).
  const double tolerance = b.Tolerance * sp.Spacing;
  thread_local std::vector<int> ids;
  thread_local std::vector<double> d2;
  index.Within(sp.Frame.Origin, std::sqrt(2.0) * reach, ids, d2, false);
  for (int id : ids)
  {
    double height = 0.0;
    const double e = std::abs(PatchOffset(
      sp.Frame, sp.Fit.Coefficients, sp.Fit.Degree, index.Point(id), inPlane2, &height));
    height = std::abs(height);
    if (inPlane2 <= reach * reach && e <= reach && (!bounded || height <= tolerance))
    {
      b.MaxDeviation = std::max(b.MaxDeviation, height);
    }
  }
}

//------------------------------------------------------------------------------
double SplatBuild::ClaimLimit(const BuiltSplat& b, double s) const
{
  // A bounded splat covers its points up to its own radius, and at a
  // finer level only as far as that level's discs reach.
  // Every point it claims lies at least ClaimMargin spacings inside its
  // disc: a point and its neighbours' claims leave no crack between them.
  return std::min(
    b.Radius - ClaimMargin * b.Fitted.Spacing, params.RadiusScale * s * b.Fitted.Frame.Scale);
}

//------------------------------------------------------------------------------
void SplatBuild::KeepClaimable(ChosenPoint& c) const
{
  // The claims of this level and of every finer one (a smaller s) reach no
  // farther than this level's limit: the cover past it is never read. On
  // Lucy resampled to 4M points the chosen points' covers were most of the
  // selection's memory at the defaults.
  const double limit = this->ClaimLimit(*c.Built, levelS);
  size_t kept = 0;
  for (size_t j = 0; j < c.Cover.size(); ++j)
  {
    if (c.Rho[j] <= limit)
    {
      c.Cover[kept] = c.Cover[j];
      c.Rho[kept] = c.Rho[j];
      ++kept;
    }
  }
  c.Cover.resize(kept);
  c.Rho.resize(kept);
  c.Cover.shrink_to_fit();
  c.Rho.shrink_to_fit();
}

//------------------------------------------------------------------------------
void SplatBuild::CoverOf(long long i, double s, std::vector<int>& out) const
{
  const ChosenPoint& c = *chosenOf[i];
  if (!c.Built)
  {
    CoverByDistance(index, index.Point(i), c.Plane, s, out);
    return;
  }
  const double limit = this->ClaimLimit(*c.Built, s);
  out.clear();
  for (size_t j = 0; j < c.Cover.size(); ++j)
  {
    if (c.Rho[j] <= limit)
    {
      out.push_back(c.Cover[j]);
    }
  }
}

//------------------------------------------------------------------------------
void SplatBuild::ClaimHalo(const std::vector<long long>& chosen,
  double s,
  std::vector<long long>& out) const
{
  std::vector<int> ids;
  for (long long i : chosen)
  {
    this->CoverOf(i, s, ids);
    for (int id : ids)
    {
      if (this->IsHalo(id))
      {
        out.push_back(id);
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

//------------------------------------------------------------------------------
double SplatBuild::MedianScale() const
{
  // Median h of a sample of points: it sizes the Lattice grid and the
  // slabs of the parallel selection.
  std::vector<double> hs;
  {
    std::mt19937 gen(params.Seed);
    std::vector<int> ids;
    std::vector<double> d2, coords;
    for (int t = 0; t < 64; ++t)
    {
      LocalFrame f;
      if (this->PlaneOf(
            static_cast<long long>(gen() % static_cast<unsigned long long>(n)), f, ids, d2, coords))
      {
        hs.push_back(f.Scale);
      }
    }
  }
  std::nth_element(hs.begin(), hs.begin() + hs.size() / 2, hs.end());
  return hs.empty() ? 0.0 : hs[hs.size() / 2];
}

//------------------------------------------------------------------------------
void SplatBuild::AllPositions(std::vector<Position>& positions, BuildResult& result) const
{
  positions.reserve(static_cast<size_t>(n));
  for (long long i = 0; i < n; ++i)
  {
    if (!this->IsHalo(i))
    {
      positions.push_back(
        Position{ { xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] }, i, 0, params.Quality });
    }
  }
  result.LevelQuality.push_back(params.Quality);
}

//------------------------------------------------------------------------------
void SplatBuild::QualityPositions(std::vector<Position>& positions, BuildResult& result)
{
  const int levels = std::max(1, params.Levels);
  const double h =
    Chunk && Chunk->MedianFeatureSize > 0.0 ? Chunk->MedianFeatureSize : this->MedianScale();
  std::vector<long long> order = params.VisitOrder == Order::Lattice
    ? LatticeOrder(xyz, n, params.LatticeSpacing * params.Quality * h, params.Seed)
    : RandomOrder(n, params.Seed);
  if (Chunk && Chunk->Halo)
  {
    order.erase(
      std::remove_if(order.begin(), order.end(), [this](long long i) { return this->IsHalo(i); }),
      order.end());
  }
  if (Chunk)
  {
    Chunk->HaloClaims.assign(static_cast<size_t>(levels), {});
  }
  const double coarsest =
    levels > 1 ? std::max(params.Quality, params.CoarsestQuality) : params.Quality;
  // A cover reaches no farther than the widest disc: RadiusScale s h, with
  // h up to MaximumFeatureScale times as wide where Widen grows it.
  const double slabWidth = params.SlabSpacing * coarsest * h *
    (bounded ? std::max(1.0, params.RadiusScale) * std::max(1.0, params.MaximumFeatureScale) : 1.0);
  std::vector<PointState> state(static_cast<size_t>(n), PointState::Free);
  std::vector<long long> chosenAll;
  for (int level = 0; level < levels && !this->Aborted(); ++level)
  {
    const double s = levels == 1
      ? params.Quality
      : params.CoarsestQuality + (params.Quality - params.CoarsestQuality) * level / (levels - 1.0);
    levelS = s;
    levelIndex = level;
    levelFit.MaximumDeviation = fit.MaximumDeviation * std::max(1.0, s / params.Quality);
    result.LevelQuality.push_back(s);
    for (long long i = 0; i < n; ++i)
    {
      PointState& st = state[i];
      if (st == PointState::Claimed)
      {
        st = PointState::Free; // claims depend on s: redo them at this level
      }
      if (st == PointState::Free && this->IsHalo(i))
      {
        st = PointState::Reserved;
      }
      else if (st == PointState::Free && Chunk && Chunk->ClaimedBefore && level < 8 &&
        (Chunk->ClaimedBefore[i] >> level) & 1)
      {
        st = PointState::Claimed; // by a chunk fitted before this one
      }
    }
    const std::vector<long long> chosen = SelectByQuality(
      index,
      s,
      order,
      [this](long long i, LocalFrame& frame) { return this->FrameOf(i, frame); },
      [this](long long i, double q, std::vector<int>& out) { this->CoverOf(i, q, out); },
      state,
      chosenAll,
      params.VisitOrder == Order::Front,
      slabWidth);
    for (size_t j = 0; j < chosen.size(); ++j)
    {
      const double* p = index.Point(chosen[j]);
      positions.push_back(Position{ { p[0], p[1], p[2] }, chosen[j], level, s });
    }
    chosenAll.insert(chosenAll.end(), chosen.begin(), chosen.end());
    if (Chunk && Chunk->Halo)
    {
      this->ClaimHalo(chosenAll, s, Chunk->HaloClaims[level]);
    }
    this->Report(0.5 * (level + 1) / levels);
  }
  for (const auto st : state)
  {
    result.Degenerate += st == PointState::Unusable ? 1 : 0;
  }
}

//------------------------------------------------------------------------------
void SplatBuild::LOPPositions(std::vector<Position>& positions, BuildResult& result) const
{
  const long long m = std::min(params.Count, n);
  const std::vector<long long> order = RandomOrder(n, params.Seed);
  std::vector<double> x(static_cast<size_t>(3 * m));
  for (long long i = 0; i < m; ++i)
  {
    std::copy(xyz + 3 * order[i], xyz + 3 * order[i] + 3, &x[3 * i]);
  }
  LocallyOptimalProjection(xyz, n, x, params.Weighted, params.LOPIterations);
  for (long long i = 0; i < m; ++i)
  {
    positions.push_back(Position{ { x[3 * i], x[3 * i + 1], x[3 * i + 2] }, -1, 0, 1.0 });
  }
  result.LevelQuality.push_back(1.0);
  this->Report(0.5);
}

//------------------------------------------------------------------------------
void SplatBuild::Fit(const std::vector<Position>& positions,
  std::vector<BuiltSplat>& built,
  std::vector<char>& ok,
  long long first,
  long long last)
{
  vtkSMPTools::For(first,
    last,
    [&](long long begin, long long end)
    {
      std::vector<int> ids;
      std::vector<double> d2, coords, w;
      for (long long k = begin; k < end && !this->Aborted(); ++k)
      {
        const Position& pos = positions[k];
        ChosenPoint* chosen = pos.Source >= 0 ? chosenOf[pos.Source].get() : nullptr;
        BuiltSplat& b = built[k];
        if (chosen && chosen->Built)
        {
          b = std::move(*chosen->Built); // fitted and bounded when it was chosen
          ok[k] = 1;
          chosenOf[pos.Source].reset(); // the selection is over: its cover is never read again
          continue;
        }
        if (chosen && !chosen->Neighbours.empty())
        {
          ids = chosen->Neighbours;
          coords.resize(3 * ids.size());
          for (size_t j = 0; j < ids.size(); ++j)
          {
            std::copy(index.Point(ids[j]), index.Point(ids[j]) + 3, &coords[3 * j]);
          }
        }
        else
        {
          Gather(index, pos.Q, kAll, ids, d2, coords);
        }
        const long long orientFrom = pos.Source >= 0 ? pos.Source : (ids.empty() ? -1 : ids[0]);
        const double* orientation = normals && orientFrom >= 0 ? normals + 3 * orientFrom : nullptr;
        const SplatFitParameters local = this->LocalFit(pos.Q, coords, fit, nullptr);
        b.Fitted = FitSplat(pos.Q,
          coords.data(),
          static_cast<int>(ids.size()),
          local,
          orientation,
          params.KeepWeights ? &w : nullptr);
        b.Tolerance = local.MaximumDeviation;
        b.Level = pos.Level;
        b.Source = pos.Source;
        b.Radius = params.RadiusScale * pos.S * b.Fitted.Frame.Scale;
        ok[k] = b.Fitted.Fit.Degree > 0;
        if (ok[k] && params.KeepWeights)
        {
          b.Ids.assign(ids.begin(), ids.begin() + w.size());
          b.Weights.assign(w.begin(), w.end());
        }
      }
    });
}

//------------------------------------------------------------------------------
void SplatBuild::FixedCountRadii(const std::vector<Position>& positions,
  std::vector<BuiltSplat>& built) const
{
  const long long count = static_cast<long long>(positions.size());
  std::vector<double> centres(static_cast<size_t>(3 * count));
  for (long long k = 0; k < count; ++k)
  {
    std::copy(positions[k].Q, positions[k].Q + 3, &centres[3 * k]);
  }
  PointIndex decimated(centres.data(), count);
  vtkSMPTools::For(0,
    count,
    [&](long long begin, long long end)
    {
      std::vector<int> ids;
      std::vector<double> d2, near;
      for (long long k = begin; k < end; ++k)
      {
        decimated.Nearest(&centres[3 * k], 7, ids, d2);
        near.resize(3 * ids.size());
        for (size_t j = 0; j < ids.size(); ++j)
        {
          std::copy(&centres[3 * ids[j]], &centres[3 * ids[j]] + 3, &near[3 * j]);
        }
        const double hd = FeatureSize(
          &centres[3 * k], built[k].Fitted.Frame, near.data(), static_cast<int>(ids.size()), 6);
        built[k].Radius = params.RadiusScale * (hd > 0.0 ? hd : built[k].Fitted.Frame.Scale);
      }
    });
}

//------------------------------------------------------------------------------
BuildResult SplatBuild::Run()
{
  BuildResult result;
  std::vector<Position> positions;
  if (params.Select == Selection::All)
  {
    this->AllPositions(positions, result);
  }
  else if (params.Select == Selection::Quality)
  {
    this->QualityPositions(positions, result);
  }
  else
  {
    this->LOPPositions(positions, result);
  }
  const long long count = static_cast<long long>(positions.size());
  // The splats move out of the chosen points' records (bounded Quality
  // selection) an eighth at a time: the records are small blocks that
  // glibc keeps for reuse, while `built` and the output arrays after it are
  // large blocks that never reuse them, so the pages of the records freed
  // go back before the next eighth of `built` is touched (at the defaults
  // on 10M points, 2.4M records, 1.8 GB).
  std::vector<BuiltSplat> built;
  built.reserve(static_cast<size_t>(count));
  std::vector<char> ok(static_cast<size_t>(count), 0);
  const bool records = bounded && params.Select == Selection::Quality;
  const long long step = records ? std::max<long long>(1, (count + 7) / 8) : count;
  for (long long first = 0; first < count; first += step)
  {
    const long long last = std::min(count, first + step);
    built.resize(static_cast<size_t>(last)); // within the reserve: never moved
    this->Fit(positions, built, ok, first, last);
#if defined(__GLIBC__)
    if (records)
    {
      malloc_trim(0);
    }
#endif
  }
  this->Report(0.9);
  if (params.Select == Selection::FixedCount && count > 1)
  {
    this->FixedCountRadii(positions, built);
  }
  // Every disc not bounded at selection: bounded (or, unbounded, measured) now.
  vtkSMPTools::For(0,
    count,
    [&](long long begin, long long end)
    {
      for (long long k = begin; k < end && !this->Aborted(); ++k)
      {
        if (ok[k] && !built[k].Bounded)
        {
          this->Bound(built[k], built[k].Tolerance, nullptr, nullptr);
        }
        if (ok[k])
        {
          this->HoldSource(built[k]);
        }
      }
    });
  this->Report(0.95);

  // The splats kept in place: no second array of them.
  size_t kept = 0;
  for (long long k = 0; k < count; ++k)
  {
    if (!ok[k])
    {
      ++result.Degenerate;
      continue;
    }
    result.Reduced += built[k].Fitted.Fit.Status == FitStatus::ReducedDegree ? 1 : 0;
    if (kept != static_cast<size_t>(k))
    {
      built[kept] = std::move(built[k]);
    }
    ++kept;
  }
  built.resize(kept);
  result.Splats = std::move(built);
  std::stable_sort(result.Splats.begin(),
    result.Splats.end(),
    [](const BuiltSplat& a, const BuiltSplat& b) { return a.Level < b.Level; });
  this->Report(1.0);
  return result;
}
} // namespace

//------------------------------------------------------------------------------
BuildResult BuildSplats(const double* xyz,
  long long n,
  const double* normals,
  const BuildParameters& params,
  const std::function<void(double)>& progress,
  const std::atomic<bool>* abort,
  ChunkContext* chunk)
{
  if (n < 3)
  {
    return BuildResult();
  }
  // ToleranceUnit::Automatic: the sample's noise decides, measured with
  // the index the build then keeps.
  std::unique_ptr<PointIndex> index;
  SampleNoise noise;
  if (params.Tolerance == ToleranceUnit::Automatic)
  {
    index = std::make_unique<PointIndex>(xyz, n);
    noise = MeasureSampleNoise(xyz, n, *index);
  }
  const BuildParameters resolved = ResolveTolerance(params, noise);
  SplatBuild build(xyz, n, normals, resolved, progress, abort, chunk, std::move(index));
  BuildResult result = build.Run();
  result.Tolerance = resolved.Tolerance;
  result.Noise = noise;
  return result;
}

//------------------------------------------------------------------------------
BuildParameters ResolveTolerance(const BuildParameters& params, const SampleNoise& noise)
{
  BuildParameters resolved = params;
  if (params.Tolerance != ToleranceUnit::Automatic)
  {
    return resolved;
  }
  if (noise.Noisy)
  {
    resolved.Tolerance = ToleranceUnit::Noise;
    // A scale the caller chose stays; one scale (the default) widens.
    resolved.MaximumFeatureScale =
      params.MaximumFeatureScale >= 2.0 ? params.MaximumFeatureScale : AutomaticFeatureScale;
    // The noise sets the bound; the spacing only floors it, lower than in
    // Noise, so that the world bound is the same at any sampling denser
    // than the noise.
    resolved.Fit.MaximumDeviation *= AutomaticNoiseFloor;
  }
  else
  {
    resolved.Tolerance = ToleranceUnit::Spacing;
  }
  return resolved;
}

} // namespace pointsurfaces
