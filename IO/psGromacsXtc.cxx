// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psGromacsXtc.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

namespace pointsurfaces
{
namespace
{
constexpr int XtcMagic = 1995;
// Bytes of a frame's header: magic, natoms, step, time, box, natoms.
constexpr std::int64_t HeaderBytes = 14 * 4;
// Bytes of a compressed block before its coded bytes: precision, minint,
// maxint, smallidx, byte count.
constexpr std::size_t BlockHeaderBytes = 9 * 4;
// Frames of at most this many atoms are stored as plain floats.
constexpr long long MaxUncompressedAtoms = 9;
// A range wider than this is coded one coordinate at a time.
constexpr std::int64_t MaxJointRange = 0xffffff;

// The sizes of the small-difference codes, indexed by smallidx: about
// 2^(i/3), so that three of them take i bits together. Part of the format.
constexpr std::array<int, 73> MagicInts = { 0,
  0,
  0,
  0,
  0,
  0,
  0,
  0,
  0,
  8,
  10,
  12,
  16,
  20,
  25,
  32,
  40,
  50,
  64,
  80,
  101,
  128,
  161,
  203,
  256,
  322,
  406,
  512,
  645,
  812,
  1024,
  1290,
  1625,
  2048,
  2580,
  3250,
  4096,
  5060,
  6501,
  8192,
  10321,
  13003,
  16384,
  20642,
  26007,
  32768,
  41285,
  52015,
  65536,
  82570,
  104031,
  131072,
  165140,
  208063,
  262144,
  330280,
  416127,
  524287,
  660561,
  832255,
  1048576,
  1321122,
  1664510,
  2097152,
  2642245,
  3329021,
  4194304,
  5284491,
  6658042,
  8388607,
  10568983,
  13316085,
  16777216 };
constexpr int FirstIndex = 9;
constexpr int LastIndex = static_cast<int>(MagicInts.size()); // one past the last valid index

std::uint32_t BigEndian(const unsigned char* p)
{
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) |
    std::uint32_t(p[3]);
}
std::int32_t Int(const unsigned char* p)
{
  return static_cast<std::int32_t>(BigEndian(p));
}
float Float(const unsigned char* p)
{
  const std::uint32_t bits = BigEndian(p);
  float f;
  static_assert(sizeof(f) == sizeof(bits), "IEEE single floats expected");
  std::memcpy(&f, &bits, sizeof(f));
  return f;
}

// The bits of the coded block, read most significant first; every read is
// checked against the block's end.
class BitReader
{
public:
  BitReader(const unsigned char* data, std::size_t size)
    : Data(data)
    , Size(size)
  {
  }
  // The next `bits` (at most 32) bits as an unsigned number; false past the end.
  bool Read(int bits, std::uint32_t& value)
  {
    if (bits < 0 || bits > 32)
    {
      return false;
    }
    std::uint64_t v = 0;
    while (bits > 0)
    {
      if (this->Available == 0)
      {
        if (this->Next >= this->Size)
        {
          return false;
        }
        this->Cache = this->Data[this->Next++];
        this->Available = 8;
      }
      const int take = bits < this->Available ? bits : this->Available;
      const unsigned chunk = (this->Cache >> (this->Available - take)) & ((1u << take) - 1u);
      v = (v << take) | chunk;
      this->Available -= take;
      bits -= take;
    }
    value = static_cast<std::uint32_t>(v);
    return true;
  }

private:
  const unsigned char* Data;
  std::size_t Size;
  std::size_t Next = 0;
  unsigned Cache = 0;
  int Available = 0;
};

// Bits that numbers in [0, size) take: the smallest b with 2^b > size - 1,
// as the format counts them (b with 2^b > size, at most 32).
int BitsOfInt(std::uint32_t size)
{
  int bits = 0;
  std::uint64_t num = 1;
  while (size >= num && bits < 32)
  {
    ++bits;
    num <<= 1;
  }
  return bits;
}

// Bits that a triple of numbers in [0, sizes[k]) takes when coded as one
// mixed-radix number, as the format counts them.
int BitsOfInts(const std::uint32_t sizes[3])
{
  std::array<unsigned, 16> bytes{};
  int numberOfBytes = 1;
  bytes[0] = 1;
  for (int i = 0; i < 3; ++i)
  {
    std::uint64_t carry = 0;
    int b = 0;
    for (; b < numberOfBytes; ++b)
    {
      carry += std::uint64_t(bytes[b]) * sizes[i];
      bytes[b] = static_cast<unsigned>(carry & 0xffu);
      carry >>= 8;
    }
    while (carry != 0)
    {
      bytes[b++] = static_cast<unsigned>(carry & 0xffu);
      carry >>= 8;
    }
    numberOfBytes = b;
  }
  int bits = 0;
  unsigned num = 1;
  --numberOfBytes;
  while (bytes[numberOfBytes] >= num)
  {
    ++bits;
    num *= 2;
  }
  return bits + numberOfBytes * 8;
}

// Reads a triple coded as one mixed-radix number of `bits` bits (its bytes
// least significant first) and splits it by `sizes`.
bool ReadInts(BitReader& reader, int bits, const std::uint32_t sizes[3], std::int64_t out[3])
{
  std::array<unsigned, 16> bytes{};
  int numberOfBytes = 0;
  if (bits < 0 || bits > 8 * static_cast<int>(bytes.size()))
  {
    return false;
  }
  std::uint32_t value = 0;
  while (bits > 8)
  {
    if (!reader.Read(8, value))
    {
      return false;
    }
    bytes[numberOfBytes++] = value;
    bits -= 8;
  }
  if (bits > 0)
  {
    if (!reader.Read(bits, value))
    {
      return false;
    }
    bytes[numberOfBytes++] = value;
  }
  for (int i = 2; i > 0; --i)
  {
    std::uint64_t num = 0;
    for (int j = numberOfBytes - 1; j >= 0; --j)
    {
      num = (num << 8) | bytes[j];
      const std::uint64_t q = num / sizes[i];
      bytes[j] = static_cast<unsigned>(q);
      num -= q * sizes[i];
    }
    out[i] = static_cast<std::int64_t>(num);
  }
  out[0] = static_cast<std::int64_t>(
    bytes[0] | (bytes[1] << 8) | (bytes[2] << 16) | (std::uint64_t(bytes[3]) << 24));
  return true;
}

bool Fail(std::string& error, const std::string& why)
{
  error = why;
  return false;
}
} // namespace

