//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// vtkMetaballUploader's assembly pass: one vec4 per ball (centre relative to
// the shift, support radius) from the arrays as they were uploaded, so that
// the host never repacks them: float positions as the input holds them (xyz,
// tightly packed; the shift is subtracted here) or already shifted when the
// host converted them, radii from an array (times radiusFactor) or one
// radius for all. A ball with a non-finite centre, radius or strength, or a
// radius <= 0, gets radius 0, which the grids skip (psMetaball's ValidBall),
// and is counted.

layout(local_size_x = 256) in;

layout(std430, binding = 0) writeonly buffer Balls { vec4 balls[]; };
layout(std430, binding = 1) readonly buffer Positions { float positions[]; };
layout(std430, binding = 2) readonly buffer Radii { float radii[]; };
layout(std430, binding = 3) readonly buffer Strengths { float strengths[]; };
layout(std430, binding = 4) buffer Invalid { uint invalid[]; };

uniform uint count;
uniform vec3 shift;
uniform int radiusArray;    // radii from `radii` times radiusFactor, else `radius`
uniform float radiusFactor;
uniform float radius;
uniform int useStrengths;

bool psFinite(float v)
{
  return !isnan(v) && !isinf(v);
}

void main()
{
  uint i = gl_GlobalInvocationID.x;
  if (i >= count)
  {
    return;
  }
  // Relative to the shift (which the host applied when it converted them).
  vec3 p = vec3(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]) - shift;
  float r = radiusArray != 0 ? radiusFactor * radii[i] : radius;
  float q = useStrengths != 0 ? strengths[i] : 1.0;
  bool valid = psFinite(p.x) && psFinite(p.y) && psFinite(p.z) && psFinite(r) && r > 0.0 &&
    psFinite(q);
  if (!valid)
  {
    atomicAdd(invalid[0], 1u);
    r = 0.0;
  }
  balls[i] = vec4(p, r);
}
