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
 * (and which are the active scalars, vectors, normals and texture
 * coordinates) and the field arrays with their names, types and sizes
 * (numeric arrays as they are in memory, string arrays value by value), and
 * counts the reader defines; cells are not included (a reader of points
 * rebuilds its vertex cells, vtkSplatDataModel::AddVertexCells). The format is
 * private to one build: parent and child are the same program.
 */
#ifndef psReadOutcome_h
#define psReadOutcome_h

#include "PointSurfacesIOModule.h" // For export macro
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstddef>    // For size_t
#include <functional> // For GuardedRead
#include <string>     // For Error
#include <vector>     // For Warnings

namespace pointsurfaces
{
/** The output (nullptr with an error), the error, the warnings and the counts of a read. */
struct ReadOutcome
{
  vtkSmartPointer<vtkPolyData> Output;
  std::string Error;
  std::vector<std::string> Warnings;
  std::vector<long long> Counts; ///< what the reader counted (dropped points, ...)
};

/** Writes `outcome` to the file descriptor `fd`; false when a write fails. */
POINTSURFACESIO_EXPORT bool WriteReadOutcome(int fd, const ReadOutcome& outcome);

/** Reads back what WriteReadOutcome wrote; false, with `why`, when the bytes are short or damaged. */
POINTSURFACESIO_EXPORT bool ParseReadOutcome(const char* bytes,
  size_t size,
  ReadOutcome& outcome,
  std::string& why);
/**
 * `read()` in a child process (psChildProcess.h) when `inChild` is set and
 * the platform supports it, else in this process. When the child ends on a
 * signal, exits with an error, or hands back damaged bytes, the outcome is
 * an error that names `fileName` and blames `library` for a signal ("PCL
 * ended the child process that read ... with SIGSEGV ..."). When no child
 * can start, the read runs here, with a warning saying so.
 */
POINTSURFACESIO_EXPORT ReadOutcome GuardedRead(const std::function<ReadOutcome()>& read,
  bool inChild,
  const std::string& fileName,
  const std::string& library);
} // namespace pointsurfaces

#endif
