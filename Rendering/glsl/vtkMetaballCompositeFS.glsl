//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// Shades vtkMetaballMapper's ray-cast hits (colour, view-space normal and
// depth images) with the renderer's lights and the actor's material, and
// writes them into VTK's framebuffer with their true depth, depth-tested
// against what is already there, so that other actors intersect correctly.
//
// The lights are VTK's: the declarations of vtkOpenGLRenderer's lighting
// uniforms go at the Light Dec hook (LIGHTING_COMPLEXITY 0 none, 1
// headlight, 2 directional, 3 positional), and the mapper puts one psLight
// call per light, with that light's uniforms, at the Light Impl hook;
// UpdateLightingUniforms sets them. Positional lights attenuate and spotlights cut off as in VTK's
// polygon shading.

in vec2 texCoord;
uniform sampler2D colorTexture;
uniform sampler2D normalTexture;
uniform sampler2D depthTexture;
uniform sampler2D shadowTexture; // 1 where light k (k < 4) is blocked
uniform int shadows;
uniform mat4 clipToView;
uniform int parallelProjection;
uniform float ambient;
uniform float diffuse;
uniform float specular;
uniform float specularPower;
uniform vec3 ambientColor;
uniform vec3 specularColor;
uniform float opacity;

//VTK::Light::Dec

//VTK::Output::Dec

// One light's diffuse and specular share at the hit `p` with normal `n`:
// `toLight` points from the hit to the light, `lit` is 0 in its shadow.
vec3 psLight(vec3 n, vec3 toEye, vec3 base, vec3 color, vec3 toLight, float lit)
{
  float df = lit * max(dot(n, toLight), 0.0);
  vec3 result = diffuse * df * color * base;
  if (df > 0.0 && specular > 0.0)
  {
    float sf = pow(max(dot(reflect(-toLight, n), toEye), 0.0), specularPower);
    result += lit * specular * sf * color * specularColor;
  }
  return result;
}

// A positional light's direction to it, and its attenuation and spotlight
// cut-off (VTK's: 1 / (a0 + a1 d + a2 d^2); cone angles below 90 degrees
// are spotlights with exponent `e` around `direction`).
vec3 psPositional(vec3 p, vec3 position, vec3 direction, vec3 attenuation, float cone, float e,
  out float strength)
{
  vec3 toLight = position - p;
  float d = length(toLight);
  toLight /= max(d, 1e-30);
  strength = 1.0 / max(attenuation.x + attenuation.y * d + attenuation.z * d * d, 1e-30);
  if (cone < 90.0)
  {
    float coneDot = dot(-toLight, direction);
    strength = coneDot >= cos(radians(cone)) ? strength * pow(coneDot, e) : 0.0;
  }
  return toLight;
}

void main()
{
  vec4 base = texture(colorTexture, texCoord);
  if (base.a <= 0.0)
  {
    discard;
  }
  vec3 n = normalize(texture(normalTexture, texCoord).xyz);
  float depth = texture(depthTexture, texCoord).r;
  vec4 p = clipToView * vec4(2.0 * texCoord - 1.0, 2.0 * depth - 1.0, 1.0);
  p /= p.w;
  vec3 toEye = parallelProjection != 0 ? vec3(0.0, 0.0, 1.0) : normalize(-p.xyz);
  vec4 blocked = shadows != 0 ? texture(shadowTexture, texCoord) : vec4(0.0);
#if LIGHTING_COMPLEXITY == 0
  vec3 result = base.rgb; // lighting off: the colour as it is
#else
  vec3 result = ambient * ambientColor * base.rgb;
  float strength = 1.0;
  vec3 toLight = vec3(0.0, 0.0, 1.0);
  //VTK::Light::Impl
#endif
  gl_FragData[0] = vec4(result, opacity);
  gl_FragDepth = depth;
}
