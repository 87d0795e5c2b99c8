//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// Coherent ray casting of metaballs through the perspective grid
// ([Bolla 2010] Algorithm 3), for vtkMetaballMapper. One work group per
// screen tile, one invocation per pixel. The group walks its tile's voxels
// front to back; empty voxels are skipped; a voxel's balls are loaded into
// shared memory (in view coordinates) by the whole group. When they fit (MAX_SHARED),
// every ray marches the voxel's stretch of itself without waiting on the
// others; otherwise the group loads them batch by batch at every sample and
// the rays march in lock step:
//
// - each ray starts and ends its march in a voxel (held in shared memory) at
//   the first and last ball support it crosses there, and skips the voxel
//   when it crosses none (the field is -T outside the supports) or when the
//   balls it crosses cannot lift f to 0 even at their closest approach;
// - the step follows the field: |f| / L, with L a bound on |grad f| over the
//   voxel's balls, so a step never jumps over the surface where f changes
//   fast, and large steps are taken in free space; it never goes below
//   stepScale times the smallest radius of the voxel (the base step of
//   [Bolla 2010]), which near silhouettes, where the gradient is small, is
//   what the rays take;
// - a sign change of f is refined by `bisections` bisections;
// - the normal is -grad f, analytic, and the colour the kernel-weighted mean
//   of the balls' colours.
//
// Outputs per pixel: colour (rgba8, alpha 0 on a miss), normal and view
// distance (rgba32f), window depth (r32f). TILE_SIZE, MAX_SHARED and KERNEL
// are defined by the mapper.
//
// Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
// M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).

//VTK::Defines::Dec

layout(local_size_x = TILE_SIZE, local_size_y = TILE_SIZE) in;

layout(std430, binding = 0) readonly buffer Balls { vec4 balls[]; };     // centre, R
layout(std430, binding = 1) readonly buffer Colors { uint colors[]; };   // rgba8
layout(std430, binding = 2) readonly buffer Strengths { float strengths[]; };
layout(std430, binding = 3) readonly buffer Offsets { uint offsets[]; }; // voxels + 1
layout(std430, binding = 4) readonly buffer VoxelBalls { uint voxelBalls[]; };
// [0]: rays starting inside the surface; [1]: rays whose loops the driver cut;
// [2]: shadow rays cut (the shadow pass's); where the time goes: [3] field
// samples of the march, [4] of the bisections, [5] (ray, voxel) visits, [6]
// of those to empty voxels, [7] kernel terms (saturating), [8] hits.
layout(std430, binding = 5) buffer Counters { uint insideCount[9]; };

layout(rgba8, binding = 0) writeonly uniform image2D colorImage;
layout(rgba32f, binding = 1) writeonly uniform image2D normalImage;
layout(r32f, binding = 2) writeonly uniform image2D depthImage;

uniform mat4 worldToView;
uniform mat4 viewToClip;
uniform mat4 clipToView;
uniform int parallelProjection;
uniform ivec2 viewport;
uniform ivec2 tiles;
uniform int slabs;
// The grid builder's statistics: [5] and [6] are the slab range (float bits).
layout(std430, binding = 6) readonly buffer GridStatistics { uint gridStatistics[]; };
#define slabNear uintBitsToFloat(gridStatistics[5])
#define slabFar uintBitsToFloat(gridStatistics[6])
uniform float threshold;
uniform float stepScale;
uniform int bisections;
uniform int useStrengths;
uniform int colorPerBall; // else colors[0] is every ball's colour
// Balls from vtkMetaballLevelOfDetail: ids from baseCount on are merged
// balls, with their strength and colour in the merged arrays.
layout(std430, binding = 7) readonly buffer MergedStrengths { float mergedStrengths[]; };
layout(std430, binding = 8) readonly buffer MergedColors { uint mergedColors[]; };
uniform uint baseCount; // the input's balls (all ids when there is no level of detail)

float psStrength(uint id)
{
  return id < baseCount ? (useStrengths != 0 ? strengths[id] : 1.0)
                        : mergedStrengths[id - baseCount];
}

uint psColor(uint id)
{
  return id < baseCount ? colors[colorPerBall != 0 ? id : 0u] : mergedColors[id - baseCount];
}

