//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// Last step of vtkAlgebraicSplatMapper's two-pass blend ([Bolla 2010] 4.2):
// normalises the accumulated (sum w C, sum w) per pixel and writes it into
// VTK's framebuffer with the true depth of the nearest splat, so that the
// splats intersect correctly with every other actor. The alpha is the
// largest coverage of any splat at the pixel (1 unless adaptive
// anti-aliasing found a partly covered silhouette pixel).
//
// Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
// M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).

in vec2 texCoord;
uniform sampler2D accumulation; // sum w C, sum w
uniform sampler2D depthCoverage; // min true depth, min (1 - coverage)

//VTK::Output::Dec

void main()
{
  vec4 sum = texture(accumulation, texCoord);
  if (sum.a <= 0.0)
  {
    discard;
  }
  vec2 dc = texture(depthCoverage, texCoord).rg;
  gl_FragData[0] = vec4(sum.rgb / sum.a, clamp(1.0 - dc.g, 0.0, 1.0));
  gl_FragDepth = dc.r;
}
