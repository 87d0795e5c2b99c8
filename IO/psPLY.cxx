// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psPLY.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <new>
#include <string_view>
#include <system_error>
#include <unordered_set>

namespace pointsurfaces
{
namespace
{
using Wide = unsigned __int128; // byte and token positions that a damaged count cannot overflow
using WideInt = __int128;       // any integer value of any PLY type, exactly

struct Property
{
  std::string Name;
  PLYType Type = PLYType::Float32;
  bool List = false;
  PLYType CountType = PLYType::UInt8;
};

struct Element
{
  std::string Name;
  std::uint64_t Count = 0; // saturates: a count beyond 2^64 - 1 cannot fit a file either
  std::vector<Property> Properties;

  bool HasList() const
  {
    return std::any_of(
      this->Properties.begin(), this->Properties.end(), [](const Property& p) { return p.List; });
  }
  std::string Label() const { return "element " + this->Name; }
};

enum class Format
{
  Ascii,
  LittleEndian,
  BigEndian
};

struct Header
{
  Format Body = Format::Ascii;
  std::vector<Element> Elements;
  std::size_t Offset = 0; // the first byte after end_header's line
};

std::string Text(Wide v)
{
  std::string s;
  do
  {
    s.insert(s.begin(), static_cast<char>('0' + static_cast<int>(v % 10)));
    v /= 10;
  } while (v != 0);
  return s;
}

std::string Text(WideInt v)
{
  return v < 0 ? "-" + Text(static_cast<Wide>(-v)) : Text(static_cast<Wide>(v));
}

bool HostIsLittleEndian()
{
  const std::uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

// What Python's str.isspace, str.splitlines and bytes.isspace take for
// white space and line breaks, among ASCII characters.
bool IsHeaderSpace(char c)
{
  return c == ' ' || (c >= '\t' && c <= '\r') || (c >= '\x1c' && c <= '\x1f');
}
bool IsLineBreak(char c)
{
  return c == '\n' || c == '\r' || c == '\v' || c == '\f' || (c >= '\x1c' && c <= '\x1e');
}
bool IsBodySpace(char c)
{
  return c == ' ' || (c >= '\t' && c <= '\r');
}

std::vector<std::string_view> SplitLines(std::string_view text)
{
  std::vector<std::string_view> lines;
  std::size_t i = 0;
  while (i < text.size())
  {
    std::size_t j = i;
    while (j < text.size() && !IsLineBreak(text[j]))
    {
      ++j;
    }
    lines.push_back(text.substr(i, j - i));
    i = j + 1;
    if (j + 1 < text.size() && text[j] == '\r' && text[j + 1] == '\n')
    {
      ++i;
    }
  }
  return lines;
}

std::vector<std::string> SplitWords(std::string_view line)
{
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size())
  {
    while (i < line.size() && IsHeaderSpace(line[i]))
    {
      ++i;
    }
    std::size_t j = i;
    while (j < line.size() && !IsHeaderSpace(line[j]))
    {
      ++j;
    }
    if (j > i)
    {
      words.emplace_back(line.substr(i, j - i));
    }
    i = j;
  }
  return words;
}

std::string Join(const std::vector<std::string>& words, std::size_t from)
{
  std::string s;
  for (std::size_t k = from; k < words.size(); ++k)
  {
    s += (k > from ? " " : "") + words[k];
  }
  return s;
}

// Python's repr() of a str (bytes past ASCII shown as U+FFFD, as a decode
// with errors="replace" leaves them).
std::string Repr(std::string_view s)
{
  const bool doubleQuotes =
    s.find('\'') != std::string_view::npos && s.find('"') == std::string_view::npos;
  const char quote = doubleQuotes ? '"' : '\'';
  std::string out(1, quote);
  for (char c : s)
  {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\\' || c == quote)
    {
      out += '\\';
      out += c;
    }
    else if (c == '\t' || c == '\n' || c == '\r')
    {
      out += c == '\t' ? "\\t" : c == '\n' ? "\\n" : "\\r";
    }
    else if (u >= 0x80)
    {
      out += "\xEF\xBF\xBD";
    }
    else if (u < 0x20 || u == 0x7f)
    {
      const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[u >> 4];
      out += hex[u & 15];
    }
    else
    {
      out += c;
    }
  }
  return out + quote;
}

bool TypeFromName(const std::string& name, PLYType& type)
{
  static const std::pair<const char*, PLYType> names[] = { { "char", PLYType::Int8 },
    { "int8", PLYType::Int8 },
    { "uchar", PLYType::UInt8 },
    { "uint8", PLYType::UInt8 },
    { "short", PLYType::Int16 },
    { "int16", PLYType::Int16 },
    { "ushort", PLYType::UInt16 },
    { "uint16", PLYType::UInt16 },
    { "int", PLYType::Int32 },
    { "int32", PLYType::Int32 },
    { "uint", PLYType::UInt32 },
    { "uint32", PLYType::UInt32 },
    { "int64", PLYType::Int64 },
    { "uint64", PLYType::UInt64 },
    { "float", PLYType::Float32 },
    { "float32", PLYType::Float32 },
    { "double", PLYType::Float64 },
    { "float64", PLYType::Float64 } };
  for (const auto& n : names)
  {
    if (name == n.first)
    {
      type = n.second;
      return true;
    }
  }
  return false;
}

bool IsDigits(const std::string& s)
{
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

std::uint64_t SaturatingCount(const std::string& digits)
{
  std::uint64_t n = 0;
  for (char c : digits)
  {
    const std::uint64_t d = static_cast<std::uint64_t>(c - '0');
    if (n > (std::numeric_limits<std::uint64_t>::max() - d) / 10)
    {
      return std::numeric_limits<std::uint64_t>::max();
    }
    n = 10 * n + d;
  }
  return n;
}

// --- the header -------------------------------------------------------------------

// Finds the line "end_header" (blanks or tabs may follow) that ends the
// header: `start`, where the header's text ends, and `body`, the first byte
// after that line; false when there is none.
bool FindEndHeader(std::string_view all, std::size_t& start, std::size_t& body)
{
  const std::size_t size = all.size();
  for (std::size_t at = all.find("end_header"); at != std::string_view::npos;
       at = all.find("end_header", at + 1))
  {
    if (at > 0 && all[at - 1] != '\n' && all[at - 1] != '\r')
    {
      continue;
    }
    std::size_t q = at + 10;
    while (q < size && (all[q] == ' ' || all[q] == '\t'))
    {
      ++q;
    }
    if (q < size && (all[q] == '\n' || all[q] == '\r'))
    {
      start = at - 1;
      body = q + 1 + (all[q] == '\r' && q + 1 < size && all[q + 1] == '\n' ? 1 : 0);
      return true;
    }
  }
  return false;
}

// Whether the first vertex element has the scalar properties x, y and z.
bool HasVertexXYZ(const Header& header)
{
  const auto vertex = std::find_if(header.Elements.begin(),
    header.Elements.end(),
    [](const Element& e) { return e.Name == "vertex"; });
  int found = 0;
  if (vertex != header.Elements.end())
  {
    for (const Property& p : vertex->Properties)
    {
      found += !p.List && (p.Name == "x" || p.Name == "y" || p.Name == "z");
    }
  }
  return found == 3;
}

bool ParseHeader(const char* data, std::size_t size, Header& header, std::string& error)
{
  if (!HasPLYMagic(data, size))
  {
    error = "not a PLY file (it does not start with 'ply')";
    return false;
  }
  const std::string_view all(data, size);
  std::size_t start = 0;
  if (!FindEndHeader(all, start, header.Offset))
  {
    error = "the PLY header has no end_header line";
    return false;
  }
  const std::string_view text = all.substr(0, start);
  if (std::any_of(text.begin(), text.end(), [](char c) { return (c & 0x80) != 0; }))
  {
    error = "the PLY header is not text";
    return false;
  }
  const std::vector<std::string_view> lines = SplitLines(text);
  bool formatted = false;
  std::unordered_set<std::string> names; // the last element's property names
  for (std::size_t k = 1; k < lines.size(); ++k)
  {
    const std::vector<std::string> words = SplitWords(lines[k]);
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info")
    {
      continue;
    }
    const std::string where = "PLY header line " + std::to_string(k + 1) + ": ";
    Element* last = header.Elements.empty() ? nullptr : &header.Elements.back();
    PLYType type, countType;
    if (words[0] == "format" && words.size() == 3 &&
      (words[1] == "ascii" || words[1] == "binary_little_endian" ||
        words[1] == "binary_big_endian"))
    {
      header.Body = words[1] == "ascii"      ? Format::Ascii
        : words[1] == "binary_little_endian" ? Format::LittleEndian
                                             : Format::BigEndian;
      formatted = true;
    }
    else if (words[0] == "format")
    {
      error = where + "unknown format " + Repr(Join(words, 1));
      return false;
    }
    else if (words[0] == "element" && words.size() == 3)
    {
      if (!IsDigits(words[2]))
      {
        error = where + "bad element count " + Repr(words[2]);
        return false;
      }
      header.Elements.push_back(Element{ words[1], SaturatingCount(words[2]), {} });
      names.clear();
    }
    else if (words[0] == "property" && last && last->Properties.size() >= MaximumProperties)
    {
      // Each kept property becomes a point array, and VTK looks names up one
      // by one: a header of 10^5 properties would take minutes, not a scan.
      error = where + "more than " + std::to_string(MaximumProperties) + " properties in " +
        last->Label();
      return false;
    }
    else if (words[0] == "property" && last && names.count(words.back()))
    {
      error = where + "a second property " + Repr(words.back()) + " in " + last->Label();
      return false;
    }
    else if (words[0] == "property" && last && words.size() == 3 && TypeFromName(words[1], type))
    {
      last->Properties.push_back(Property{ words[2], type, false, PLYType::UInt8 });
      names.insert(words[2]);
    }
    else if (words[0] == "property" && last && words.size() == 5 && words[1] == "list" &&
      TypeFromName(words[2], countType) && PLYTypeIsInteger(countType) &&
      TypeFromName(words[3], type))
    {
      last->Properties.push_back(Property{ words[4], type, true, countType });
      names.insert(words[4]);
    }
    else
    {
      const std::string_view line = lines[k];
      std::size_t a = 0, b = line.size();
      while (a < b && IsHeaderSpace(line[a]))
      {
        ++a;
      }
      while (b > a && IsHeaderSpace(line[b - 1]))
      {
        --b;
      }
      error = where + "cannot parse " + Repr(line.substr(a, b - a));
      return false;
    }
  }
  if (!formatted)
  {
    error = "the PLY header has no format line";
    return false;
  }
  if (!HasVertexXYZ(header))
  {
    error = "the PLY header has no vertex element with x, y and z";
    return false;
  }
  return true;
}

// --- values ----------------------------------------------------------------------

// The range of an integer type.
void Limits(PLYType type, WideInt& low, WideInt& high)
{
  switch (type)
  {
    case PLYType::Int8:
      low = -128, high = 127;
      return;
    case PLYType::UInt8:
      low = 0, high = 255;
      return;
    case PLYType::Int16:
      low = -32768, high = 32767;
      return;
    case PLYType::UInt16:
      low = 0, high = 65535;
      return;
    case PLYType::Int32:
      low = std::numeric_limits<std::int32_t>::min();
      high = std::numeric_limits<std::int32_t>::max();
      return;
    case PLYType::UInt32:
      low = 0, high = std::numeric_limits<std::uint32_t>::max();
      return;
    case PLYType::Int64:
      low = std::numeric_limits<std::int64_t>::min();
      high = std::numeric_limits<std::int64_t>::max();
      return;
    default:
      low = 0, high = std::numeric_limits<std::uint64_t>::max();
      return;
  }
}

template<typename T>
T Load(const unsigned char* p, bool swap)
{
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap)
  {
    std::reverse(b, b + sizeof(T));
  }
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

// An integer of `type` at `p`, exactly.
WideInt LoadInteger(const unsigned char* p, PLYType type, bool swap)
{
  switch (type)
  {
    case PLYType::Int8:
      return Load<std::int8_t>(p, swap);
    case PLYType::UInt8:
      return Load<std::uint8_t>(p, swap);
    case PLYType::Int16:
      return Load<std::int16_t>(p, swap);
    case PLYType::UInt16:
      return Load<std::uint16_t>(p, swap);
    case PLYType::Int32:
      return Load<std::int32_t>(p, swap);
    case PLYType::UInt32:
      return Load<std::uint32_t>(p, swap);
    case PLYType::Int64:
      return Load<std::int64_t>(p, swap);
    default:
      return Load<std::uint64_t>(p, swap);
  }
}

void StoreInteger(unsigned char* p, PLYType type, WideInt v)
{
  switch (type)
  {
#define PS_STORE(E, T)                                                                             \
  case PLYType::E:                                                                                 \
  {                                                                                                \
    const T t = static_cast<T>(v);                                                                 \
    std::memcpy(p, &t, sizeof(T));                                                                 \
    return;                                                                                        \
  }
    PS_STORE(Int8, std::int8_t)
    PS_STORE(UInt8, std::uint8_t)
    PS_STORE(Int16, std::int16_t)
    PS_STORE(UInt16, std::uint16_t)
    PS_STORE(Int32, std::int32_t)
    PS_STORE(UInt32, std::uint32_t)
    PS_STORE(Int64, std::int64_t)
    PS_STORE(UInt64, std::uint64_t)
#undef PS_STORE
    default:
      return;
  }
}

// A number as Python's float() reads it: an optional sign, decimal digits
// (single underscores between them allowed), an exponent, inf, infinity, nan.
bool ParseDouble(std::string_view token, double& value)
{
  std::string clean;
  if (token.find('_') != std::string_view::npos)
  {
    for (std::size_t k = 0; k < token.size(); ++k)
    {
      const auto digit = [&](std::size_t i)
      { return i < token.size() && token[i] >= '0' && token[i] <= '9'; };
      if (token[k] == '_' && !(k > 0 && digit(k - 1) && digit(k + 1)))
      {
        return false;
      }
      if (token[k] != '_')
      {
        clean += token[k];
      }
    }
    token = clean;
  }
  bool negative = false;
  if (!token.empty() && (token[0] == '+' || token[0] == '-'))
  {
    negative = token[0] == '-';
    token.remove_prefix(1);
  }
  if (token.empty() || token[0] == '+' || token[0] == '-' ||
    token.find('(') != std::string_view::npos)
  {
    return false;
  }
  const char* end = token.data() + token.size();
  const std::from_chars_result r = std::from_chars(token.data(), end, value);
  if (r.ptr != end || (r.ec != std::errc() && r.ec != std::errc::result_out_of_range))
  {
    return false;
  }
  if (r.ec == std::errc::result_out_of_range)
  {
    // from_chars leaves the value alone: an overflow is infinite, an underflow zero.
    const std::string copy(token);
    value = std::strtod(copy.c_str(), nullptr);
  }
  value = negative ? -value : value;
  return true;
}

enum class Parsed
{
  Ok,
  NotANumber,
  OutOfRange
};

// An ASCII value of `type`: integers exactly when written as integers, else
// read as a double, checked against the type's range and cut toward zero
// (as numpy's astype does); floats through double.
Parsed ParseValue(std::string_view token, PLYType type, WideInt& integer, double& real)
{
  if (!PLYTypeIsInteger(type))
  {
    return ParseDouble(token, real) ? Parsed::Ok : Parsed::NotANumber;
  }
  WideInt low, high;
  Limits(type, low, high);
  std::string_view digits = token;
  if (!digits.empty() && digits[0] == '+' && digits.size() > 1 && digits[1] != '-')
  {
    digits.remove_prefix(1);
  }
  const char* end = digits.data() + digits.size();
  if (!digits.empty() && digits[0] == '-')
  {
    std::int64_t v = 0;
    const auto r = std::from_chars(digits.data(), end, v);
    if (r.ptr == end && r.ec == std::errc())
    {
      integer = v;
      return v >= low ? Parsed::Ok : Parsed::OutOfRange;
    }
  }
  else
  {
    std::uint64_t v = 0;
    const auto r = std::from_chars(digits.data(), end, v);
    if (r.ptr == end && r.ec == std::errc())
    {
      integer = v;
      return integer <= high ? Parsed::Ok : Parsed::OutOfRange;
    }
  }
  double v = 0.0;
  if (!ParseDouble(token, v))
  {
    return Parsed::NotANumber;
  }
  if (!(v >= static_cast<double>(low) && v < static_cast<double>(high) + 1.0))
  {
    return Parsed::OutOfRange; // NaN too
  }
  integer = static_cast<WideInt>(std::trunc(v));
  return Parsed::Ok;
}

// --- the body ----------------------------------------------------------------------

// The faces as they are read: list lengths and indices, and the first index
// that names no vertex.
struct FaceSink
{
  PLYType Type = PLYType::Int32;
  std::uint64_t NumberOfPoints = 0;
  std::vector<std::int64_t> Counts;
  std::vector<std::int64_t> Indices;
  std::string BadIndex;

  void Add(WideInt index)
  {
    if ((index < 0 || index >= static_cast<WideInt>(this->NumberOfPoints)) &&
      this->BadIndex.empty())
    {
      this->BadIndex = Text(index);
    }
    this->Indices.push_back(static_cast<std::int64_t>(index));
  }
};

// What to keep of one element: per property, the column it fills (or null),
// and which property is the face list.
struct Wanted
{
  std::vector<PLYColumn*> Columns;
  int FaceList = -1;
  FaceSink* Faces = nullptr;
};

std::string Truncated(const Element& e)
{
  return "truncated: the file ends inside " + e.Label();
}

std::string Truncated(const Element& e, Wide needed, std::size_t size)
{
  return "truncated: " + e.Label() + " needs " + Text(needed) + " bytes, the file has " +
    std::to_string(size);
}

std::string NegativeLength(const Element& e)
{
  return e.Label() + " has a list of negative length";
}

// Element `e` of fixed-size records (no lists), from byte `at`: its extent
// is known before anything is allocated.
bool BinaryFixedElement(const unsigned char* data,
  std::size_t size,
  std::size_t& at,
  const Element& e,
  bool swap,
  Wanted& want,
  std::string& error)
{
  const std::size_t n = e.Properties.size();
  std::size_t record = 0;
  std::vector<std::size_t> offsets(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    offsets[i] = record;
    record += PLYTypeSize(e.Properties[i].Type);
  }
  const Wide end = static_cast<Wide>(at) + static_cast<Wide>(e.Count) * record;
  if (end > size)
  {
    error = Truncated(e, end, size);
    return false;
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    PLYColumn* column = want.Columns.empty() ? nullptr : want.Columns[i];
    if (!column)
    {
      continue;
    }
    const std::size_t bytes = PLYTypeSize(column->Type);
    column->Bytes.resize(static_cast<std::size_t>(e.Count) * bytes);
    const unsigned char* from = data + at + offsets[i];
    unsigned char* to = column->Bytes.data();
    for (std::uint64_t r = 0; r < e.Count; ++r, from += record, to += bytes)
    {
      std::memcpy(to, from, bytes);
      if (swap)
      {
        std::reverse(to, to + bytes);
      }
    }
  }
  at = static_cast<std::size_t>(end);
  return true;
}

// The length of the list property `p` whose count is at byte `pos`.
bool BinaryListLength(const unsigned char* data,
  std::size_t size,
  Wide pos,
  const Property& p,
  const Element& e,
  bool swap,
  WideInt& length,
  std::string& error)
{
  const std::size_t countSize = PLYTypeSize(p.CountType);
  if (pos + countSize > size)
  {
    error = Truncated(e, pos + countSize, size);
    return false;
  }
  length = LoadInteger(data + static_cast<std::size_t>(pos), p.CountType, swap);
  if (length < 0)
  {
    error = NegativeLength(e);
    return false;
  }
  return true;
}

// Element `e` with lists, from byte `at`, one record at a time.
bool BinaryListElement(const unsigned char* data,
  std::size_t size,
  std::size_t& at,
  const Element& e,
  bool swap,
  Wanted& want,
  std::string& error)
{
  const std::size_t n = e.Properties.size();
  // Records with lists, one at a time; each takes at least a byte, so the
  // walk ends at the file's end at the latest, and only what the file holds
  // is stored.
  for (std::size_t i = 0; i < n && !want.Columns.empty(); ++i)
  {
    if (want.Columns[i])
    {
      want.Columns[i]->Bytes.clear();
    }
  }
  // The first record's list lengths are read first, checked against the
  // file (as the numpy reader did: the numbers its errors give follow).
  Wide pos = at;
  for (const Property& p : e.Properties)
  {
    if (!p.List)
    {
      pos += PLYTypeSize(p.Type);
      continue;
    }
    WideInt length = 0;
    if (!BinaryListLength(data, size, pos, p, e, swap, length, error))
    {
      return false;
    }
    pos += PLYTypeSize(p.CountType) + static_cast<Wide>(length) * PLYTypeSize(p.Type);
  }
  pos = at;
  for (std::uint64_t r = 0; r < e.Count; ++r)
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      const Property& p = e.Properties[i];
      const std::size_t item = PLYTypeSize(p.Type);
      if (!p.List)
      {
        if (pos + item > size)
        {
          error = Truncated(e, pos + item, size);
          return false;
        }
        PLYColumn* column = want.Columns.empty() ? nullptr : want.Columns[i];
        if (column)
        {
          const std::size_t old = column->Bytes.size();
          const unsigned char* from = data + static_cast<std::size_t>(pos);
          column->Bytes.insert(column->Bytes.end(), from, from + item);
          if (swap)
          {
            std::reverse(column->Bytes.begin() + old, column->Bytes.end());
          }
        }
        pos += item;
        continue;
      }
      WideInt length = 0;
      if (!BinaryListLength(data, size, pos, p, e, swap, length, error))
      {
        return false;
      }
      pos += PLYTypeSize(p.CountType);
      const Wide end = pos + static_cast<Wide>(length) * item;
      if (end > size)
      {
        error = Truncated(e, end, size);
        return false;
      }
      if (static_cast<int>(i) == want.FaceList)
      {
        want.Faces->Counts.push_back(static_cast<std::int64_t>(length));
        if (PLYTypeIsInteger(p.Type))
        {
          for (Wide q = pos; q < end; q += item)
          {
            want.Faces->Add(LoadInteger(data + static_cast<std::size_t>(q), p.Type, swap));
          }
        }
      }
      pos = end;
    }
  }
  at = static_cast<std::size_t>(pos);
  return true;
}

// Element `e` from byte `at` of a binary body; `at` moves past it.
bool BinaryElement(const unsigned char* data,
  std::size_t size,
  std::size_t& at,
  const Element& e,
  bool swap,
  Wanted& want,
  std::string& error)
{
  if (e.Count == 0 || e.Properties.empty())
  {
    return true;
  }
  return e.HasList() ? BinaryListElement(data, size, at, e, swap, want, error)
                     : BinaryFixedElement(data, size, at, e, swap, want, error);
}

// ASCII words, one after another, and how many are left.
struct Tokens
{
  const char* At;
  const char* End;
  Wide Left = 0;

