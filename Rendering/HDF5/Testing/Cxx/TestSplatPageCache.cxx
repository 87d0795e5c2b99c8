// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The page cache of vtkStreamingSplatMapper (psSplatPageCache.h) on a fitted
// sphere written with three levels in pages of 128 splats, with and without
// its loading thread:
// - every page wanted whole, no budget: what is resident is the file's rows
//   bit for bit, page by page;
// - a budget that holds every page's level 0 and little more: each page
//   holds level 0 before any holds level 1 (coarsest first);
// - a second request for other pages within the budget evicts the first
//   ones, never more than the budget is resident, and none of the wanted
//   ones are evicted;
// - a smaller budget with a coarser request evicts the finer levels at
//   once (before any read); a page named twice wants the most levels named;
// - a budget of one splat: at most that is read, Wait returns and
//   Loading is false;
// - a truncated file is refused at Open with one line.
#include "psIOTestSupport.h"
#include "psLocalFit.h"
#include "psSplatFileTestSupport.h"
#include "psSplatPageCache.h"

#include <cstdlib>
#include <cstring>

using namespace pointsurfaces_test;

namespace
{
std::vector<int> Pages(const pointsurfaces::SplatFileInfo& info)
{
  std::vector<int> pages;
  for (size_t id = 0; id < info.Pages.Tree.Nodes.size(); ++id)
  {
    const pointsurfaces::OctreeNode& node = info.Pages.Tree.Nodes[id];
    if (node.ChildCount == 0 && node.End > node.Begin)
    {
      pages.push_back(static_cast<int>(id));
    }
  }
  return pages;
}

long long LevelSplats(const pointsurfaces::SplatFileInfo& info, int node, int levels)
{
  const pointsurfaces::Octree& tree = info.Pages.Tree;
  return tree.LevelEnds[static_cast<size_t>(node) * tree.Levels + levels - 1] -
    tree.Nodes[node].Begin;
}

template<typename T>
bool SameBits(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(T) * a.size()) == 0;
}

