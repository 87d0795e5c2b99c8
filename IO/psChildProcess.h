// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psChildProcess.h
 * @brief Runs a job in a forked child process that hands back its result as bytes.
 *
 * A library that aborts on a damaged input (an assertion built into
 * Debian's OpenVDB) or leaks what it had allocated when it throws takes
 * the whole program, or a little of its memory on every read, with it.
 * Run in a child, the abort ends only the child, and everything the child
 * allocated goes when it exits. The child writes its result to an
 * anonymous memory file (memfd) that the parent maps once the child has
 * ended: no pipe to drain while waiting, and no file on disk.
 *
 * The child is a fork() of a program that may run other threads; it must
 * do only the job (no GUI, no VTK output window, no thread pools of the
 * parent) and it leaves through _exit(), so no atexit handler and no
 * buffered stdio of the parent runs twice. Linux only (memfd_create);
 * elsewhere Supported() is false and callers run the job in process.
 */
#ifndef psChildProcess_h
#define psChildProcess_h

#include "PointSurfacesIOModule.h" // For export macro

#include <cstddef>    // For size_t
#include <functional> // For the job
#include <string>     // For Error

namespace pointsurfaces
{
class POINTSURFACESIO_EXPORT ChildProcess
{
public:
  ChildProcess() = default;
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /** Whether this platform runs jobs in a child (Linux). */
  static bool Supported();

  /**
   * Runs `job(fd)` in a child process, where `fd` is the memory file to
   * write the result to; the job's return value is the child's exit status.
   * Waits for the child: with a `timeout` above 0 seconds, at most that
   * long, then kills it (SIGKILL; TimedOut() is true). False when no child
   * could be started (Error() says why); true once it has ended, however
   * it ended.
   */
  bool Run(const std::function<int(int fd)>& job, double timeout = 0.0);

  /** Whether the last Run killed its child at the timeout. */
  bool TimedOut() const { return this->Killed; }

  /** The child's exit status, or -1 when it did not exit (a signal ended it). */
  int ExitStatus() const { return this->Status; }
  /** The signal that ended the child (0 when it exited). */
  int Signal() const { return this->EndSignal; }
  /** Why Run() failed, or why the result cannot be read. */
  const std::string& Error() const { return this->Message; }

  /** The bytes the child wrote (nullptr and 0 when none). */
  const char* Data() const { return this->Bytes; }
  size_t Size() const { return this->Length; }

private:
  void Release();

  int File = -1;
  int Status = -1;
  int EndSignal = 0;
  bool Killed = false;
  std::string Message;
  const char* Bytes = nullptr;
  size_t Length = 0;
};

/** "SIGABRT (an assertion failed or the program aborted)", and the like. */
POINTSURFACESIO_EXPORT std::string DescribeSignal(int signal);
} // namespace pointsurfaces

#endif
