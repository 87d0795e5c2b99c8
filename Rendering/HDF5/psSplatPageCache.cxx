// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psSplatPageCache.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <limits>
#include <map>
#include <mutex>
#include <thread>

namespace pointsurfaces
{
namespace
{
struct Page
{
  std::vector<std::shared_ptr<const SplatColumns>> Blocks; // one per level present
  long long Splats = 0;
  long long LastWanted = 0; // the request that last wanted it
};
} // namespace

struct SplatPageCache::Impl
{
  explicit Impl(bool asynchronous)
    : Asynchronous(asynchronous)
  {
  }

  const bool Asynchronous;
  SplatFileReader File; // read by the loader only (the thread, or Wait's caller)
  bool Opened = false;
  bool Failed = false; // a read failed: nothing more is read until Open

  mutable std::mutex Mutex;
  std::condition_variable Work; // a request came, or the thread must stop
  std::condition_variable Done; // a block arrived, or the loader went idle
  std::thread Loader;
  bool Stop = false;

  long long Opens = 0;       // Open calls: a read from an earlier file is dropped
  std::map<int, Page> Pages; // by page node
  std::vector<PageWant> Wants;
  std::map<int, int> WantLevels;
  long long Budget = 0; // splats; <= 0: none
  long long RequestId = 0;
  bool Blocked = false; // the next read does not fit: wait for another request
  int InFlight = -1;    // the page being read
  long long Generation = 0;
  long long ResidentSplats = 0;
  PageCacheStatistics Stats;
  std::string Error;

  int Levels() const { return std::max(1, this->File.Info().Pages.Tree.Levels); }

  // Rows [begin, end) of `node`'s level `level`.
  void LevelRows(int node, int level, long long& begin, long long& end) const
  {
    const Octree& tree = this->File.Info().Pages.Tree;
    const size_t L = static_cast<size_t>(tree.Levels);
    begin = level == 0 ? tree.Nodes[node].Begin : tree.LevelEnds[node * L + level - 1];
    end = tree.LevelEnds[node * L + level];
  }

  int PresentLevels(int node) const
  {
    auto it = this->Pages.find(node);
    return it == this->Pages.end() ? 0 : static_cast<int>(it->second.Blocks.size());
  }

  // The next (page, level) to read: the coarsest level missing anywhere,
  // nearest page first. -1 when nothing is missing.
  int Pick(int& level) const
  {
    int best = -1;
    double bestDistance = 0.0;
    level = std::numeric_limits<int>::max();
    for (const PageWant& want : this->Wants)
    {
      const int present = this->PresentLevels(want.Node);
      if (present >= want.Levels ||
        (present > level || (present == level && want.Distance >= bestDistance)))
      {
        continue;
      }
      best = want.Node;
      level = present;
      bestDistance = want.Distance;
    }
    return best;
  }

  bool HasWork() const
  {
    int level;
    return this->Opened && !this->Failed && !this->Blocked && this->Pick(level) >= 0;
  }

  // Drop a page, or only its finest level.
  void Evict(std::map<int, Page>::iterator it, bool whole)
  {
    Page& page = it->second;
    const long long freed = whole ? page.Splats : page.Blocks.back()->Count;
    if (whole)
    {
      this->Pages.erase(it);
    }
    else
    {
      page.Splats -= freed;
      page.Blocks.pop_back();
    }
    this->ResidentSplats -= freed;
    this->Stats.Evicted += freed;
    ++this->Generation;
  }

  // Evict what the request does not want until `rows` more fit the budget.
  bool MakeRoom(long long rows)
  {
    while (this->Budget > 0 && this->ResidentSplats + rows > this->Budget)
    {
      // Pages not wanted at all, least recently wanted first.
      auto victim = this->Pages.end();
      for (auto it = this->Pages.begin(); it != this->Pages.end(); ++it)
      {
        if (it->first != this->InFlight && !this->WantLevels.count(it->first) &&
          (victim == this->Pages.end() || it->second.LastWanted < victim->second.LastWanted))
        {
          victim = it;
        }
      }
      if (victim != this->Pages.end())
      {
        this->Evict(victim, true);
        continue;
      }
      // Then levels past a page's wanted prefix, the most such levels first.
      int excess = 0;
      for (auto it = this->Pages.begin(); it != this->Pages.end(); ++it)
      {
        if (it->first == this->InFlight)
        {
          continue;
        }
        auto want = this->WantLevels.find(it->first);
        const int extra = static_cast<int>(it->second.Blocks.size()) -
          (want == this->WantLevels.end() ? 0 : want->second);
        if (extra > excess)
        {
          excess = extra;
          victim = it;
        }
      }
      if (victim == this->Pages.end())
      {
        return false;
      }
      this->Evict(victim, victim->second.Blocks.size() == 1);
    }
    return true;
  }

