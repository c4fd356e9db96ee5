#version 450 core
// The Whitted integrator of raytrace/integrator.cpp on the GPU, one pixel per
// invocation: the same camera rays (formed in double, rounded once to float), the same
// per-pixel PCG32 stream for jittered samples and area-light points, the same shadow
// rays (offset by the hit's error bound), mirror bounces and the one BRDF text
// (common/brdf.glsl). What this path cannot draw yet (textures, alpha, image skies) is
// refused on the CPU side (engine/gputrace/gpu_tracer.cpp) before it gets here.
#include "rt/trace.glsl"
#include "common/brdf.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

struct RtMaterial {
  vec4 colorAmbient;                         // colour, ambient
  vec4 diffuseSpecularShininessReflection;
  vec4 metallicRoughnessUnlit;               // metallic, roughness, unlit (0 or 1)
  vec4 emission;
};
struct RtLight {
  ivec4 typeShadowsFalloff;  // type (0 sun, 1 point, 2 area), shadows, falloff
  vec4 position;             // point and area (the centre)
  vec4 direction;            // sun: toward the light
  vec4 radiance;             // colour * intensity
  vec4 edgeU;
  vec4 edgeV;
};

layout(std430, binding = BUFFER_RT_MATERIALS) readonly buffer RtMaterials { RtMaterial rtMaterials[]; };
layout(std430, binding = BUFFER_RT_LIGHTS) readonly buffer RtLights { RtLight rtLights[]; };
layout(std430, binding = BUFFER_RT_OUTPUT) writeonly buffer Image { vec4 pixels[]; };
// Rays traced: primary, shadow, reflection.
layout(std430, binding = BUFFER_RT_INPUT) buffer Counters { uint rayCounters[3]; };

uniform int u_lightCount;
uniform ivec2 u_size;
uniform ivec2 u_strata;  // detail::strataFor(spp)
uniform int u_spp;
uniform int u_maxDepth;  // RT_MAX_DEPTH, which sizes the arrays
uniform int u_shadowSamples;
uniform int u_pbr;       // Shading::Pbr
uniform uvec2 u_seed;    // RenderSettings::seed, low and high words
// PinholeCamera, in double as there.
uniform dvec3 u_cameraPosition, u_cameraRight, u_cameraUp, u_cameraForward;
uniform dvec2 u_cameraScale;  // xScale, yScale
uniform double u_farPlane;
// Environment: 0 the background colour, 1 the gradient sky (with the last sun's disk).
uniform int u_skyKind;
uniform vec3 u_background, u_zenith, u_horizon, u_ground;
uniform int u_sunDisk;  // the gradient draws a disk toward u_sun
uniform vec3 u_sun;
uniform vec3 u_ambientSky, u_ambientGround;
uniform int u_fog;
uniform vec3 u_fogColor;
uniform float u_fogDensity;

uint primaryRays = 0u, shadowRays = 0u, reflectionRays = 0u;

// ---- PCG32 (raytrace/rng.h) in 64-bit words made of two uints (lo, hi) ----

uvec2 u64Add(uvec2 a, uvec2 b) {
  uint carry;
  uint lo = uaddCarry(a.x, b.x, carry);
  return uvec2(lo, a.y + b.y + carry);
}
uvec2 u64Mul(uvec2 a, uvec2 b) {
  uint hi, lo;
  umulExtended(a.x, b.x, hi, lo);
  return uvec2(lo, hi + a.x * b.y + a.y * b.x);
}
uvec2 u64Shr(uvec2 a, int n) {  // 0 < n < 64
  if (n >= 32) return uvec2(a.y >> (n - 32), 0u);
  return uvec2((a.x >> n) | (a.y << (32 - n)), a.y >> n);
}
uvec2 u64Shl1(uvec2 a) { return uvec2(a.x << 1, (a.y << 1) | (a.x >> 31)); }

uvec2 mixBits(uvec2 v) {
  v ^= u64Shr(v, 31);
  v = u64Mul(v, uvec2(0x728ea185u, 0x7fb5d329u));
  v ^= u64Shr(v, 27);
  v = u64Mul(v, uvec2(0xbc2dd44du, 0x81dadef4u));
  v ^= u64Shr(v, 33);
  return v;
}

