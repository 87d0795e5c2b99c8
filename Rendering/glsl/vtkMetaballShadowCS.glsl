//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// Shadows of vtkMetaballMapper from secondary rays ([Bolla 2010] 5.3): for every
// pixel that the primary rays hit, a ray toward one light is tested against
// the surface. The world-space structure is a perspective grid built from
// the light's point of view for this frame (vtkMetaballGridBuilder with the
// light as camera; parallel for a directional light): a ray from a surface
// point to the light is a ray of that grid's camera, so it crosses a single
// tile, and it walks that tile's voxels from the light towards the point.
// Any sample with f >= 0 before the point (short of a small offset, so that
// the point does not shadow itself) puts the pixel in shadow for this
// light: channel `lightIndex` of the shadow image becomes 1.
//
// The march is the primary rays' (field-adaptive steps, never below
// stepScale times the voxel's smallest radius); its sums are checked
// against llvmpipe's loop limit, and a cut ray is counted and left lit.
//
// Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
// M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).

//VTK::Defines::Dec

layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer Balls { vec4 balls[]; };
layout(std430, binding = 2) readonly buffer Strengths { float strengths[]; };
layout(std430, binding = 3) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = 4) readonly buffer VoxelBalls { uint voxelBalls[]; };
layout(std430, binding = 5) buffer Counters { uint counters[9]; }; // [2]: cut shadow rays

layout(r32f, binding = 2) readonly uniform image2D depthImage;
layout(rgba32f, binding = 3) uniform image2D shadowImage;

uniform mat4 clipToView;   // the camera's
uniform mat4 viewToModel;  // camera view to ball-buffer coordinates
uniform mat4 modelToLight; // ball-buffer coordinates to the light's view
uniform mat4 lightToClip;
uniform int lightParallel;
uniform ivec2 viewport;      // the camera's
uniform ivec2 lightViewport; // the light grid's
uniform int tileSize;
uniform ivec2 tiles;
uniform int slabs;
// The grid builder's statistics: [5] and [6] are the slab range (float bits).
layout(std430, binding = 6) readonly buffer GridStatistics { uint gridStatistics[]; };
#define slabNear uintBitsToFloat(gridStatistics[5])
#define slabFar uintBitsToFloat(gridStatistics[6])
uniform float threshold;
uniform float stepScale;
uniform float selfOffset; // model units kept clear around the surface point
uniform int lightIndex;
uniform int useStrengths;

//VTK::Kernel::Dec

float psAddBall(vec3 p, uint id)
{
  vec4 b = balls[id];
  vec3 c = (modelToLight * vec4(b.xyz, 1.0)).xyz;
  vec3 d = p - c;
  float q = useStrengths != 0 ? strengths[id] : 1.0;
  float slope;
  return q * psKernel(dot(d, d) / (b.w * b.w), slope);
}

// f at p (light view) over a voxel's list; `complete` is false when the
// driver cut the loop short.
float psField(vec3 p, uint first, uint count, out bool complete)
{
  float f = -threshold;
  uint j = 0u;
  for (; j + 3u < count; j += 4u)
  {
    f += psAddBall(p, voxelBalls[first + j]) + psAddBall(p, voxelBalls[first + j + 1u]) +
      psAddBall(p, voxelBalls[first + j + 2u]) + psAddBall(p, voxelBalls[first + j + 3u]);
  }
  for (; j < count; ++j)
  {
    f += psAddBall(p, voxelBalls[first + j]);
  }
  complete = j == count;
  return f;
}

void main()
{
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= viewport.x || pixel.y >= viewport.y)
  {
    return;
  }
  float depth = imageLoad(depthImage, pixel).r;
  if (depth >= 1.0)
  {
    return; // no surface here
  }
  // The surface point, from the camera's depth, into the light's view.
  vec2 ndc = (vec2(pixel) + 0.5) / vec2(viewport) * 2.0 - 1.0;
  vec4 pv = clipToView * vec4(ndc, 2.0 * depth - 1.0, 1.0);
  pv /= pv.w;
  vec3 pl = (modelToLight * (viewToModel * pv)).xyz;
  vec4 clip = lightToClip * vec4(pl, 1.0);
  if (clip.w <= 0.0)
  {
    return;
  }
  vec2 lp = (0.5 * clip.xy / clip.w + 0.5) * vec2(lightViewport);
  if (any(lessThan(lp, vec2(0.0))) || any(greaterThanEqual(lp, vec2(lightViewport))))
  {
    return; // outside the light's view: nothing between it and the light
  }
  ivec2 tile = ivec2(lp) / tileSize;
  // The ray from the light to the point: origin, direction, and its end.
  vec3 origin = lightParallel != 0 ? vec3(pl.xy, 0.0) : vec3(0.0);
  vec3 dir = lightParallel != 0 ? vec3(0.0, 0.0, -1.0) : normalize(pl);
  float tEnd = dot(pl - origin, dir) - selfOffset;
  float perDistance = -dir.z;
  bool shadowed = false;
  bool cut = false;
  for (int slab = 0; slab < slabs && !shadowed && !cut; ++slab)
  {
    float t0 = (slabNear + (slabFar - slabNear) * float(slab) / float(slabs)) / perDistance;
    float t1 = (slabNear + (slabFar - slabNear) * float(slab + 1) / float(slabs)) / perDistance;
    if (t0 >= tEnd)
    {
      break;
    }
    uint voxel = uint((slab * tiles.y + tile.y) * tiles.x + tile.x);
    uint first = offsets[voxel];
    uint count = offsets[voxel + 1u] - first;
    if (count == 0u)
    {
      continue;
    }
    float lipschitz = 0.0, minRadius = 3.0e38;
    uint k = 0u;
    for (; k < count; ++k)
    {
      uint id = voxelBalls[first + k];
      float R = balls[id].w;
      lipschitz += (useStrengths != 0 ? abs(strengths[id]) : 1.0) / R;
      minRadius = min(minRadius, R);
    }
    if (k != count)
    {
      cut = true;
      break;
    }
    lipschitz = lipschitz * psKernelSlopeBound() + 1e-30;
    float t = t0;
    float stop = min(t1, tEnd);
    int steps = 0;
    while (t <= stop && steps++ < 4096)
    {
      bool complete;
      float f = psField(origin + t * dir, first, count, complete);
      if (!complete)
      {
        cut = true;
        break;
      }
      if (f >= 0.0)
      {
        shadowed = true;
        break;
      }
      if (t >= stop)
      {
        break;
      }
      t = min(t + max(stepScale * minRadius, abs(f) / lipschitz), stop);
    }
  }
  if (cut)
  {
    atomicAdd(counters[2], 1u);
    return;
  }
  if (shadowed)
  {
    vec4 s = imageLoad(shadowImage, pixel);
    s[lightIndex] = 1.0;
    imageStore(shadowImage, pixel, s);
  }
}
