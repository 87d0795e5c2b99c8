//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// vtkMetaballLevelOfDetail: balls whose support covers less than
// `lodPixels` pixels on screen are merged, per cell of lodPixels x lodPixels
// pixels and the matching depth (cells about as deep as they are wide), into
// one ball each, so that a cloud seen whole costs what its pixels cost. One
// source, compiled once per pass (PASS is defined by the class):
//
// 0 CLASSIFY per ball: copies it to the level's balls, or, when it is small
//            on screen, removes it there (radius 0), gives it a cell and a
//            depth bin, and lowers its cell's front bin; clears one merged
//            slot
// 1 KEY      per small ball: its key, the cell times `depthBins` plus its
//            bin behind the cell's front bin (the deeper ones share the
//            last), counted in the keys' histogram
// 2 PLACE    per small ball: its id into its key's list (counting sort,
//            after the builder's scan of the histogram)
// 3 MERGE    per key: its balls become one ball: the centroid weighted by
//            |q| R^3, R^2 their weighted mean R_i^2 plus SPREAD times their
//            variance about the centroid (second moments add), q the sum
//            of q_i R_i^3 over R^3 (the kernel's mass), the colour weighted
//            as the centroid. A key of one ball keeps the ball.
//
// The level's balls are the n balls (small ones removed) followed by up to
// n merged ones; merged ball j has id n + j, its strength and colour in
// mergedStrengths[j] and mergedColors[j].

//VTK::Pass::Dec

layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer Balls { vec4 balls[]; };
layout(std430, binding = 1) readonly buffer Colors { uint colors[]; };
layout(std430, binding = 2) readonly buffer Strengths { float strengths[]; };
layout(std430, binding = 3) buffer LevelBalls { vec4 levelBalls[]; }; // 2n
layout(std430, binding = 4) buffer KeyOf { uint keyOf[]; };           // per ball: cell, then key
layout(std430, binding = 5) buffer BinOf { int binOf[]; };            // per ball
layout(std430, binding = 6) buffer Histogram { uint histogram[]; };   // per key, + 1
layout(std430, binding = 7) buffer Cursor { uint cursor[]; };         // per key
layout(std430, binding = 12) buffer FrontBin { int frontBin[]; };     // per cell
layout(std430, binding = 8) buffer CellBalls { uint cellBalls[]; };   // per small ball
layout(std430, binding = 9) buffer MergedStrengths { float mergedStrengths[]; };
layout(std430, binding = 10) buffer MergedColors { uint mergedColors[]; };
layout(std430, binding = 11) buffer Level { uint level[]; }; // [0] merged balls, [1] balls merged

uniform mat4 worldToView;
uniform mat4 viewToClip;
uniform uint count;     // balls, or keys (MERGE)
uniform int depthBins;  // bins a cell keeps behind its front one
uniform uint ballCount; // balls (MERGE)
uniform int parallelProjection;
uniform ivec2 viewport;
uniform float lodPixels;
uniform ivec2 cells;   // cells across and up
uniform float binStep; // perspective: log(1 + cell depth / distance); parallel: cell depth
uniform int useStrengths;
uniform int colorPerBall;

const uint NONE = 0xFFFFFFFFu;
#define SPREAD 3.0

// The pixels per unit of length at view distance d (0 behind the eye).
float psPixelsPerUnit(float d)
{
  float scale = 0.5 * float(viewport.y) * viewToClip[1][1];
  return parallelProjection != 0 ? scale : (d > 0.0 ? scale / d : 0.0);
}

#if PASS == 3
float psStrength(uint id)
{
  return useStrengths != 0 ? strengths[id] : 1.0;
}

vec4 psUnpack(uint c)
{
  return vec4(float(c & 255u), float((c >> 8) & 255u), float((c >> 16) & 255u), float(c >> 24));
}

