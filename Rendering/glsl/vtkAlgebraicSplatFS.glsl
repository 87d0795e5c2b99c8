// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// Ray casting of one algebraic splat, substituted by vtkAlgebraicSplatMapper
// into VTK's polydata fragment shader: SplatDecl at //VTK::Normal::Dec,
// SplatImpl at //VTK::Depth::Impl and SplatOutput after
// //VTK::Coincident::Impl, the last hook of main().
//
// Reference: N. K. R. Bolla, "High Quality Rendering of Large Point-based Surfaces",
// M.S. thesis, IIIT Hyderabad, 2010 ([Bolla 2010]).
//
// In the splat's normalised frame (u, v, w) = M^-1 (x - centre), with
// M = [h t, h b, h n], the ray meets F(s) = g(u(s), v(s)) - w(s) = 0. The ray
// is re-centred at its closest approach to the splat and scaled so that the
// volume spans |tau| <= 2. F's coefficients in tau come straight from g's
// value, gradient and Hessian at degree 1 and 2; at degree 3 and 4, F is
// sampled at tau = -2..2, which gives its (at most quartic) coefficients
// exactly. F is then solved in closed form. The nearest root inside the
// splat's cylinder (the disc, at most R above or below it, as in
// [Bolla 2010] Figure 3.1) and between the clipping planes is the hit: its
// normal comes from the gradient of g, its depth goes to gl_FragDepth (the
// blending pass tests it instead), and VTK's lighting shades it.
//
// Adaptive anti-aliasing ([Bolla 2010] 4.3): a pixel is a silhouette pixel of the
// splat when its ray hits the patch at a grazing angle (|cos| between the
// normal and the ray below splatSilhouetteCos, i.e. dF/dt is small), or
// misses it by less than the pixel's footprint at an extremum of F inside
// the disc. Only those pixels cast SPLAT_SAMPLES x SPLAT_SAMPLES sub-pixel rays;
// the fragment then carries the mean normal of the rays that hit, the
// nearest hit's depth, and their fraction as coverage.
//
// Passes (SPLAT_PASS): 0 draws the splat opaque; 1 is the visibility pass
// of the two-pass blend ([Bolla 2010] 4.2), which writes only the depth pushed
// back along the ray by splatBlendOffset h; 2 is the blending pass, which
// writes (w C, w) to target 0 for the Gaussian weight w of the hit's
// distance from the splat centre (times its coverage), and (true depth,
// 1 - coverage) to target 1, blended with MIN; it keeps the hits up to the
// visibility depth.
//
// The mapper defines SPLAT_DEGREE (1 to 4), SPLAT_PASS, SPLAT_SAMPLES (the
// silhouette pixels' n, 1 for none), SPLAT_SHOW_SILHOUETTE (0 or 1) and
// SPLAT_CULL_FACES (bit 0: back faces, bit 1: front faces), and
// builds one program per combination it draws with, rather than branching
// on uniforms: a software rasteriser such as llvmpipe runs both sides of
// every branch for its whole block of pixels, so a branch that no pixel
// takes still costs its full price there (1.75x the frame time of opaque
// quadratic splats at 1024^2 before this was compiled out).

//VTK::SplatDecl::Begin

uniform mat4 VCDCMatrix;
uniform float splatBlendOffset;
#if SPLAT_PASS == 2
uniform sampler2D splatVisibleDepth; // the visibility pass's depth
uniform float splatDepthTolerance;   // its rounding: a step of a fixed-point format, 2^-22 for float
#endif
// A pixel's width and height on the view plane z = -1 (perspective camera)
// or in view units (parallel camera).
uniform vec2 splatPixelStep;
// The view-plane point of window position (0, 0): a pixel's ray goes through
// xy + gl_FragCoord.xy * splatPixelStep (plus zw times its view depth, for a
// parallel camera with an oblique projection). The rays come from the exact
// pixel centres, not from the quad's interpolated position, which a GPU
// computes from vertices snapped to its sub-pixel grid (NVIDIA: up to 1/512
// of a pixel off, 1e-5 of the model's size in depth).
uniform vec4 splatPixelToView;
uniform float splatBlendSharpness;
uniform float splatSilhouetteCos;
flat in vec3 splatCenterVCVSOutput;
flat in vec3 splatAxisUVSOutput;
flat in vec3 splatAxisVVSOutput;
flat in vec3 splatAxisNVSOutput;
flat in mat3 splatInverseVSOutput;
flat in float splatRadiusVSOutput;
flat in vec4 splatC0VSOutput;
flat in vec4 splatC1VSOutput;
flat in vec4 splatC2VSOutput;
flat in vec4 splatC3VSOutput;

