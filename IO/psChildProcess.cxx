// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psChildProcess.h"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>

#if defined(__linux__)
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#endif

namespace pointsurfaces
{
//------------------------------------------------------------------------------
ChildProcess::~ChildProcess()
{
  this->Release();
}

//------------------------------------------------------------------------------
bool ChildProcess::Supported()
{
#if defined(__linux__)
  return true;
#else
  return false;
#endif
}

//------------------------------------------------------------------------------
void ChildProcess::Release()
{
#if defined(__linux__)
  if (this->Bytes)
  {
    ::munmap(const_cast<char*>(this->Bytes), this->Length);
  }
  if (this->File >= 0)
  {
    ::close(this->File);
  }
#endif
  this->Bytes = nullptr;
  this->Length = 0;
  this->File = -1;
}

#if defined(__linux__)
//------------------------------------------------------------------------------
bool ChildProcess::Run(const std::function<int(int fd)>& job, double timeout)
{
  this->Release();
  this->Status = -1;
  this->EndSignal = 0;
  this->Killed = false;
  this->Message.clear();
  this->File = ::memfd_create("pointsurfaces-child", MFD_CLOEXEC);
  if (this->File < 0)
  {
    this->Message = std::string("memfd_create failed: ") + std::strerror(errno);
    return false;
  }
  const pid_t pid = ::fork();
  if (pid < 0)
  {
    this->Message = std::string("fork failed: ") + std::strerror(errno);
    this->Release();
    return false;
  }
  if (pid == 0)
  {
    // An abort here is expected now and then: leave no core file behind,
    // and let the child end quietly. The program's own crash handlers
    // (ParaView's loguru prints a stack trace and "FATL") would report it
    // as the program's crash; the parent reports it instead.
    const struct rlimit noCore = { 0, 0 };
    ::setrlimit(RLIMIT_CORE, &noCore);
    for (int fault : { SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL })
    {
      ::signal(fault, SIG_DFL);
    }
    int status = 125;
    try
    {
      status = job(this->File);
    }
    catch (...)
    {
      status = 124;
    }
    ::_exit(status);
  }
  int waited = 0;
  pid_t ended = -1;
  bool reaped = false;
  if (timeout > 0.0)
  {
    // Poll every 5 ms; at the timeout, kill the child and reap it below.
    const auto start = std::chrono::steady_clock::now();
    for (;;)
    {
      ended = ::waitpid(pid, &waited, WNOHANG);
      if (ended > 0 || (ended < 0 && errno != EINTR))
      {
        reaped = true;
        break;
      }
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout)
      {
        ::kill(pid, SIGKILL);
        this->Killed = true;
        break;
      }
      ::usleep(5000);
    }
  }
  if (!reaped)
  {
    do
    {
      ended = ::waitpid(pid, &waited, 0);
    } while (ended < 0 && errno == EINTR);
  }
  if (ended < 0)
  {
    // ECHILD: the program ignores SIGCHLD, so the child was reaped unseen.
    this->Message = std::string("cannot wait for the child process: ") + std::strerror(errno);
    return true;
  }
  if (WIFSIGNALED(waited))
  {
    this->EndSignal = WTERMSIG(waited);
    return true;
  }
  this->Status = WIFEXITED(waited) ? WEXITSTATUS(waited) : -1;
  struct stat info;
  if (::fstat(this->File, &info) != 0)
  {
    this->Message = std::string("cannot size the child's output: ") + std::strerror(errno);
    return true;
  }
  if (info.st_size > 0)
  {
    void* mapped =
      ::mmap(nullptr, static_cast<size_t>(info.st_size), PROT_READ, MAP_PRIVATE, this->File, 0);
    if (mapped == MAP_FAILED)
    {
      this->Message = std::string("cannot map the child's output: ") + std::strerror(errno);
      return true;
    }
    this->Bytes = static_cast<const char*>(mapped);
    this->Length = static_cast<size_t>(info.st_size);
  }
  return true;
}
#else
//------------------------------------------------------------------------------
bool ChildProcess::Run(const std::function<int(int fd)>&, double)
{
  this->Message = "child processes are supported on Linux only";
  return false;
}
#endif

//------------------------------------------------------------------------------
std::string DescribeSignal(int signal)
{
  switch (signal)
  {
    case SIGABRT:
      return "SIGABRT (an assertion failed or the program aborted)";
    case SIGSEGV:
      return "SIGSEGV (a read or write outside its memory)";
    case SIGBUS:
      return "SIGBUS (a bad memory access)";
    case SIGFPE:
      return "SIGFPE (an arithmetic fault)";
    case SIGKILL:
      return "SIGKILL (killed, for example by the kernel when memory ran out)";
    case SIGILL:
      return "SIGILL (an illegal instruction)";
    default:
      return "signal " + std::to_string(signal);
  }
}
} // namespace pointsurfaces
