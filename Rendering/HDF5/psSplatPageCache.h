// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psSplatPageCache.h
 * @brief The pages of a splat file that are in memory, loaded by a thread, within a budget.
 *
 * A splat file (psSplatFile.h) keeps each page's splats by level, coarsest
 * first. The cache holds, for each page, a prefix of its levels, read one
 * level at a time:
 *
 * - Request() says which prefix of which pages the view wants (the choice
 *   of SelectPages, psSplatPages.h) and how many splats may be resident;
 *   it replaces the previous request and returns at once.
 * - A loading thread reads what is missing, one (page, level) at a time,
 *   coarsest level first and, within a level, pages nearest the eye first:
 *   every wanted page gets its level 0 before any page gets its level 1,
 *   so that the first picture covers the view and detail comes after.
 * - Before a read would pass the budget, the cache evicts what the request
 *   no longer wants: whole pages it does not name (the least recently
 *   wanted first), then the finest levels of pages past their wanted
 *   prefix. What the request wants is never evicted for it, and a read that
 *   still does not fit waits for the next request.
 * - Resident() copies the list of resident pages (shared, immutable level
 *   blocks), for the renderer to assemble; Generation() tells when it
 *   changed.
 *
 * Without a thread (synchronous), Wait() does the same reads in the
 * caller's thread. All HDF5 calls are in psSplatFile, under its lock.
 * Plain C++: no VTK, no GL.
 */
#ifndef psSplatPageCache_h
#define psSplatPageCache_h

#include "PointSurfacesRenderingHDF5Module.h" // For export macro
#include "psSplatFile.h"                      // For SplatFileInfo, SplatColumns

#include <memory> // For the implementation
#include <string> // For errors
#include <vector> // For pages

namespace pointsurfaces
{
/** One page the view wants: its first `Levels` levels; `Distance` orders pages within a level. */
struct PageWant
{
  int Node = 0;
  int Levels = 0;
  double Distance = 0.0;
};

/** A page in memory: its first Levels levels, one immutable block each. */
struct ResidentPage
{
  int Node = 0;
  int Levels = 0;
  long long Splats = 0;
  std::vector<std::shared_ptr<const SplatColumns>> Blocks;
};

struct PageCacheStatistics
{
  long long Reads = 0; ///< (page, level) blocks read
  long long SplatsRead = 0;
  long long Evicted = 0;  ///< splats evicted
  long long Resident = 0; ///< splats in memory now
  long long Wanted = 0;   ///< splats the last request wants
  long long Missing = 0;  ///< of those, not yet in memory
};

class POINTSURFACESRENDERINGHDF5_EXPORT SplatPageCache
{
public:
  /** With a loading thread (`asynchronous`) or without (Wait reads). */
  explicit SplatPageCache(bool asynchronous = true);
  ~SplatPageCache();
  SplatPageCache(const SplatPageCache&) = delete;
  SplatPageCache& operator=(const SplatPageCache&) = delete;

  /** Open and check `path` (one-line `error` when it cannot be used); drops every page. */
  bool Open(const std::string& path, std::string& error);
  bool IsOpen() const;
  /** The open file's header and page octree (unchanged while it is open). */
  const SplatFileInfo& Info() const;

  /**
   * Want the first Levels levels of each page of `wants` (other pages:
   * none), with at most `budgetSplats` splats resident (<= 0: no limit).
   * Replaces the previous request (a page named twice wants the most
   * levels named); what it no longer wants is evicted at once as far as the
   * budget needs; returns without reading.
   */
  void Request(const std::vector<PageWant>& wants, long long budgetSplats);

  /**
   * Until what the last request wants and the budget holds is resident, or
   * `seconds` have passed (< 0: no limit); without a thread, reads it here.
   * False on a read error, a timeout, or without an open file.
   */
  bool Wait(double seconds = -1.0);

  /** True while something the last request wants is missing and may still be read. */
  bool Loading() const;

  /** Bumped each time the resident pages change. */
  long long Generation() const;

  /** The resident pages, in the file's order (their first rows ascending). */
  std::vector<ResidentPage> Resident() const;

  PageCacheStatistics Statistics() const;

  /** The first read error since the last call ("" when none); nothing more is read until Open. */
  std::string TakeError();

private:
  struct Impl;
  std::unique_ptr<Impl> P;
};
} // namespace pointsurfaces

#endif