namespace
{
bool Decode(const unsigned char* data,
  std::size_t size,
  long long natoms,
  std::vector<float>& positions,
  std::string& error)
{
  if (natoms <= MaxUncompressedAtoms || size < BlockHeaderBytes)
  {
    return Fail(error, "the coded block is too short for " + std::to_string(natoms) + " atoms");
  }
  const float precision = Float(data);
  if (!(precision > 0.0f) || !std::isfinite(precision))
  {
    return Fail(error, "the precision " + std::to_string(precision) + " is not positive");
  }
  std::int64_t minInt[3], maxInt[3];
  std::uint32_t sizeInt[3];
  bool joint = true;
  int bitSizeInt[3] = { 0, 0, 0 };
  for (int k = 0; k < 3; ++k)
  {
    minInt[k] = Int(data + 4 + 4 * k);
    maxInt[k] = Int(data + 16 + 4 * k);
    const std::int64_t range = maxInt[k] - minInt[k] + 1;
    if (range < 1 || range > std::numeric_limits<std::uint32_t>::max())
    {
      return Fail(error,
        "the coordinate range [" + std::to_string(minInt[k]) + ", " + std::to_string(maxInt[k]) +
          "] is empty or too wide");
    }
    sizeInt[k] = static_cast<std::uint32_t>(range);
    joint = joint && range <= MaxJointRange;
    bitSizeInt[k] = BitsOfInt(sizeInt[k]);
  }
  const int bitSize = joint ? BitsOfInts(sizeInt) : 0;
  int smallIndex = Int(data + 28);
  if (smallIndex < FirstIndex || smallIndex >= LastIndex)
  {
    return Fail(error,
      "the small-difference size index " + std::to_string(smallIndex) + " is out of [" +
        std::to_string(FirstIndex) + ", " + std::to_string(LastIndex - 1) + "]");
  }
  const std::int64_t bytes = Int(data + 32);
  if (bytes < 0 || static_cast<std::uint64_t>(bytes) > size - BlockHeaderBytes)
  {
    return Fail(error,
      "the coded block claims " + std::to_string(bytes) + " bytes, the frame has " +
        std::to_string(size - BlockHeaderBytes));
  }
  // Every atom takes at least two bits: a damaged count must not allocate.
  if (natoms > 4 * bytes || static_cast<unsigned long long>(natoms) > positions.max_size() / 3)
  {
    return Fail(error,
      std::to_string(natoms) + " atoms cannot fit in " + std::to_string(bytes) + " coded bytes");
  }
  BitReader reader(data + BlockHeaderBytes, static_cast<std::size_t>(bytes));

  std::int64_t smaller = MagicInts[std::max(FirstIndex, smallIndex - 1)] / 2;
  std::int64_t smallNum = MagicInts[smallIndex] / 2;
  std::uint32_t sizeSmall[3];
  sizeSmall[0] = sizeSmall[1] = sizeSmall[2] = static_cast<std::uint32_t>(MagicInts[smallIndex]);

  positions.resize(static_cast<std::size_t>(3 * natoms));
  float* out = positions.data();
  const float inverse = 1.0f / precision;
  if (!std::isfinite(2147483648.0f * inverse))
  {
    return Fail(error, "the precision " + std::to_string(precision) + " is too small");
  }
  auto emit = [&out, inverse](const std::int64_t c[3])
  {
    for (int k = 0; k < 3; ++k)
    {
      *out++ = static_cast<float>(static_cast<std::int32_t>(c[k])) * inverse;
    }
  };
  const std::string truncated = "the coded block ends before its last atom";
  long long atom = 0;
  std::uint32_t run = 0;
  while (atom < natoms)
  {
    std::int64_t first[3];
    if (joint)
    {
      if (!ReadInts(reader, bitSize, sizeInt, first))
      {
        return Fail(error, truncated);
      }
    }
    else
    {
      for (int k = 0; k < 3; ++k)
      {
        std::uint32_t v = 0;
        if (!reader.Read(bitSizeInt[k], v))
        {
          return Fail(error, truncated);
        }
        first[k] = v;
      }
    }
    ++atom;
    for (int k = 0; k < 3; ++k)
    {
      first[k] += minInt[k];
    }
    std::int64_t previous[3] = { first[0], first[1], first[2] };
    std::uint32_t flag = 0;
    int isSmaller = 0;
    if (!reader.Read(1, flag))
    {
      return Fail(error, truncated);
    }
    if (flag == 1)
    {
      if (!reader.Read(5, run))
      {
        return Fail(error, truncated);
      }
      isSmaller = static_cast<int>(run % 3);
      run -= isSmaller;
      --isSmaller;
    }
    if (run > 0)
    {
      if (atom + run / 3 > natoms)
      {
        return Fail(error,
          "a run of " + std::to_string(run / 3) + " atoms goes past the last atom (" +
            std::to_string(natoms) + ")");
      }
      for (std::uint32_t k = 0; k < run; k += 3)
      {
        std::int64_t current[3];
        if (!ReadInts(reader, smallIndex, sizeSmall, current))
        {
          return Fail(error, truncated);
        }
        ++atom;
        for (int c = 0; c < 3; ++c)
        {
          current[c] += previous[c] - smallNum;
        }
        if (k == 0)
        {
          // The encoder swaps a run's first two atoms (a water's O and H
          // code smaller that way): the second comes out first.
          for (int c = 0; c < 3; ++c)
          {
            std::swap(current[c], previous[c]);
          }
          emit(previous);
        }
        else
        {
          for (int c = 0; c < 3; ++c)
          {
            previous[c] = current[c];
          }
        }
        emit(current);
      }
    }
    else
    {
      emit(first);
    }
    smallIndex += isSmaller;
    if (smallIndex < FirstIndex || smallIndex >= LastIndex)
    {
      return Fail(
        error, "the small-difference size index leaves its range at atom " + std::to_string(atom));
    }
    if (isSmaller < 0)
    {
      smallNum = smaller;
      smaller = smallIndex > FirstIndex ? MagicInts[smallIndex - 1] / 2 : 0;
    }
    else if (isSmaller > 0)
    {
      smaller = smallNum;
      smallNum = MagicInts[smallIndex] / 2;
    }
    sizeSmall[0] = sizeSmall[1] = sizeSmall[2] = static_cast<std::uint32_t>(MagicInts[smallIndex]);
  }
  return true;
}

} // namespace

