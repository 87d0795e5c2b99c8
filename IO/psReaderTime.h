// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psReaderTime.h
 * @brief What the readers of simulation trajectories share: time steps in and out of the pipeline.
 *
 * A trajectory file holds frames, each with a time. A reader scans the
 * file once (again when the file changes), offers the times as TIME_STEPS,
 * and reads the frame at or before the time asked for, on the first piece
 * of a parallel pipeline only.
 */
#ifndef psReaderTime_h
#define psReaderTime_h

#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkSetGet.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

namespace pointsurfaces
{
/**
 * A file as it was when last read: its name, modification time (whole
 * seconds) and size, to tell whether it must be read again.
 */
struct FileStamp
{
  std::string File;
  long long Modified = -1;
  long long Size = -1;

  /** Whether `file` must be read (again): another file, or changed since. */
  bool Stale(const std::string& file) const
  {
    return file != this->File ||
      static_cast<long long>(vtksys::SystemTools::ModifiedTime(file)) != this->Modified ||
      static_cast<long long>(vtksys::SystemTools::FileLength(file)) != this->Size;
  }
  /** Remember `file` as it is now. */
  void Take(const std::string& file)
  {
    this->File = file;
    this->Modified = static_cast<long long>(vtksys::SystemTools::ModifiedTime(file));
    this->Size = static_cast<long long>(vtksys::SystemTools::FileLength(file));
  }
};

/** A scanned file: its stamp and frames (each with a Time). */
template<typename Frame>
struct FrameIndex
{
  FileStamp Stamp;
  std::vector<Frame> Frames;

  /**
   * Order the frames by time, keeping the last of frames with equal times
   * (a restarted run repeats them). Returns how many were dropped.
   */
  size_t SortByTime()
  {
    std::stable_sort(this->Frames.begin(),
      this->Frames.end(),
      [](const Frame& a, const Frame& b) { return a.Time < b.Time; });
    std::vector<Frame> unique;
    for (const Frame& f : this->Frames)
    {
      if (!unique.empty() && unique.back().Time == f.Time)
      {
        unique.back() = f;
      }
      else
      {
        unique.push_back(f);
      }
    }
    const size_t dropped = this->Frames.size() - unique.size();
    this->Frames.swap(unique);
    return dropped;
  }
  /**
   * Scan `file` with `scan` (a function of an istream and an error string
   * that returns the frames) unless it is scanned already and unchanged.
   * Returns whether it scanned; then `error` tells what went wrong (the
   * frames before damage are kept) and `dropped` how many repeated times
   * SortByTime dropped.
   */
  template<typename Scan>
  bool Refresh(const std::string& file, Scan scan, std::string& error, size_t& dropped)
  {
    error.clear();
    dropped = 0;
    if (!this->Stamp.Stale(file))
    {
      return false;
    }
    *this = FrameIndex();
    std::ifstream in(file, std::ios::binary);
    if (!in)
    {
      error = "cannot be opened";
      return true;
    }
    if (in.peek() == std::ifstream::traits_type::eof())
    {
      error = "is empty"; // said once, here, rather than as damage after 0 frames
      return true;
    }
    std::string damage;
    this->Frames = scan(in, damage);
    this->Stamp.Take(file);
    if (!damage.empty())
    {
      error = "is damaged after " + std::to_string(this->Frames.size()) + " frames: " + damage;
    }
    dropped = this->SortByTime();
    return true;
  }

  /**
   * A reader's RequestInformation: Refresh from `file` with `scan`, report
   * what went wrong through `reader` (one error; a warning for repeated
   * times, naming the `unit` a frame is called in the format), and Publish
   * the time steps into `info`.
   */
  template<typename Scan>
  void Update(vtkObject* reader,
    const std::string& file,
    Scan scan,
    const char* unit,
    vtkInformation* info)
  {
    std::string error;
    size_t dropped = 0;
    if (file.empty())
    {
      *this = FrameIndex();
      vtkErrorWithObjectMacro(reader, << "No FileName: nothing to read.");
    }
    else if (this->Refresh(file, scan, error, dropped))
    {
      if (!error.empty())
      {
        vtkErrorWithObjectMacro(reader, << file << " " << error << ".");
      }
      if (dropped > 0)
      {
        vtkWarningWithObjectMacro(reader,
          << file << " repeats " << dropped << " times (a restarted run?): the last " << unit
          << " of each is read.");
      }
    }
    this->Publish(info);
  }

  /** TIME_STEPS and TIME_RANGE of the frames (removed when there are none). */
  void Publish(vtkInformation* info) const
  {
    info->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    info->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
    if (this->Frames.empty())
    {
      return;
    }
    std::vector<double> times;
    for (const Frame& f : this->Frames)
    {
      times.push_back(f.Time);
    }
    info->Set(
      vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), static_cast<int>(times.size()));
    const double range[2] = { times.front(), times.back() };
    info->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  }
  /** The last frame at or before the requested time (the first when earlier). */
  size_t Pick(vtkInformation* info) const
  {
    size_t pick = 0;
    if (info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
    {
      const double t = info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
      for (size_t k = 0; k < this->Frames.size() && this->Frames[k].Time <= t; ++k)
      {
        pick = k;
      }
    }
    return pick;
  }
};

/**
 * A frame's field data, as the GROMACS readers write it: `Time`, `Step` and,
 * when given, `Box` (nine numbers); and the output's DATA_TIME_STEP.
 */
inline void StampFrame(vtkDataObject* output, double time, long long step, const double* box)
{
  vtkFieldData* fd = output->GetFieldData();
  vtkNew<vtkDoubleArray> t;
  t->SetName("Time");
  t->InsertNextValue(time);
  fd->AddArray(t);
  vtkNew<vtkIdTypeArray> s;
  s->SetName("Step");
  s->InsertNextValue(static_cast<vtkIdType>(step));
  fd->AddArray(s);
  if (box)
  {
    vtkNew<vtkDoubleArray> b;
    b->SetName("Box");
    b->SetNumberOfComponents(9);
    b->InsertNextTypedTuple(box);
    fd->AddArray(b);
  }
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), time);
}

/**
 * Whether this update asks for a piece other than the first: a text
 * trajectory is one stream, read whole into piece 0; the others stay empty.
 */
inline bool LaterPiece(vtkInformation* info)
{
  return info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) &&
    info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) > 0;
}

/**
 * The piece this update asks for and how many there are (0 of 1 when the
 * request names none; at least one piece).
 */
inline void RequestedPiece(vtkInformation* info, int& piece, int& pieces)
{
  piece = info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    ? info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    : 0;
  pieces = info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    ? std::max(1, info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()))
    : 1;
}
} // namespace pointsurfaces

#endif
