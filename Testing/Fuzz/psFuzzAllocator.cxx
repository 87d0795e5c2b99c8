// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
// Linked into every fuzz target.
#include <cstdlib>
#include <new>

// A damaged file can make a library ask for absurd buffers (OpenVDB: a
// compressed block "of" 6e18 bytes, a name of 4 GB; PCL: 64 GB for an
// ASCII body). Outside the fuzzer that throws std::bad_alloc, which the
// readers report as an error; ASan instead aborts on any failed operator
// new. These replacements restore the ordinary behaviour above 256 MB (the
// seeds need far less). Blocks still come from malloc, so ASan keeps its
// redzones and use-after-free checks (not its new/delete mismatch check).
namespace
{
constexpr size_t Limit = size_t(1) << 28;
void* Allocate(size_t n)
{
  void* p = n <= Limit ? std::malloc(n ? n : 1) : nullptr;
  if (!p)
  {
    throw std::bad_alloc();
  }
  return p;
}
void* AllocateAligned(size_t n, std::align_val_t a)
{
  const size_t align = static_cast<size_t>(a);
  void* p = n <= Limit ? std::aligned_alloc(align, (n + align - 1) / align * align) : nullptr;
  if (!p)
  {
    throw std::bad_alloc();
  }
  return p;
}
}
void* operator new(size_t n)
{
  return Allocate(n);
}
void* operator new[](size_t n)
{
  return Allocate(n);
}
void* operator new(size_t n, const std::nothrow_t&) noexcept
{
  return n <= Limit ? std::malloc(n ? n : 1) : nullptr;
}
void* operator new[](size_t n, const std::nothrow_t&) noexcept
{
  return n <= Limit ? std::malloc(n ? n : 1) : nullptr;
}
void* operator new(size_t n, std::align_val_t a)
{
  return AllocateAligned(n, a);
}
void* operator new[](size_t n, std::align_val_t a)
{
  return AllocateAligned(n, a);
}
void operator delete(void* p) noexcept
{
  std::free(p);
}
void operator delete[](void* p) noexcept
{
  std::free(p);
}
void operator delete(void* p, size_t) noexcept
{
  std::free(p);
}
void operator delete[](void* p, size_t) noexcept
{
  std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept
{
  std::free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept
{
  std::free(p);
}
void operator delete(void* p, size_t, std::align_val_t) noexcept
{
  std::free(p);
}
void operator delete[](void* p, size_t, std::align_val_t) noexcept
{
  std::free(p);
}
