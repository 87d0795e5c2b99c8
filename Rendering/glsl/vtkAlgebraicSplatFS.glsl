// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// Ray casting of one algebraic splat, substituted by vtkAlgebraicSplatMapper
// at the //VTK::Depth::Impl hook of VTK's polydata fragment shader (the
// declarations go to //VTK::Normal::Dec). In the splat's normalised frame
// (u, v, w) = M^-1 (x - centre), with M = [h t, h b, h n], the ray meets
// F(s) = g(u(s), v(s)) - w(s) = 0. The ray is re-centred at its closest
// approach to the splat and scaled so that the volume spans |tau| <= 2;
// F is sampled at tau = -2..2, which gives its (at most quartic)
// coefficients exactly, and solved in closed form. The nearest root inside
// the splat's cylinder (the disc, at most R above or below it, as in the
// thesis's Figure 3.1) is the hit: its normal comes from the gradient of g, its depth
// goes to gl_FragDepth, and VTK's lighting shades it.
//
// SPLAT_DEGREE (1 to 4) is defined by the mapper.

//VTK::SplatDecl::Begin

uniform mat4 VCDCMatrix;
in vec3 splatCenterVCVSOutput;
in vec3 splatAxisUVSOutput;
in vec3 splatAxisVVSOutput;
in vec3 splatAxisNVSOutput;
in float splatRadiusVSOutput;
in vec4 splatC0VSOutput;
in vec4 splatC1VSOutput;
in vec4 splatC2VSOutput;
in vec4 splatC3VSOutput;

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
//VTK::SplatDecl::End

//VTK::SplatImpl::Begin
  vec3 normalVCVSOutput;
  mat3 M = mat3(splatAxisUVSOutput, splatAxisVVSOutput, splatAxisNVSOutput);
  mat3 Minv = inverse(M);
  vec3 rayO = cameraParallel != 0 ? vertexVC.xyz : vec3(0.0);
  vec3 rayD = cameraParallel != 0 ? vec3(0.0, 0.0, -1.0) : normalize(vertexVC.xyz);
  vec3 o = Minv * (rayO - splatCenterVCVSOutput);
  vec3 d = Minv * rayD;
  float dd = dot(d, d);
  float sc = -dot(o, d) / dd;            // closest approach to the centre
  vec3 oc = o + sc * d;
  float len = sqrt(dd);
  float rho = splatRadiusVSOutput;
  // Half the volume's extent along the ray, in local units: |tau| <= 2 spans it.
  float halfSpan = (2.0 * rho + 2.0 * length(oc)) / len + 1e-6;
  float step = 0.5 * halfSpan;
  float f[5];
  vec2 gradUnused;
  for (int k = 0; k < 5; ++k)
  {
    vec3 p = oc + d * (step * float(k - 2));
    f[k] = psSplatG(p.xy, gradUnused) - p.z;
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
    float lower = 0.0;
    for (int k = 0; k < degree; ++k)
    {
      lower += abs(a[k]) * pow(2.0, float(k));
    }
    if (abs(a[degree]) * pow(2.0, float(degree)) > 1e-4 * lower)
    {
      break;
    }
  }
  vec4 roots;
  int count = psSolvePolynomial(degree, a0, a1, a2, a3, a4, roots);
  if (degree < SPLAT_DEGREE)
  {
    for (int k = 0; k < 4; ++k)
    {
      if (k < count)
      {
        roots[k] = psPolish4(a0, a1, a2, a3, a4, roots[k]);
      }
    }
  }
  bool hit = false;
  vec3 local = vec3(0.0);
  // Roots ascend along the ray: the first one inside the disc and in front
  // of the eye is the visible surface.
  float sEye = -sc / step; // tau of the ray origin
  for (int k = 0; k < 4; ++k)
  {
    if (k >= count || hit)
    {
      continue;
    }
    float tau = roots[k];
    if (cameraParallel == 0 && tau <= sEye)
    {
      continue;
    }
    vec3 p = oc + d * (step * tau);
    if (dot(p.xy, p.xy) <= rho * rho && abs(p.z) <= rho)
    {
      hit = true;
      local = p;
    }
  }
  if (!hit)
  {
    discard;
  }
  vec2 grad;
  psSplatG(local.xy, grad);
  vec3 hitVC = splatCenterVCVSOutput + M * local;
  vec3 nVC = normalize(transpose(Minv) * vec3(grad, -1.0));
  if (dot(nVC, rayD) > 0.0)
  {
    nVC = -nVC;
  }
  vertexVC = vec4(hitVC, 1.0);
  normalVCVSOutput = nVC;
  vec4 clipPos = VCDCMatrix * vertexVC;
  // The quad is clamped into the depth range, the hit is not: clip it
  // against the near and far planes as rasterised geometry would be.
  if (clipPos.z < -clipPos.w || clipPos.z > clipPos.w)
  {
    discard;
  }
  gl_FragDepth = 0.5 * (clipPos.z / clipPos.w) + 0.5;
//VTK::SplatImpl::End
