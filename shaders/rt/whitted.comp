#version 450 core
// The Whitted integrator of raytrace/integrator.cpp on the GPU, one pixel per
// invocation: the same camera rays (formed in double, rounded once to float), the same
// per-pixel PCG32 stream for jittered samples and area-light points, the same shadow
// rays (offset by the hit's error bound), mirror and transmitted rays, and the one BRDF
// text (common/brdf.glsl) with glTF's layers. What this path cannot draw is refused on
// the CPU side (engine/gputrace/gpu_tracer.cpp) before it gets here.
#include "rt/trace.glsl"
#include "rt/pcg.glsl"
#include "rt/materials.glsl"
#include "common/brdf.glsl"
#include "rt/surface.glsl"
#include "rt/texture.glsl"
#include "rt/material_at.glsl"
#include "rt/sky.glsl"
#include "rt/camera.glsl"

// The sheen's albedo table, where some material has a sheen (RT_SHEEN_TABLE); else
// nothing reads it.
#ifdef RT_SHEEN_TABLE
layout(std430, binding = BUFFER_RT_ENVIRONMENT) readonly buffer RtEnvironment { float rtEnv[]; };
#else
const float rtEnv[1] = float[1](0.0);
#endif
#include "rt/view_layers.glsl"
#include "common/spot_cone.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

struct RtLight {
  ivec4 typeShadowsFalloff;  // type (0 sun, 1 point or spot, 2 area), shadows, falloff
  vec4 position;             // point, spot and area (the centre); w: the inner cone's cosine
  vec4 direction;            // sun: toward the light
  vec4 radiance;             // colour * intensity
  vec4 edgeU;
  vec4 edgeV;
  vec4 cone;                 // point and spot: the axis toward the light; w: the outer cone's cosine
};

layout(std430, binding = BUFFER_RT_LIGHTS) readonly buffer RtLights { RtLight rtLights[]; };
layout(std430, binding = BUFFER_RT_OUTPUT) writeonly buffer Image { vec4 pixels[]; };
// Rays traced: primary, shadow, reflection.
layout(std430, binding = BUFFER_RT_INPUT) buffer Counters { uint rayCounters[3]; };

uniform int u_lightCount;
uniform ivec2 u_strata;  // detail::strataFor(spp)
uniform int u_spp;
uniform int u_maxDepth;  // RT_MAX_DEPTH, which sizes the arrays
// 63: Tracer::firstSolidHit passes 64 surfaces at most. A uniform, as u_rayBound:
// with the constant a compiler may unroll the loop, and with it 64 copies of the
// traversal (a suspect in the 50 s NVIDIA's driver 580 took to compile demo.json's
// kernel, not yet measured apart; llvmpipe compiles either in the same time).
uniform int u_lastPass;
uniform int u_shadowSamples;
uniform int u_pbr;       // Shading::Pbr
uniform uvec2 u_seed;    // RenderSettings::seed, low and high words
uniform vec3 u_ambientSky, u_ambientGround;
uniform float u_coneSpread;  // pixelConeSpread: a camera sample's cone (raytrace/ray_cone.h)
uniform int u_fog;
uniform vec3 u_fogColor;
uniform float u_fogDensity;
uniform int u_rayBound;  // the most rays one camera sample may trace: 2^(maxDepth + 1) - 1

// Scene::fogged: the fog's colour over what lies `distance` away.
vec3 rtFogged(vec3 color, float distance) {
  if (u_fog == 0) return color;
  return mix(u_fogColor, color, clamp(exp(-u_fogDensity * distance), 0.0, 1.0));
}

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
    // A point's cone holds every direction: its share is exactly 1. Outside a spot's
    // cone no shadow ray is traced (Tracer::sampleLight).
    float share = spotAttenuation(rtDot(wi, light.cone.xyz), light.cone.w, light.position.w);
    radiance *= share;
    if (share == 0.0) {
      visibility = 1.0;
      return radiance;
    }
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

