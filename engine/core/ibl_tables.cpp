#include "core/ibl_tables.h"

#include <cmath>

#include "core/sampling.h"
#include "core/ibl_sampling.h"

namespace engine {
namespace {

// The solid angle of the part of a cube face (at distance 1) from its centre to the
// corner (x, y), in face coordinates [-1, 1]^2 (Driscoll's closed form).
double cornerSolidAngle(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0)); }

double texelSolidAngle(int i, int j, int size) {
  const double x0 = 2.0 * i / size - 1.0, x1 = 2.0 * (i + 1) / size - 1.0;
  const double y0 = 2.0 * j / size - 1.0, y1 = 2.0 * (j + 1) / size - 1.0;
  return cornerSolidAngle(x0, y0) - cornerSolidAngle(x0, y1) - cornerSolidAngle(x1, y0) + cornerSolidAngle(x1, y1);
}

// A cosine-weighted direction about +z (Malley's method).
glm::vec3 cosineDirection(glm::vec2 u) {
  const float r = std::sqrt(u.x), phi = 2.0f * brdf::BRDF_PI * u.y;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(1.0f - u.x, 0.0f))};
}

}  // namespace

glm::vec3 ShIrradiance::irradiance(const glm::vec3& n) const {
  glm::vec3 e(0.0f);
  for (int i = 0; i < 9; ++i) e += coefficients[size_t(i)] * brdf::shBasis(i, n);
  return e;
}

ShIrradiance projectIrradiance(const std::vector<glm::vec3>& texels, int size) {
  // Summed in double: 6 x 256^2 terms of a few 1e-5 sr each.
  std::array<glm::dvec3, 9> sum{};
  for (int face = 0; face < 6; ++face) {
    for (int j = 0; j < size; ++j) {
      for (int i = 0; i < size; ++i) {
        const glm::vec3 d = brdf::cubeFaceDirection(face, (float(i) + 0.5f) / float(size), (float(j) + 0.5f) / float(size));
        const glm::dvec3 weighted = glm::dvec3(texels[size_t((face * size + j) * size + i)]) * texelSolidAngle(i, j, size);
        for (int k = 0; k < 9; ++k) sum[size_t(k)] += weighted * double(brdf::shBasis(k, d));
      }
    }
  }
  ShIrradiance sh;
  for (int k = 0; k < 9; ++k) sh.coefficients[size_t(k)] = glm::vec3(sum[size_t(k)] * double(brdf::shBandWeight(k)));
  return sh;
}

glm::vec3 splitSumEntry(float nDotV, float roughness, int samples) {
  const glm::vec3 n(0.0f, 0.0f, 1.0f);
  const glm::vec3 v(std::sqrt(std::max(1.0f - nDotV * nDotV, 0.0f)), 0.0f, nDotV);
  const float alpha = brdf::ggxAlpha(roughness);
  const uint32_t count = uint32_t(samples);
  double scale = 0.0, bias = 0.0, diffuse = 0.0;
  for (uint32_t i = 0; i < count; ++i) {
    const glm::vec2 u = brdf::hammersley(i, count);
    // The specular lobe: metallic 1 makes f0 the albedo and leaves no diffuse, and
    // the lobe is linear in f0, so f0 = 1 and f0 = 0 give scale + bias and bias.
    // Visible normals (the path tracer's sampler): pdf(l) = G1(v) D / (4 N.V), so the
    // estimator f N.L / pdf stays bounded even at grazing views, where drawing h
    // from D alone converged to 5 % only after tens of thousands of points.
    const glm::vec3 h = sampleGgxVisibleNormal(v, alpha, u);
    const glm::vec3 l = 2.0f * glm::dot(v, h) * h - v;
    if (l.z > 0.0f) {
      const float pdf = ggxSmithG1(v.z, alpha) * brdf::ggxDistribution(n, h, alpha) / (4.0f * v.z);
      const double weight = double(l.z) / double(pdf);
      const float one = brdf::metallicRoughnessBrdf(n, v, l, glm::vec3(1.0f), 1.0f, roughness).x;
      const float zero = brdf::metallicRoughnessBrdf(n, v, l, glm::vec3(0.0f), 1.0f, roughness).x;
      scale += double(one - zero) * weight;
      bias += double(zero) * weight;
    }
    // The diffuse lobe: a dielectric's BRDF at albedo 1 less that at albedo 0 is
    // (1 - F) / pi with f0 = 0.04; cosine-weighted directions make the estimator
    // that times pi.
    const glm::vec3 ld = cosineDirection(u);
    const float white = brdf::metallicRoughnessBrdf(n, v, ld, glm::vec3(1.0f), 0.0f, roughness).x;
    const float black = brdf::metallicRoughnessBrdf(n, v, ld, glm::vec3(0.0f), 0.0f, roughness).x;
    diffuse += double(white - black) * double(brdf::BRDF_PI) / (1.0 - 0.04);
  }
  return glm::vec3(glm::dvec3(scale, bias, diffuse) / double(count));
}

SplitSumTable makeSplitSumTable(int size, int samples) {
  SplitSumTable table;
  table.size = size;
  table.texels.resize(size_t(size * size));
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i)
      table.texels[size_t(j * size + i)] =
          splitSumEntry((float(i) + 0.5f) / float(size), (float(j) + 0.5f) / float(size), samples);
  return table;
}

}  // namespace engine
