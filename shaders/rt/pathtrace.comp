#version 450 core
// The path tracer of raytrace/path_tracer.cpp on the GPU, one pixel per invocation,
// for the scenes the GPU tracer draws (what it cannot draw is refused by
// engine/gputrace/gpu_tracer.cpp before this runs). The same algorithm on the same
// numbers: the CPU's camera rays through the R2 sequence turned per pixel, a PCG32
// stream per sample, next-event estimation to every light and the environment
// weighed by the power heuristic against BSDF samples, emitters found by BSDF rays,
// Russian roulette from the same depth by the same rule. The lights come as the CPU
// prepared them (PathLight, in double where it keeps doubles).
//
// llvmpipe inlines every call, and a traversal is long: the closest hit is called
// from Li's loop only and the any hit from directLight's loop only, every light and
// the environment going through that one shadow ray.
#include "rt/trace.glsl"
#include "rt/pcg.glsl"
#include "rt/materials.glsl"
#include "common/brdf.glsl"
#include "rt/surface.glsl"
#include "rt/texture.glsl"
#include "rt/material_at.glsl"
#include "rt/sky.glsl"
#include "rt/camera.glsl"
#include "common/sampling.glsl"
#include "rt/environment_light.glsl"
#include "rt/view_layers.glsl"
#include "rt/bsdf.glsl"
#include "common/spot_cone.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

#define RT_MAX_PASS_THROUGH 64  // path_tracer.cpp's kMaxPassThrough

// PathLight, std430 (engine/gputrace/path_kernel.cpp's GpuPathLight).
struct PtLight {
  ivec4 typeShadowsFalloff;  // type (0 sun, 1 point or spot, 2 area), shadows, falloff
  vec4 powerArea;            // colour * intensity; w: an area light's area
  vec4 directionCosMax;      // sun: unit, toward it; w: the cone's cos (1: a delta);
                             // spot: its axis toward it
  vec4 radiance;             // a cone sun's radiance
  vec4 normal;               // area: the unit normal of the side it emits from
  vec4 cone;                 // point and spot: x, y the cosines of the outer and inner cones
  dvec4 position;            // point; area: the centre
  dvec4 edgeU, edgeV;
};

layout(std430, binding = BUFFER_RT_LIGHTS) readonly buffer PtLights { PtLight ptLights[]; };
// The sums of the samples so far; the CPU divides by their number.
layout(std430, binding = BUFFER_RT_OUTPUT) buffer Image { vec4 pixels[]; };
// Rays traced: primary, shadow, bounce.
layout(std430, binding = BUFFER_RT_INPUT) buffer Counters { uint rayCounters[3]; };

uniform int u_lightCount;
uniform int u_firstSample, u_spp;  // this batch: samples [first, first + spp) of each pixel
uniform int u_accumulate;          // add to the sums of the batches before
uniform int u_maxDepth, u_rouletteDepth;
uniform int u_pbr;                 // Shading::Pbr
uniform int u_coneSun;             // PathLights::coneSun: the camera sees no sky disk
uniform uvec2 u_seed;              // RenderSettings::seed, low and high words
uniform float u_coneSpread;  // pixelConeSpread: a camera sample's cone (raytrace/ray_cone.h)
uniform int u_fog;
uniform vec3 u_fogColor;
uniform float u_fogDensity;

uint primaryRays = 0u, shadowRays = 0u, bounceRays = 0u;

// ---- Lights (PathTracer::sampleLight, hitsArea) ----

// A direction toward a light and what arrives along it: radiance over the pdf, or a
// delta light's radiance-equivalent (pdf 0). toPoint: the shadow ray ends at target.
struct LightSample {
  vec3 wi, value;
  float pdf;
  bool toPoint;
  vec3 target;
};