shared vec4 sharedBalls[MAX_SHARED]; // view-space centre, R
shared float sharedStrength[MAX_SHARED];
shared uint sharedColor[MAX_SHARED];
shared float sharedReduce[TILE_SIZE * TILE_SIZE];
shared uint sharedMinRadius;
shared uint sharedActive;

//VTK::Kernel::Dec

// One ball's contribution at p: field, gradient, colour weight.
void psAddBall(vec3 p, vec4 b, float q, uint rgba, inout float f, inout vec3 grad,
  inout vec4 color, bool wantColor)
{
  vec3 d = p - b.xyz;
  float R2 = b.w * b.w;
  float x = dot(d, d) / R2;
  if (x < 1.0)
  {
    float slope;
    float value = q * psKernel(x, slope);
    f += value;
    grad += (q * slope * 2.0 / R2) * d;
    if (wantColor)
    {
      color += max(value, 0.0) * unpackUnorm4x8(rgba);
    }
  }
}

// The sum over the voxel's balls in shared memory at p, four balls per loop
// iteration. llvmpipe ends every loop of a shader invocation once they have
// run 65535 iterations together (LP_MAX_TGSI_LOOP_ITERATIONS), silently: the
// sum tells whether it ran to the end, and a ray whose sums were cut stops
// and is counted (vtkMetaballMapper warns), instead of hitting garbage.
bool psAccumulate(vec3 p, int count, inout float f, inout vec3 grad, inout vec4 color,
  bool wantColor)
{
  int k = 0;
  for (; k + 3 < count; k += 4)
  {
    psAddBall(p, sharedBalls[k], sharedStrength[k], sharedColor[k], f, grad, color, wantColor);
    psAddBall(p, sharedBalls[k + 1], sharedStrength[k + 1], sharedColor[k + 1], f, grad, color,
      wantColor);
    psAddBall(p, sharedBalls[k + 2], sharedStrength[k + 2], sharedColor[k + 2], f, grad, color,
      wantColor);
    psAddBall(p, sharedBalls[k + 3], sharedStrength[k + 3], sharedColor[k + 3], f, grad, color,
      wantColor);
  }
  for (; k < count; ++k)
  {
    psAddBall(p, sharedBalls[k], sharedStrength[k], sharedColor[k], f, grad, color, wantColor);
  }
  return k == count; // false: the driver cut the loop short
}

// Does any invocation of the group pass `mine`? Uniform over the group.
bool psAny(bool mine)
{
  memoryBarrierShared();
  barrier();
  if (gl_LocalInvocationIndex == 0u)
  {
    sharedActive = 0u;
  }
  memoryBarrierShared();
  barrier();
  if (mine)
  {
    atomicAdd(sharedActive, 1u);
  }
  memoryBarrierShared();
  barrier();
  bool any = sharedActive > 0u;
  memoryBarrierShared();
  barrier();
  return any;
}

// f, its gradient and the colour weights at p over the voxel's list, from
// global memory (the path for voxels with more than MAX_SHARED balls).
void psAddGlobal(vec3 p, uint id, inout float f, inout vec3 grad, inout vec4 color,
  bool wantColor)
{
  vec4 b = balls[id];
  psAddBall(p, vec4((worldToView * vec4(b.xyz, 1.0)).xyz, b.w),
    psStrength(id), psColor(id), f, grad, color, wantColor);
}

bool psAccumulateGlobal(vec3 p, uint first, uint count, inout float f, inout vec3 grad,
  inout vec4 color, bool wantColor)
{
  uint j = 0u;
  for (; j + 3u < count; j += 4u)
  {
    psAddGlobal(p, voxelBalls[first + j], f, grad, color, wantColor);
    psAddGlobal(p, voxelBalls[first + j + 1u], f, grad, color, wantColor);
    psAddGlobal(p, voxelBalls[first + j + 2u], f, grad, color, wantColor);
    psAddGlobal(p, voxelBalls[first + j + 3u], f, grad, color, wantColor);
  }
  for (; j < count; ++j)
  {
    psAddGlobal(p, voxelBalls[first + j], f, grad, color, wantColor);
  }
  return j == count; // false: the driver cut the loop short
}