  Tokens(const char* at, const char* end)
    : At(at)
    , End(end)
  {
    for (const char* p = at; p < end;)
    {
      while (p < end && IsBodySpace(*p))
      {
        ++p;
      }
      if (p < end)
      {
        ++this->Left;
      }
      while (p < end && !IsBodySpace(*p))
      {
        ++p;
      }
    }
  }
  bool Next(std::string_view& token)
  {
    while (this->At < this->End && IsBodySpace(*this->At))
    {
      ++this->At;
    }
    const char* begin = this->At;
    while (this->At < this->End && !IsBodySpace(*this->At))
    {
      ++this->At;
    }
    token = std::string_view(begin, static_cast<std::size_t>(this->At - begin));
    if (this->At == begin)
    {
      return false;
    }
    --this->Left;
    return true;
  }
  void Skip(Wide words)
  {
    std::string_view ignored;
    for (Wide k = 0; k < words && this->Next(ignored); ++k)
    {
    }
  }
};

// A list length as Python's int() reads it: false, with `error` set, when it is none.
bool ListLength(std::string_view token, const Element& e, Wide& length, std::string& error)
{
  WideInt value = 0;
  double ignored = 0.0;
  const bool whole = token.find_first_of(".eEnNiI") == std::string_view::npos;
  const Parsed how = whole ? ParseValue(token, PLYType::Int64, value, ignored) : Parsed::NotANumber;
  if (how == Parsed::NotANumber)
  {
    error = e.Label() + " has the list length " + Repr(token) + ", not a whole number";
    return false;
  }
  if (value < 0 || (how == Parsed::OutOfRange && token[0] == '-'))
  {
    error = NegativeLength(e);
    return false;
  }
  // Beyond int64: more words than any file holds.
  length = how == Parsed::OutOfRange ? ~Wide(0) >> 1 : static_cast<Wide>(value);
  return true;
}

// What went wrong with one property's ASCII values: numpy read a column at
// a time, so the first column with a bad value is the one reported.
struct ValueProblem
{
  std::string NotANumber; // the first word that is no number
  bool OutOfRange = false;
};

// Whether every record of an element with lists has the first record's list
// lengths, as the numpy reader tried first; its errors follow from that: a
// list length that is no number at all is reported as such, and when every
// record matches, lengths such as "3.0" pass.
bool UniformLists(const Tokens& tokens,
  const Element& e,
  std::vector<Wide>& first,
  bool& uniform,
  std::string& error)
{
  uniform = false;
  first.assign(e.Properties.size(), 0);
  Wide width = 0;
  for (std::size_t i = 0; i < e.Properties.size(); ++i)
  {
    if (!e.Properties[i].List)
    {
      ++width;
      continue;
    }
    if (width >= tokens.Left)
    {
      error = Truncated(e);
      return false;
    }
    Tokens at = tokens;
    at.Skip(width);
    std::string_view token;
    at.Next(token);
    if (!ListLength(token, e, first[i], error))
    {
      return false;
    }
    width += 1 + first[i];
  }
  if (width > tokens.Left || static_cast<Wide>(e.Count) * width > tokens.Left)
  {
    return true;
  }
  // Each list length column in turn, as numbers.
  uniform = true;
  for (std::size_t i = 0; i < e.Properties.size(); ++i)
  {
    if (!e.Properties[i].List)
    {
      continue;
    }
    Wide column = 0;
    for (std::size_t j = 0; j < i; ++j)
    {
      column += e.Properties[j].List ? 1 + first[j] : 1;
    }
    Tokens at = tokens;
    at.Skip(column);
    std::string_view token;
    for (std::uint64_t r = 0; r < e.Count; ++r)
    {
      at.Next(token);
      double length = 0.0;
      if (!ParseDouble(token, length))
      {
        error = e.Label() + " holds something that is not a number (" + Repr(token) + ")";
        return false;
      }
      uniform = uniform && length == static_cast<double>(first[i]);
      at.Skip(width - 1);
    }
  }
  return true;
}

// One ASCII word of PLY type `type`: stored at `to` (null: added to `faces`
// when not null and an integer); a word that is no number, or out of the
// type's range, is noted in `problem` instead.
void StoreAsciiValue(std::string_view token,
  PLYType type,
  unsigned char* to,
  FaceSink* faces,
  ValueProblem& problem)
{
  WideInt integer = 0;
  double real = 0.0;
  const Parsed how = ParseValue(token, type, integer, real);
  if (how == Parsed::NotANumber && problem.NotANumber.empty())
  {
    problem.NotANumber = Repr(token);
  }
  problem.OutOfRange |= how == Parsed::OutOfRange;
  if (how != Parsed::Ok)
  {
    return;
  }
  if (to && type == PLYType::Float32)
  {
    const float f = PLYFloat(real);
    std::memcpy(to, &f, sizeof(f));
  }
  else if (to && type == PLYType::Float64)
  {
    std::memcpy(to, &real, sizeof(real));
  }
  else if (to)
  {
    StoreInteger(to, type, integer);
  }
  else if (faces && PLYTypeIsInteger(type))
  {
    faces->Add(integer);
  }
}

// False, with `error` naming the first property of `e` that held a word
// that is no number (or else one out of its type's range).
bool NoValueProblem(const Element& e, const std::vector<ValueProblem>& problems, std::string& error)
{
  for (std::size_t i = 0; i < problems.size(); ++i)
  {
    if (!problems[i].NotANumber.empty())
    {
      error = e.Label() + " holds something that is not a number (" + problems[i].NotANumber + ")";
      return false;
    }
    if (problems[i].OutOfRange)
    {
      error = e.Label() + " holds a number that is not a " + PLYTypeName(e.Properties[i].Type);
      return false;
    }
  }
  return true;
}

bool AsciiElement(Tokens& tokens, const Element& e, Wanted& want, std::string& error)
{
  if (e.Count == 0 || e.Properties.empty())
  {
    return true;
  }
  const std::size_t n = e.Properties.size();
  const bool lists = e.HasList();
  if (!lists && static_cast<Wide>(e.Count) * n > tokens.Left)
  {
    error = Truncated(e);
    return false;
  }
  std::vector<Wide> first;
  bool uniform = false;
  if (lists && !UniformLists(tokens, e, first, uniform, error))
  {
    return false;
  }
  std::vector<ValueProblem> problems(n);
  auto parse = [&](std::size_t i, std::string_view token, PLYType type, unsigned char* to)
  { StoreAsciiValue(token, type, to, to ? nullptr : want.Faces, problems[i]); };
  // Fixed records: the columns are allocated once (the element's words are
  // known to be there); records with lists grow them as they are read.
  for (std::size_t i = 0; i < n && !want.Columns.empty(); ++i)
  {
    if (want.Columns[i])
    {
      const std::size_t bytes = PLYTypeSize(want.Columns[i]->Type);
      want.Columns[i]->Bytes.assign(lists ? 0 : static_cast<std::size_t>(e.Count) * bytes, 0);
    }
  }
  std::string_view token;
  for (std::uint64_t r = 0; r < e.Count; ++r)
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      const Property& p = e.Properties[i];
      if (!tokens.Next(token))
      {
        error = Truncated(e);
        return false;
      }
      PLYColumn* column = want.Columns.empty() ? nullptr : want.Columns[i];
      if (!p.List)
      {
        if (column)
        {
          const std::size_t bytes = PLYTypeSize(p.Type);
          std::size_t offset = static_cast<std::size_t>(r) * bytes;
          if (lists)
          {
            offset = column->Bytes.size();
            column->Bytes.resize(offset + bytes);
          }
          parse(i, token, p.Type, column->Bytes.data() + offset);
        }
        continue;
      }
      Wide length = first.empty() ? 0 : first[i];
      if (!uniform && !ListLength(token, e, length, error))
      {
        return false;
      }
      if (length > tokens.Left)
      {
        error = Truncated(e);
        return false;
      }
      const bool faces = static_cast<int>(i) == want.FaceList;
      if (!faces)
      {
        tokens.Skip(length);
        continue;
      }
      want.Faces->Counts.push_back(static_cast<std::int64_t>(length));
      for (Wide k = 0; k < length; ++k)
      {
        tokens.Next(token);
        parse(i, token, p.Type, nullptr);
      }
    }
  }
  return NoValueProblem(e, problems, error);
}
} // namespace

