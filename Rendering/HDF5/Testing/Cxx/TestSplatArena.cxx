// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// pointsurfaces::SplatArena, the rows of vtkStreamingSplatMapper's buffers:
// - a block goes whole into the smallest free extent that holds it;
// - when none does, it is split over free extents from the lowest row, so
//   that an allocation succeeds whenever enough rows are free;
// - released rows merge with free neighbours, and Grow adds rows;
// - a random run of allocations and releases against a map of the rows:
//   no row handed out twice, none lost.
#include "psIOTestSupport.h"
#include "psSplatArena.h"

#include <cstdlib>
#include <random>
#include <vector>

using pointsurfaces::RowExtent;
using pointsurfaces::SplatArena;
using namespace pointsurfaces_test;

namespace
{
long long Rows(const std::vector<RowExtent>& extents)
{
  long long n = 0;
  for (const RowExtent& e : extents)
  {
    n += e.Size();
  }
  return n;
}
} // namespace

int TestSplatArena(int, char*[])
{
  {
    SplatArena arena(100);
    std::vector<RowExtent> a, b, c;
    Check(arena.Allocate(30, a) && a.size() == 1 && a[0].Begin == 0 && a[0].End == 30,
      "the first block from row 0");
    Check(arena.Allocate(30, b) && b.size() == 1 && b[0].Begin == 30, "the next one after it");
    Check(arena.Allocate(30, c) && arena.FreeRows() == 10, "ten rows left");
    arena.Release(a[0]);
    arena.Release(c[0]);
    // Free: [0, 30) and [60, 100): 35 rows go whole into the 40.
    std::vector<RowExtent> d;
    Check(arena.Allocate(35, d) && d.size() == 1 && d[0].Begin == 60,
      "the smallest free extent that holds the block whole");
    // Free: [0, 30) and [95, 100): 33 rows are split, lowest first.
    std::vector<RowExtent> e;
    Check(arena.Allocate(33, e) && e.size() == 2 && e[0].Begin == 0 && e[0].End == 30 &&
        e[1].Begin == 95 && e[1].End == 98,
      "split over free extents from the lowest row when none holds the block");
    std::vector<RowExtent> f;
    Check(!arena.Allocate(3, f) && f.empty() && arena.FreeRows() == 2,
      "more rows than are free: false, nothing taken");
    Check(arena.Allocate(0, f) && f.empty(), "no rows: nothing taken");
    arena.Release(b[0]);
    arena.Release(e[0]);
    const std::vector<RowExtent> free = arena.FreeExtents();
    Check(free.size() == 2 && free[0].Begin == 0 && free[0].End == 60 && free[1].Begin == 98,
      "released rows merge with their free neighbours");
    arena.Grow(150);
    const std::vector<RowExtent> grown = arena.FreeExtents();
    Check(arena.Capacity() == 150 && grown.back().Begin == 98 && grown.back().End == 150,
      "Grow adds free rows at the end, merged");
  }

  // Random allocations and releases against a map of the rows.
  {
    const long long capacity = 5000;
    SplatArena arena(capacity);
    std::vector<int> owner(capacity, -1);
    std::vector<std::vector<RowExtent>> blocks;
    std::mt19937 random(7);
    bool consistent = true;
    long long used = 0;
    for (int step = 0; step < 4000; ++step)
    {
      const bool release = !blocks.empty() && random() % 3 == 0;
      if (release)
      {
        const size_t k = random() % blocks.size();
        for (const RowExtent& e : blocks[k])
        {
          for (long long r = e.Begin; r < e.End; ++r)
          {
            consistent = consistent && owner[r] >= 0;
            owner[r] = -1;
          }
          arena.Release(e);
        }
        used -= Rows(blocks[k]);
        blocks.erase(blocks.begin() + k);
        continue;
      }
      const long long n = 1 + static_cast<long long>(random() % 400);
      std::vector<RowExtent> block;
      const bool ok = arena.Allocate(n, block);
      consistent = consistent && ok == (n <= capacity - used);
      if (!ok)
      {
        continue;
      }
      consistent = consistent && Rows(block) == n;
      for (const RowExtent& e : block)
      {
        for (long long r = e.Begin; r < e.End; ++r)
        {
          consistent = consistent && r >= 0 && r < capacity && owner[r] < 0;
          owner[r] = step;
        }
      }
      used += n;
      blocks.push_back(block);
    }
    long long free = 0;
    for (int o : owner)
    {
      free += o < 0 ? 1 : 0;
    }
    Check(consistent && free == arena.FreeRows() && Rows(arena.FreeExtents()) == free,
      "random allocations and releases: no row handed out twice, none lost");
  }
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
