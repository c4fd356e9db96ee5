#version 450 core
// Shading of scene meshes into the HDR target. Variants (#defines) are chosen per
// scene and per material: CLASSIC (the course's ambient + diffuse model) or PBR
// (glTF metallic-roughness, GGX) with its ambient (AMBIENT_SH or AMBIENT_IBL, else
// the hemisphere; common/shading.glsl), SUN_SHADOWS, POINT_SHADOWS, FOG, and the glTF
// material inputs of common/material.glsl (TEXTURED, NORMAL_MAP, MR_TEXTURE,
// EMISSIVE_TEXTURE, OCCLUSION, ALPHA_MASK) and glTF's dielectric layers
// (MATERIAL_LAYERS), with transmission (TRANSMISSION), sheen (SHEEN), anisotropy
// (ANISOTROPY) and iridescence (IRIDESCENCE). Alpha goes out with the colour: BLEND
// materials are drawn with blending on, in linear HDR. The deferred characters'
// surface pass (SURFACE_OUT) writes what the shading reads instead of shading, and
// their shading pass (SURFACE_IN) reads it back a pixel at a time
// (common/surface.glsl).
#include "common/frame.glsl"
#include "common/shading.glsl"
#include "common/shadows.glsl"
#include "common/material.glsl"
#include "common/direct_light.glsl"
#include "common/fog.glsl"
#ifdef AERIAL_PERSPECTIVE
#include "common/aerial_perspective.glsl"
#endif
#ifdef TRANSMISSION
#include "common/transmission.glsl"
#endif

#include "common/surface.glsl"
#ifndef SURFACE_IN
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
#endif
#if defined(NORMAL_MAP) || defined(CLEARCOAT_NORMAL) || defined(ANISOTROPY)
in vec4 v_tangent;
#endif

uniform float u_metallic;
uniform float u_roughness;
uniform float u_ambient;   // classic weights
uniform float u_diffuse;
uniform float u_specular;
uniform float u_shininess;
uniform float u_reflection;
uniform vec3 u_emissive;

#ifdef SURFACE_OUT
vec4 o_color;  // the surface pass writes common/surface.glsl's outputs instead
#else
layout(location = 0) out vec4 o_color;
#endif
#include "common/output.glsl"

#ifdef DEBUG_VIEW
// The viewer's debug views (render/scene_renderer.h's DebugView, by number): one
// input as it is. Data are decoded from sRGB here, so that the post pass's encoding
// gives their values back as bytes; the base colour and emission go through as
// colours.
vec3 srgbDecoded(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}

vec3 debugValue(Surface s, vec4 base, vec2 mr) {
#if DEBUG_VIEW == 1
  return srgbDecoded(s.n * 0.5 + 0.5);
#elif DEBUG_VIEW == 2
  return srgbDecoded(vec3(fract(v_uv), 0.0));
#elif DEBUG_VIEW == 3
  return base.rgb;
#elif DEBUG_VIEW == 4
  return srgbDecoded(vec3(mr.x));
#elif DEBUG_VIEW == 5
  return srgbDecoded(vec3(mr.y));
#elif DEBUG_VIEW == 6
  return srgbDecoded(vec3(materialOcclusion(v_uv)));
#elif DEBUG_VIEW == 7
  return materialEmissive(u_emissive, v_uv);
#else
  return srgbDecoded(vec3(base.a));
#endif
}
#endif

void main() {
#ifdef SURFACE_IN
  readSurface();
#endif
  vec4 base = materialBaseColor(v_uv);
  materialAlphaTest(base.a);
#ifdef UNLIT
  // KHR_materials_unlit: the base colour as it is, lit by nothing (fog still
  // falls between it and the eye).
  vec3 unlit = base.rgb;
#ifdef FOG
  unlit = applyFog(unlit, length(v_position), u_fog.rgb, u_fog.w);
#endif
#ifdef AERIAL_PERSPECTIVE
  unlit = applyAerialPerspective(unlit, v_position);
#endif
  o_color = targetColor(unlit, base.a);
  return;
#endif
  // Planes and double-sided meshes: a back face is lit as the other side (normal,
  // tangent and bitangent all flipped, which flips the perturbed normal).
#if defined(ONE_SIDED) || defined(SURFACE_IN)
  // Back faces are culled (ShaderVariant::oneSided), or the surface holds the lit
  // side's normal already.
  const float side = 1.0;
#else
  float side = gl_FrontFacing ? 1.0 : -1.0;
#endif
  vec3 geometric = normalize(v_normal);
  vec3 n = geometric;
#ifdef NORMAL_MAP
  n = materialNormal(geometric, v_tangent, v_uv);
#endif
  n *= side;
  geometric *= side;  // for the shadow lookups (common/direct_light.glsl)
#ifdef SURFACE_OUT
  writeSurface(v_position, n, v_uv);  // no normal map there: n is the geometric normal
  return;
#endif
#ifdef MATERIAL_LAYERS
  materialLayers(v_uv);
  g_clearcoatNormal = geometric;  // the surface's, before its own normal map
#ifdef CLEARCOAT_NORMAL
  g_clearcoatNormal = materialClearcoatNormal(normalize(v_normal), v_tangent, v_uv) * side;
#endif
#ifdef ANISOTROPY
  materialAnisotropy(normalize(v_normal), geometric, v_tangent);
#endif
#endif
  vec3 toEye = normalize(-v_position);
  vec2 mr = materialMetallicRoughness(u_metallic, u_roughness, v_uv);
  Surface s = Surface(base.rgb, n, toEye, v_position, mr.x, mr.y, u_ambient, u_diffuse,
                      u_specular, u_shininess, u_reflection);
#ifdef SHEEN
  surfaceSheen(s);
#endif
#ifdef IRIDESCENCE
  g_iridescenceF = surfaceIridescence(s);
#endif
#ifdef DEBUG_VIEW
  o_color = vec4(debugValue(s, base, mr), 1.0);
  return;
#endif
  vec3 color = materialEmissive(u_emissive, v_uv) + shadeAmbient(s) * materialOcclusion(v_uv);
  color += shadeDirectLight(s, geometric);
  color += reflectedEnvironment(s);
#ifdef TRANSMISSION
  color += transmittedLight(s);
#endif
#ifdef FOG
  color = applyFog(color, length(v_position), u_fog.rgb, u_fog.w);
#endif
#ifdef AERIAL_PERSPECTIVE
  color = applyAerialPerspective(color, v_position);
#endif
  o_color = targetColor(color, base.a);
}