// --- the public functions --------------------------------------------------------------

std::size_t PLYTypeSize(PLYType type)
{
  switch (type)
  {
    case PLYType::Int8:
    case PLYType::UInt8:
      return 1;
    case PLYType::Int16:
    case PLYType::UInt16:
      return 2;
    case PLYType::Int32:
    case PLYType::UInt32:
    case PLYType::Float32:
      return 4;
    default:
      return 8;
  }
}

bool PLYTypeIsInteger(PLYType type)
{
  return type != PLYType::Float32 && type != PLYType::Float64;
}

const char* PLYTypeName(PLYType type)
{
  static const char* names[] = {
    "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64", "float32", "float64"
  };
  return names[static_cast<int>(type)];
}

float PLYFloat(double v)
{
  const double overflow = std::ldexp(1.0, 128) - std::ldexp(1.0, 103); // rounds up to 2^128
  if (std::abs(v) >= overflow)
  {
    const float inf = std::numeric_limits<float>::infinity();
    return v > 0 ? inf : -inf;
  }
  return static_cast<float>(v);
}

double PLYColumn::Value(std::size_t k) const
{
  const unsigned char* p = this->Bytes.data() + k * PLYTypeSize(this->Type);
  switch (this->Type)
  {
    case PLYType::Float32:
      return Load<float>(p, false);
    case PLYType::Float64:
      return Load<double>(p, false);
    default:
      return static_cast<double>(LoadInteger(p, this->Type, false));
  }
}