#define PS_MAX_DEGREE SPLAT_DEGREE
//VTK::SplatRoots::Dec

float psSplatG(vec2 p, out vec2 grad)
{
  float u = p.x, v = p.y;
  vec4 a = splatC0VSOutput, b = splatC1VSOutput, c = splatC2VSOutput, d = splatC3VSOutput;
  // monomials: 1 u v | u2 uv v2 | u3 u2v uv2 v3 | u4 u3v u2v2 uv3 v4
  float g = a.x + a.y * u + a.z * v;
  grad = vec2(a.y, a.z);
#if SPLAT_DEGREE >= 2
  g += a.w * u * u + b.x * u * v + b.y * v * v;
  grad += vec2(2.0 * a.w * u + b.x * v, b.x * u + 2.0 * b.y * v);
#endif
#if SPLAT_DEGREE >= 3
  g += b.z * u * u * u + b.w * u * u * v + c.x * u * v * v + c.y * v * v * v;
  grad += vec2(3.0 * b.z * u * u + 2.0 * b.w * u * v + c.x * v * v,
    b.w * u * u + 2.0 * c.x * u * v + 3.0 * c.y * v * v);
#endif
#if SPLAT_DEGREE >= 4
  float u2 = u * u, v2 = v * v;
  g += c.z * u2 * u2 + c.w * u2 * u * v + d.x * u2 * v2 + d.y * u * v2 * v + d.z * v2 * v2;
  grad += vec2(4.0 * c.z * u2 * u + 3.0 * c.w * u2 * v + 2.0 * d.x * u * v2 + d.y * v2 * v,
    c.w * u2 * u + 2.0 * d.x * u2 * v + 3.0 * d.y * u * v2 + 4.0 * d.z * v2 * v);
#endif
  return g;
}

// Narrows [lo, hi] to where a + b s >= 0.
void psClipRange(float a, float b, inout float lo, inout float hi)
{
  if (b > 0.0)
  {
    lo = max(lo, -a / b);
  }
  else if (b < 0.0)
  {
    hi = min(hi, -a / b);
  }
  else if (a < 0.0)
  {
    lo = 1e30;
    hi = -1e30;
  }
}

