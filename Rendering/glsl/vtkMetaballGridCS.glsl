//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// The per-frame perspective grid of vtkMetaballGridBuilder ([Bolla 2010]
// Algorithm 2): screen tiles times depth slabs, each voxel listing the balls
// whose support reaches into it. One source, compiled once per pass (PASS is
// defined by the builder):
//
// 0 RANGE    nearest and farthest view distance of the balls in the view
//            (automatic slab placement), as float bits with atomicMin/Max
// 1 COUNT    per ball: frustum cull, voxel range, number of voxels (the
//            ranges are found again by SCATTER, not stored)
// 2 SCAN     exclusive scan of 1024 values per work group (Blelloch), with
//            each group's total written out; optionally the largest value
// 3 ADD      adds the scanned group totals back (multi-level scans)
// 4 SCATTER  per ball: its (voxel, ball) pairs at its scanned offset, and a
//            histogram of pairs per voxel; pairs beyond the capacity are
//            left out (and counted: the builder grows its buffers)
// 5 PLACE    per pair: the ball id into its voxel's list (counting sort),
//            dispatched indirectly with the sizes that PAIRS wrote
// 6 SLABS    one invocation: the slab range, fixed or from RANGE's result,
//            with the CPU geometry's fallback when no ball is in view
// 7 PAIRS    one invocation: the pair count from the scan, the pairs placed
//            (at most the capacity) and PLACE's indirect dispatch sizes
//
// Nothing is read back inside a build: the slab range, the pair count and the
// dispatch sizes stay in `stats`, which the ray casters read too:
// [0] [1] nearest and farthest ball distance (float bits), [2] culled,
// [3] invalid, [4] most balls in a voxel, [5] [6] the slab range (float bits),
// [7] pairs needed, [8] pairs placed, [9..11] PLACE's work groups.
//
// The arithmetic follows pointsurfaces::BallVoxels (psMetaball.cxx), in
// float: a ball's view-space box is projected to find its tiles.
//
// Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
// M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).

//VTK::Pass::Dec

#if PASS == 2
layout(local_size_x = 512) in;
#elif PASS >= 6
layout(local_size_x = 1) in;
#else
layout(local_size_x = 256) in;
#endif

layout(std430, binding = 0) readonly buffer Balls { vec4 balls[]; };  // centre, radius
layout(std430, binding = 2) buffer Counts { uint counts[]; };         // per ball, + 1
layout(std430, binding = 3) buffer Sums { uint sums[]; };             // per work group
layout(std430, binding = 4) buffer PairVoxels { uint pairVoxels[]; };
layout(std430, binding = 5) buffer PairBalls { uint pairBalls[]; };
layout(std430, binding = 6) buffer Histogram { uint histogram[]; };  // per voxel, + 1
layout(std430, binding = 7) buffer Cursor { uint cursor[]; };        // per voxel
layout(std430, binding = 8) buffer VoxelBalls { uint voxelBalls[]; };
layout(std430, binding = 9) buffer Stats { uint stats[]; }; // as listed above

uniform mat4 worldToView;
uniform mat4 viewToClip;
uniform vec4 frustum[6]; // view-space planes, inside >= 0, unit normals
uniform uint count;      // balls, pairs or values, by pass
uniform int parallelProjection;
uniform ivec2 viewport;
uniform int tileSize;
uniform ivec2 tiles;
uniform int slabs;
uniform vec2 fixedRange;      // the slab range when fixed (SLABS), else y <= x
uniform vec2 projectionRange; // near and far view distance of the projection
uniform int recordMax;
uniform uint capacity;  // pairs the buffers hold (SCATTER, PAIRS)
uniform uint maxGroups; // work groups a dispatch dimension allows (PAIRS)

bool psValid(vec4 b)
{
  return !any(isnan(b)) && !any(isinf(b)) && b.w > 0.0;
}

bool psOutside(vec3 c, float r)
{
  for (int k = 0; k < 6; ++k)
  {
    if (dot(frustum[k].xyz, c) + frustum[k].w < -r)
    {
      return true;
    }
  }
  return false;
}