//------------------------------------------------------------------------------
bool DecodeXtcCoordinates(const unsigned char* data,
  std::size_t size,
  long long natoms,
  std::vector<float>& positions,
  std::string& error)
{
  positions.clear();
  if (!Decode(data, size, natoms, positions, error))
  {
    positions.clear();
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
std::vector<XtcFrameInfo> ScanXtc(std::istream& in, std::string& error)
{
  std::vector<XtcFrameInfo> frames;
  error.clear();
  in.clear();
  in.seekg(0, std::ios::end);
  const std::int64_t fileSize = static_cast<std::int64_t>(in.tellg());
  if (fileSize < 0)
  {
    error = "cannot be read";
    return frames;
  }
  if (fileSize == 0)
  {
    error = "the file is empty";
    return frames;
  }
  std::int64_t offset = 0;
  unsigned char header[HeaderBytes + BlockHeaderBytes];
  while (offset < fileSize)
  {
    const std::string where =
      "frame " + std::to_string(frames.size()) + " (byte " + std::to_string(offset) + ")";
    const std::int64_t available = std::min(fileSize - offset, HeaderBytes);
    in.seekg(offset);
    if (!in.read(reinterpret_cast<char*>(header), available))
    {
      error = where + " cannot be read";
      return frames;
    }
    if (available < 4 || Int(header) != XtcMagic)
    {
      error = where + " does not start with the .xtc magic number 1995";
      return frames;
    }
    if (available < HeaderBytes)
    {
      error = where + " is truncated";
      return frames;
    }
    XtcFrameInfo f;
    f.Offset = offset;
    f.NumberOfAtoms = Int(header + 4);
    f.Step = Int(header + 8);
    f.Time = Float(header + 12);
    float box[9];
    bool finite = std::isfinite(f.Time);
    for (int k = 0; k < 9; ++k)
    {
      box[k] = Float(header + 16 + 4 * k);
      finite = finite && std::isfinite(box[k]);
    }
    // Rows are box vectors: the same nine numbers in .gro's order.
    const int order[9] = { 0, 4, 8, 1, 2, 3, 5, 6, 7 };
    for (int k = 0; k < 9; ++k)
    {
      f.Box[k] = box[order[k]];
    }
    if (f.NumberOfAtoms <= 0 || Int(header + 52) != f.NumberOfAtoms)
    {
      error = where + " has atom counts " + std::to_string(f.NumberOfAtoms) + " and " +
        std::to_string(Int(header + 52));
      return frames;
    }
    if (!frames.empty() && f.NumberOfAtoms != frames.front().NumberOfAtoms)
    {
      error = where + " has " + std::to_string(f.NumberOfAtoms) + " atoms, the first frame " +
        std::to_string(frames.front().NumberOfAtoms);
      return frames;
    }
    if (!finite)
    {
      error = where + " has a time or box that is not a finite number";
      return frames;
    }
    std::int64_t size = 0;
    if (f.NumberOfAtoms <= MaxUncompressedAtoms)
    {
      size = HeaderBytes + 12 * f.NumberOfAtoms;
    }
    else
    {
      if (fileSize - offset < HeaderBytes + static_cast<std::int64_t>(BlockHeaderBytes) ||
        !in.read(reinterpret_cast<char*>(header + HeaderBytes), BlockHeaderBytes))
      {
        error = where + " is truncated";
        return frames;
      }
      f.Precision = Float(header + HeaderBytes);
      const std::int64_t bytes = Int(header + HeaderBytes + 32);
      if (bytes < 0 || f.NumberOfAtoms > 4 * bytes)
      {
        // Every atom takes at least two bits of the coded bytes.
        error = where + " claims " + std::to_string(f.NumberOfAtoms) + " atoms in " +
          std::to_string(bytes) + " coded bytes";
        return frames;
      }
      size = HeaderBytes + static_cast<std::int64_t>(BlockHeaderBytes) + (bytes + 3) / 4 * 4;
    }
    if (size > fileSize - offset)
    {
      error = where + " is truncated: it needs " + std::to_string(size) + " bytes, " +
        std::to_string(fileSize - offset) + " are left";
      return frames;
    }
    f.Size = size;
    frames.push_back(f);
    offset += size;
  }
  return frames;
}

//------------------------------------------------------------------------------
bool ReadXtcFrame(std::istream& in,
  const XtcFrameInfo& where,
  std::vector<float>& positions,
  std::string& error)
{
  positions.clear();
  if (where.Size < HeaderBytes || where.NumberOfAtoms <= 0 ||
    (where.NumberOfAtoms <= MaxUncompressedAtoms &&
      where.Size != HeaderBytes + 12 * where.NumberOfAtoms))
  {
    return Fail(error, "the frame was not indexed");
  }
  std::vector<unsigned char> bytes(static_cast<std::size_t>(where.Size - HeaderBytes));
  in.clear();
  in.seekg(where.Offset + HeaderBytes);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())))
  {
    return Fail(error, "the frame cannot be read (has the file changed?)");
  }
  if (where.NumberOfAtoms > MaxUncompressedAtoms)
  {
    return DecodeXtcCoordinates(bytes.data(), bytes.size(), where.NumberOfAtoms, positions, error);
  }
  positions.resize(static_cast<std::size_t>(3 * where.NumberOfAtoms));
  for (std::size_t k = 0; k < positions.size(); ++k)
  {
    positions[k] = Float(bytes.data() + 4 * k);
    if (!std::isfinite(positions[k]))
    {
      positions.clear();
      return Fail(error, "a position is not a finite number");
    }
  }
  return true;
}
} // namespace pointsurfaces
