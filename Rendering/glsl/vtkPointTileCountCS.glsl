//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// Counting pass of a screen-tiled grid build: project each point with the
// world-to-clip matrix, find its screen tile and count the points per tile.
// Points behind the eye or outside the view frustum get tile -1.

layout(local_size_x = 128) in;

layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 1) buffer TileCounts { uint tileCounts[]; };
layout(std430, binding = 2) writeonly buffer PointTiles { int pointTiles[]; };

uniform mat4 worldToClip;
uniform uint numberOfPoints;
uniform ivec2 viewportSize;
uniform int tileSize;
uniform ivec2 tileCount;

void main()
{
  uint i = gl_GlobalInvocationID.x;
  if (i >= numberOfPoints)
  {
    return;
  }
  vec4 clip = worldToClip * vec4(points[i].xyz, 1.0);
  int tile = -1;
  if (clip.w > 0.0)
  {
    vec3 ndc = clip.xyz / clip.w;
    if (all(greaterThanEqual(ndc, vec3(-1.0))) && all(lessThan(ndc, vec3(1.0))))
    {
      vec2 pixel = (ndc.xy * 0.5 + 0.5) * vec2(viewportSize);
      ivec2 t = min(ivec2(pixel) / tileSize, tileCount - 1);
      tile = t.y * tileCount.x + t.x;
      atomicAdd(tileCounts[tile], 1u);
    }
  }
  pointTiles[i] = tile;
}
