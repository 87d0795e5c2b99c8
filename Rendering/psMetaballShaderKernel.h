// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psMetaballShaderKernel.h
 * @brief The kernel defines of the metaball compute shaders, from the kernel table.
 *
 * vtkMetaballKernel.glsl selects its formulas by KERNEL and returns
 * KERNEL_SLOPE_BOUND as the Lipschitz bound: both come from here, so the slope
 * bound is written once (psMetaballKernels.h). Private to PointSurfaces::Rendering
 * and its tests.
 */
#ifndef psMetaballShaderKernel_h
#define psMetaballShaderKernel_h

#include "vtkComputeShaderProgram.h"
#include "vtkMetaballKernel.h"

#include "psMetaballKernels.h"
#include "psShaderHooks.h"

#include <locale>
#include <sstream>
#include <string>

namespace pointsurfaces
{
/** "#define KERNEL <n>\n#define KERNEL_SLOPE_BOUND <bound>\n" for `kernel`. */
inline std::string MetaballKernelDefines(MetaballKernel kernel)
{
  std::ostringstream text;
  text.imbue(std::locale::classic()); // a decimal point whatever the user's locale
  text.precision(9);                  // every float's digits
  text << std::showpoint << "#define KERNEL " << static_cast<int>(kernel)
       << "\n#define KERNEL_SLOPE_BOUND "
       << VisitMetaballKernel<float>(kernel, [](auto k) { return k.SlopeBound; }) << "\n";
  return text.str();
}

/**
 * `program` made from `source` with its //VTK::Defines::Dec hook filled by
 * `defines` and its //VTK::Kernel::Dec hook by the kernels, and compiled;
 * remade only when the defines differ from `current`, which remembers them.
 * Null when a hook is missing (an error reported by `owner`) or it does not
 * compile (the program reports its compile log).
 */
inline vtkComputeShaderProgram* ReadyMetaballProgram(vtkComputeShaderProgram* program,
  vtkOpenGLRenderWindow* renWin,
  const char* name,
  const char* source,
  const std::string& defines,
  std::string& current,
  vtkObject* owner)
{
  if (defines != current)
  {
    std::string text = source;
    if (!ReplaceHook(text, "//VTK::Defines::Dec", defines) ||
      !ReplaceHook(text, "//VTK::Kernel::Dec", vtkMetaballKernel))
    {
      vtkErrorWithObjectMacro(owner,
        << name << " lacks its //VTK::Defines::Dec or //VTK::Kernel::Dec hook: nothing is drawn.");
      return nullptr;
    }
    program->ReleaseGraphicsResources(renWin);
    program->SetName(name);
    program->SetSource(text);
    current = defines;
  }
  if (!program->IsCompiled() && !program->Compile(renWin))
  {
    return nullptr;
  }
  return program;
}
} // namespace pointsurfaces

#endif
