#pragma once
// Per-vertex tangents for normal mapping, for meshes that come without them.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace engine {

// One tangent per vertex of an indexed (or, with `indices` empty, non-indexed)
// triangle list: xyz is unit length and orthogonal to the vertex normal, w = +1 or
// -1 is the handedness, so that glTF's bitangent is cross(normal, xyz) * w.
// Every output is finite: a vertex whose triangles have degenerate uvs (or none)
// gets an arbitrary unit tangent orthogonal to its normal, with w = +1.
// `normals` and `uvs` have one entry per position; out-of-range indices and a
// trailing partial triangle are skipped.
std::vector<glm::vec4> generateTangents(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                        std::span<const glm::vec2> uvs, std::span<const std::uint32_t> indices);

}  // namespace engine