struct Pcg32 {
  uvec2 state, inc;
};

uint pcgNext(inout Pcg32 g) {
  uvec2 old = g.state;
  g.state = u64Add(u64Mul(old, uvec2(0x4c957f2du, 0x5851f42du)), g.inc);
  uint xorShifted = u64Shr(u64Shr(old, 18) ^ old, 27).x;
  uint rot = old.y >> 27;
  return (xorShifted >> rot) | (xorShifted << ((~rot + 1u) & 31u));
}

float pcgUniform(inout Pcg32 g) { return float(pcgNext(g) >> 8) * 5.9604644775390625e-8; }

Pcg32 pcgForPixel(int x, int y) {
  uvec2 key = uvec2(uint(y), uint(x));
  Pcg32 g;
  uvec2 seed = mixBits(u_seed ^ mixBits(key));
  g.state = uvec2(0u);
  g.inc = u64Shl1(mixBits(u64Add(key, uvec2(0x7f4a7c15u, 0x9e3779b9u)))) | uvec2(1u, 0u);
  pcgNext(g);
  g.state = u64Add(g.state, seed);
  pcgNext(g);
  return g;
}

// ---- Hits as SurfaceInteraction (raytrace/shapes.h) ----

struct Surface {
  vec3 p, pError, n, ns;
  int material;
};

float nextUp(float v) {
  if (isinf(v) && v > 0.0) return v;
  if (v == 0.0) return uintBitsToFloat(1u);
  uint bits = floatBitsToUint(v);
  return uintBitsToFloat(v > 0.0 ? bits + 1u : bits - 1u);
}
float nextDown(float v) {
  if (isinf(v) && v < 0.0) return v;
  if (v == 0.0) return -uintBitsToFloat(1u);
  uint bits = floatBitsToUint(v);
  return uintBitsToFloat(v > 0.0 ? bits - 1u : bits + 1u);
}

// offsetRayOrigin (ray.h): off the surface by more than the point's error bound.
vec3 offsetRayOrigin(Surface s, vec3 w) {
  precise float d = rtDot(abs(s.n), s.pError);
  precise vec3 offset = s.n * d;
  if (rtDot(w, s.n) < 0.0) offset = -offset;
  precise vec3 po = s.p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0.0) po[i] = nextUp(po[i]);
    else if (offset[i] < 0.0) po[i] = nextDown(po[i]);
  }
  return po;
}

// glm::normalize: v * (1 / sqrt(v . v)).
vec3 rtNormalize(vec3 v) {
  precise float inv = 1.0 / sqrt(rtDot(v, v));
  precise vec3 r = v * inv;
  return r;
}

Surface surfaceAt(RtHit hit, vec3 o, vec3 d) {
  Surface s;
  precise vec3 at = o + d * hit.t;
  if (hit.kind == RT_SPHERE) {
    RtSphere sp = rtSpheres[hit.index];
    precise vec3 local = at - sp.centerRadius.xyz;
    s.n = local / sqrt(rtDot(local, local));
    s.p = sp.centerRadius.xyz + s.n * sp.centerRadius.w;
    s.pError = RT_GAMMA8 * (abs(sp.centerRadius.xyz) + vec3(sp.centerRadius.w));
    s.ns = s.n;
    s.material = sp.material.x;
  } else if (hit.kind == RT_PLANE) {
    RtPlane pl = rtPlanes[hit.index];
    precise vec3 p = at - (rtDot(pl.normalD.xyz, at) - pl.normalD.w) * pl.normalD.xyz;
    s.p = p;
    s.pError = RT_GAMMA8 * (abs(p) + vec3(abs(pl.normalD.w)));
    s.n = pl.normalD.xyz;
    s.ns = s.n;
    s.material = int(pl.axisU.w);
  } else {
    RtLeaf l = rtLeaves[hit.slot / 4u];
    int lane = int(hit.slot % 4u);
    vec3 p0 = vec3(l.p[0][lane], l.p[1][lane], l.p[2][lane]);
    vec3 p1 = vec3(l.p[3][lane], l.p[4][lane], l.p[5][lane]);
    vec3 p2 = vec3(l.p[6][lane], l.p[7][lane], l.p[8][lane]);
    vec3 b = hit.bary;
    precise vec3 p = b.x * p0 + b.y * p1 + b.z * p2;
    s.p = p;
    s.pError = RT_GAMMA7 * (abs(b.x * p0) + abs(b.y * p1) + abs(b.z * p2));
    precise vec3 n = cross(p1 - p0, p2 - p0);
    float len = sqrt(rtDot(n, n));
    s.n = len > 0.0 ? n / len : vec3(0.0, 1.0, 0.0);
    s.ns = s.n;
    RtTriangle tri = rtTriangles[hit.index];
    if (tri.n[1].w > 0.0) {
      precise vec3 ns = b.x * tri.n[0].xyz + b.y * tri.n[1].xyz + b.z * tri.n[2].xyz;
      float nsLen = sqrt(rtDot(ns, ns));
      if (nsLen > 0.0) s.ns = ns / nsLen;
    }
    s.material = int(tri.n[0].w);
  }
  return s;
}

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
    ++shadowRays;
    seen += rtAnyHit(o, d, type == 0 ? rtInfinity() : 1.0) ? 0.0 : 1.0;
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

