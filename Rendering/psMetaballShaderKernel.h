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

#include "psMetaballKernels.h"

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
} // namespace pointsurfaces

#endif