const PLYColumn* PLYMesh::Find(const std::string& name) const
{
  for (const PLYColumn& c : this->Columns)
  {
    if (c.Name == name)
    {
      return &c;
    }
  }
  return nullptr;
}

bool HasPLYMagic(const char* data, std::size_t size)
{
  return size >= 4 && std::memcmp(data, "ply", 3) == 0 && (data[3] == '\n' || data[3] == '\r');
}

namespace
{
// Every element of the body in turn, by its declared types, into `wanted`.
bool WalkBody(const char* data,
  std::size_t size,
  const Header& header,
  std::vector<Wanted>& wanted,
  std::string& error)
{
  const std::vector<Element>& elements = header.Elements;
  if (header.Body == Format::Ascii)
  {
    Tokens tokens{ data + header.Offset, data + size };
    for (std::size_t k = 0; k < elements.size(); ++k)
    {
      if (!AsciiElement(tokens, elements[k], wanted[k], error))
      {
        return false;
      }
    }
    return true;
  }
  const bool swap = (header.Body == Format::LittleEndian) != HostIsLittleEndian();
  std::size_t at = header.Offset;
  const auto* bytes = reinterpret_cast<const unsigned char*>(data);
  for (std::size_t k = 0; k < elements.size(); ++k)
  {
    if (!BinaryElement(bytes, size, at, elements[k], swap, wanted[k], error))
    {
      return false;
    }
  }
  return true;
}

// The faces read into `faces` (list type `indexType`) as the mesh's polygons:
// integer indices naming one of `vertices` vertices; faces of fewer than
// three corners left out, with a warning.
bool KeepFaces(FaceSink& faces,
  PLYType indexType,
  std::uint64_t vertices,
  PLYMesh& mesh,
  std::string& error)
{
  if (!PLYTypeIsInteger(indexType))
  {
    error = "the face indices are not integers";
    return false;
  }
  if (!faces.BadIndex.empty())
  {
    error = "a face refers to vertex " + faces.BadIndex + ", but there are " +
      std::to_string(vertices) + " vertices";
    return false;
  }
  std::size_t shortFaces = 0, from = 0;
  mesh.FaceOffsets.reserve(faces.Counts.size() + 1);
  mesh.FaceOffsets.push_back(0);
  for (std::int64_t count : faces.Counts)
  {
    const auto corners = static_cast<std::size_t>(count);
    if (corners < 3)
    {
      ++shortFaces;
    }
    else
    {
      // Shift the kept faces' indices down over those left out (in place).
      const std::size_t to = static_cast<std::size_t>(mesh.FaceOffsets.back());
      if (to != from)
      {
        std::copy(faces.Indices.begin() + from,
          faces.Indices.begin() + from + corners,
          faces.Indices.begin() + to);
      }
      mesh.FaceOffsets.push_back(static_cast<std::int64_t>(to + corners));
    }
    from += corners;
  }
  faces.Indices.resize(static_cast<std::size_t>(mesh.FaceOffsets.back()));
  mesh.FaceConnectivity.swap(faces.Indices);
  if (mesh.FaceOffsets.size() == 1)
  {
    mesh.FaceOffsets.clear();
  }
  if (shortFaces > 0)
  {
    mesh.Warnings.push_back(
      "faces with fewer than three corners left out: " + std::to_string(shortFaces));
  }
  return true;
}
} // namespace