bool sampleLight(Surface s, PtLight l, vec2 u, out LightSample ls) {
  ls.wi = vec3(0.0, 1.0, 0.0);
  ls.value = vec3(0.0);
  ls.pdf = 0.0;
  ls.toPoint = false;
  ls.target = vec3(0.0);
  int type = l.typeShadowsFalloff.x;
  if (type == 0) {
    float cosMax = l.directionCosMax.w;
    if (cosMax < 1.0) {
      ls.wi = toWorld(frameAbout(l.directionCosMax.xyz), sampleUniformCone(u, cosMax));
      ls.pdf = uniformConePdf(cosMax);
      ls.value = l.radiance.xyz / ls.pdf;
    } else {
      ls.wi = l.directionCosMax.xyz;
      ls.value = l.powerArea.xyz * BRDF_PI;
    }
    return true;
  }
  if (type == 2 && l.powerArea.w <= 0.0) return false;
  ls.toPoint = true;
  if (type == 1) {
    ls.target = vec3(l.position.xyz);
  } else {
    precise dvec3 target = l.position.xyz + (double(u.x) - 0.5lf) * l.edgeU.xyz + (double(u.y) - 0.5lf) * l.edgeV.xyz;
    ls.target = vec3(target);
  }
  precise vec3 toLight = ls.target - s.p;
  precise float d2 = rtDot(toLight, toLight);
  if (!(d2 > 0.0)) return false;
  precise vec3 wi = toLight / sqrt(d2);
  ls.wi = wi;
  if (type == 1) {
    // A point's cone holds every direction: its weight is exactly 1.
    ls.value = l.powerArea.xyz * (BRDF_PI / (l.typeShadowsFalloff.z != 0 ? d2 : 1.0)) *
               spotAttenuation(rtDot(ls.wi, l.directionCosMax.xyz), l.cone.x, l.cone.y);
    return true;
  }
  float cosLight = -rtDot(ls.wi, l.normal.xyz);
  if (cosLight <= 0.0) return false;
  precise float pdf = d2 / (l.powerArea.w * cosLight);
  ls.pdf = pdf;
  ls.value = l.powerArea.xyz / ls.pdf;
  return true;
}

// Whether the ray (o, d; v its unit direction) crosses the area light's emitting side
// before tHit, and the solid-angle density of that point as a light sample. In
// double, as the CPU.
bool hitsArea(PtLight l, vec3 o, vec3 d, vec3 v, float tHit, out float pdf) {
  pdf = 0.0;
  if (l.powerArea.w <= 0.0) return false;
  float cosLight = -rtDot(v, l.normal.xyz);
  if (cosLight <= 0.0) return false;
  dvec3 od = dvec3(o), dir = dvec3(d), n = dvec3(l.normal.xyz);
  precise dvec3 toCentre = l.position.xyz - od;
  precise double t = (toCentre.x * n.x + toCentre.y * n.y + toCentre.z * n.z) / (dir.x * n.x + dir.y * n.y + dir.z * n.z);
  if (!(t > 0.0lf) || t >= double(tHit)) return false;
  precise dvec3 q = od + t * dir - l.position.xyz;
  dvec3 eu = l.edgeU.xyz, ev = l.edgeV.xyz;
  precise double a = (q.x * eu.x + q.y * eu.y + q.z * eu.z) / (eu.x * eu.x + eu.y * eu.y + eu.z * eu.z);
  precise double b = (q.x * ev.x + q.y * ev.y + q.z * ev.z) / (ev.x * ev.x + ev.y * ev.y + ev.z * ev.z);
  if (abs(a) > 0.5lf || abs(b) > 0.5lf) return false;
  precise double distance = t * sqrt(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z);
  pdf = float(distance * distance / (double(l.powerArea.w) * double(cosLight)));
  return true;
}

// ---- Next-event estimation (PathTracer::directLight, shade) ----

// The one shadow ray of the kernel: spawnRayTo the target (tMax 1), or spawnRay
// along wi to infinity. 1 when nothing is in the way.
float transmittance(Surface s, LightSample ls) {
  vec3 o = offsetRayOrigin(s, ls.toPoint ? ls.target - s.p : ls.wi);
  precise vec3 toTarget = ls.target - o;
  return rtTransmittance(o, ls.toPoint ? toTarget : ls.wi, ls.toPoint ? 1.0 : rtInfinity(), ls.toPoint, ls.target,
                         shadowRays);
}

vec3 shade(Surface s, LightSample ls, bool shadows, Bsdf b, vec3 ng) {
  if (rtDot(ls.wi, ng) <= 0.0) return vec3(0.0);
  vec3 f = bsdfF(b, ls.wi);
  if (f == vec3(0.0) || ls.value == vec3(0.0)) return vec3(0.0);
  float visible = shadows ? transmittance(s, ls) : 1.0;
  if (visible <= 0.0) return vec3(0.0);
  float cosine = max(rtDot(b.frame.n, ls.wi), 0.0);
  float weight = ls.pdf > 0.0 ? powerHeuristic(ls.pdf, bsdfPdf(b, ls.wi)) : 1.0;
  precise vec3 c = f * ls.value * (cosine * weight * visible);
  return c;
}

