#pragma once
// Random draws the GPU tests share, in an order fixed by the code (a function's
// arguments are evaluated in an order each compiler picks: the cases must be the same
// under g++ and clang).
#include <random>

#include <glm/glm.hpp>

namespace engine::test {

// Three draws in order.
template <typename Distribution>
glm::vec3 draw3(Distribution& d, std::mt19937& rng) {
  const float x = d(rng), y = d(rng), z = d(rng);
  return {x, y, z};
}

// A direction uniform over the sphere.
inline glm::vec3 randomUnitVector(std::mt19937& rng) {
  std::normal_distribution<float> g;
  return glm::normalize(draw3(g, rng));
}

}  // namespace engine::test