// One iteration of a ray's march at t, where the field is f. Marching, a
// sign change against the previous sample starts a bisection of that
// bracket; otherwise the ray advances by max(baseStep, |f| / L) up to the
// voxel's end t1. Bisecting, f at the bracket's middle halves it; after
// `bisections` halvings the middle is the hit, shaded from the analytic
// gradient and the kernel-weighted colours. Bisection runs in the same loop
// as the march, one field evaluation per iteration, so that the lanes of a
// SIMD vector share their iterations (llvmpipe counts them per vector).
void psStep(inout float t, float f, float t1, float baseStep, float lipschitz, vec3 origin,
  vec3 dir, uint first, uint count, bool single, inout int steps, inout bool haveA,
  inout float tA, inout float fA, inout bool marching, inout bool searching, inout bool hit,
  inout float tHit, inout vec3 normal, inout vec4 color, bool nearSlab, bool complete,
  inout int bisecting, inout float a, inout float b, inout float fa)
{
  if (!complete)
  {
    // The driver cut the field's sum short (llvmpipe's loop limit): stop,
    // and say so.
    atomicAdd(insideCount[1], 1u);
    marching = false;
    searching = false;
    return;
  }
  if (bisecting > 0)
  {
    if ((fa < 0.0) == (f < 0.0))
    {
      a = t;
      fa = f;
    }
    else
    {
      b = t;
    }
    if (bisecting++ <= bisections)
    {
      t = 0.5 * (a + b);
      return;
    }
  }
  else if (haveA && (fA < 0.0) != (f < 0.0))
  {
    a = tA;
    b = t;
    fa = fA;
    bisecting = 1;
    if (bisections > 0)
    {
      t = 0.5 * (a + b);
      return;
    }
  }
  if (bisecting > 0)
  {
    tHit = 0.5 * (a + b);
    hit = true;
    searching = false;
    marching = false;
    vec3 ph = origin + tHit * dir;
    float fh = -threshold;
    vec3 gh = vec3(0.0);
    vec4 ch = vec4(0.0);
    bool shaded = single ? psAccumulate(ph, int(count), fh, gh, ch, true)
                         : psAccumulateGlobal(ph, first, count, fh, gh, ch, true);
    if (!shaded)
    {
      atomicAdd(insideCount[1], 1u);
      hit = false;
      return;
    }
    normal = length(gh) > 0.0 ? -normalize(gh) : -dir;
    color = ch.a > 0.0 ? vec4(ch.rgb / ch.a, 1.0) : vec4(1.0);
    return;
  }
  if (!haveA && nearSlab && f >= 0.0)
  {
    atomicAdd(insideCount[0], 1u); // the ray starts inside the surface
  }
  tA = t;
  fA = f;
  haveA = true;
  if (t >= t1 || ++steps > 4096)
  {
    marching = false;
    return;
  }
  t = min(t + max(baseStep, abs(f) / lipschitz), t1);
}

