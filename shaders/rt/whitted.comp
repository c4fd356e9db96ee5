#version 450 core
// The Whitted integrator of raytrace/integrator.cpp on the GPU, one pixel per
// invocation: the same camera rays (formed in double, rounded once to float), the same
// per-pixel PCG32 stream for jittered samples and area-light points, the same shadow
// rays (offset by the hit's error bound), mirror bounces and the one BRDF text
// (common/brdf.glsl). What this path cannot draw yet (textures, alpha, image skies) is
// refused on the CPU side (engine/gputrace/gpu_tracer.cpp) before it gets here.
#include "rt/trace.glsl"
#include "rt/pcg.glsl"
#include "rt/materials.glsl"
#include "common/brdf.glsl"
#include "rt/surface.glsl"
#include "rt/texture.glsl"
#include "rt/material_at.glsl"
#include "rt/sky.glsl"
#include "rt/camera.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

struct RtLight {
  ivec4 typeShadowsFalloff;  // type (0 sun, 1 point, 2 area), shadows, falloff
  vec4 position;             // point and area (the centre)
  vec4 direction;            // sun: toward the light
  vec4 radiance;             // colour * intensity
  vec4 edgeU;
  vec4 edgeV;
};

layout(std430, binding = BUFFER_RT_LIGHTS) readonly buffer RtLights { RtLight rtLights[]; };
layout(std430, binding = BUFFER_RT_OUTPUT) writeonly buffer Image { vec4 pixels[]; };
// Rays traced: primary, shadow, reflection.
layout(std430, binding = BUFFER_RT_INPUT) buffer Counters { uint rayCounters[3]; };

uniform int u_lightCount;
uniform ivec2 u_strata;  // detail::strataFor(spp)
uniform int u_spp;
uniform int u_maxDepth;  // RT_MAX_DEPTH, which sizes the arrays
uniform int u_shadowSamples;
uniform int u_pbr;       // Shading::Pbr
uniform uvec2 u_seed;    // RenderSettings::seed, low and high words
uniform vec3 u_ambientSky, u_ambientGround;
uniform float u_coneSpread;  // pixelConeSpread: a camera sample's cone (raytrace/ray_cone.h)
uniform int u_fog;
uniform vec3 u_fogColor;
uniform float u_fogDensity;

uint primaryRays = 0u, shadowRays = 0u, reflectionRays = 0u;

// ---- Lights (Tracer::sampleLight, areaVisibility) ----

// llvmpipe inlines every call, and a traversal is long: each query has one call site
// (a shadow ray here, a closest hit in Li), or compiling the kernel takes minutes.

// The light's radiance at the point, the direction to it, and its visibility: the
// sun one ray along its direction, a point one ray to it (tMax 1 on d = target - o,
// spawnRayTo), an area light N x N stratified jittered points on its rectangle.
vec3 sampleLight(Surface s, RtLight light, inout Pcg32 rng, out vec3 wi, out float visibility) {
  vec3 radiance = light.radiance.xyz;
  int type = light.typeShadowsFalloff.x;
  if (type == 0) {
    wi = rtNormalize(light.direction.xyz);
  } else if (type == 1) {
    precise vec3 toLight = light.position.xyz - s.p;
    precise float dist2 = rtDot(toLight, toLight);
    wi = toLight / sqrt(dist2);
    if (light.typeShadowsFalloff.z != 0) radiance /= dist2;
  } else {
    wi = rtNormalize(light.position.xyz - s.p);
  }
  visibility = 1.0;
  if (light.typeShadowsFalloff.y == 0) return radiance;
  int n = type == 2 ? max(1, u_shadowSamples) : 1;
  float seen = 0.0;
  for (int k = 0; k < n * n; ++k) {
    vec3 target = light.position.xyz;
    if (type == 2) {
      precise float u = (float(k % n) + pcgUniform(rng)) / float(n) - 0.5;
      precise float w = (float(k / n) + pcgUniform(rng)) / float(n) - 0.5;
      precise vec3 t = light.position.xyz + u * light.edgeU.xyz + w * light.edgeV.xyz;
      target = t;
    }
    vec3 toward = type == 0 ? wi : target - s.p;
    vec3 o = offsetRayOrigin(s, toward);
    vec3 d = type == 0 ? wi : target - o;
    seen += rtTransmittance(o, d, type == 0 ? rtInfinity() : 1.0, type != 0, target, shadowRays);
  }
  visibility = type == 2 ? seen / float(n * n) : seen;
  return radiance;
}

// ---- Shading (Tracer::shadeClassic, shadePbr) ----

