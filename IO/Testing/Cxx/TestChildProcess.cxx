// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// pointsurfaces::ChildProcess, the forked child that the PCD, OpenVDB and
// splat file readers read or check a file in:
// - a job's bytes and exit status come back;
// - a job that faults ends the child only, with its signal;
// - a job that hangs is killed at the timeout (TimedOut, SIGKILL), and Run
//   returns soon after it;
// - without a timeout, a slow job is waited for.
#include "psChildProcess.h"
#include "psIOTestSupport.h"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <unistd.h>

using namespace pointsurfaces_test;

int TestChildProcess(int, char*[])
{
  if (!pointsurfaces::ChildProcess::Supported())
  {
    std::cout << "child processes are not supported here: nothing to test\n";
    return EXIT_SUCCESS;
  }
  using Clock = std::chrono::steady_clock;
  {
    pointsurfaces::ChildProcess child;
    Check(child.Run(
            [](int fd)
            {
              const char text[] = "from the child";
              return ::write(fd, text, sizeof(text) - 1) == sizeof(text) - 1 ? 3 : 1;
            }),
      "a child runs");
    Check(child.ExitStatus() == 3 && child.Signal() == 0 && !child.TimedOut(),
      "its exit status comes back");
    Check(std::string(child.Data(), child.Size()) == "from the child", "its bytes come back");
  }
  {
    pointsurfaces::ChildProcess child;
    Check(child.Run(
            [](int)
            {
              std::raise(SIGSEGV);
              return 0;
            }),
      "a faulting child runs");
    Check(child.Signal() == SIGSEGV && child.ExitStatus() == -1 && !child.TimedOut(),
      "a fault ends the child only, with its signal");
  }
  {
    pointsurfaces::ChildProcess child;
    const auto start = Clock::now();
    Check(child.Run(
            [](int)
            {
              std::this_thread::sleep_for(std::chrono::seconds(30));
              return 0;
            },
            0.2),
      "a hanging child runs");
    const double waited = std::chrono::duration<double>(Clock::now() - start).count();
    std::cout << "a hanging child was killed after " << waited << " s (timeout 0.2 s)\n";
    Check(child.TimedOut() && child.Signal() == SIGKILL && waited < 10.0,
      "a hanging child is killed at the timeout");
  }
  {
    pointsurfaces::ChildProcess child;
    Check(child.Run(
            [](int)
            {
              std::this_thread::sleep_for(std::chrono::milliseconds(300));
              return 7;
            },
            20.0),
      "a slow child runs");
    Check(!child.TimedOut() && child.ExitStatus() == 7, "a slow child within its timeout ends");
  }
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