  // One read, with the lock held on entry and on return (released while
  // reading). 1: a block arrived; 0: nothing to read (or it does not fit);
  // -1: the read failed.
  int Step(std::unique_lock<std::mutex>& lock)
  {
    if (!this->Opened || this->Failed || this->Blocked)
    {
      return 0;
    }
    int level = 0;
    const int node = this->Pick(level);
    if (node < 0)
    {
      return 0;
    }
    long long begin = 0, end = 0;
    this->LevelRows(node, level, begin, end);
    if (!this->MakeRoom(end - begin))
    {
      this->Blocked = true;
      return 0;
    }
    this->InFlight = node;
    const long long opens = this->Opens;
    const SplatFileInfo& info = this->File.Info();
    auto block = std::make_shared<SplatColumns>();
    block->Resize(0, info.Degree, info.AttributeComponents);
    std::string error;
    lock.unlock();
    const bool ok = end == begin || this->File.Read(begin, end - begin, *block, error);
    lock.lock();
    this->InFlight = -1;
    if (!ok)
    {
      this->Failed = true;
      if (this->Error.empty())
      {
        this->Error = error;
      }
      return -1;
    }
    if (opens != this->Opens || this->PresentLevels(node) != level)
    {
      return 1; // the page changed meanwhile: this level no longer follows what it holds
    }
    Page& page = this->Pages[node];
    page.Blocks.push_back(std::move(block));
    page.Splats += end - begin;
    if (this->WantLevels.count(node))
    {
      page.LastWanted = this->RequestId;
    }
    this->ResidentSplats += end - begin;
    ++this->Stats.Reads;
    this->Stats.SplatsRead += end - begin;
    ++this->Generation;
    return 1;
  }

  void Run()
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    while (true)
    {
      this->Work.wait(lock, [this] { return this->Stop || this->HasWork(); });
      if (this->Stop)
      {
        return;
      }
      this->Step(lock);
      this->Done.notify_all();
    }
  }

  void StopLoader()
  {
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      this->Stop = true;
    }
    this->Work.notify_all();
    if (this->Loader.joinable())
    {
      this->Loader.join();
    }
    this->Stop = false;
    this->Done.notify_all();
  }
};

//------------------------------------------------------------------------------
SplatPageCache::SplatPageCache(bool asynchronous)
  : P(new Impl(asynchronous))
{
}

SplatPageCache::~SplatPageCache()
{
  P->StopLoader();
}

bool SplatPageCache::Open(const std::string& path, std::string& error)
{
  P->StopLoader();
  std::lock_guard<std::mutex> lock(P->Mutex);
  P->Pages.clear();
  P->Wants.clear();
  P->WantLevels.clear();
  P->Blocked = P->Failed = false;
  P->ResidentSplats = 0;
  P->Stats = PageCacheStatistics();
  P->Error.clear();
  ++P->Generation;
  ++P->Opens;
  P->Opened = P->File.Open(path, error);
  if (P->Opened && P->Asynchronous)
  {
    P->Loader = std::thread([this] { P->Run(); });
  }
  P->Done.notify_all();
  return P->Opened;
}

bool SplatPageCache::IsOpen() const
{
  std::lock_guard<std::mutex> lock(P->Mutex);
  return P->Opened && !P->Failed;
}

const SplatFileInfo& SplatPageCache::Info() const
{
  return P->File.Info();
}

