//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// Solves a batch of polynomials with the splat ray caster's float solvers,
// so that they can be checked against the double-precision reference
// (psRoots.h) and timed. Five coefficients per polynomial (c0..c4).

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Coefficients { float coefficients[]; };
layout(std430, binding = 1) readonly buffer Degrees { int degrees[]; };
layout(std430, binding = 2) writeonly buffer Roots { vec4 roots[]; };
layout(std430, binding = 3) writeonly buffer Counts { int counts[]; };

uniform uint numberOfPolynomials;

//VTK::SplatRoots::Dec

void main()
{
  uint i = gl_GlobalInvocationID.x;
  if (i >= numberOfPolynomials)
  {
    return;
  }
  float c0 = coefficients[5u * i];
  float c1 = coefficients[5u * i + 1u];
  float c2 = coefficients[5u * i + 2u];
  float c3 = coefficients[5u * i + 3u];
  float c4 = coefficients[5u * i + 4u];
  vec4 r;
  int n = psSolvePolynomial(degrees[i], c0, c1, c2, c3, c4, r);
  roots[i] = r;
  counts[i] = n;
}
