//VTK::System::Dec
// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
//
// Shades vtkMetaballMapper's ray-cast hits (colour, view-space normal and
// depth images) with the renderer's lights and the actor's material, and
// writes them into VTK's framebuffer with their true depth, depth-tested
// against what is already there, so that other actors intersect correctly.

in vec2 texCoord;
uniform sampler2D colorTexture;
uniform sampler2D normalTexture;
uniform sampler2D depthTexture;
uniform sampler2D shadowTexture; // 1 where light k (k < 4) is blocked
uniform int shadows;
uniform mat4 clipToView;
uniform int parallelProjection;
uniform int numberOfLights;
uniform vec3 lightColor[8];
uniform vec3 lightDirection[8]; // view space, from the light into the scene
uniform vec3 lightPosition[8];  // view space
uniform int lightPositional[8];
uniform float ambient;
uniform float diffuse;
uniform float specular;
uniform float specularPower;
uniform vec3 ambientColor;
uniform vec3 specularColor;
uniform float opacity;

//VTK::Output::Dec

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
  vec3 result = ambient * ambientColor * base.rgb;
  vec4 blocked = shadows != 0 ? texture(shadowTexture, texCoord) : vec4(0.0);
  for (int k = 0; k < 8; ++k)
  {
    if (k >= numberOfLights)
    {
      break;
    }
    vec3 toLight =
      lightPositional[k] != 0 ? normalize(lightPosition[k] - p.xyz) : -lightDirection[k];
    float lit = k < 4 ? 1.0 - blocked[k] : 1.0;
    float df = lit * max(dot(n, toLight), 0.0);
    result += diffuse * df * lightColor[k] * base.rgb;
    if (df > 0.0 && specular > 0.0)
    {
      float sf = pow(max(dot(reflect(-toLight, n), toEye), 0.0), specularPower);
      result += lit * specular * sf * lightColor[k] * specularColor;
    }
  }
  gl_FragData[0] = vec4(result, opacity);
  gl_FragDepth = depth;
}
