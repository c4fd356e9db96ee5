#version 450 core
// The viewer's glTF meshes: classic lighting (hemisphere ambient, one sun,
// Blinn-Phong) with the base colour, normal map, emission and alpha mask of the
// glTF material (common/material.glsl). Metallic-roughness and occlusion textures
// are not read here; scene.frag does.
#include "common/lighting.glsl"
#include "common/fog.glsl"
#include "common/material.glsl"

in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
#ifdef NORMAL_MAP
in vec4 v_tangent;
#endif

uniform vec3 u_emissive;
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
  vec4 base = materialBaseColor(v_uv);
  materialAlphaTest(base.a);
  vec3 n = normalize(v_normal);
#ifdef NORMAL_MAP
  n = materialNormal(n, v_tangent, v_uv);
#endif
  if (!gl_FrontFacing) n = -n;  // double-sided materials
  vec3 toEye = normalize(-v_position);  // the camera sits at the origin
  vec3 albedo = base.rgb;
  Sun sun = Sun(u_sunDirection, u_sunColor);
  vec3 color = albedo * hemisphereAmbient(n, u_skyColor, u_groundColor) +
               blinnPhong(albedo, n, toEye, sun, u_specular, u_shininess) + materialEmissive(u_emissive, v_uv);
  color = applyFog(color, length(v_position), u_fogColor, u_fogDensity);
  // Linear out; the sRGB render target encodes. A simple Reinhard keeps the sun's
  // highlights from clipping hard. Alpha is for BLEND materials.
  o_color = vec4(color / (1.0 + color), base.a);
}
