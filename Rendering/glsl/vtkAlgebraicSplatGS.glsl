//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// Geometry shader of vtkAlgebraicSplatMapper: a screen-aligned quad that
// tightly bounds the splat's volume, the disc of radius R (u, v) times the
// height range of g over it (w), at most R, so that only the pixels the splat can cover
// are ray cast. The quad lies at the volume's nearest depth; the fragment
// shader writes the true depth.

//VTK::PrimID::Dec

//VTK::Color::Dec

layout(points) in;
layout(triangle_strip, max_vertices = 4) out;

uniform mat4 VCDCMatrix;

in vec3 splatAxisUVSOutput[];
in vec3 splatAxisVVSOutput[];
in vec3 splatAxisNVSOutput[];
in float splatRadiusVSOutput[];
in vec4 splatC0VSOutput[];
in vec4 splatC1VSOutput[];
in vec4 splatC2VSOutput[];
in vec4 splatC3VSOutput[];

out vec4 vertexVCGSOutput;
// Per splat, constant over the quad: flat, so nothing is interpolated.
flat out vec3 splatCenterVCGSOutput;
flat out vec3 splatAxisUGSOutput;
flat out vec3 splatAxisVGSOutput;
flat out vec3 splatAxisNGSOutput;
flat out mat3 splatInverseGSOutput; // view coordinates to the normalised frame
flat out float splatRadiusGSOutput;
flat out vec4 splatC0GSOutput;
flat out vec4 splatC1GSOutput;
flat out vec4 splatC2GSOutput;
flat out vec4 splatC3GSOutput;

//VTK::Picking::Dec

void main()
{
  int i = 0; // the vertex index VTK's colour and picking code reads

  //VTK::PrimID::Impl

  //VTK::Color::Impl

  //VTK::Picking::Impl

  vec3 centre = gl_in[0].gl_Position.xyz / gl_in[0].gl_Position.w;
  float rho = splatRadiusVSOutput[0];
  if (!(rho > 0.0 && rho < 1e30))
  {
    return; // an invalid splat (zero radius), or one culled by its level
  }
  // |g| over the disc is at most sum |c_k| rho^(total degree of monomial k).
  vec4 c0 = splatC0VSOutput[0], c1 = splatC1VSOutput[0], c2 = splatC2VSOutput[0],
       c3 = splatC3VSOutput[0];
  float r2 = rho * rho;
  float bound = abs(c0.x) + (abs(c0.y) + abs(c0.z)) * rho +
    (abs(c0.w) + abs(c1.x) + abs(c1.y)) * r2 +
    (abs(c1.z) + abs(c1.w) + abs(c2.x) + abs(c2.y)) * r2 * rho +
    (abs(c2.z) + abs(c2.w) + abs(c3.x) + abs(c3.y) + abs(c3.z)) * r2 * r2;
  // The splat is bounded to its cylinder: |w| <= rho.
  bound = min(bound, rho);

  vec2 lo = vec2(1e30), hi = vec2(-1e30);
  float nearest = 1.0;
  bool behind = false;
  for (int k = 0; k < 8; ++k)
  {
    vec3 corner = centre + splatAxisUVSOutput[0] * ((k & 1) != 0 ? rho : -rho) +
      splatAxisVVSOutput[0] * ((k & 2) != 0 ? rho : -rho) +
      splatAxisNVSOutput[0] * ((k & 4) != 0 ? bound : -bound);
    vec4 clip = VCDCMatrix * vec4(corner, 1.0);
    if (clip.w <= 0.0)
    {
      behind = true;
      continue;
    }
    vec3 ndc = clip.xyz / clip.w;
    lo = min(lo, ndc.xy);
    hi = max(hi, ndc.xy);
    nearest = min(nearest, ndc.z);
  }
  if (behind)
  {
    // The volume reaches behind the eye: cover the whole viewport.
    lo = vec2(-1.0);
    hi = vec2(1.0);
    nearest = -1.0;
  }
  if (lo.x > 1.0 || lo.y > 1.0 || hi.x < -1.0 || hi.y < -1.0)
  {
    return; // off screen
  }
  lo = max(lo, vec2(-1.0));
  hi = min(hi, vec2(1.0));
  nearest = clamp(nearest, -1.0, 1.0);
  mat4 dcvc = inverse(VCDCMatrix);
  mat3 toLocal = inverse(mat3(splatAxisUVSOutput[0], splatAxisVVSOutput[0], splatAxisNVSOutput[0]));
  for (int k = 0; k < 4; ++k)
  {
    vec4 ndc = vec4((k & 1) != 0 ? hi.x : lo.x, (k & 2) != 0 ? hi.y : lo.y, nearest, 1.0);
    vec4 vc = dcvc * ndc;
    vertexVCGSOutput = vec4(vc.xyz / vc.w, 1.0);
    splatCenterVCGSOutput = centre;
    splatAxisUGSOutput = splatAxisUVSOutput[0];
    splatAxisVGSOutput = splatAxisVVSOutput[0];
    splatAxisNGSOutput = splatAxisNVSOutput[0];
    splatInverseGSOutput = toLocal;
    splatRadiusGSOutput = rho;
    splatC0GSOutput = c0;
    splatC1GSOutput = c1;
    splatC2GSOutput = c2;
    splatC3GSOutput = c3;
    gl_Position = ndc;
    EmitVertex();
  }
  EndPrimitive();
}
