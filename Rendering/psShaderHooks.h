// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psShaderHooks.h
 * @brief Hook substitution and marker blocks in shader text, with a result to check.
 *
 * The mappers splice their GLSL into templates (VTK's and their own) at
 * named hooks, and cut marked blocks out of their .glsl files. A hook or
 * marker that is missing (a template that changed, a VTK whose text
 * differs) must be reported, never turned into an empty string, a silent
 * no-op or an exception: these return false so that the caller can say
 * which one and refuse to draw. Private to PointSurfaces::Rendering.
 */
#ifndef psShaderHooks_h
#define psShaderHooks_h

#include <string>

namespace pointsurfaces
{
/**
 * Replace the first occurrence of `hook` in `source` (every one when `all`)
 * with `replacement`. False, and `source` unchanged, when `hook` is absent.
 */
inline bool ReplaceHook(std::string& source,
  const std::string& hook,
  const std::string& replacement,
  bool all = false)
{
  size_t at = source.find(hook);
  if (hook.empty() || at == std::string::npos)
  {
    return false;
  }
  while (at != std::string::npos)
  {
    source.replace(at, hook.size(), replacement);
    at = all ? source.find(hook, at + replacement.size()) : std::string::npos;
  }
  return true;
}

/**
 * The text between `//VTK::<name>::Begin` and `//VTK::<name>::End` of
 * `source` into `block`. False, and `block` empty, when either marker is
 * missing or they are out of order.
 */
inline bool ExtractBlock(const std::string& source, const std::string& name, std::string& block)
{
  const std::string begin = "//VTK::" + name + "::Begin";
  const std::string end = "//VTK::" + name + "::End";
  const size_t b = source.find(begin);
  const size_t e = source.find(end);
  block.clear();
  if (b == std::string::npos || e == std::string::npos || e < b)
  {
    return false;
  }
  block = source.substr(b + begin.size(), e - b - begin.size());
  return true;
}
} // namespace pointsurfaces

#endif