#if PASS == 1 || PASS == 4
int psSlabOf(float d, float slabNear, float slabFar)
{
  float s = (d - slabNear) / (slabFar - slabNear) * float(slabs);
  return clamp(int(floor(s)), 0, slabs - 1);
}

// Ball b's voxels: its tile ranges in x and y and its slab range; 0 when it
// is invalid, 1 when it is culled, 2 with the ranges. COUNT counts them,
// SCATTER finds them again (storing them would take 24 bytes a ball).
int psBallVoxels(vec4 b, out ivec2 xr, out ivec2 yr, out ivec2 zr)
{
  xr = yr = zr = ivec2(0, -1);
  if (!psValid(b))
  {
    return 0;
  }
  vec3 c = (worldToView * vec4(b.xyz, 1.0)).xyz;
  float r = b.w;
  float d = -c.z;
  float slabNear = uintBitsToFloat(stats[5]), slabFar = uintBitsToFloat(stats[6]);
  if (psOutside(c, r) || d + r < slabNear || d - r > slabFar)
  {
    return 1;
  }
  zr = ivec2(psSlabOf(d - r, slabNear, slabFar), psSlabOf(d + r, slabNear, slabFar));
  vec2 lo = vec2(1e30), hi = vec2(-1e30);
  bool everywhere = parallelProjection == 0 && d - r <= 0.0;
  for (int k = 0; k < 8 && !everywhere; ++k)
  {
    vec3 corner = c + vec3((k & 1) != 0 ? r : -r, (k & 2) != 0 ? r : -r, (k & 4) != 0 ? r : -r);
    vec4 clip = viewToClip * vec4(corner, 1.0);
    if (!(clip.w > 0.0))
    {
      everywhere = true;
    }
    else
    {
      vec2 p = (0.5 * clip.xy / clip.w + 0.5) * vec2(viewport);
      lo = min(lo, p);
      hi = max(hi, p);
    }
  }
  if (everywhere)
  {
    xr = ivec2(0, tiles.x - 1);
    yr = ivec2(0, tiles.y - 1);
    return 2;
  }
  if (hi.x < 0.0 || hi.y < 0.0 || lo.x >= float(viewport.x) || lo.y >= float(viewport.y))
  {
    zr = ivec2(0, -1);
    return 1;
  }
  xr = ivec2(max(0, int(floor(lo.x / float(tileSize)))),
    min(tiles.x - 1, int(floor(hi.x / float(tileSize)))));
  yr = ivec2(max(0, int(floor(lo.y / float(tileSize)))),
    min(tiles.y - 1, int(floor(hi.y / float(tileSize)))));
  return 2;
}
#endif

#if PASS == 2
shared uint scratch[1024];
#endif

#if PASS == 2 || PASS == 3
// Saturating: a total beyond 2^32 - 1 pairs stays at the top instead of
// wrapping, so that it reads as an overflow and no offset wraps below the
// capacity. (Saturating addition of unsigned values is associative.)
uint psAdd(uint a, uint b)
{
  return a > 0xFFFFFFFFu - b ? 0xFFFFFFFFu : a + b;
}
#endif

