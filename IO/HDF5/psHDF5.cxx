// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psHDF5.h"

#include "psChildProcess.h"

#include <algorithm>
#include <fstream>
#include <functional>
#include <set>
#include <sys/stat.h>
#include <unistd.h> // For write in the checking child

namespace pointsurfaces
{
namespace
{
// The longest a checking child may take (seconds); a splat file's header,
// octree and chunk indexes for 10^8 points take well under a second.
constexpr double CheckTimeout = 60.0;

// The first and last 64 KiB of a file, hashed: a file rewritten within one
// tick of the file system's clock at the same size (a fuzzer's inputs) is
// not taken for the version checked before.
std::string EndsDigest(const std::string& path, long long size)
{
  std::ifstream in(path, std::ios::binary);
  const long long window = 65536;
  std::string bytes(static_cast<size_t>(std::min(size, 2 * window)), '\0');
  in.read(&bytes[0], std::min(size, window));
  if (size > window)
  {
    const long long tail = std::min(size - window, window);
    in.seekg(size - tail);
    in.read(&bytes[static_cast<size_t>(window)], tail);
  }
  return std::to_string(std::hash<std::string>()(bytes));
}

// The file versions and probes that a checking child ran to their end, in
// this process. Guarded by HDF5Mutex.
std::set<std::string>& CheckedFiles()
{
  static std::set<std::string> files;
  return files;
}
} // namespace

//------------------------------------------------------------------------------
bool CheckInChild(const std::string& path,
  const char* what,
  const std::function<void()>& probe,
  std::string& error)
{
  if (!ChildProcess::Supported() || InCheckingChild())
  {
    return true;
  }
  struct stat s;
  const bool found = ::stat(path.c_str(), &s) == 0;
  const std::string key = std::string(what) + '\n' + path + '\n' +
    (found ? std::to_string(static_cast<long long>(s.st_mtim.tv_sec)) + '.' +
          std::to_string(static_cast<long long>(s.st_mtim.tv_nsec)) + '\n' +
          std::to_string(static_cast<long long>(s.st_size)) + '\n' +
          std::to_string(static_cast<long long>(s.st_ino)) + '\n' +
          EndsDigest(path, static_cast<long long>(s.st_size))
           : std::string("missing"));
  if (CheckedFiles().count(key))
  {
    return true;
  }
  ChildProcess child;
  const bool ran = child.Run(
    [&probe](int fd)
    {
      InCheckingChild() = true;
      probe();
      // One byte: the probe ran to its end. None: the child ended some
      // other way (a crash, a sanitizer's report, exit()).
      return ::write(fd, "0", 1) == 1 ? 0 : 1;
    },
    CheckTimeout);
  if (!ran || child.TimedOut())
  {
    // No child could be made, or it did not finish in time (a slow disk, or
    // an HDF5 call of another library on another thread at the fork): the
    // caller reads in process, as without the check.
    return true;
  }
  if (child.Signal() != 0 || child.Size() != 1)
  {
    error = "damaged: HDF5 crashed while a child process checked it (" +
      (child.Signal() != 0 ? DescribeSignal(child.Signal())
                           : "exit status " + std::to_string(child.ExitStatus())) +
      ")";
    return false;
  }
  CheckedFiles().insert(key);
  return true;
}
} // namespace pointsurfaces