// Casts the ray rayO + s rayD (view coordinates, |rayD| = 1) at the splat.
// Returns true on a hit, with the hit point in the splat's normalised frame.
// With probe set, `silhouette` tells whether the pixel is a silhouette pixel
// (see above); `footprint` is the pixel's size in local units at distance
// s along the ray: footprint.x + footprint.y s.
bool psCastSplat(vec3 rayO, vec3 rayD, mat3 Minv, bool probe, vec2 footprint, out vec3 local,
  out bool silhouette)
{
  silhouette = false;
  local = vec3(0.0);
  vec3 o = Minv * (rayO - splatCenterVCVSOutput);
  vec3 d = Minv * rayD;
  float dd = dot(d, d);
  float sc = -dot(o, d) / dd; // closest approach to the centre
  vec3 oc = o + sc * d;
  float len = sqrt(dd);
  float rho = splatRadiusVSOutput;
  // The part of the ray between the near and far planes (-w <= z <= w in
  // clip coordinates, both linear in s): roots outside it are clipped away,
  // as rasterised geometry would be, and the ray goes on to the next one.
  // Behind the eye is outside it too.
  vec4 rowZ = vec4(VCDCMatrix[0][2], VCDCMatrix[1][2], VCDCMatrix[2][2], VCDCMatrix[3][2]);
  vec4 rowW = vec4(VCDCMatrix[0][3], VCDCMatrix[1][3], VCDCMatrix[2][3], VCDCMatrix[3][3]);
  float z0 = dot(rowZ, vec4(rayO, 1.0)), z1 = dot(rowZ.xyz, rayD);
  float w0 = dot(rowW, vec4(rayO, 1.0)), w1 = dot(rowW.xyz, rayD);
  float sLo = -1e30, sHi = 1e30;
  psClipRange(w0 - z0, w1 - z1, sLo, sHi);
  psClipRange(w0 + z0, w1 + z1, sLo, sHi);
  // Most of the quad's rays miss the splat's cylinder (|(u, v)| <= rho,
  // |w| <= rho) altogether: skip them before sampling F.
  {
    float a = dot(d.xy, d.xy);
    float b = dot(o.xy, d.xy);
    float c = dot(o.xy, o.xy) - rho * rho;
    float disc = b * b - a * c;
    float s0 = -1e30, s1 = 1e30;
    if (a > 0.0)
    {
      if (disc < 0.0)
      {
        return false;
      }
      float root = sqrt(disc);
      s0 = (-b - root) / a;
      s1 = (-b + root) / a;
    }
    else if (c > 0.0)
    {
      return false;
    }
    if (abs(d.z) > 0.0)
    {
      float z0 = (-rho - o.z) / d.z, z1 = (rho - o.z) / d.z;
      s0 = max(s0, min(z0, z1));
      s1 = min(s1, max(z0, z1));
    }
    else if (abs(o.z) > rho)
    {
      return false;
    }
    if (s0 > s1 || s1 < sLo || s0 > sHi)
    {
      return false;
    }
  }
  // Half the volume's extent along the ray, in local units: |tau| <= 2 spans it.
  float halfSpan = (2.0 * rho + 2.0 * length(oc)) / len + 1e-6;
  float step = 0.5 * halfSpan;
  vec2 grad;
  vec4 roots;
#if SPLAT_DEGREE <= 2
  // Along the ray F is exactly (at most) quadratic in tau: its coefficients
  // from g's value, gradient and Hessian at oc. The cancellation-free
  // quadratic formula copes with a vanishing leading coefficient, so no
  // lowering or polishing is needed.
  vec2 duv = d.xy * step;
  float a0 = psSplatG(oc.xy, grad) - oc.z;
  float a1 = dot(grad, duv) - d.z * step;
  float a2 = 0.0, a3 = 0.0, a4 = 0.0;
#if SPLAT_DEGREE == 2
  a2 = splatC0VSOutput.w * duv.x * duv.x + splatC1VSOutput.x * duv.x * duv.y +
    splatC1VSOutput.y * duv.y * duv.y;
#endif
  int degree = SPLAT_DEGREE;
  int count = psSolvePolynomial(degree, a0, a1, a2, 0.0, 0.0, roots);
#else
  float f[5];
  for (int k = 0; k < 5; ++k)
  {
    vec3 p = oc + d * (step * float(k - 2));
    f[k] = psSplatG(p.xy, grad) - p.z;
  }
  float a0 = f[2];
  float a1 = (f[0] - 8.0 * f[1] + 8.0 * f[3] - f[4]) / 12.0;
  float a2 = (-f[0] + 16.0 * f[1] - 30.0 * f[2] + 16.0 * f[3] - f[4]) / 24.0;
  float a3 = (-f[0] + 2.0 * f[1] - 2.0 * f[3] + f[4]) / 12.0;
  float a4 = (f[0] - 4.0 * f[1] + 6.0 * f[2] - 4.0 * f[3] + f[4]) / 24.0;
  // Over the ray's span (|tau| <= 2) a top coefficient whose term stays
  // below 1e-4 of the others only adds roots far outside it and costs the
  // near ones their precision: lower the degree, then polish on F itself.
  float a[5] = float[5](a0, a1, a2, a3, a4);
  int degree = SPLAT_DEGREE;
  for (; degree > 1; --degree)
  {
    float lower = 0.0, scale = 1.0;
    for (int k = 0; k < degree; ++k)
    {
      lower += abs(a[k]) * scale;
      scale *= 2.0;
    }
    if (abs(a[degree]) * scale > 1e-4 * lower)
    {
      break;
    }
  }
  int count = psSolvePolynomial(degree, a0, a1, a2, a3, a4, roots);
  if (degree < SPLAT_DEGREE)
  {
    // A lowered degree has at most SPLAT_DEGREE - 1 roots.
    for (int k = 0; k < SPLAT_DEGREE - 1; ++k)
    {
      if (k < count)
      {
        roots[k] = psPolish4(a0, a1, a2, a3, a4, roots[k]);
      }
    }
  }
#endif
  // Roots ascend along the ray: the first one inside the disc and between
  // the clipping planes is the visible surface.
  float tauLo = (sLo - sc) / step, tauHi = (sHi - sc) / step; // the clipped ray
  for (int k = 0; k < SPLAT_DEGREE; ++k)
  {
    float tau = roots[k];
    if (k >= count || tau < tauLo || tau > tauHi)
    {
      continue;
    }
    vec3 p = oc + d * (step * tau);
    if (dot(p.xy, p.xy) <= rho * rho && abs(p.z) <= rho)
    {
#if SPLAT_CULL_FACES != 0
      // Face culling: a hit whose oriented normal (-grad g, 1), in the
      // splat's frame, faces away from the eye (or towards it) is not
      // there; the ray goes on to the next root.
      psSplatG(p.xy, grad);
      float facing = dot(vec3(-grad, 1.0), d);
#if (SPLAT_CULL_FACES & 1) != 0
      if (facing > 0.0)
      {
        continue;
      }
#endif
#if (SPLAT_CULL_FACES & 2) != 0
      if (facing < 0.0)
      {
        continue;
      }
#endif
#endif
      local = p;
      if (probe)
      {
        psSplatG(p.xy, grad);
        vec3 n = vec3(grad, -1.0);
        // M is a scaled rotation: the local angle is the view angle.
        silhouette = abs(dot(n, d)) < splatSilhouetteCos * length(n) * len;
      }
      return true;
    }
  }
  if (probe && SPLAT_DEGREE >= 2)
  {
    // A grazing miss: F comes close to zero at one of its extrema on the ray.
    vec4 extrema;
    int e = psSolvePolynomial(max(degree - 1, 1), a1, 2.0 * a2, 3.0 * a3, 4.0 * a4, 0.0, extrema);
    for (int k = 0; k < max(SPLAT_DEGREE - 1, 1); ++k)
    {
      float tau = extrema[k];
      if (k >= e || abs(tau) > 2.0 || tau < tauLo || tau > tauHi)
      {
        continue;
      }
      vec3 p = oc + d * (step * tau);
      if (dot(p.xy, p.xy) > rho * rho || abs(p.z) > rho)
      {
        continue;
      }
      float F = psSplatG(p.xy, grad) - p.z;
      float distance = abs(F) / length(vec3(grad, -1.0));
      silhouette = silhouette ||
        distance < footprint.x + footprint.y * (sc + step * tau);
    }
  }
  return false;
}