// One sample of every light, then of the environment (when it is not black).
vec3 directLight(Surface s, Bsdf b, vec3 ng, inout Pcg32 rng) {
  vec3 sum = vec3(0.0);
  int count = u_lightCount + (u_envBlack == 0 ? 1 : 0);
  for (int i = 0; i < count; ++i) {
    vec2 u = pcgUniform2(rng);
    LightSample ls;
    bool shadows = true, valid;
    if (i < u_lightCount) {
      valid = sampleLight(s, ptLights[i], u, ls);
      shadows = ptLights[i].typeShadowsFalloff.y != 0;
    } else {
      ls.toPoint = false;
      ls.target = vec3(0.0);
      ls.wi = envSample(u, ls.pdf);
      valid = ls.pdf > 0.0;
      ls.value = valid ? rtSky(ls.wi, false) / ls.pdf : vec3(0.0);
    }
    if (valid) sum += shade(s, ls, shadows, b, ng);
  }
  return sum;
}

// ---- Paths (PathTracer::Li, emittersAlong) ----

// What the ray meets before tHit that no surface is: the area lights it passes and,
// escaped, a cone sun and the environment; weighed against the light samples that
// could have found them unless nothing sampled them (camera rays, mirrors).
vec3 emittersAlong(vec3 o, vec3 d, vec3 v, float tHit, bool escaped, bool countEmitters, float bsdfPdf,
                   bool cameraRay) {
  vec3 sum = vec3(0.0);
  for (int i = 0; i < u_lightCount; ++i) {
    PtLight l = ptLights[i];
    float lightPdf;
    if (l.typeShadowsFalloff.x != 2 || !hitsArea(l, o, d, v, tHit, lightPdf)) continue;
    sum += l.powerArea.xyz * (countEmitters ? 1.0 : powerHeuristic(bsdfPdf, lightPdf));
  }
  if (!escaped) return sum;
  for (int i = 0; i < u_lightCount; ++i) {
    PtLight l = ptLights[i];
    float cosMax = l.directionCosMax.w;
    if (l.typeShadowsFalloff.x != 0 || cosMax >= 1.0 || rtDot(v, l.directionCosMax.xyz) < cosMax) continue;
    sum += l.radiance.xyz * (countEmitters ? 1.0 : powerHeuristic(bsdfPdf, uniformConePdf(cosMax)));
  }
  // The camera sees the sky's sun disk; light paths find the sun through its light.
  if (cameraRay) return sum + rtSky(v, u_coneSun == 0);
  if (u_envBlack != 0) return sum;
  return sum + rtSky(v, false) * (countEmitters ? 1.0 : powerHeuristic(bsdfPdf, envPdf(v)));
}

// Beer-Lambert's coefficient per unit length: attenuationColor remains of white
// light after attenuationDistance (PathTracer::volumeAbsorption).
vec3 volumeAbsorption(RtMaterial m) {
  if (m.transmission.w <= 0.0) return vec3(0.0);
  precise vec3 k = -log(max(m.attenuation.xyz, vec3(1e-6))) / m.transmission.w;
  return k;
}