void SplatPageCache::Request(const std::vector<PageWant>& wants, long long budgetSplats)
{
  {
    std::lock_guard<std::mutex> lock(P->Mutex);
    if (!P->Opened)
    {
      return;
    }
    const Octree& tree = P->File.Info().Pages.Tree;
    const int levels = P->Levels();
    ++P->RequestId;
    P->Wants.clear();
    P->WantLevels.clear();
    for (const PageWant& want : wants)
    {
      if (want.Node < 0 || want.Node >= static_cast<int>(tree.Nodes.size()) ||
        tree.Nodes[want.Node].ChildCount > 0 || want.Levels <= 0)
      {
        continue; // not a page of this file
      }
      PageWant w = want;
      w.Levels = std::min(want.Levels, levels);
      auto known = P->WantLevels.find(w.Node);
      if (known != P->WantLevels.end())
      {
        known->second = std::max(known->second, w.Levels); // named twice: the most levels
        continue;
      }
      P->Wants.push_back(w);
      P->WantLevels[w.Node] = w.Levels;
      auto it = P->Pages.find(w.Node);
      if (it != P->Pages.end())
      {
        it->second.LastWanted = P->RequestId;
      }
    }
    for (PageWant& w : P->Wants)
    {
      w.Levels = P->WantLevels[w.Node];
    }
    P->Budget = budgetSplats;
    P->Blocked = false;
    // A smaller budget: what is no longer wanted goes now, not at the next read.
    P->MakeRoom(0);
  }
  P->Work.notify_all();
}

bool SplatPageCache::Wait(double seconds)
{
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() +
    std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(std::min(seconds, 1e8))); // about three years
  std::unique_lock<std::mutex> lock(P->Mutex);
  if (!P->Opened)
  {
    return false;
  }
  if (!P->Asynchronous)
  {
    // Another caller's read first (a second Wait on another thread).
    P->Done.wait(lock, [this] { return P->InFlight < 0; });
    while (P->Step(lock) > 0)
    {
      P->Done.notify_all();
      if (seconds >= 0.0 && Clock::now() > deadline)
      {
        return false;
      }
    }
    return !P->Failed;
  }
  auto idle = [this] { return P->Failed || (!P->HasWork() && P->InFlight < 0); };
  if (seconds < 0.0)
  {
    P->Done.wait(lock, idle);
    return !P->Failed;
  }
  return P->Done.wait_until(lock, deadline, idle) && !P->Failed;
}

bool SplatPageCache::Loading() const
{
  std::lock_guard<std::mutex> lock(P->Mutex);
  return P->HasWork() || P->InFlight >= 0;
}

long long SplatPageCache::Generation() const
{
  std::lock_guard<std::mutex> lock(P->Mutex);
  return P->Generation;
}

std::vector<ResidentPage> SplatPageCache::Resident() const
{
  std::lock_guard<std::mutex> lock(P->Mutex);
  std::vector<ResidentPage> pages;
  pages.reserve(P->Pages.size());
  for (const auto& entry : P->Pages)
  {
    if (entry.second.Blocks.empty())
    {
      continue;
    }
    ResidentPage page;
    page.Node = entry.first;
    page.Levels = static_cast<int>(entry.second.Blocks.size());
    page.Splats = entry.second.Splats;
    page.Blocks = entry.second.Blocks;
    pages.push_back(std::move(page));
  }
  const Octree& tree = P->File.Info().Pages.Tree;
  std::sort(pages.begin(),
    pages.end(),
    [&tree](const ResidentPage& a, const ResidentPage& b)
    { return tree.Nodes[a.Node].Begin < tree.Nodes[b.Node].Begin; });
  return pages;
}

PageCacheStatistics SplatPageCache::Statistics() const
{
  std::lock_guard<std::mutex> lock(P->Mutex);
  PageCacheStatistics stats = P->Stats;
  stats.Resident = P->ResidentSplats;
  if (P->Opened)
  {
    const Octree& tree = P->File.Info().Pages.Tree;
    const size_t L = static_cast<size_t>(tree.Levels);
    for (const PageWant& want : P->Wants)
    {
      const long long wanted =
        tree.LevelEnds[want.Node * L + want.Levels - 1] - tree.Nodes[want.Node].Begin;
      stats.Wanted += wanted;
      auto it = P->Pages.find(want.Node);
      stats.Missing += wanted - std::min(wanted, it == P->Pages.end() ? 0 : it->second.Splats);
    }
  }
  return stats;
}

std::string SplatPageCache::TakeError()
{
  std::lock_guard<std::mutex> lock(P->Mutex);
  std::string error;
  std::swap(error, P->Error);
  return error;
}
} // namespace pointsurfaces