void Run(const std::string& path, bool asynchronous)
{
  const std::string mode = asynchronous ? " (thread)" : " (no thread)";
  pointsurfaces::SplatPageCache cache(asynchronous);
  std::string error;
  Check(cache.Open(path, error), "the cache opens the file" + mode + ": " + error);
  const pointsurfaces::SplatFileInfo& info = cache.Info();
  const int L = info.Pages.Tree.Levels;
  const std::vector<int> pages = Pages(info);
  Check(pages.size() > 8 && L == 3, "the sphere's file has pages and three levels" + mode);

  // Everything, no budget: the file's rows bit for bit.
  std::vector<pointsurfaces::PageWant> all;
  for (int node : pages)
  {
    all.push_back({ node, L, 0.0 });
  }
  cache.Request(all, 0);
  Check(cache.Wait(60.0), "every page loads" + mode);
  Check(!cache.Loading(), "nothing is loading after Wait" + mode);
  pointsurfaces::SplatFileReader file;
  Check(file.Open(path, error), "the file opens: " + error);
  long long resident = 0;
  bool same = true;
  const std::vector<pointsurfaces::ResidentPage> whole = cache.Resident();
  for (const pointsurfaces::ResidentPage& page : whole)
  {
    pointsurfaces::SplatColumns rows, got;
    rows.Resize(0, info.Degree, info.AttributeComponents);
    got.Resize(0, info.Degree, info.AttributeComponents);
    const pointsurfaces::OctreeNode& node = info.Pages.Tree.Nodes[page.Node];
    file.Read(node.Begin, node.End - node.Begin, rows, error);
    for (const auto& block : page.Blocks)
    {
      const long long at = got.Count;
      got.Resize(at + block->Count, info.Degree, info.AttributeComponents);
      std::copy(block->Origin.begin(), block->Origin.end(), got.Origin.begin() + 3 * at);
      std::copy(block->Coefficients.begin(),
        block->Coefficients.end(),
        got.Coefficients.begin() + pointsurfaces::MonomialCount(info.Degree) * at);
      std::copy(block->Radius.begin(), block->Radius.end(), got.Radius.begin() + at);
      std::copy(block->LOD.begin(), block->LOD.end(), got.LOD.begin() + at);
      std::copy(block->Attributes[0].begin(),
        block->Attributes[0].end(),
        got.Attributes[0].begin() + 3 * at);
    }
    same = same && page.Levels == L && SameBits(rows.Origin, got.Origin) &&
      SameBits(rows.Coefficients, got.Coefficients) && SameBits(rows.Radius, got.Radius) &&
      SameBits(rows.LOD, got.LOD) && SameBits(rows.Attributes[0], got.Attributes[0]);
    resident += page.Splats;
  }
  Check(whole.size() == pages.size() && resident == info.Splats && same,
    "every page resident, the file's rows bit for bit" + mode);
  for (size_t k = 1; k < whole.size(); ++k)
  {
    Check(
      info.Pages.Tree.Nodes[whole[k - 1].Node].Begin < info.Pages.Tree.Nodes[whole[k].Node].Begin,
      "resident pages in the file's order" + mode);
  }

  // Coarsest first: a budget of every page's level 0 plus half a page.
  pointsurfaces::SplatPageCache coarse(asynchronous);
  coarse.Open(path, error);
  long long level0 = 0;
  for (int node : pages)
  {
    level0 += LevelSplats(info, node, 1);
  }
  coarse.Request(all, level0 + 64);
  coarse.Wait(60.0);
  long long inMemory = 0;
  bool onlyCoarse = true;
  for (const pointsurfaces::ResidentPage& page : coarse.Resident())
  {
    inMemory += page.Splats;
    onlyCoarse = onlyCoarse && page.Levels >= 1;
  }
  const pointsurfaces::PageCacheStatistics stats = coarse.Statistics();
  std::cout << "coarse" << mode << ": " << pages.size() << " pages, level 0 " << level0
            << " splats, resident " << inMemory << " of " << info.Splats << ", missing "
            << stats.Missing << "\n";
  Check(coarse.Resident().size() == pages.size() && onlyCoarse && inMemory <= level0 + 64 &&
      inMemory >= level0,
    "within the budget every page holds its level 0 first" + mode);
  Check(!coarse.Loading(), "a request the budget cannot finish leaves nothing loading" + mode);

  // Eviction: the first half of the pages, then the second within the same budget.
  pointsurfaces::SplatPageCache evicting(asynchronous);
  evicting.Open(path, error);
  std::vector<pointsurfaces::PageWant> first, second;
  long long firstSplats = 0, secondSplats = 0;
  for (size_t k = 0; k < pages.size(); ++k)
  {
    (k < pages.size() / 2 ? first : second).push_back({ pages[k], L, double(k) });
    (k < pages.size() / 2 ? firstSplats : secondSplats) += LevelSplats(info, pages[k], L);
  }
  const long long budget = secondSplats;
  evicting.Request(first, budget);
  evicting.Wait(60.0);
  const long long before = evicting.Statistics().Resident;
  Check(before > 0 && before <= budget && before <= firstSplats,
    "the first half resident within the budget" + mode);
  evicting.Request(second, budget);
  evicting.Wait(60.0);
  const pointsurfaces::PageCacheStatistics after = evicting.Statistics();
  std::cout << "evicting" << mode << ": resident " << before << " then " << after.Resident
            << " (budget " << budget << "), evicted " << after.Evicted << "\n";
  Check(after.Resident == secondSplats && after.Missing == 0 && after.Evicted == before,
    "the second half replaces the first within the budget" + mode);

  // A smaller budget evicts at once what the request no longer wants; a page
  // named twice wants the most levels named.
  pointsurfaces::SplatPageCache shrinking(asynchronous);
  shrinking.Open(path, error);
  shrinking.Request(all, 0);
  shrinking.Wait(60.0);
  std::vector<pointsurfaces::PageWant> coarseTwice;
  for (int node : pages)
  {
    coarseTwice.push_back({ node, 1, 0.0 });
  }
  coarseTwice.push_back({ pages[0], 2, 0.0 });
  const long long coarseBudget =
    level0 + LevelSplats(info, pages[0], 2) - LevelSplats(info, pages[0], 1);
  shrinking.Request(coarseTwice, coarseBudget);
  const pointsurfaces::PageCacheStatistics shrunk = shrinking.Statistics();
  Check(shrunk.Resident <= coarseBudget && shrunk.Missing == 0 && shrunk.Wanted == coarseBudget,
    "a smaller budget evicts the levels no longer wanted at once, a page named twice wants the "
    "most levels" +
      mode + " (" + std::to_string(shrunk.Resident) + " resident, " +
      std::to_string(shrunk.Wanted) + " wanted, budget " + std::to_string(coarseBudget) + ")");

  // A budget of one splat.
  pointsurfaces::SplatPageCache tiny(asynchronous);
  tiny.Open(path, error);
  tiny.Request(all, 1);
  Check(tiny.Wait(10.0) && !tiny.Loading() && tiny.Statistics().Resident <= 1,
    "a budget of one splat reads at most one and does not hang" + mode);
}
} // namespace

int TestSplatPageCache(int, char*[])
{
  const std::string path = psScratchPath("TestSplatPageCache.psplat");
  psWriteSphereSplatFile(path, 20000, 1.0, 128);

  Run(path, false);
  Run(path, true);

  // A truncated file: refused at Open, one line.
  const std::string bytes = Slurp(path);
  const std::string cut =
    Write(psScratchPath("TestSplatPageCache-cut.psplat"), bytes.substr(0, bytes.size() / 2));
  pointsurfaces::SplatPageCache cache;
  std::string error;
  Check(!cache.Open(cut, error) && !error.empty() && error.find('\n') == std::string::npos &&
      !cache.IsOpen(),
    "a truncated file is refused with one line (got '" + error + "')");
  cache.Request({ { 0, 1, 0.0 } }, 0);
  Check(!cache.Wait(1.0) && !cache.Loading() && cache.Resident().empty(),
    "a cache without a file reads nothing, and Wait says so");

  std::remove(path.c_str());
  std::remove(cut.c_str());
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
