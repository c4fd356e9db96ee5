#version 450 core
#include "common/lighting.glsl"
#include "common/fog.glsl"

in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;

layout(binding = 0) uniform sampler2D u_baseColorTexture;
uniform vec4 u_baseColorFactor;
uniform float u_specular;
uniform float u_shininess;
uniform vec3 u_sunDirection;
uniform vec3 u_sunColor;
uniform vec3 u_skyColor;
uniform vec3 u_groundColor;
uniform vec3 u_fogColor;
uniform float u_fogDensity;

layout(location = 0) out vec4 o_color;

void main() {
  vec3 n = normalize(v_normal);
  vec3 toEye = normalize(-v_position);  // the camera sits at the origin
  vec3 albedo = texture(u_baseColorTexture, v_uv).rgb * u_baseColorFactor.rgb;
  Sun sun = Sun(u_sunDirection, u_sunColor);
  vec3 color = albedo * hemisphereAmbient(n, u_skyColor, u_groundColor) +
               blinnPhong(albedo, n, toEye, sun, u_specular, u_shininess);
  color = applyFog(color, length(v_position), u_fogColor, u_fogDensity);
  // Linear out; the sRGB render target encodes. A simple Reinhard keeps the sun's
  // highlights from clipping hard.
  o_color = vec4(color / (1.0 + color), 1.0);
}
