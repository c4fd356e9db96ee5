#version 450 core
// One level of the split-sum's prefiltered environment (Karis 2013): for each texel
// direction R, the environment convolved with brdf.glsl's GGX lobe of the level's
// roughness, with N = V = R, weighted by N.L. The lobe is importance-sampled with
// ggxDistribution; each sample reads the source cube at the mip level whose texel
// covers the sample's share of the lobe (filtered importance sampling, Krivanek and
// Colbert 2008), so 128 samples give a smooth result. Their +1 level of bias is
// left out: it blurred roughness 0.5 by 5.9 % against the exact convolution, where
// this measures 1.55 % (tests/render/ibl_test.cpp).
#include "common/brdf.glsl"
#include "common/ibl_sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = UNIT_IBL_SOURCE) uniform samplerCube u_environment;  // mipmapped, seamless
layout(binding = IMAGE_IBL_LEVEL, rgba16f) writeonly uniform imageCube u_level;
uniform int u_size;          // of the level written
uniform float u_roughness;
uniform int u_samples;
uniform float u_sourceSize;  // of the source's level 0

void main() {
  ivec3 texel = ivec3(gl_GlobalInvocationID);
  if (texel.x >= u_size || texel.y >= u_size) return;
  vec3 n = cubeFaceDirection(texel.z, (float(texel.x) + 0.5) / float(u_size), (float(texel.y) + 0.5) / float(u_size));
  float alpha = ggxAlpha(u_roughness);
  // The solid angle of one source texel, near enough everywhere on the cube.
  float texelAngle = 4.0 * BRDF_PI / (6.0 * u_sourceSize * u_sourceSize);
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  for (int i = 0; i < u_samples; ++i) {
    vec3 h = ggxSampleHalfVector(hammersley(uint(i), uint(u_samples)), alpha, n);
    vec3 l = 2.0 * dot(n, h) * h - n;
    float nDotL = dot(n, l);
    if (nDotL <= 0.0) continue;
    // pdf(l) = D N.H / (4 V.H) = D / 4 with V = N.
    float pdf = ggxDistribution(n, h, alpha) * 0.25;
    float sampleAngle = 1.0 / (float(u_samples) * pdf);
    float lod = max(0.5 * log2(sampleAngle / texelAngle), 0.0);
    sum += textureLod(u_environment, l, lod).rgb * nDotL;
    weight += nDotL;
  }
  imageStore(u_level, texel, vec4(sum / max(weight, 1e-6), 1.0));
}
