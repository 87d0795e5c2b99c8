// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// The check counter of the numerics unit tests, and the metaball kernels they
// loop over: Check() reports a failed check by name and counts it; a test
// returns EXIT_FAILURE when Failures is not zero. One test runs per process,
// so one counter serves them all.
#ifndef psFiltersTestSupport_h
#define psFiltersTestSupport_h

#include "psMetaball.h"

#include <iostream>

namespace pstest
{
inline int Failures = 0;

inline void Check(bool ok, const char* what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++Failures;
  }
}
/** Every metaball kernel (the kernel table's list; MetaballKernelName names each). */
inline constexpr const auto& MetaballKernels = pointsurfaces::AllMetaballKernels;
} // namespace pstest

using pstest::Check;
using pstest::Failures;
using pstest::MetaballKernels;

#endif