// The course's model per light plus colour * ambient; or glTF's layered BRDF per light
// (common/brdf.glsl's layeredBrdf, the CPU's own text) and the hemisphere ambient
// scaled by the material.
vec3 shade(Surface s, RtMaterial m, vec3 n, vec3 v, ViewLayers view, inout Pcg32 rng) {
  vec3 albedo = m.colorAmbient.xyz;
  vec4 dssr = m.diffuseSpecularShininessReflection;
  float metallic = m.metallicRoughnessUnlit.x, roughness = m.metallicRoughnessUnlit.y;
  vec3 f0 = m.dielectric.xyz;
  float f90 = m.dielectric.w, clearcoat = m.coatSheen.x, clearcoatRoughness = m.coatSheen.y;
  float transmission = m.transmission.x, iridescence = m.coatSheen.w;
  vec3 sheenColor = m.sheenColorFilmIor.xyz;
  vec3 toEye = -v;
  float nDotV = max(rtDot(n, toEye), 1e-4);
  vec3 color = u_pbr != 0 ? vec3(0.0) : albedo * m.colorAmbient.w;
  for (int i = 0; i < u_lightCount; ++i) {
    vec3 wi;
    float visibility;
    vec3 radiance = sampleLight(s, rtLights[i], rng, wi, visibility);
    if (u_pbr == 0) {
      if (visibility <= 0.0) continue;
      color += radiance * visibility * classicReflected(n, toEye, wi, albedo, dssr.x, dssr.y, dssr.z);
    } else {
      float nDotL = rtDot(n, wi);
      if (nDotL <= 0.0 || visibility <= 0.0) continue;
      vec3 f = layeredBrdf(n, toEye, wi, albedo, metallic, roughness, f0, f90, n, clearcoat, clearcoatRoughness,
                           transmission, sheenColor, m.coatSheen.z, view.sheenScale, view.anisotropyT,
                           view.anisotropyB, view.anisotropy, view.iridescenceF, iridescence);
      color += radiance * visibility * brdfLightFactor(f, nDotL);
    }
  }
  if (u_pbr != 0) {
    vec3 ambientLight = mix(u_ambientGround, u_ambientSky, 0.5 + 0.5 * n.y);
    color += ambientLight * hemisphereAmbient(albedo, metallic, roughness, f0, nDotV, clearcoat, clearcoatRoughness,
                                              transmission, sheenColor, view.sheenAlbedo, view.iridescenceF,
                                              iridescence);
  }
  return color;
}

// ---- Tracer::Li, its recursion on a stack ----

// A surface whose mirror and transmitted rays are still to come back: the frame of
// Tracer::Li at depth k is frames[k]. Its colour starts as its shading plus emission;
// the mirror's light is added when that ray's tree is done, then the transmitted
// light, as the recursion adds them, so the float sums round in the CPU's order.
struct LiFrame {
  vec3 color;
  int next;           // 0: its mirror ray, 1: its transmitted ray, 2: nothing left
  bool through;       // it has a transmitted ray
  float distance;     // from the ray's origin to the surface (fog; the parent's absorption)
  float coneWidth;    // the ray cone's width there, which both rays carry on
  float reflection;   // the mirror's weight; 0: none
  vec3 mirrorOrigin, mirrorDirection;
  vec3 share;         // Tracer::transmitted's weight
  vec3 throughOrigin, throughDirection;
  vec4 absorption;    // the volume's attenuation colour and distance, where the ray enters one (w 0: none)
};

// Tracer::transmitted's ray and weight (KHR_materials_transmission the course's way:
// straight on through a thin wall, bent by the ior into and out of a volume,
// reflected past the critical angle), the weight with Fresnel at the view angle.
// `nDotV` and `view` are the hit's (N.V is -N.v here, the same float).
void transmittedRay(inout LiFrame f, Surface s, RtMaterial m, vec3 n, vec3 v, float nDotV, ViewLayers view) {
  float metallic = m.metallicRoughnessUnlit.x;
  vec3 fresnel = schlickFresnel90(m.dielectric.xyz, m.dielectric.w, nDotV);
  precise vec3 share = transmittedShare(m.colorAmbient.xyz, metallic, m.transmission.x, fresnel) * view.sheenScale;
  f.through = true;
  f.share = share;
  vec3 d = v;
  float thickness = m.transmission.z;
  if (thickness > 0.0) {
    float ior = max(m.transmission.y, 1.0);
    d = refractAsGlm(v, n, rtDot(s.n, v) < 0.0 ? 1.0 / ior : ior);
    if (d == vec3(0.0)) {
      precise vec3 mirrored = v - 2.0 * rtDot(n, v) * n;
      d = mirrored;
    }
  }
  f.throughOrigin = offsetRayOrigin(s, d);
  f.throughDirection = d;
  bool entering = thickness > 0.0 && m.transmission.w > 0.0 && rtDot(s.n, d) < 0.0;
  f.absorption = entering ? vec4(m.attenuation.xyz, m.transmission.w) : vec4(0.0);
}