bool ReadPLY(const char* data, std::size_t size, PLYMesh& mesh, std::string& error)
{
  mesh = PLYMesh();
  Header header;
  if (!ParseHeader(data, size, header, error))
  {
    return false;
  }
  std::vector<Element>& elements = header.Elements;
  const auto byName = [&](const char* name)
  {
    return static_cast<int>(
      std::find_if(
        elements.begin(), elements.end(), [&](const Element& e) { return e.Name == name; }) -
      elements.begin());
  };
  const int vertex = byName("vertex");
  const int face = byName("face");
  mesh.NumberOfPoints = static_cast<std::size_t>(elements[vertex].Count);

  // What to keep: the vertex element's scalars, the face element's index list.
  std::vector<Wanted> wanted(elements.size());
  const Element& v = elements[vertex];
  for (const Property& p : v.Properties)
  {
    if (!p.List)
    {
      mesh.Columns.push_back(PLYColumn{ p.Name, p.Type, {} });
    }
  }
  for (std::size_t i = 0, c = 0; i < v.Properties.size(); ++i)
  {
    wanted[vertex].Columns.push_back(v.Properties[i].List ? nullptr : &mesh.Columns[c++]);
  }
  FaceSink faces;
  const Property* faceList = nullptr;
  if (face < static_cast<int>(elements.size()))
  {
    const std::vector<Property>& props = elements[face].Properties;
    for (std::size_t i = 0; i < props.size() && !faceList; ++i)
    {
      if (props[i].List && (props[i].Name == "vertex_indices" || props[i].Name == "vertex_index"))
      {
        faceList = &props[i];
        wanted[face].FaceList = static_cast<int>(i);
        wanted[face].Faces = &faces;
        faces.Type = props[i].Type;
        faces.NumberOfPoints = v.Count;
      }
    }
  }

  // Every element in turn, by its declared types.
  if (!WalkBody(data, size, header, wanted, error))
  {
    return false;
  }

  // The faces: integer indices naming vertices; fewer than three corners left out.
  return !faceList || KeepFaces(faces, faceList->Type, v.Count, mesh, error);
}

