// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// Real roots of polynomials of degree 1 to 4 in float, for ray casting
// algebraic splats: F(t) = c0 + c1 t + c2 t^2 + c3 t^3 + c4 t^4 along a ray.
// No version line: this file is substituted into shaders at their
// //VTK::SplatRoots::Dec hook. Roots come back in ascending order; each
// function returns how many it found.
//
// - Quadratic: the cancellation-free formula (q = -(b + sign(b) sqrt(D)) / 2;
//   roots q / a and c / q), exact for tiny leading coefficients.
// - Cubic: trigonometric or Cardano form on the monic cubic after scaling t
//   so that its coefficients are at most 1 (no overflow when the leading
//   coefficient is small), then two Newton steps on the original cubic.
// - Quartic: Ferrari's method through the resolvent cubic, on the same
//   scaled monic form, then two Newton steps on the original quartic.
//   Known limit: Ferrari's shift by a/4 costs the small roots their digits
//   when the roots span more than about 1e3 (see TestSplatRootSolvers); the
//   ray caster keeps its roots of interest near 1 by starting each ray at
//   the splat's bounding volume.
// - A leading coefficient below psLeadingEpsilon times the largest one
//   lowers the degree: the roots it drops lie beyond about 1/psLeadingEpsilon
//   times the scale of the others, outside any splat's bounding volume.
//
// PS_MAX_DEGREE (default 4), defined before this file, leaves the solvers of
// higher degrees out of psSolvePolynomial: the splat shader of degree 2
// never needs a cubic, and a software rasteriser would run it anyway.

#ifndef PS_MAX_DEGREE
#define PS_MAX_DEGREE 4
#endif

const float psLeadingEpsilon = 1e-7;

void psSort2(inout float a, inout float b)
{
  float lo = min(a, b);
  b = max(a, b);
  a = lo;
}