vec3 shade(Surface s, RtMaterial m, vec3 n, vec3 v, inout Pcg32 rng) {
  vec3 albedo = m.colorAmbient.xyz;
  vec4 dssr = m.diffuseSpecularShininessReflection;
  float metallic = m.metallicRoughnessUnlit.x, roughness = m.metallicRoughnessUnlit.y;
  vec3 color = u_pbr != 0 ? vec3(0.0) : albedo * m.colorAmbient.w;
  for (int i = 0; i < u_lightCount; ++i) {
    vec3 wi;
    float visibility;
    vec3 radiance = sampleLight(s, rtLights[i], rng, wi, visibility);
    if (u_pbr == 0) {
      if (visibility <= 0.0) continue;
      color += radiance * visibility * classicReflected(n, -v, wi, albedo, dssr.x, dssr.y, dssr.z);
    } else {
      float nDotL = rtDot(n, wi);
      if (nDotL <= 0.0 || visibility <= 0.0) continue;
      vec3 f = metallicRoughnessBrdf(n, -v, wi, albedo, metallic, roughness);
      color += radiance * visibility * brdfLightFactor(f, nDotL);
    }
  }
  if (u_pbr != 0) {
    vec3 ambientLight = mix(u_ambientGround, u_ambientSky, 0.5 + 0.5 * n.y);
    vec3 f0 = metallicF0(albedo, metallic);
    color += ambientLight * (albedo * (1.0 - metallic) + f0 * (1.0 - roughness) * 0.5);
  }
  return color;
}

// Tracer::Li, the recursion unrolled: each bounce's own colour and mirror weight are
// kept, then summed from the deepest up as the recursion adds them, so the float
// sums round in the CPU's order.
vec3 Li(vec3 o, vec3 d, float tMax, inout Pcg32 rng) {
  vec3 own[RT_MAX_DEPTH + 1];
  float weight[RT_MAX_DEPTH + 1];
  int bounces = 0;
  float firstDistance = -1.0;
  float coneWidth = 0.0;
  // The bound is a uniform: a constant one lets the compiler unroll the loop, and
  // with it six copies of the traversal.
  for (int depth = 0; depth <= u_maxDepth; ++depth) {
    bounces = depth + 1;
    weight[depth] = 0.0;
    // Tracer::firstSolidHit: MASK's cut-away parts and single-sided faces seen from
    // behind are passed (at the full-resolution level), at most 64 of them, in a
    // scene built with RT_PASS_THROUGH (some material is not opaque or is single-sided).
    RtHit hit;
    Surface s;
    float travelled = 0.0;
    for (int pass = 0;; ++pass) {
      hit = rtClosestHit(o, d, tMax);
      if (hit.kind == RT_NONE) break;
      s = surfaceAt(hit, o, d);
#ifdef RT_PASS_THROUGH
      if (rtSurfaceOpacity(s, 0.0, rtDot(s.n, d) > 0.0) > 0.0) break;
#else
      break;
#endif
      if (pass == 63) {
        hit.kind = RT_NONE;
        break;
      }
      travelled += hit.t;
      o = offsetRayOrigin(s, d);
      precise float rest = tMax - hit.t;
      tMax = rest;
    }
    if (hit.kind == RT_NONE) {
      own[depth] = rtSky(d, true);
      break;
    }
    vec3 v = rtNormalize(d);
    precise float along = hit.t + travelled;
    float distance = along * sqrt(rtDot(d, d));
    if (depth == 0) firstDistance = distance;
    RtMaterial m = rtMaterialAt(s, rtFootprint(coneWidth, u_coneSpread, s, v, distance));
    if (m.metallicRoughnessUnlit.z != 0.0) {
      own[depth] = m.colorAmbient.xyz;
      break;
    }
    vec3 n = rtDot(s.n, v) > 0.0 ? -s.ns : s.ns;
    own[depth] = shade(s, m, n, v, rng) + m.emission.xyz;
    float reflection = m.diffuseSpecularShininessReflection.w;
    if (!(reflection > 0.0 && depth < u_maxDepth)) break;
    precise float c1 = -rtDot(n, v);
    precise vec3 r = v + 2.0 * c1 * n;
    ++reflectionRays;
    weight[depth] = reflection;
    o = offsetRayOrigin(s, r);
    d = r;
    tMax = rtInfinity();
  }
  vec3 color = own[bounces - 1];
  for (int k = bounces - 2; k >= 0; --k) color = own[k] + weight[k] * color;
  if (firstDistance >= 0.0 && u_fog != 0) {
    color = mix(u_fogColor, color, clamp(exp(-u_fogDensity * firstDistance), 0.0, 1.0));
  }
  return color;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= u_size.x || pixel.y >= u_size.y) return;
  Pcg32 rng = pcgForPixel(u_seed, pixel.x, pixel.y);
  vec3 o = vec3(u_cameraPosition);
  // One sample at the pixel's centre, or strata with a jittered point each.
  bool jitter = u_spp > 1;
  ivec2 strata = jitter ? u_strata : ivec2(1);
  vec3 sum = vec3(0.0);
  for (int k = 0; k < strata.x * strata.y; ++k) {
    double px = double(pixel.x) + 0.5lf, py = double(pixel.y) + 0.5lf;
    if (jitter) {
      px = double(pixel.x) + (double(k % strata.x) + double(pcgUniform(rng))) / double(strata.x);
      py = double(pixel.y) + (double(k / strata.x) + double(pcgUniform(rng))) / double(strata.y);
    }
    float tMax;
    vec3 d = primaryRay(px, py, tMax);
    ++primaryRays;
    vec3 c = Li(o, d, tMax, rng);
    sum = jitter ? sum + c : c;
  }
  pixels[pixel.y * u_size.x + pixel.x] = vec4(jitter ? sum / float(u_spp) : sum, 1.0);
  atomicAdd(rayCounters[0], primaryRays);
  atomicAdd(rayCounters[1], shadowRays);
  atomicAdd(rayCounters[2], reflectionRays);
}