bool ReadPLYFile(const std::string& path, PLYMesh& mesh, std::string& error)
{
  mesh = PLYMesh();
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in ? static_cast<std::streamoff>(in.tellg()) : -1;
  if (!in || size < 0)
  {
    error = "cannot be opened";
    return false;
  }
  if (size == 0)
  {
    error = "the file is empty";
    return false;
  }
  std::string bytes;
  try
  {
    bytes.resize(static_cast<std::size_t>(size));
  }
  catch (const std::bad_alloc&)
  {
    error = "too large to read into memory";
    return false;
  }
  in.seekg(0);
  if (!in.read(&bytes[0], size))
  {
    error = "cannot be read";
    return false;
  }
  try
  {
    return ReadPLY(bytes.data(), bytes.size(), mesh, error);
  }
  catch (const std::bad_alloc&)
  {
    mesh = PLYMesh();
    error = "too large to read into memory";
    return false;
  }
}

bool ReadPLYFilePiece(const std::string& path,
  std::size_t piece,
  std::size_t pieces,
  PLYMesh& mesh,
  bool& streamed,
  std::string& error)
{
  mesh = PLYMesh();
  streamed = false;
  pieces = std::max<std::size_t>(1, pieces);
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in ? static_cast<std::streamoff>(in.tellg()) : -1;
  if (!in || size <= 0)
  {
    error = !in || size < 0 ? "cannot be opened" : "the file is empty";
    return false;
  }
  // The header: at most its 4096 properties' lines.
  std::string head(static_cast<std::size_t>(std::min<std::streamoff>(size, 1 << 20)), '\0');
  in.seekg(0);
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  Header header;
  std::string headerError;
  const bool parsed = ParseHeader(head.data(), head.size(), header, headerError);
  const auto vertex = std::find_if(header.Elements.begin(),
    header.Elements.end(),
    [](const Element& e) { return e.Name == "vertex"; });
  // A binary body whose vertex records have a fixed size and a known place.
  bool direct =
    parsed && header.Body != Format::Ascii && vertex != header.Elements.end() && !vertex->HasList();
  Wide offset = header.Offset;
  for (auto e = header.Elements.begin(); direct && e != vertex; ++e)
  {
    direct = !e->HasList();
    std::size_t record = 0;
    for (const Property& p : e->Properties)
    {
      record += PLYTypeSize(p.Type);
    }
    offset += static_cast<Wide>(e->Count) * record;
  }
  if (!direct)
  {
    // ASCII, or lists before the vertices: the whole file, then the piece.
    if (!ReadPLYFile(path, mesh, error))
    {
      return false;
    }
    const std::size_t n = mesh.NumberOfPoints;
    const std::size_t first = n * piece / pieces, last = n * (piece + 1) / pieces;
    for (PLYColumn& c : mesh.Columns)
    {
      const std::size_t bytes = PLYTypeSize(c.Type);
      c.Bytes =
        std::vector<unsigned char>(c.Bytes.begin() + first * bytes, c.Bytes.begin() + last * bytes);
    }
    mesh.NumberOfPoints = last - first;
    mesh.FaceOffsets.clear();
    mesh.FaceConnectivity.clear();
    return true;
  }
  std::size_t record = 0;
  for (const Property& p : vertex->Properties)
  {
    record += PLYTypeSize(p.Type);
  }
  if (offset + static_cast<Wide>(vertex->Count) * record > static_cast<Wide>(size))
  {
    error = Truncated(*vertex);
    return false;
  }
  const std::uint64_t n = vertex->Count;
  const std::uint64_t first = n * piece / pieces, last = n * (piece + 1) / pieces;
  Element e = *vertex;
  e.Count = last - first;
  std::vector<unsigned char> bytes;
  try
  {
    bytes.resize(static_cast<std::size_t>(e.Count * record));
  }
  catch (const std::bad_alloc&)
  {
    error = "too large to read into memory";
    return false;
  }
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset + static_cast<Wide>(first) * record));
  if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())))
  {
    error = "cannot be read";
    return false;
  }
  Wanted want;
  for (const Property& p : e.Properties)
  {
    mesh.Columns.push_back(PLYColumn{ p.Name, p.Type, {} });
  }
  for (PLYColumn& c : mesh.Columns)
  {
    want.Columns.push_back(&c);
  }
  std::size_t at = 0;
  const bool swap = (header.Body == Format::LittleEndian) != HostIsLittleEndian();
  if (!BinaryFixedElement(bytes.data(), bytes.size(), at, e, swap, want, error))
  {
    return false;
  }
  mesh.NumberOfPoints = static_cast<std::size_t>(e.Count);
  streamed = true;
  return true;
}

