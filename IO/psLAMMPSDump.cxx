// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psLAMMPSDump.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace pointsurfaces
{
namespace
{
// Lines with their byte offsets; \r\n endings are accepted.
class LineReader
{
public:
  explicit LineReader(std::istream& in)
    : In(in)
  {
    const std::streampos here = in.tellg();
    in.seekg(0, std::ios::end);
    this->Size = static_cast<std::int64_t>(in.tellg());
    in.seekg(here);
    this->Offset = static_cast<std::int64_t>(here);
  }
  bool Next(std::string& line)
  {
    if (!std::getline(this->In, line))
    {
      return false;
    }
    this->Offset += static_cast<std::int64_t>(line.size()) + 1;
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    return true;
  }
  std::int64_t Offset = 0; ///< of the next line
  std::int64_t Size = 0;   ///< of the whole stream

private:
  std::istream& In;
};

bool StartsWith(const std::string& s, const char* prefix)
{
  return s.compare(0, std::char_traits<char>::length(prefix), prefix) == 0;
}

std::vector<std::string> Words(const std::string& line)
{
  std::istringstream ss(line);
  std::vector<std::string> words;
  std::string w;
  while (ss >> w)
  {
    words.push_back(w);
  }
  return words;
}

bool ParseDouble(const char* text, const char** end, double& value)
{
  errno = 0;
  char* stop = nullptr;
  value = std::strtod(text, &stop);
  if (stop == text)
  {
    return false;
  }
  *end = stop;
  return true;
}

bool ParseLong(const std::string& text, long long& value)
{
  errno = 0;
  char* stop = nullptr;
  value = std::strtoll(text.c_str(), &stop, 10);
  while (stop && (*stop == ' ' || *stop == '\t'))
  {
    ++stop;
  }
  return stop != text.c_str() && stop && *stop == '\0' && errno == 0;
}

// The header of one snapshot, up to and including its ITEM: ATOMS line.
// `first` is its first line, already read. Returns false with `error` set.
// The three lines after an ITEM: BOX BOUNDS line `item` into s's box
// (orthogonal or triclinic, tilts undone) and boundary flags.
bool ReadBoxBounds(LineReader& lines, const std::string& item, DumpSnapshot& s, std::string& error)
{
  const std::vector<std::string> words = Words(item.substr(16));
  s.Triclinic = words.size() >= 3 && words[0] == "xy";
  s.Boundary.clear();
  for (size_t k = s.Triclinic ? 3 : 0; k < words.size(); ++k)
  {
    s.Boundary += (s.Boundary.empty() ? "" : " ") + words[k];
  }
  std::string line;
  double bound[3][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };
  for (int axis = 0; axis < 3; ++axis)
  {
    if (!lines.Next(line))
    {
      error = "the file ends in ITEM: BOX BOUNDS";
      return false;
    }
    const char* p = line.c_str();
    for (int k = 0; k < (s.Triclinic ? 3 : 2); ++k)
    {
      const char* end = nullptr;
      if (!ParseDouble(p, &end, bound[axis][k]) || !std::isfinite(bound[axis][k]))
      {
        error = "a BOX BOUNDS line holds no numbers: '" + line + "'";
        return false;
      }
      p = end;
    }
  }
  if (s.Triclinic)
  {
    // The bounds of a triclinic box are those of its bounding box: undo the tilts.
    const double xy = bound[0][2], xz = bound[1][2], yz = bound[2][2];
    s.Tilt[0] = xy;
    s.Tilt[1] = xz;
    s.Tilt[2] = yz;
    s.Box[0] = bound[0][0] - std::min({ 0.0, xy, xz, xy + xz });
    s.Box[1] = bound[0][1] - std::max({ 0.0, xy, xz, xy + xz });
    s.Box[2] = bound[1][0] - std::min(0.0, yz);
    s.Box[3] = bound[1][1] - std::max(0.0, yz);
  }
  else
  {
    s.Box[0] = bound[0][0];
    s.Box[1] = bound[0][1];
    s.Box[2] = bound[1][0];
    s.Box[3] = bound[1][1];
  }
  s.Box[4] = bound[2][0];
  s.Box[5] = bound[2][1];
  return true;
}

// Whether the snapshot's ITEM: ATOMS line (its columns in s) may start its
// atoms: the timestep, count and box came before it, and the file can hold
// that many atom lines. Sets the time to the timestep when none was given.
bool CheckAtomsItem(const LineReader& lines,
  bool haveStep,
  bool haveCount,
  bool haveBox,
  DumpSnapshot& s,
  std::string& error)
{
  if (!haveStep || !haveCount)
  {
    error = "ITEM: ATOMS comes before the timestep or the atom count";
    return false;
  }
  if (!haveBox)
  {
    error = "a snapshot has no ITEM: BOX BOUNDS";
    return false;
  }
  if (s.Columns.empty() && s.Info.NumberOfAtoms > 0)
  {
    error = "ITEM: ATOMS names no columns";
    return false;
  }
  // Each atom needs a line of at least two bytes per column.
  if (s.Info.NumberOfAtoms >
    (lines.Size - lines.Offset) / (2 * std::max<std::int64_t>(1, s.Columns.size())) + 1)
  {
    error = "the file is too short for " + std::to_string(s.Info.NumberOfAtoms) + " atoms of " +
      std::to_string(s.Columns.size()) + " columns (truncated?)";
    return false;
  }
  if (!s.Info.HasTime)
  {
    s.Info.Time = static_cast<double>(s.Info.Timestep);
  }
  return true;
}

bool ReadHeader(LineReader& lines, std::string first, DumpSnapshot& s, std::string& error)
{
  std::string line = std::move(first);
  bool haveStep = false, haveCount = false, haveBox = false;
  for (;;)
  {
    if (StartsWith(line, "ITEM: UNITS"))
    {
      if (!lines.Next(line))
      {
        error = "the file ends in ITEM: UNITS";
        return false;
      }
    }
    else if (StartsWith(line, "ITEM: TIMESTEP"))
    {
      if (!lines.Next(line) || !ParseLong(line, s.Info.Timestep))
      {
        error = "ITEM: TIMESTEP is not followed by a timestep";
        return false;
      }
      haveStep = true;
    }
    else if (StartsWith(line, "ITEM: TIME"))
    {
      const char* end = nullptr;
      if (!lines.Next(line) || !ParseDouble(line.c_str(), &end, s.Info.Time))
      {
        error = "ITEM: TIME is not followed by a time";
        return false;
      }
      s.Info.HasTime = true;
    }
    else if (StartsWith(line, "ITEM: NUMBER OF ATOMS"))
    {
      if (!lines.Next(line) || !ParseLong(line, s.Info.NumberOfAtoms) || s.Info.NumberOfAtoms < 0)
      {
        error = "ITEM: NUMBER OF ATOMS is not followed by a count";
        return false;
      }
      haveCount = true;
    }
    else if (StartsWith(line, "ITEM: BOX BOUNDS"))
    {
      if (!ReadBoxBounds(lines, line, s, error))
      {
        return false;
      }
      haveBox = true;
    }
    else if (StartsWith(line, "ITEM: ATOMS"))
    {
      s.Columns = Words(line.substr(11));
      return CheckAtomsItem(lines, haveStep, haveCount, haveBox, s, error);
    }
    else if (StartsWith(line, "ITEM:"))
    {
      error = "unknown item '" + line + "'";
      return false;
    }
    else
    {
      error = "expected an ITEM line, found '" + line.substr(0, 60) + "'";
      return false;
    }
    if (!lines.Next(line))
    {
      error = "the file ends inside a snapshot's header";
      return false;
    }
  }
}

bool NextNonEmpty(LineReader& lines, std::string& line, std::int64_t& start)
{
  for (;;)
  {
    start = lines.Offset;
    if (!lines.Next(line))
    {
      return false;
    }
    if (line.find_first_not_of(" \t") != std::string::npos)
    {
      return true;
    }
  }
}
} // namespace

std::vector<DumpSnapshotInfo> ScanDump(std::istream& in, std::string& error)
{
  std::vector<DumpSnapshotInfo> found;
  error.clear();
  in.clear();
  in.seekg(0);
  LineReader lines(in);
  std::string line;
  std::int64_t start = 0;
  while (NextNonEmpty(lines, line, start))
  {
    DumpSnapshot s;
    if (!ReadHeader(lines, line, s, error))
    {
      return found;
    }
    s.Info.Offset = start;
    for (long long a = 0; a < s.Info.NumberOfAtoms; ++a)
    {
      if (!lines.Next(line))
      {
        error = "the file ends after " + std::to_string(a) + " of the " +
          std::to_string(s.Info.NumberOfAtoms) + " atoms of timestep " +
          std::to_string(s.Info.Timestep);
        return found;
      }
    }
    found.push_back(s.Info);
  }
  return found;
}

bool ReadSnapshot(std::istream& in, std::int64_t offset, DumpSnapshot& s, std::string& error)
{
  s = DumpSnapshot();
  in.clear();
  in.seekg(offset);
  if (!in)
  {
    error = "no snapshot at that offset";
    return false;
  }
  LineReader lines(in);
  std::string line;
  std::int64_t start = 0;
  if (!NextNonEmpty(lines, line, start) || !ReadHeader(lines, line, s, error))
  {
    if (error.empty())
    {
      error = "no snapshot at that offset";
    }
    return false;
  }
  s.Info.Offset = start;
  const size_t columns = s.Columns.size();
  s.Values.resize(static_cast<size_t>(s.Info.NumberOfAtoms) * columns);
  for (long long a = 0; a < s.Info.NumberOfAtoms; ++a)
  {
    if (!lines.Next(line))
    {
      error = "the file ends after " + std::to_string(a) + " of the " +
        std::to_string(s.Info.NumberOfAtoms) + " atoms";
      return false;
    }
    const char* p = line.c_str();
    for (size_t c = 0; c < columns; ++c)
    {
      const char* end = nullptr;
      if (!ParseDouble(p, &end, s.Values[a * columns + c]))
      {
        error = "atom line " + std::to_string(a + 1) + " has " + std::to_string(c) +
          " numbers, the header names " + std::to_string(columns) + " columns";
        return false;
      }
      p = end;
    }
    while (*p == ' ' || *p == '\t')
    {
      ++p;
    }
    if (*p != '\0')
    {
      error = "atom line " + std::to_string(a + 1) + " has more than the " +
        std::to_string(columns) + " columns the header names";
      return false;
    }
  }
  return true;
}

bool SnapshotPositions(const DumpSnapshot& s, std::vector<double>& xyz, int used[3])
{
  static const char* const sets[4][3] = {
    { "xu", "yu", "zu" }, { "x", "y", "z" }, { "xsu", "ysu", "zsu" }, { "xs", "ys", "zs" }
  };
  for (int set = 0; set < 4; ++set)
  {
    for (int c = 0; c < 3; ++c)
    {
      const auto it = std::find(s.Columns.begin(), s.Columns.end(), sets[set][c]);
      used[c] = it == s.Columns.end() ? -1 : static_cast<int>(it - s.Columns.begin());
    }
    if (used[0] < 0 || used[1] < 0 || used[2] < 0)
    {
      continue;
    }
    const bool scaled = set >= 2;
    const size_t columns = s.Columns.size();
    const long long n = s.Info.NumberOfAtoms;
    xyz.resize(static_cast<size_t>(3 * n));
    const double lx = s.Box[1] - s.Box[0], ly = s.Box[3] - s.Box[2], lz = s.Box[5] - s.Box[4];
    for (long long a = 0; a < n; ++a)
    {
      const double u = s.Values[a * columns + used[0]], v = s.Values[a * columns + used[1]],
                   w = s.Values[a * columns + used[2]];
      if (scaled)
      {
        // Fractional coordinates of the (triclinic) cell: the box's edge
        // vectors are (lx, 0, 0), (xy, ly, 0), (xz, yz, lz).
        xyz[3 * a] = s.Box[0] + u * lx + v * s.Tilt[0] + w * s.Tilt[1];
        xyz[3 * a + 1] = s.Box[2] + v * ly + w * s.Tilt[2];
        xyz[3 * a + 2] = s.Box[4] + w * lz;
      }
      else
      {
        xyz[3 * a] = u;
        xyz[3 * a + 1] = v;
        xyz[3 * a + 2] = w;
      }
    }
    return true;
  }
  used[0] = used[1] = used[2] = -1;
  return false;
}
} // namespace pointsurfaces
