#pragma once
// The CPU half of image-based lighting (the split-sum shortcut of Karis 2013, "Real
// Shading in Unreal Engine 4"): the BRDF table of f0's scale and bias, computed from
// core/brdf.h, the very BRDF the shaders and the path tracer evaluate; and the
// order-2 spherical-harmonic irradiance of a cube map (Ramamoorthi and Hanrahan
// 2001). GL-free: render/ibl.cpp uploads what these compute.
#include <array>
#include <vector>

#include <glm/glm.hpp>

namespace engine {

// Irradiance E(n) = integral of L(w) max(n.w, 0) dw, as nine RGB coefficients with
// the clamped cosine's band weights already applied: E(n) = sum c_i Y_i(n).
struct ShIrradiance {
  std::array<glm::vec3, 9> coefficients{};
  glm::vec3 irradiance(const glm::vec3& n) const;
};

// Projects a cube map's radiance: `texels` holds the six faces in GL's order (+x,
// -x, +y, -y, +z, -z), each `size` x `size`, rows from t = 0 (as glGetTextureImage
// returns them). Each texel weighs its exact solid angle, so the weights sum to 4 pi.
ShIrradiance projectIrradiance(const std::vector<glm::vec3>& texels, int size);

// The split-sum directional albedo of brdf.glsl's metallic-roughness lobes under
// uniform light, at N.V and roughness: x, y are the specular's scale and bias of f0
// (integral of f_spec N.L = f0 x + y), z the mean of (1 - Fresnel) / (1 - f0) over
// the diffuse lobe (its cosine-weighted directions), so that the diffuse reflects
// (1 - f0) z (1 - metallic) albedo E / pi. `samples` Hammersley points per lobe.
glm::vec3 splitSumEntry(float nDotV, float roughness, int samples);

// The table of splitSumEntry over a size x size grid of texel centres: column i at
// N.V = (i + 0.5) / size, row j at roughness (j + 0.5) / size; row-major from row 0.
struct SplitSumTable {
  int size = 0;
  std::vector<glm::vec3> texels;
};
SplitSumTable makeSplitSumTable(int size, int samples);

}  // namespace engine