std::size_t DropNonFinitePoints(PLYMesh& mesh)
{
  const PLYColumn* xyz[3] = { mesh.Find("x"), mesh.Find("y"), mesh.Find("z") };
  if (!xyz[0] || !xyz[1] || !xyz[2])
  {
    return 0;
  }
  const std::size_t n = mesh.NumberOfPoints;
  std::vector<std::int64_t> renumber(n, -1);
  std::size_t kept = 0;
  for (std::size_t k = 0; k < n; ++k)
  {
    if (std::isfinite(xyz[0]->Value(k)) && std::isfinite(xyz[1]->Value(k)) &&
      std::isfinite(xyz[2]->Value(k)))
    {
      renumber[k] = static_cast<std::int64_t>(kept++);
    }
  }
  if (kept == n)
  {
    return 0;
  }
  for (PLYColumn& c : mesh.Columns)
  {
    const std::size_t bytes = PLYTypeSize(c.Type);
    for (std::size_t k = 0; k < n; ++k)
    {
      if (renumber[k] >= 0)
      {
        std::memmove(
          &c.Bytes[static_cast<std::size_t>(renumber[k]) * bytes], &c.Bytes[k * bytes], bytes);
      }
    }
    c.Bytes.resize(kept * bytes);
  }
  // Faces that use a point left out go with it.
  if (!mesh.FaceOffsets.empty())
  {
    std::vector<std::int64_t> offsets(1, 0);
    std::size_t to = 0;
    for (std::size_t f = 0; f + 1 < mesh.FaceOffsets.size(); ++f)
    {
      const auto begin = static_cast<std::size_t>(mesh.FaceOffsets[f]);
      const auto end = static_cast<std::size_t>(mesh.FaceOffsets[f + 1]);
      bool whole = true;
      for (std::size_t i = begin; i < end && whole; ++i)
      {
        whole = renumber[static_cast<std::size_t>(mesh.FaceConnectivity[i])] >= 0;
      }
      if (!whole)
      {
        continue;
      }
      for (std::size_t i = begin; i < end; ++i)
      {
        mesh.FaceConnectivity[to++] = renumber[static_cast<std::size_t>(mesh.FaceConnectivity[i])];
      }
      offsets.push_back(static_cast<std::int64_t>(to));
    }
    mesh.FaceConnectivity.resize(to);
    mesh.FaceOffsets.swap(offsets);
    if (mesh.FaceOffsets.size() == 1)
    {
      mesh.FaceOffsets.clear();
    }
  }
  mesh.NumberOfPoints = kept;
  return n - kept;
}

