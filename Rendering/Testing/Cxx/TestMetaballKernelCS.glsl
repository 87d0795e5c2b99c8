//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// TestMetaballKernelGLSL's probe: evaluates vtkMetaballKernel.glsl's psKernel
// and psKernelSlopeBound at the given x = r^2 / R^2, one invocation per x.

//VTK::Defines::Dec

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Arguments { float arguments[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };

uniform uint count;

//VTK::Kernel::Dec

void main()
{
  uint i = gl_GlobalInvocationID.x;
  if (i >= count)
  {
    return;
  }
  float slope;
  float value = psKernel(arguments[i], slope);
  results[i] = vec4(value, slope, psKernelSlopeBound(), 0.0);
}
