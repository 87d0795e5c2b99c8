//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// Geometry shader of vtkAlgebraicSplatMapper: bounds each splat's volume,
// the square around its disc of radius R (u, v) times the height range of g
// over the disc (w, within +-R), by a box, and emits the box's faces that
// face the eye (at most three quads), so that only the pixels the splat can
// cover are ray cast, each once. Where the box crosses the near plane it
// falls back to a screen-aligned quad at the near plane; under
// anti-aliasing, to one grown by half a pixel. The true depth of the hit
// (written by the fragment shader, or tested there in the blending pass) is
// never nearer than the face's or the quad's.

//VTK::PrimID::Dec

//VTK::Color::Dec

layout(points) in;
layout(triangle_strip, max_vertices = 12) out;

uniform mat4 VCDCMatrix;
uniform int cameraParallel;
uniform int splatCullFaces; // bit 0: back faces, bit 1: front faces
uniform vec2 splatOutlineMargin; // > 0 (NDC): grown screen-aligned quads, for anti-aliasing

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

// Emits one vertex of a bounding face. Every output is undefined after
// EmitVertex, so each vertex sets them all, VTK's colour, picking and
// primitive id included.
void psEmitVertex(vec4 position, vec3 vertexVC, vec3 centre, mat3 toLocal, float rho, vec4 c0,
  vec4 c1, vec4 c2, vec4 c3)
{
  int i = 0; // the vertex index VTK's colour and picking code reads

  //VTK::PrimID::Impl

  //VTK::Color::Impl

  //VTK::Picking::Impl

  vertexVCGSOutput = vec4(vertexVC, 1.0);
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
  gl_Position = position;
  EmitVertex();
}