int psSolveQuadratic(float c0, float c1, float c2, out vec2 r)
{
  r = vec2(0.0);
  if (c2 == 0.0)
  {
    if (c1 == 0.0)
    {
      return 0;
    }
    r = vec2(-c0 / c1);
    return 1;
  }
  float disc = c1 * c1 - 4.0 * c2 * c0;
  if (disc < 0.0)
  {
    return 0;
  }
  float q = -0.5 * (c1 + (c1 >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
  float t0 = q / c2;
  float t1 = q != 0.0 ? c0 / q : t0;
  r = vec2(min(t0, t1), max(t0, t1));
  return 2;
}

// Newton steps, each kept only if it lowers |p|: next to a double root p'
// is nearly zero and an unguarded step can jump far.
float psPolish3(float c0, float c1, float c2, float c3, float t)
{
  float f = ((c3 * t + c2) * t + c1) * t + c0;
  for (int i = 0; i < 2; ++i)
  {
    float d = (3.0 * c3 * t + 2.0 * c2) * t + c1;
    if (d == 0.0)
    {
      break;
    }
    float next = t - f / d;
    float g = ((c3 * next + c2) * next + c1) * next + c0;
    if (!(abs(g) < abs(f)))
    {
      break;
    }
    t = next;
    f = g;
  }
  return t;
}

int psSolveCubic(float c0, float c1, float c2, float c3, out vec3 r)
{
  r = vec3(0.0);
  float big = max(max(abs(c0), abs(c1)), abs(c2));
  if (abs(c3) <= psLeadingEpsilon * big)
  {
    vec2 q;
    int n = psSolveQuadratic(c0, c1, c2, q);
    r = vec3(q, 0.0);
    return n;
  }
  // Monic, then t = s u with s chosen so that every coefficient is <= 1.
  float a = c2 / c3, b = c1 / c3, c = c0 / c3;
  float s = max(max(abs(a), sqrt(abs(b))), pow(abs(c), 1.0 / 3.0));
  if (s == 0.0)
  {
    return 1; // t^3 = 0
  }
  a /= s;
  b /= s * s;
  c /= s * s * s;
  float Q = (a * a - 3.0 * b) / 9.0;
  float R = (2.0 * a * a * a - 9.0 * a * b + 27.0 * c) / 54.0;
  float Q3 = Q * Q * Q;
  int n;
  if (R * R < Q3)
  {
    float phi = acos(clamp(R / sqrt(Q3), -1.0, 1.0)) / 3.0;
    float m = -2.0 * sqrt(Q);
    // cos(phi + 2 pi / 3) and cos(phi - 2 pi / 3) from one cosine and one sine.
    float cp = cos(phi), sp = 0.86602540378 * sin(phi);
    r = m * vec3(cp, -0.5 * cp - sp, -0.5 * cp + sp) - a / 3.0;
    n = 3;
  }
  else
  {
    // R^2 >= Q^3 here, but a GPU may fuse R * R - Q3 into one rounding
    // (NVIDIA does) and take it below zero next to a double root: the square
    // root of that was NaN, and the quartic's resolvent lost every root.
    float A = (R > 0.0 ? -1.0 : 1.0) * pow(abs(R) + sqrt(max(R * R - Q3, 0.0)), 1.0 / 3.0);
    float B = A != 0.0 ? Q / A : 0.0;
    r = vec3(A + B - a / 3.0);
    n = 1;
  }
  for (int i = 0; i < 3; ++i)
  {
    r[i] = psPolish3(c0, c1, c2, c3, r[i] * s);
  }
  if (n == 3)
  {
    psSort2(r.x, r.y);
    psSort2(r.y, r.z);
    psSort2(r.x, r.y);
  }
  return n;
}

float psPolish4(float c0, float c1, float c2, float c3, float c4, float t)
{
  float f = (((c4 * t + c3) * t + c2) * t + c1) * t + c0;
  for (int i = 0; i < 2; ++i)
  {
    float d = ((4.0 * c4 * t + 3.0 * c3) * t + 2.0 * c2) * t + c1;
    if (d == 0.0)
    {
      break;
    }
    float next = t - f / d;
    float g = (((c4 * next + c3) * next + c2) * next + c1) * next + c0;
    if (!(abs(g) < abs(f)))
    {
      break;
    }
    t = next;
    f = g;
  }
  return t;
}

int psSolveQuartic(float c0, float c1, float c2, float c3, float c4, out vec4 r)
{
  r = vec4(0.0);
  float big = max(max(max(abs(c0), abs(c1)), abs(c2)), abs(c3));
  if (abs(c4) <= psLeadingEpsilon * big)
  {
    vec3 q;
    int n = psSolveCubic(c0, c1, c2, c3, q);
    r = vec4(q, 0.0);
    return n;
  }
  float a = c3 / c4, b = c2 / c4, c = c1 / c4, d = c0 / c4;
  float s = max(max(abs(a), sqrt(abs(b))), max(pow(abs(c), 1.0 / 3.0), sqrt(sqrt(abs(d)))));
  if (s == 0.0)
  {
    return 1; // t^4 = 0
  }
  a /= s;
  b /= s * s;
  c /= s * s * s;
  d /= s * s * s * s;
  // Depressed quartic y^4 + p y^2 + q y + e with t = s (y - a / 4).
  float a2 = a * a;
  float p = b - 0.375 * a2;
  float q = c - 0.5 * a * b + 0.125 * a2 * a;
  float e = d - 0.25 * a * c + 0.0625 * a2 * b - 0.01171875 * a2 * a2;
  float y[4];
  int n = 0;
  // Resolvent cubic z^3 + 2 p z^2 + (p^2 - 4 e) z - q^2: its largest root.
  vec3 z3;
  int nz = psSolveCubic(-q * q, p * p - 4.0 * e, 2.0 * p, 1.0, z3);
  float z = z3.x;
  for (int i = 1; i < nz; ++i)
  {
    z = max(z, z3[i]);
  }
  if (z <= 1e-12)
  {
    // Biquadratic: w^2 + p w + e with w = y^2.
    vec2 w;
    int nw = psSolveQuadratic(e, p, 1.0, w);
    for (int i = 0; i < nw; ++i)
    {
      if (w[i] >= 0.0)
      {
        float sw = sqrt(w[i]);
        y[n++] = -sw;
        y[n++] = sw;
      }
    }
  }
  else
  {
    float sz = sqrt(z);
    vec2 y1, y2;
    int n1 = psSolveQuadratic(0.5 * (p + z) - 0.5 * q / sz, sz, 1.0, y1);
    int n2 = psSolveQuadratic(0.5 * (p + z) + 0.5 * q / sz, -sz, 1.0, y2);
    for (int i = 0; i < n1; ++i)
    {
      y[n++] = y1[i];
    }
    for (int i = 0; i < n2; ++i)
    {
      y[n++] = y2[i];
    }
  }
  // Polish, and keep only true roots: near double roots Ferrari's quadratic
  // factors can be off, and a candidate whose residual is far above the
  // rounding of p(t) is not a root.
  int kept = 0;
  for (int i = 0; i < n; ++i)
  {
    float t = psPolish4(c0, c1, c2, c3, c4, s * (y[i] - 0.25 * a));
    float f = (((c4 * t + c3) * t + c2) * t + c1) * t + c0;
    float at = abs(t);
    float size = (((abs(c4) * at + abs(c3)) * at + abs(c2)) * at + abs(c1)) * at + abs(c0);
    if (abs(f) <= 1e-4 * size)
    {
      r[kept++] = t;
    }
  }
  n = kept;
  // Sort the n roots (n <= 4).
  for (int i = 1; i < 4; ++i)
  {
    for (int j = i; j > 0; --j)
    {
      if (j < n && r[j - 1] > r[j])
      {
        float t = r[j - 1];
        r[j - 1] = r[j];
        r[j] = t;
      }
    }
  }
  return n;
}

// Roots of c0 + c1 t + ... up to `degree` (1 to 4), ascending.
int psSolvePolynomial(int degree, float c0, float c1, float c2, float c3, float c4, out vec4 r)
{
  r = vec4(0.0);
  if (degree == 1)
  {
    if (c1 == 0.0)
    {
      return 0;
    }
    r.x = -c0 / c1;
    return 1;
  }
  if (degree == 2)
  {
    vec2 q;
    int n = psSolveQuadratic(c0, c1, c2, q);
    r.xy = q;
    return n;
  }
#if PS_MAX_DEGREE >= 3
  if (degree == 3)
  {
    vec3 q;
    int n = psSolveCubic(c0, c1, c2, c3, q);
    r.xyz = q;
    return n;
  }
#endif
#if PS_MAX_DEGREE >= 4
  return psSolveQuartic(c0, c1, c2, c3, c4, r);
#else
  return 0;
#endif
}
