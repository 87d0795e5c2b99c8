// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psSplatArena.h"

#include <algorithm>
#include <iterator>

namespace pointsurfaces
{
//------------------------------------------------------------------------------
SplatArena::SplatArena(long long capacity)
{
  this->Grow(capacity);
}

//------------------------------------------------------------------------------
void SplatArena::Grow(long long capacity)
{
  if (capacity <= this->Rows)
  {
    return;
  }
  this->Release(RowExtent{ this->Rows, capacity });
  this->Rows = capacity;
}

//------------------------------------------------------------------------------
bool SplatArena::Allocate(long long n, std::vector<RowExtent>& out)
{
  if (n <= 0)
  {
    return true;
  }
  if (n > this->Available)
  {
    return false;
  }
  this->Available -= n;
  // The smallest extent that holds all n rows.
  auto best = this->Free.end();
  for (auto it = this->Free.begin(); it != this->Free.end(); ++it)
  {
    const long long size = it->second - it->first;
    if (size >= n && (best == this->Free.end() || size < best->second - best->first))
    {
      best = it;
    }
  }
  if (best != this->Free.end())
  {
    out.push_back(this->Take(best, n));
    return true;
  }
  // None does: free extents from the lowest row up.
  while (n > 0)
  {
    out.push_back(this->Take(this->Free.begin(), n));
    n -= out.back().Size();
  }
  return true;
}

//------------------------------------------------------------------------------
RowExtent SplatArena::Take(std::map<long long, long long>::iterator extent, long long n)
{
  const RowExtent taken{ extent->first,
    extent->first + std::min(n, extent->second - extent->first) };
  const long long end = extent->second;
  this->Free.erase(extent);
  if (taken.End < end)
  {
    this->Free[taken.End] = end;
  }
  return taken;
}

//------------------------------------------------------------------------------
void SplatArena::Release(const RowExtent& extent)
{
  if (extent.End <= extent.Begin)
  {
    return;
  }
  long long begin = extent.Begin, end = extent.End;
  this->Available += end - begin;
  // Merge with the free extent after it and the one before it.
  auto next = this->Free.lower_bound(begin);
  if (next != this->Free.end() && next->first == end)
  {
    end = next->second;
    next = this->Free.erase(next);
  }
  if (next != this->Free.begin())
  {
    auto previous = std::prev(next);
    if (previous->second == begin)
    {
      begin = previous->first;
      this->Free.erase(previous);
    }
  }
  this->Free[begin] = end;
}

//------------------------------------------------------------------------------
std::vector<RowExtent> SplatArena::FreeExtents() const
{
  std::vector<RowExtent> extents;
  for (const auto& free : this->Free)
  {
    extents.push_back(RowExtent{ free.first, free.second });
  }
  return extents;
}
} // namespace pointsurfaces