// `firstHit` receives the distance to the first surface the path scatters at (-1 when
// the camera ray escapes).
vec3 Li(vec3 o, vec3 d, float tMax, inout Pcg32 rng, out float firstHit) {
  vec3 radiance = vec3(0.0), beta = vec3(1.0);
  bool countEmitters = true;
  float bsdfPdf = 0.0;
  float coneWidth = 0.0;
  int passes = 0;  // through cut-away or transparent surfaces
  vec3 absorption = vec3(0.0);  // of the volume the ray travels in (KHR_materials_volume)
  firstHit = -1.0;
  for (int depth = 0;; ++depth) {
    RtHit hit = rtClosestHit(o, d, tMax);
    bool escaped = hit.kind == RT_NONE;
    vec3 v = rtNormalize(d);
    if (absorption != vec3(0.0)) {
      dvec3 dd = dvec3(d);
      precise double travelled = double(escaped ? tMax : hit.t) * sqrt(dd.x * dd.x + dd.y * dd.y + dd.z * dd.z);
      beta *= exp(-absorption * float(travelled));
    }
    radiance += beta * emittersAlong(o, d, v, escaped ? tMax : hit.t, escaped, countEmitters, bsdfPdf, depth == 0);
    if (escaped) break;
    Surface s = surfaceAt(hit, o, d);
    float footprint = rtFootprint(coneWidth, u_coneSpread, s, v, hit.t * sqrt(rtDot(d, d)));
    // MASK's cut-away parts and single-sided faces seen from behind are not there;
    // BLEND stops a share alpha of the paths. Either way the ray goes on unbent.
#ifdef RT_PASS_THROUGH
    float opacity = rtSurfaceOpacity(s, footprint, rtDot(s.n, v) > 0.0);
    if (opacity < 1.0 && (opacity <= 0.0 || pcgUniform(rng) >= opacity)) {
      if (++passes > RT_MAX_PASS_THROUGH) break;
      o = offsetRayOrigin(s, d);
      precise float rest = tMax - hit.t;
      tMax = rest;
      --depth;
      continue;
    }
#endif
    RtMaterial m = rtMaterialAt(s, footprint);
    if (firstHit < 0.0) {
      precise dvec3 e = dvec3(s.p) - u_cameraPosition;
      firstHit = float(sqrt(e.x * e.x + e.y * e.y + e.z * e.z));
    }
    radiance += beta * m.emission.xyz;
    if (m.metallicRoughnessUnlit.z != 0.0) {
      radiance += beta * m.colorAmbient.xyz;  // KHR_materials_unlit: its colour, no bounce
      break;
    }
    // Past the last bounce a vertex only shows what it emits.
    if (depth > u_maxDepth) break;
    bool back = rtDot(s.n, v) > 0.0;
    vec3 ng = back ? -s.n : s.n;
    vec3 ns = back ? -s.ns : s.ns;
    Bsdf b = bsdfOf(m, u_pbr != 0, ns, -v, !back);
    if (b.pMirror < 1.0) radiance += beta * directLight(s, b, ng, rng);
    vec2 u = pcgUniform2(rng);
    float uLobe = pcgUniform(rng);
    BsdfSample bs;
    // A direction under the geometric surface would leak light through it; one
    // transmitted must be under it.
    if (!bsdfSample(b, u, uLobe, bs) || (rtDot(bs.wi, ng) <= 0.0) != bs.transmitted) break;
    // In or out of a volume: its absorption applies along the next segment.
    if (m.transmission.x > 0.0 && m.transmission.z > 0.0) {
      dvec3 wi = dvec3(bs.wi), n = dvec3(s.n);
      absorption = wi.x * n.x + wi.y * n.y + wi.z * n.z < 0.0lf ? volumeAbsorption(m) : vec3(0.0);
    }
    beta *= bs.weight;
    countEmitters = bs.delta;
    bsdfPdf = bs.pdf;
    if (depth + 1 >= u_rouletteDepth) {
      float survive = min(1.0, max(beta.x, max(beta.y, beta.z)));
      if (!(survive > 0.0) || pcgUniform(rng) >= survive) break;
      beta /= survive;
    }
    ++bounceRays;
    o = offsetRayOrigin(s, bs.wi);
    d = bs.wi;
    tMax = rtInfinity();
  }
  return radiance;
}

vec3 finiteOr0(vec3 c) { return any(isnan(c)) || any(isinf(c)) ? vec3(0.0) : c; }

// PathTracer::renderPixel: samples [first, first + spp) at the R2 sequence's points
// turned by the pixel's random offset, each with a random stream of its own, summed
// in the CPU's order onto the batches before.
void main() {
  bool inside;
  ivec2 pixel = bandPixel(inside);
  if (!inside) return;
  Pcg32 pixelRng = pcgForPixel(u_seed, pixel.x, pixel.y);
  double offsetX = double(pcgUniform(pixelRng));
  double offsetY = double(pcgUniform(pixelRng));
  vec3 origin = vec3(u_cameraPosition);
  int first = max(0, u_firstSample), spp = max(1, u_spp);
  int index = bandIndex(pixel);
  vec3 sum = u_accumulate != 0 ? pixels[index].xyz : vec3(0.0);
  for (int k = first; k < first + spp; ++k) {
    precise double jx = offsetX + 0.75487766624669276lf * double(k);
    precise double jy = offsetY + 0.56984029099805327lf * double(k);
    Pcg32 rng = pcgForSample(u_seed, pixel.x, pixel.y, k);
    ++primaryRays;
    float tMax;
    vec3 d = primaryRay(double(pixel.x) + (jx - floor(jx)), double(pixel.y) + (jy - floor(jy)), tMax);
    float distance;
    vec3 c = Li(origin, d, tMax, rng, distance);
    if (distance >= 0.0 && u_fog != 0) c = mix(u_fogColor, c, clamp(exp(-u_fogDensity * distance), 0.0, 1.0));
    sum += finiteOr0(c);
  }
  pixels[index] = vec4(sum, 1.0);
  atomicAdd(rayCounters[0], primaryRays);
  atomicAdd(rayCounters[1], shadowRays);
  atomicAdd(rayCounters[2], bounceRays);
}
