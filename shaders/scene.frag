#version 450 core
// Shading of scene meshes into the HDR target. Variants (#defines) are chosen per
// scene and per material: CLASSIC (the course's ambient + diffuse model) or PBR
// (glTF metallic-roughness, GGX), TEXTURED, SUN_SHADOWS, POINT_SHADOWS, FOG.
#include "common/frame.glsl"
#include "common/shading.glsl"
#include "common/shadows.glsl"

in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;

#ifdef TEXTURED
layout(binding = 0) uniform sampler2D u_baseColorTexture;
#endif
uniform vec4 u_baseColorFactor;
uniform float u_metallic;
uniform float u_roughness;
uniform float u_ambient;   // classic weights
uniform float u_diffuse;
uniform float u_specular;
uniform float u_shininess;
uniform float u_reflection;
uniform vec3 u_emissive;

layout(location = 0) out vec4 o_color;

void main() {
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;  // planes and double-sided meshes
  vec3 toEye = normalize(-v_position);
  vec4 base = u_baseColorFactor;
#ifdef TEXTURED
  base *= texture(u_baseColorTexture, v_uv);
#endif
  Surface s = Surface(base.rgb, n, toEye, v_position, u_metallic, u_roughness, u_ambient, u_diffuse,
                      u_specular, u_shininess, u_reflection);
  vec3 color = u_emissive + shadeAmbient(s);
  if (u_sunDirection.w > 0.0) {
    float visibility = 1.0;
#ifdef SUN_SHADOWS
    visibility = sunShadow(v_position, n);
#endif
    color += shadeLight(s, u_sunDirection.xyz, u_sunColor.rgb, visibility);
  }
  for (int i = 0; i < u_counts.x; ++i) {
    vec3 toLight = u_pointPosition[i].xyz - v_position;
    float d2 = dot(toLight, toLight);
    float visibility = 1.0;
#ifdef POINT_SHADOWS
    if (i == 0 && u_pointColor[0].w > 0.0) visibility = pointShadow(v_position, n);
#endif
    vec3 radiance = u_pointColor[i].rgb / (u_pointPosition[i].w > 0.0 ? max(d2, 1e-8) : 1.0);
    color += shadeLight(s, toLight * inversesqrt(max(d2, 1e-30)), radiance, visibility);
  }
  color += reflectedEnvironment(s);
#ifdef FOG
  color = mix(u_fog.rgb, color, exp(-u_fog.w * length(v_position)));
#endif
  o_color = vec4(color, 1.0);
}
