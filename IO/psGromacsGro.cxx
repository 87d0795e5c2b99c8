// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psGromacsGro.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace pointsurfaces
{
namespace
{
bool GetLine(std::istream& in, std::string& line, std::int64_t& offset)
{
  if (!std::getline(in, line))
  {
    return false;
  }
  offset += static_cast<std::int64_t>(line.size()) + 1;
  if (!line.empty() && line.back() == '\r')
  {
    line.pop_back();
  }
  return true;
}

std::int64_t StreamSize(std::istream& in)
{
  const std::streampos here = in.tellg();
  in.seekg(0, std::ios::end);
  const std::int64_t size = static_cast<std::int64_t>(in.tellg());
  in.seekg(here);
  return size;
}

bool ParseCount(const std::string& line, long long& n)
{
  errno = 0;
  char* end = nullptr;
  n = std::strtoll(line.c_str(), &end, 10);
  while (end && std::isspace(static_cast<unsigned char>(*end)))
  {
    ++end;
  }
  return end != line.c_str() && end && *end == '\0' && errno == 0 && n >= 0;
}

// "t= 10.0 step= 5000" in a title.
void ParseTitle(const std::string& title, GroFrameInfo& info)
{
  const size_t t = title.find("t=");
  if (t != std::string::npos)
  {
    char* end = nullptr;
    const double value = std::strtod(title.c_str() + t + 2, &end);
    if (end != title.c_str() + t + 2 && std::isfinite(value))
    {
      info.Time = value;
      info.HasTime = true;
    }
  }
  const size_t s = title.find("step=");
  if (s != std::string::npos)
  {
    info.Step = std::strtoll(title.c_str() + s + 5, nullptr, 10);
  }
}

std::string Trim(const std::string& s)
{
  const size_t a = s.find_first_not_of(' ');
  const size_t b = s.find_last_not_of(' ');
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

bool Field(const std::string& line, size_t start, size_t width, double& value)
{
  if (line.size() < start + width)
  {
    return false;
  }
  const std::string text = line.substr(start, width);
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  while (end && *end == ' ')
  {
    ++end;
  }
  return end != text.c_str() && end && *end == '\0' && std::isfinite(value);
}
} // namespace

std::vector<GroFrameInfo> ScanGro(std::istream& in, std::string& error)
{
  std::vector<GroFrameInfo> frames;
  error.clear();
  in.clear();
  in.seekg(0);
  const std::int64_t size = StreamSize(in);
  std::int64_t offset = 0;
  std::string line;
  for (;;)
  {
    GroFrameInfo info;
    info.Offset = offset;
    if (!GetLine(in, line, offset))
    {
      break; // the end
    }
    if (Trim(line).empty() && in.peek() == std::char_traits<char>::eof())
    {
      break; // a last empty line
    }
    ParseTitle(line, info);
    std::string count;
    if (!GetLine(in, count, offset) || !ParseCount(count, info.NumberOfAtoms))
    {
      error = "frame " + std::to_string(frames.size() + 1) + " has no atom count after its title";
      return frames;
    }
    // Each atom line holds at least 44 bytes.
    if (info.NumberOfAtoms > (size - offset) / 44 + 1)
    {
      error = "the file is too short for the " + std::to_string(info.NumberOfAtoms) +
        " atoms of frame " + std::to_string(frames.size() + 1) + " (truncated?)";
      return frames;
    }
    for (long long a = 0; a <= info.NumberOfAtoms; ++a) // the atoms, then the box
    {
      if (!GetLine(in, line, offset))
      {
        error = "frame " + std::to_string(frames.size() + 1) + " ends after " + std::to_string(a) +
          " of its " + std::to_string(info.NumberOfAtoms) + " atoms";
        return frames;
      }
    }
    if (!info.HasTime)
    {
      info.Time = static_cast<double>(frames.size());
    }
    frames.push_back(info);
  }
  return frames;
}

bool ReadGroFrame(std::istream& in, const GroFrameInfo& where, GroFrame& f, std::string& error)
{
  f = GroFrame();
  f.Info = where;
  in.clear();
  in.seekg(where.Offset);
  std::int64_t offset = where.Offset;
  std::string line;
  if (!GetLine(in, f.Title, offset) || !GetLine(in, line, offset))
  {
    error = "no frame at that offset";
    return false;
  }
  const size_t n = static_cast<size_t>(where.NumberOfAtoms);
  f.ResidueNumbers.resize(n);
  f.ResidueNames.resize(n);
  f.AtomNames.resize(n);
  f.AtomNumbers.resize(n);
  f.Positions.resize(3 * n);
  size_t width = 8;
  bool velocities = false;
  for (size_t a = 0; a < n; ++a)
  {
    if (!GetLine(in, line, offset))
    {
      error = "the frame ends after " + std::to_string(a) + " atoms";
      return false;
    }
    if (a == 0)
    {
      // The field width: the distance between the first two decimal points.
      const size_t p1 = line.find('.', 20);
      const size_t p2 = p1 == std::string::npos ? p1 : line.find('.', p1 + 1);
      if (p2 == std::string::npos || p2 - p1 < 4 || p2 - p1 > 20)
      {
        error = "atom line 1 has no coordinates in GROMACS's columns: '" + line + "'";
        return false;
      }
      width = p2 - p1;
      velocities =
        line.size() >= 20 + 6 * width && line.find('.', 20 + 3 * width) != std::string::npos;
      if (velocities)
      {
        f.Velocities.resize(3 * n);
      }
    }
    double value = 0.0;
    if (line.size() < 20 || !Field(line, 0, 5, value))
    {
      error = "atom line " + std::to_string(a + 1) + " is too short or has no residue number";
      return false;
    }
    f.ResidueNumbers[a] = static_cast<int>(value);
    f.ResidueNames[a] = Trim(line.substr(5, 5));
    f.AtomNames[a] = Trim(line.substr(10, 5));
    f.AtomNumbers[a] = Field(line, 15, 5, value) ? static_cast<int>(value) : 0;
    for (int c = 0; c < 3; ++c)
    {
      if (!Field(line, 20 + c * width, width, f.Positions[3 * a + c]))
      {
        error = "atom line " + std::to_string(a + 1) + " has no coordinate " +
          std::string(1, "xyz"[c]) + " in its column";
        return false;
      }
      if (velocities && !Field(line, 20 + (3 + c) * width, width, f.Velocities[3 * a + c]))
      {
        error = "atom line " + std::to_string(a + 1) + " has no velocity " +
          std::string(1, "xyz"[c]) + ", which the first line has";
        return false;
      }
    }
  }
  if (!GetLine(in, line, offset))
  {
    error = "the frame has no box line";
    return false;
  }
  const char* p = line.c_str();
  int found = 0;
  for (; found < 9; ++found)
  {
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p)
    {
      break;
    }
    f.Box[found] = v;
    p = end;
  }
  if (found != 3 && found != 9)
  {
    error = "the box line holds " + std::to_string(found) + " numbers, not 3 or 9";
    return false;
  }
  return true;
}

} // namespace pointsurfaces