uint psPack(vec4 c)
{
  uvec4 u = uvec4(clamp(round(c), 0.0, 255.0));
  return u.x | (u.y << 8) | (u.z << 16) | (u.w << 24);
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
  levelBalls[count + i] = vec4(0.0); // merged slot i: empty until MERGE fills it
  vec4 b = balls[i];
  levelBalls[i] = b;
  keyOf[i] = NONE;
  if (any(isnan(b)) || any(isinf(b)) || !(b.w > 0.0))
  {
    return;
  }
  vec3 c = (worldToView * vec4(b.xyz, 1.0)).xyz;
  float d = -c.z;
  float perUnit = psPixelsPerUnit(d);
  if (!(perUnit > 0.0) || b.w * perUnit >= lodPixels)
  {
    return; // large on screen, or behind the eye: drawn as it is
  }
  vec4 clip = viewToClip * vec4(c, 1.0);
  if (!(clip.w > 0.0))
  {
    return;
  }
  vec2 p = (0.5 * clip.xy / clip.w + 0.5) * vec2(viewport);
  ivec2 cell = ivec2(floor(p / lodPixels));
  if (any(lessThan(cell, ivec2(0))) || any(greaterThanEqual(cell, cells)))
  {
    return; // off screen: the grid culls it
  }
  uint id = uint(cell.y * cells.x + cell.x);
  int bin = int(floor(parallelProjection != 0 ? d / binStep : log(max(d, 1e-30)) / binStep));
  keyOf[i] = id;
  binOf[i] = bin;
  levelBalls[i] = vec4(b.xyz, 0.0); // removed: its key's ball stands for it
  atomicMin(frontBin[id], bin);

#elif PASS == 1
  uint i = gl_GlobalInvocationID.x;
  if (i >= count || keyOf[i] == NONE)
  {
    return;
  }
  uint cell = keyOf[i];
  int behind = clamp(binOf[i] - frontBin[cell], 0, depthBins - 1);
  uint key = cell * uint(depthBins) + uint(behind);
  keyOf[i] = key;
  atomicAdd(histogram[key], 1u);

#elif PASS == 2
  uint i = gl_GlobalInvocationID.x;
  if (i >= count || keyOf[i] == NONE)
  {
    return;
  }
  cellBalls[atomicAdd(cursor[keyOf[i]], 1u)] = i;

#elif PASS == 3
  uint key = gl_GlobalInvocationID.x;
  if (key >= count)
  {
    return;
  }
  uint first = histogram[key], last = histogram[key + 1u];
  if (last - first == 1u)
  {
    levelBalls[cellBalls[first]] = balls[cellBalls[first]]; // alone: the ball itself
  }
  if (last - first < 2u)
  {
    return;
  }
  // Moments relative to the first ball (no cancellation far from 0).
  vec3 origin = balls[cellBalls[first]].xyz;
  float mass = 0.0, weight = 0.0, spread = 0.0, size = 0.0;
  vec3 centre = vec3(0.0);
  vec4 color = vec4(0.0);
  for (uint k = first; k < last; ++k)
  {
    uint id = cellBalls[k];
    vec4 b = balls[id];
    float v = b.w * b.w * b.w;
    float q = psStrength(id);
    float w = abs(q) * v + 1e-30;
    vec3 x = b.xyz - origin;
    mass += q * v;
    weight += w;
    centre += w * x;
    spread += w * dot(x, x);
    size += w * b.w * b.w;
    color += w * psUnpack(colors[colorPerBall != 0 ? id : 0u]);
  }
  centre /= weight;
  float variance = max(spread / weight - dot(centre, centre), 0.0);
  float R = sqrt(size / weight + SPREAD * variance);
  uint j = atomicAdd(level[0], 1u);
  levelBalls[ballCount + j] = vec4(origin + centre, R);
  mergedStrengths[j] = mass / (R * R * R);
  mergedColors[j] = psPack(color / weight);
  atomicAdd(level[1], last - first);
#endif
}