// Environment::radiance for the background and the gradient sky.
vec3 escaped(vec3 dir) {
  if (u_skyKind == 0) return u_background;
  vec3 d = rtNormalize(dir);
  vec3 color = d.y >= 0.0 ? mix(u_horizon, u_zenith, sqrt(d.y)) : mix(u_horizon, u_ground, sqrt(-d.y));
  if (u_sunDisk != 0) {
    float c = rtDot(d, u_sun);
    float s = clamp((c - 0.9995) / (0.9998 - 0.9995), 0.0, 1.0);
    color += vec3(4.0, 3.6, 3.0) * (s * s * (3.0 - 2.0 * s));
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
  // The bound is a uniform: a constant one lets the compiler unroll the loop, and
  // with it six copies of the traversal.
  for (int depth = 0; depth <= u_maxDepth; ++depth) {
    bounces = depth + 1;
    weight[depth] = 0.0;
    RtHit hit = rtClosestHit(o, d, tMax);
    if (hit.kind == RT_NONE) {
      own[depth] = escaped(d);
      break;
    }
    vec3 v = rtNormalize(d);
    float distance = hit.t * sqrt(rtDot(d, d));
    if (depth == 0) firstDistance = distance;
    Surface s = surfaceAt(hit, o, d);
    RtMaterial m = rtMaterials[s.material];
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

// PinholeCamera::generateRay and clippedToFarPlane: formed in double, rounded once.
vec3 primaryRay(double px, double py, out float tMax) {
  double x = (2.0lf * px / double(u_size.x) - 1.0lf) * u_cameraScale.x;
  double y = -(2.0lf * py / double(u_size.y) - 1.0lf) * u_cameraScale.y;
  precise dvec3 v = dvec3(x, y, 1.0lf);
  precise dvec3 local = v * (1.0lf / sqrt(v.x * v.x + v.y * v.y + v.z * v.z));
  precise dvec3 d = local.x * u_cameraRight + local.y * u_cameraUp + local.z * u_cameraForward;
  vec3 df = vec3(d);
  tMax = rtInfinity();
  precise double depthPerT = double(df.x) * u_cameraForward.x + double(df.y) * u_cameraForward.y + double(df.z) * u_cameraForward.z;
  if (depthPerT > 0.0lf) tMax = min(tMax, float(u_farPlane / depthPerT));
  ++primaryRays;
  return df;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= u_size.x || pixel.y >= u_size.y) return;
  Pcg32 rng = pcgForPixel(pixel.x, pixel.y);
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
    vec3 c = Li(o, d, tMax, rng);
    sum = jitter ? sum + c : c;
  }
  pixels[pixel.y * u_size.x + pixel.x] = vec4(jitter ? sum / float(u_spp) : sum, 1.0);
  atomicAdd(rayCounters[0], primaryRays);
  atomicAdd(rayCounters[1], shadowRays);
  atomicAdd(rayCounters[2], reflectionRays);
}