// The pixel's colour along the camera's ray. One closest-hit call site (llvmpipe
// inlines every call): each turn of the loop traces one ray, makes a frame of its
// surface or has a value (the sky, an unlit surface), then hands values up to the
// frames whose rays are all back and takes the next ray still to trace.
vec3 Li(vec3 o, vec3 d, float tMax, inout Pcg32 rng) {
  LiFrame frames[RT_MAX_DEPTH + 1];
  int depth = 0;
  float coneWidth = 0.0;
  // The bound is a uniform: a constant one lets the compiler unroll the loop, and
  // with it copies of the traversal.
  for (int ray = 0; ray < u_rayBound; ++ray) {
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
      if (pass == u_lastPass) {
        hit.kind = RT_NONE;
        break;
      }
      travelled += hit.t;
      o = offsetRayOrigin(s, d);
      precise float rest = tMax - hit.t;
      tMax = rest;
    }
    vec3 value;
    float distance = -1.0;  // Li's hitDistance: left at -1 when the ray escapes
    bool framed = false;
    if (hit.kind == RT_NONE) {
      value = rtSky(d, true);
    } else {
      vec3 v = rtNormalize(d);
      precise float along = hit.t + travelled;
      distance = along * sqrt(rtDot(d, d));
      RtMaterial m = rtMaterialAt(s, rtFootprint(coneWidth, u_coneSpread, s, v, distance));
      if (m.metallicRoughnessUnlit.z != 0.0) {
        value = m.colorAmbient.xyz;
        if (depth == 0) value = rtFogged(value, distance);
      } else {
        vec3 n = rtDot(s.n, v) > 0.0 ? -s.ns : s.ns;
        float nDotV = max(rtDot(n, -v), 1e-4);
        ViewLayers view;
        if (u_pbr != 0) view = rtViewLayers(m, n, nDotV);
        LiFrame f;
        f.color = shade(s, m, n, v, view, rng) + m.emission.xyz;
        f.next = 0;
        f.through = false;
        f.distance = distance;
        f.coneWidth = coneWidth;
        f.reflection = 0.0;
        f.share = vec3(0.0);
        bool deeper = depth < u_maxDepth;
        float reflection = m.diffuseSpecularShininessReflection.w;
        if (reflection > 0.0 && deeper) {
          precise float c1 = -rtDot(n, v);
          precise vec3 r = v + 2.0 * c1 * n;
          f.reflection = reflection;
          f.mirrorOrigin = offsetRayOrigin(s, r);
          f.mirrorDirection = r;
        }
        if (m.transmission.x > 0.0 && deeper && u_pbr != 0) transmittedRay(f, s, m, n, v, nDotV, view);
        frames[depth] = f;
        framed = true;
      }
    }
    // Hand the value up, frame by frame, until one has a ray left to trace.
    int top = framed ? depth : depth - 1;
    bool more = false;
    while (top >= 0) {
      LiFrame f = frames[top];
      if (!framed) {
        if (f.next == 1) {
          f.color += f.reflection * value;
        } else {
          vec3 light = value;
          if (f.absorption.w > 0.0 && distance >= 0.0) light *= volumeAttenuation(f.absorption.xyz, f.absorption.w, distance);
          f.color += f.share * light;
        }
      }
      framed = false;
      if (f.next == 0 && f.reflection > 0.0) {
        f.next = 1;
        o = f.mirrorOrigin;
        d = f.mirrorDirection;
        more = true;
      } else if (f.next <= 1 && f.through) {
        f.next = 2;
        o = f.throughOrigin;
        d = f.throughDirection;
        more = true;
      }
      frames[top] = f;
      if (more) {
        ++reflectionRays;
        depth = top + 1;
        coneWidth = f.coneWidth;
        tMax = rtInfinity();
        break;
      }
      value = top == 0 ? rtFogged(f.color, f.distance) : f.color;
      distance = f.distance;
      --top;
    }
    if (!more) return value;
  }
  return vec3(0.0);
}

void main() {
  bool inside;
  ivec2 pixel = bandPixel(inside);
  if (!inside) return;
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
  pixels[bandIndex(pixel)] = vec4(jitter ? sum / float(u_spp) : sum, 1.0);
  atomicAdd(rayCounters[0], primaryRays);
  atomicAdd(rayCounters[1], shadowRays);
  atomicAdd(rayCounters[2], reflectionRays);
}