void main()
{
  vec3 centre = gl_in[0].gl_Position.xyz / gl_in[0].gl_Position.w;
  float rho = splatRadiusVSOutput[0];
  if (!(rho > 0.0 && rho < 1e30))
  {
    return; // an invalid splat (zero radius), or one culled by its level
  }
  // The height range [lo, hi] of g over the disc |(u, v)| <= rho: the
  // constant, the linear part's reach |grad| rho, the quadratic form's
  // eigenvalues times rho^2 (each sign on its own side), and the cubic and
  // quartic terms' sum |c_k| rho^k on both sides.
  vec4 c0 = splatC0VSOutput[0], c1 = splatC1VSOutput[0], c2 = splatC2VSOutput[0],
       c3 = splatC3VSOutput[0];
  float r2 = rho * rho;
  float linear = length(c0.yz) * rho;
  float mean = 0.5 * (c0.w + c1.y);
  float spread = length(vec2(0.5 * (c0.w - c1.y), 0.5 * c1.x));
  float higher = (abs(c1.z) + abs(c1.w) + abs(c2.x) + abs(c2.y)) * r2 * rho +
    (abs(c2.z) + abs(c2.w) + abs(c3.x) + abs(c3.y) + abs(c3.z)) * r2 * r2;
  // The splat is bounded to its cylinder: |w| <= rho.
  float hi = min(c0.x + linear + max(mean + spread, 0.0) * r2 + higher, rho);
  float lo = max(c0.x - linear + min(mean - spread, 0.0) * r2 - higher, -rho);
  if (!(lo <= hi))
  {
    return; // the patch leaves the cylinder over the whole disc (or is NaN)
  }

  vec3 U = splatAxisUVSOutput[0] * rho, V = splatAxisVVSOutput[0] * rho,
       W = splatAxisNVSOutput[0];
  mat3 toLocal = inverse(mat3(splatAxisUVSOutput[0], splatAxisVVSOutput[0], splatAxisNVSOutput[0]));
  if (splatCullFaces != 0)
  {
    // Face culling by the splat's oriented normal: a splat goes when every
    // normal of its patch faces away from (or towards) every ray from the
    // eye to its box. Worked in the splat's normalised frame, where g is
    // defined (whether a normal faces a ray is the same in any affine frame,
    // so a non-uniform actor scale changes nothing): the patch's normals
    // (-grad g, 1) lie within atan(G) of (0, 0, 1), G a bound on |grad g|
    // over the disc; the rays from the eye e to the box lie within
    // asin(r / |e|) of the ray to the frame's origin, r the box's radius.
    float slope = length(c0.yz) + 2.0 * (abs(mean) + spread) * rho +
      3.0 * (abs(c1.z) + abs(c1.w) + abs(c2.x) + abs(c2.y)) * r2 +
      4.0 * (abs(c2.z) + abs(c2.w) + abs(c3.x) + abs(c3.y) + abs(c3.z)) * r2 * rho;
    float reach = sqrt(2.0 * r2 + max(lo * lo, hi * hi));
    vec3 e = toLocal * (cameraParallel != 0 ? vec3(0.0, 0.0, 1.0) : -centre);
    float distance = length(e);
    float cone = atan(slope) + (cameraParallel != 0 ? 0.0 : asin(min(reach / distance, 1.0)));
    float margin = cone < 1.5707963 ? sin(cone) : 2.0;
    float facing = e.z / distance;
    if (((splatCullFaces & 1) != 0 && facing < -margin) ||
      ((splatCullFaces & 2) != 0 && facing > margin))
    {
      return;
    }
  }
  vec4 clip[8];
  vec3 corner[8];
  vec2 lower = vec2(1e30), upper = vec2(-1e30);
  float nearest = 1.0;
  bool behind = false;
  for (int k = 0; k < 8; ++k)
  {
    corner[k] = centre + U * ((k & 1) != 0 ? 1.0 : -1.0) + V * ((k & 2) != 0 ? 1.0 : -1.0) +
      W * ((k & 4) != 0 ? hi : lo);
    clip[k] = VCDCMatrix * vec4(corner[k], 1.0);
    if (clip[k].w <= 0.0)
    {
      behind = true;
      continue;
    }
    vec3 ndc = clip[k].xyz / clip[k].w;
    lower = min(lower, ndc.xy);
    upper = max(upper, ndc.xy);
    nearest = min(nearest, ndc.z);
  }
  if (behind)
  {
    // The volume reaches behind the eye: cover the whole viewport.
    lower = vec2(-1.0);
    upper = vec2(1.0);
    nearest = -1.0;
  }
  if (lower.x > 1.0 || lower.y > 1.0 || upper.x < -1.0 || upper.y < -1.0)
  {
    return; // off screen
  }
  if (!behind && nearest >= -1.0 && splatOutlineMargin.x <= 0.0)
  {
    // The box's faces that face the eye: together they cover its projection
    // exactly once (a convex solid), tighter than any screen-aligned quad,
    // and each pixel's ray enters the box there, so the hit is never nearer
    // than the fragment (conservative depth holds).
    vec3 faceNormal[3] = vec3[3](cross(V, W), cross(W, U), cross(U, V));
    vec3 axis[3] = vec3[3](U, V, W);
    for (int f = 0; f < 6; ++f)
    {
      int a = f / 2; // the axis the face is normal to
      bool high = (f & 1) != 0;
      int bit = 1 << a;
      // The face's corners: the other two axes' bits, in strip order.
      int b0 = a == 0 ? 2 : 1, b1 = a == 2 ? 2 : 4;
      int base = high ? bit : 0;
      int ids[4] = int[4](base, base | b0, base | b1, base | b0 | b1);
      vec3 outward = faceNormal[a] * (dot(faceNormal[a], axis[a]) > 0.0 ? 1.0 : -1.0) *
        (high ? 1.0 : -1.0);
      vec3 toEye = cameraParallel != 0 ? vec3(0.0, 0.0, 1.0) : -corner[ids[0]];
      if (dot(outward, toEye) <= 0.0)
      {
        continue;
      }
      for (int k = 0; k < 4; ++k)
      {
        psEmitVertex(clip[ids[k]], corner[ids[k]], centre, toLocal, rho, c0, c1, c2, c3);
      }
      EndPrimitive();
    }
    return;
  }
  // A screen-aligned quad: at the near plane where the box crosses it (or
  // reaches behind the eye), which the rasteriser cannot clip; otherwise
  // (anti-aliasing) at the box's nearest depth, grown by half a pixel, so
  // that the pixels that the patch covers only in part along the box's
  // outline get their sub-pixel rays too.
  if (behind || nearest < -1.0)
  {
    nearest = -1.0;
  }
  lower = max(lower - splatOutlineMargin, vec2(-1.0));
  upper = min(upper + splatOutlineMargin, vec2(1.0));
  mat4 dcvc = inverse(VCDCMatrix);
  for (int k = 0; k < 4; ++k)
  {
    vec4 ndc = vec4((k & 1) != 0 ? upper.x : lower.x, (k & 2) != 0 ? upper.y : lower.y, nearest, 1.0);
    vec4 vc = dcvc * ndc;
    psEmitVertex(ndc, vc.xyz / vc.w, centre, toLocal, rho, c0, c1, c2, c3);
  }
  EndPrimitive();
}
