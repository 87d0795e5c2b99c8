//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// Vertex shader of vtkAlgebraicSplatMapper: one vertex per splat. Passes the
// splat's frame, scaled by its feature size h, and its polynomial to the
// geometry shader in view coordinates. Only the coefficients that the
// degree needs are vertex attributes (SPLAT_DEGREE is defined by the mapper).
//
// Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
// M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).

//VTK::SplatDegree::Dec

in vec4 vertexMC;
in vec3 splatNormalMC;
in vec3 splatTangentMC;
in vec3 splatSizeMC; // h, disc radius R, R / s of the splat's level
uniform float lodQuality; // > 0: the quality s of the finest level drawn
in vec4 splatC0;
#if SPLAT_DEGREE >= 2
in vec4 splatC1;
#endif
#if SPLAT_DEGREE >= 3
in vec4 splatC2;
#endif
#if SPLAT_DEGREE >= 4
in vec4 splatC3;
#endif

out vec3 splatAxisUVSOutput;
out vec3 splatAxisVVSOutput;
out vec3 splatAxisNVSOutput;
out float splatRadiusVSOutput; // R / h
out vec4 splatC0VSOutput;
out vec4 splatC1VSOutput;
out vec4 splatC2VSOutput;
out vec4 splatC3VSOutput;

//VTK::Color::Dec

//VTK::Camera::Dec

//VTK::Picking::Dec

void main()
{
  //VTK::Color::Impl

  mat3 mcvc = mat3(MCVCMatrix);
  vec3 n = normalize(splatNormalMC);
  vec3 t = normalize(splatTangentMC - dot(splatTangentMC, n) * n);
  vec3 b = cross(n, t);
  float h = splatSizeMC.x;
  splatAxisUVSOutput = mcvc * (t * h);
  splatAxisVVSOutput = mcvc * (b * h);
  splatAxisNVSOutput = mcvc * (n * h);
  // With LOD, a splat's disc follows the finest level drawn around it
  // ([Bolla 2010] 3.2: R is chosen at run time from h and s), never past
  // its own (error-bounded) radius.
  splatRadiusVSOutput =
    (lodQuality > 0.0 ? min(lodQuality * splatSizeMC.z, splatSizeMC.y) : splatSizeMC.y) / h;
  splatC0VSOutput = splatC0;
  splatC1VSOutput = vec4(0.0);
  splatC2VSOutput = vec4(0.0);
  splatC3VSOutput = vec4(0.0);
#if SPLAT_DEGREE >= 2
  splatC1VSOutput = splatC1;
#endif
#if SPLAT_DEGREE >= 3
  splatC2VSOutput = splatC2;
#endif
#if SPLAT_DEGREE >= 4
  splatC3VSOutput = splatC3;
#endif
  gl_Position = MCVCMatrix * vertexMC;

  //VTK::Picking::Impl
}