void main()
{
#if PASS == 0
  uint i = gl_GlobalInvocationID.x;
  if (i >= count)
  {
    return;
  }
  vec4 b = balls[i];
  if (!psValid(b))
  {
    return;
  }
  vec3 c = (worldToView * vec4(b.xyz, 1.0)).xyz;
  if (psOutside(c, b.w))
  {
    return;
  }
  float lo = clamp(-c.z - b.w, projectionRange.x, projectionRange.y);
  float hi = clamp(-c.z + b.w, projectionRange.x, projectionRange.y);
  atomicMin(stats[0], floatBitsToUint(max(lo, 0.0)));
  atomicMax(stats[1], floatBitsToUint(max(hi, 0.0)));

#elif PASS == 1
  uint i = gl_GlobalInvocationID.x;
  if (i >= count)
  {
    if (i == count)
    {
      counts[i] = 0u; // the scan's total lands here
    }
    return;
  }
  ivec2 xr, yr, zr;
  int kind = psBallVoxels(balls[i], xr, yr, zr);
  counts[i] = kind == 2 ? uint((xr.y - xr.x + 1) * (yr.y - yr.x + 1) * (zr.y - zr.x + 1)) : 0u;
  if (kind < 2)
  {
    atomicAdd(stats[kind == 0 ? 3 : 2], 1u); // invalid, or culled
  }

#elif PASS == 2
  // Blelloch scan of 1024 values of `counts` from offset group * 1024.
  uint local = gl_LocalInvocationID.x;
  uint base = gl_WorkGroupID.x * 1024u;
  uint a = base + 2u * local, b = a + 1u;
  uint va = a < count ? counts[a] : 0u;
  uint vb = b < count ? counts[b] : 0u;
  if (recordMax != 0)
  {
    atomicMax(stats[4], max(va, vb));
  }
  scratch[2u * local] = va;
  scratch[2u * local + 1u] = vb;
  uint offset = 1u;
  for (uint d = 512u; d > 0u; d >>= 1)
  {
    barrier();
    if (local < d)
    {
      uint ai = offset * (2u * local + 1u) - 1u;
      uint bi = offset * (2u * local + 2u) - 1u;
      scratch[bi] = psAdd(scratch[bi], scratch[ai]);
    }
    offset <<= 1;
  }
  if (local == 0u)
  {
    sums[gl_WorkGroupID.x] = scratch[1023];
    scratch[1023] = 0u;
  }
  for (uint d = 1u; d < 1024u; d <<= 1)
  {
    offset >>= 1;
    barrier();
    if (local < d)
    {
      uint ai = offset * (2u * local + 1u) - 1u;
      uint bi = offset * (2u * local + 2u) - 1u;
      uint t = scratch[ai];
      scratch[ai] = scratch[bi];
      scratch[bi] = psAdd(scratch[bi], t);
    }
  }
  barrier();
  if (a < count)
  {
    counts[a] = scratch[2u * local];
  }
  if (b < count)
  {
    counts[b] = scratch[2u * local + 1u];
  }

#elif PASS == 3
  uint i = gl_GlobalInvocationID.x;
  if (i < count)
  {
    counts[i] = psAdd(counts[i], sums[i / 1024u]);
  }

#elif PASS == 4
  uint i = gl_GlobalInvocationID.x;
  if (i >= count)
  {
    return;
  }
  uint first = counts[i];
  uint n = counts[i + 1u] - first;
  if (n == 0u)
  {
    return;
  }
  ivec2 xr, yr, zr;
  psBallVoxels(balls[i], xr, yr, zr);
  uint k = first;
  for (int z = zr.x; z <= zr.y; ++z)
  {
    for (int y = yr.x; y <= yr.y; ++y)
    {
      for (int x = xr.x; x <= xr.y && k < capacity; ++x)
      {
        uint voxel = uint((z * tiles.y + y) * tiles.x + x);
        pairVoxels[k] = voxel;
        pairBalls[k] = i;
        atomicAdd(histogram[voxel], 1u);
        ++k;
      }
    }
  }

#elif PASS == 5
  // Rows of work groups when there are more than one dimension allows.
  uint k = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 256u +
    gl_LocalInvocationID.x;
  if (k >= stats[8])
  {
    return;
  }
  uint voxel = pairVoxels[k];
  uint position = atomicAdd(cursor[voxel], 1u);
  voxelBalls[position] = pairBalls[k];

#elif PASS == 6
  // As pointsurfaces::PerspectiveGridGeometry::SetSlabRange.
  vec2 range = fixedRange.y > fixedRange.x ? fixedRange
                                           : vec2(uintBitsToFloat(stats[0]), uintBitsToFloat(stats[1]));
  if (!(range.y > range.x))
  {
    range = vec2(projectionRange.x, min(projectionRange.y, projectionRange.x + 1.0));
  }
  stats[5] = floatBitsToUint(range.x);
  stats[6] = floatBitsToUint(range.y);

#elif PASS == 7
  uint needed = counts[count];
  uint placed = min(needed, capacity);
  stats[7] = needed;
  stats[8] = placed;
  uint groups = (placed + 255u) / 256u;
  stats[9] = min(groups, maxGroups);
  stats[10] = max(1u, (groups + maxGroups - 1u) / maxGroups);
  stats[11] = 1u;
#endif
}