std::vector<unsigned char> PLYColours(const std::vector<const PLYColumn*>& channels,
  std::size_t numberOfPoints)
{
  const std::size_t m = channels.size();
  std::vector<unsigned char> rgb(numberOfPoints * m);
  bool real = false, wide = false;
  for (const PLYColumn* c : channels)
  {
    real |= !PLYTypeIsInteger(c->Type);
    wide |= c->Type == PLYType::Float64 || (PLYTypeIsInteger(c->Type) && PLYTypeSize(c->Type) > 2);
  }
  for (std::size_t j = 0; j < m; ++j)
  {
    const PLYColumn& c = *channels[j];
    for (std::size_t k = 0; k < numberOfPoints; ++k)
    {
      const double value = c.Value(k);
      double byte;
      if (!real)
      {
        byte = std::min(std::max(value, 0.0), 255.0);
      }
      else if (wide)
      {
        const double unit = std::isnan(value) ? 0.0 : std::min(std::max(value, 0.0), 1.0);
        byte = std::nearbyint(255.0 * unit);
      }
      else
      {
        const float f = PLYFloat(value);
        const float unit = std::isnan(f) ? 0.0f : std::min(std::max(f, 0.0f), 1.0f);
        byte = static_cast<double>(std::nearbyint(255.0f * unit));
      }
      rgb[k * m + j] = static_cast<unsigned char>(byte);
    }
  }
  return rgb;
}

} // namespace pointsurfaces