// The unit normal, in view coordinates and facing the ray, at a local hit.
vec3 psSplatNormal(vec3 local, mat3 Minv, vec3 rayD)
{
  vec2 grad;
  psSplatG(local.xy, grad);
  vec3 n = normalize(transpose(Minv) * vec3(grad, -1.0));
  return dot(n, rayD) > 0.0 ? -n : n;
}
//VTK::SplatDecl::End

//VTK::SplatImpl::Begin
  vec3 normalVCVSOutput;
  mat3 M = mat3(splatAxisUVSOutput, splatAxisVVSOutput, splatAxisNVSOutput);
  mat3 Minv = splatInverseVSOutput;
  float splatH = length(splatAxisNVSOutput);
  // The fragment's ray through a plane of constant view depth (z = -1 for
  // a perspective camera), where pixels are evenly spaced whatever the tilt
  // of the bounding face it was drawn on; the pixel's steps there (from the
  // projection, not from derivatives, which a face seen edge-on spoils)
  // offset the sub-pixel rays, and its size is the footprint.
  vec2 pixelPlane = splatPixelToView.xy + gl_FragCoord.xy * splatPixelStep;
  // The pixel's point on the bounding face (parallel camera: any point of
  // the ray will do) or on the view plane z = -1 (perspective).
  vec3 pixelVC = cameraParallel != 0
    ? vec3(pixelPlane + splatPixelToView.zw * vertexVCVSOutput.z, vertexVCVSOutput.z)
    : vec3(pixelPlane, -1.0);
  vec3 viewPlane = cameraParallel != 0 ? vec3(pixelVC.xy, 0.0) : pixelVC;
  vec3 pixelDX = vec3(splatPixelStep.x, 0.0, 0.0);
  vec3 pixelDY = vec3(0.0, splatPixelStep.y, 0.0);
  float pixelSize = max(length(pixelDX), length(pixelDY));
  vec2 footprint = cameraParallel != 0
    ? vec2(pixelSize / splatH, 0.0)
    : vec2(0.0, pixelSize / (length(viewPlane) * splatH));
  vec3 rayO = cameraParallel != 0 ? pixelVC : vec3(0.0);
  vec3 rayD = cameraParallel != 0 ? vec3(0.0, 0.0, -1.0) : normalize(pixelVC);
  const bool probe = SPLAT_SAMPLES > 1 || SPLAT_SHOW_SILHOUETTE != 0;
  vec3 local;
  bool splatSilhouette;
  bool hit = psCastSplat(rayO, rayD, Minv, probe, footprint, local, splatSilhouette);
  float splatCoverage = 1.0;
  vec3 nVC = vec3(0.0);
  if (hit)
  {
    nVC = psSplatNormal(local, Minv, rayD);
  }
