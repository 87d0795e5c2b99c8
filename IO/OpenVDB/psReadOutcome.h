// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psReadOutcome.h
 * @brief A reader's result as bytes: how a child process hands back what it read.
 *
 * The OpenVDB reader reads in a child process (psChildProcess.h). The child
 * must not report through VTK's output window (in ParaView that is the
 * GUI's), so its result holds the output or the error, and the warnings,
 * and the parent reports them. The bytes hold the points, the point arrays
 * and the field arrays with their names, types and sizes (numeric arrays
 * as they are in memory, string arrays value by value); cells are not
 * included (a reader of points rebuilds its vertex cells). The format is
 * private to one build: parent and child are the same program.
 */
#ifndef psReadOutcome_h
#define psReadOutcome_h

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstddef> // For size_t
#include <string>  // For Error
#include <vector>  // For Warnings

namespace pointsurfaces
{
/** The output (nullptr with an error), the error, and the warnings of a read. */
struct ReadOutcome
{
  vtkSmartPointer<vtkPolyData> Output;
  std::string Error;
  std::vector<std::string> Warnings;
};

/** Writes `outcome` to the file descriptor `fd`; false when a write fails. */
bool WriteReadOutcome(int fd, const ReadOutcome& outcome);

/** Reads back what WriteReadOutcome wrote; false, with `why`, when the bytes are short or damaged. */
bool ParseReadOutcome(const char* bytes, size_t size, ReadOutcome& outcome, std::string& why);
} // namespace pointsurfaces

#endif