void main()
{
  ivec2 tile = ivec2(gl_WorkGroupID.xy);
  ivec2 pixel = tile * TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
  uint local = gl_LocalInvocationIndex;
  const uint groupSize = uint(TILE_SIZE * TILE_SIZE);
  bool inside = pixel.x < viewport.x && pixel.y < viewport.y;

  // This pixel's ray, in view coordinates; -z(t) = -origin.z + t perDistance.
  vec2 ndc = (vec2(pixel) + 0.5) / vec2(viewport) * 2.0 - 1.0;
  vec4 nearPoint = clipToView * vec4(ndc, -1.0, 1.0);
  vec4 farPoint = clipToView * vec4(ndc, 1.0, 1.0);
  nearPoint /= nearPoint.w;
  farPoint /= farPoint.w;
  vec3 origin = parallelProjection != 0 ? vec3(nearPoint.xy, 0.0) : vec3(0.0);
  vec3 dir = normalize(farPoint.xyz - nearPoint.xyz);
  float perDistance = -dir.z;

  bool searching = inside;
  bool hit = false;
  float tHit = 0.0;
  bool haveA = false;
  float tA = 0.0, fA = 0.0;
  vec3 normal = -dir;
  vec4 color = vec4(1.0);

  uint samples = 0u, bisectionSamples = 0u, visits = 0u, emptyVisits = 0u, terms = 0u;
  int lastSlab = -1;
  for (int slab = 0; slab < slabs; ++slab)
  {
    lastSlab = slab;
    if (!psAny(searching))
    {
      break; // every ray of the tile has its hit
    }
    uint voxel = uint((slab * tiles.y + tile.y) * tiles.x + tile.x);
    uint first = offsets[voxel];
    uint count = offsets[voxel + 1u] - first;
    float t0 = (slabNear + (slabFar - slabNear) * float(slab) / float(slabs) + origin.z) /
      perDistance;
    float t1 = (slabNear + (slabFar - slabNear) * float(slab + 1) / float(slabs) + origin.z) /
      perDistance;
    visits += searching ? 1u : 0u;
    if (count == 0u)
    {
      // An empty voxel, skipped: f = -T all through it.
      emptyVisits += searching ? 1u : 0u;
      tA = t1;
      fA = -threshold;
      haveA = true;
      continue;
    }
    bool single = count <= uint(MAX_SHARED);

    // Step bounds: the smallest radius, and L >= |grad f| over the voxel.
    if (local == 0u)
    {
      sharedMinRadius = floatBitsToUint(3.0e38);
    }
    memoryBarrierShared();
    barrier();
    float partial = 0.0;
    uint kb = local;
    for (; kb < count; kb += groupSize)
    {
      uint id = voxelBalls[first + kb];
      float R = balls[id].w;
      partial += abs(psStrength(id)) / R;
      atomicMin(sharedMinRadius, floatBitsToUint(R));
    }
    sharedReduce[local] = partial;
    uint stride = groupSize / 2u;
    for (; stride > 0u; stride >>= 1)
    {
      memoryBarrierShared();
      barrier();
      if (local < stride)
      {
        sharedReduce[local] += sharedReduce[local + stride];
      }
    }
    memoryBarrierShared();
    barrier();
    float lipschitz = sharedReduce[0] * psKernelSlopeBound() + 1e-30;
    float baseStep = stepScale * uintBitsToFloat(sharedMinRadius);
    // A bound cut short by the driver is too small, and its steps too long.
    bool loaded = !psAny(kb < count || stride > 0u);
    if (single)
    {
      // The whole list in shared memory, in view coordinates.
      uint k = local;
      for (; k < count; k += groupSize)
      {
        uint id = voxelBalls[first + k];
        vec4 b = balls[id];
        sharedBalls[k] = vec4((worldToView * vec4(b.xyz, 1.0)).xyz, b.w);
        sharedStrength[k] = psStrength(id);
        sharedColor[k] = psColor(id);
      }
      loaded = !psAny(k < count) && loaded; // a load cut short by the driver
    }
    memoryBarrierShared();
    barrier();

    float t = t0;
    bool marching = searching;
    int steps = 0;
    int bisecting = 0; // > 0: bisection step of the bracket [ba, bb]
    float ba = 0.0, bb = 0.0, bfa = 0.0;
    if (single)
    {
      // This ray's stretch of the voxel inside some ball's support: the field
      // is -T before the first support it enters and after the last it
      // leaves, so the march starts and ends there, and a ray that crosses
      // no support skips the voxel. (A loop cut short by the driver keeps
      // the whole voxel.)
      float tEnd = t1;
      if (marching)
      {
        float enter = 3.0e38, leave = -3.0e38, peaks = 0.0;
        int k = 0;
        for (; k < int(count); ++k)
        {
          vec4 b = sharedBalls[k];
          vec3 oc = b.xyz - origin;
          float along = dot(oc, dir);
          vec3 across = oc - along * dir;
          float h2 = b.w * b.w - dot(across, across);
          if (h2 > 0.0 && along + sqrt(h2) > t0 && along - sqrt(h2) < t1)
          {
            float h = sqrt(h2);
            enter = min(enter, along - h);
            leave = max(leave, along + h);
            float slope;
            peaks += max(sharedStrength[k], 0.0) * psKernel(dot(across, across) / (b.w * b.w), slope);
          }
        }
        if (k == int(count))
        {
          // f <= the balls' peaks on the ray (at their closest approach) - T:
          // below T there is no crossing in this voxel.
          if (!(max(enter, t0) < min(leave, t1)) || peaks < threshold)
          {
            emptyVisits += 1u;
            tA = t1;
            fA = -threshold;
            haveA = true;
            marching = false;
          }
          else
          {
            t = max(enter, t0);
            tEnd = min(leave, t1);
          }
        }
      }
      // The list is in shared memory: every ray marches on its own.
      while (marching)
      {
        float f = -threshold;
        vec3 g = vec3(0.0);
        vec4 c = vec4(0.0);
        bool complete = psAccumulate(origin + t * dir, int(count), f, g, c, false) && loaded;
        samples += bisecting > 0 ? 0u : 1u;
        bisectionSamples += bisecting > 0 ? 1u : 0u;
        terms += count;
        psStep(t, f, tEnd, baseStep, lipschitz, origin, dir, first, count, true, steps, haveA, tA,
          fA, marching, searching, hit, tHit, normal, color, slab == 0, complete, bisecting, ba,
          bb, bfa);
      }
    }
    else
    {
      // More balls than shared memory holds: the group loads them in batches
      // and every ray sums each batch at its own sample, in lock step.
      while (true)
      {
        vec3 p = origin + t * dir;
        float f = -threshold;
        vec3 g = vec3(0.0);
        vec4 c = vec4(0.0);
        bool complete = true;
        uint base = 0u;
        for (; base < count; base += uint(MAX_SHARED))
        {
          int n = int(min(uint(MAX_SHARED), count - base));
          memoryBarrierShared();
          barrier();
          uint k = local;
          for (; k < uint(n); k += groupSize)
          {
            uint id = voxelBalls[first + base + k];
            vec4 b = balls[id];
            sharedBalls[k] = vec4((worldToView * vec4(b.xyz, 1.0)).xyz, b.w);
            sharedStrength[k] = psStrength(id);
            sharedColor[k] = psColor(id);
          }
          // A load cut short by the driver leaves stale balls: no sum to trust.
          complete = psAny(k < uint(n)) || !loaded ? false : complete;
          if (marching)
          {
            complete = psAccumulate(p, n, f, g, c, false) && complete;
          }
        }
        complete = complete && base >= count;
        if (marching)
        {
          samples += bisecting > 0 ? 0u : 1u;
          bisectionSamples += bisecting > 0 ? 1u : 0u;
          terms += count;
          psStep(t, f, t1, baseStep, lipschitz, origin, dir, first, count, false, steps, haveA,
            tA, fA, marching, searching, hit, tHit, normal, color, slab == 0, complete,
            bisecting, ba, bb, bfa);
        }
        if (!psAny(marching))
        {
          break;
        }
      }
    }
    if (marching)
    {
      // The march loop itself was cut short by the driver.
      atomicAdd(insideCount[1], 1u);
      searching = false;
    }
    memoryBarrierShared();
    barrier(); // the next voxel's list overwrites shared memory
  }

  if (searching && lastSlab < slabs - 1)
  {
    atomicAdd(insideCount[1], 1u); // the slab loop was cut short by the driver
  }
  // This ray's counts, one atomic each.
  if (samples > 0u)
  {
    atomicAdd(insideCount[3], samples);
    atomicAdd(insideCount[4], bisectionSamples);
    uint before = atomicAdd(insideCount[7], terms);
    if (before + terms < before)
    {
      atomicMax(insideCount[7], 0xffffffffu); // saturated
    }
  }
  if (visits > 0u)
  {
    atomicAdd(insideCount[5], visits);
    atomicAdd(insideCount[6], emptyVisits);
  }
  if (hit && inside)
  {
    atomicAdd(insideCount[8], 1u);
  }
  if (!inside)
  {
    return;
  }
  if (!hit)
  {
    imageStore(colorImage, pixel, vec4(0.0));
    imageStore(normalImage, pixel, vec4(0.0));
    imageStore(depthImage, pixel, vec4(1.0));
    return;
  }
  vec3 p = origin + tHit * dir;
  // Seen from inside the surface (the camera in a blob): face the eye.
  if (dot(normal, dir) > 0.0)
  {
    normal = -normal;
  }
  vec4 clip = viewToClip * vec4(p, 1.0);
  float depth = 0.5 * clip.z / clip.w + 0.5;
  imageStore(colorImage, pixel, color);
  imageStore(normalImage, pixel, vec4(normal, -p.z));
  imageStore(depthImage, pixel, vec4(clamp(depth, 0.0, 1.0)));
}