#if SPLAT_SAMPLES > 1
  if (splatSilhouette)
  {
    // Supersample the silhouette pixel on an n x n grid.
    int hits = 0;
    float nearest = 1e30;
    vec3 normalSum = vec3(0.0);
    for (int i = 0; i < SPLAT_SAMPLES; ++i)
    {
      for (int j = 0; j < SPLAT_SAMPLES; ++j)
      {
        vec2 offset = (vec2(i, j) + 0.5) / float(SPLAT_SAMPLES) - 0.5;
        vec3 q = pixelVC + offset.x * pixelDX +
          offset.y * pixelDY;
        vec3 subO = cameraParallel != 0 ? q : vec3(0.0);
        vec3 subD = cameraParallel != 0 ? vec3(0.0, 0.0, -1.0) : normalize(q);
        vec3 subLocal;
        bool unused;
        if (psCastSplat(subO, subD, Minv, false, footprint, subLocal, unused))
        {
          ++hits;
          normalSum += psSplatNormal(subLocal, Minv, subD);
          // Depth along the view: the sub-rays' origins lie on a face
          // that may be tilted to it.
          vec3 subHit = splatCenterVCVSOutput + M * subLocal;
          float distance = cameraParallel != 0 ? -subHit.z : length(subHit);
          if (distance < nearest)
          {
            nearest = distance;
            local = subLocal;
            rayD = subD;
          }
        }
      }
    }
    hit = hits > 0;
    splatCoverage = float(hits) / float(SPLAT_SAMPLES * SPLAT_SAMPLES);
    nVC = hits > 0 ? normalize(normalSum) : nVC;
  }
#endif
  if (!hit)
  {
    discard;
  }
  vec3 hitVC = splatCenterVCVSOutput + M * local;
  vertexVC = vec4(hitVC, 1.0);
  normalVCVSOutput = nVC;
  vec4 clipPos = VCDCMatrix * vertexVC;
  // The quad is clamped into the depth range, the hit is not: clip it
  // against the near and far planes as rasterised geometry would be.
  if (clipPos.z < -clipPos.w || clipPos.z > clipPos.w)
  {
    discard;
  }
  float splatDepth = 0.5 * (clipPos.z / clipPos.w) + 0.5;
  float splatClipW = clipPos.w;
#if SPLAT_PASS == 2
  // The blending pass leaves gl_FragDepth alone, so that the depth test runs
  // before the shader on the face's depth, which is never behind the hit:
  // fragments whose face is behind the visibility depth are dropped unshaded.
  // The hit itself is tested here against a copy of that depth, give or take
  // the rounding to its format (the hardware test compared rounded values).
  if (splatDepth > texelFetch(splatVisibleDepth, ivec2(gl_FragCoord.xy), 0).r + splatDepthTolerance)
  {
    discard;
  }
#else
  gl_FragDepth = splatDepth;
#endif
#if SPLAT_PASS == 1
  // Visibility pass: the depth pushed back by delta h along the ray.
  vec4 shifted = VCDCMatrix * vec4(hitVC + rayD * (splatBlendOffset * splatH), 1.0);
  gl_FragDepth = clamp(0.5 * (shifted.z / shifted.w) + 0.5, 0.0, 1.0);
  return;
#endif
  float splatWeight = exp(-splatBlendSharpness * dot(local.xy, local.xy) /
    (splatRadiusVSOutput * splatRadiusVSOutput));
//VTK::SplatImpl::End

//VTK::SplatOutput::Begin
#if SPLAT_SHOW_SILHOUETTE
  if (splatSilhouette)
  {
    gl_FragData[0].rgb = vec3(1.0, 0.0, 1.0);
  }
#endif
#if SPLAT_PASS == 2
  float weight = splatWeight * splatCoverage;
  gl_FragData[0] = vec4(gl_FragData[0].rgb * weight, weight);
  gl_FragData[1] = vec4(splatDepth, 1.0 - splatCoverage, 0.0, 1.0);
#endif
//VTK::SplatOutput::End
