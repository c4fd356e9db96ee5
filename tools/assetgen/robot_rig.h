#pragma once
// The robot's skeleton and the shape of its body parts. The mesh builder, the
// texture painter and the clips all read these tables, so a joint moved here moves
// the geometry, the painted bands and the animation pivots together.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "character.h"

namespace assetgen {

enum JointId : int {
  kPelvis,
  kSpine,
  kChest,
  kNeck,
  kHead,
  kUpperArmL,
  kLowerArmL,
  kHandL,
  kUpperArmR,
  kLowerArmR,
  kHandR,
  kThighL,
  kShinL,
  kFootL,
  kThighR,
  kShinR,
  kFootR,
  kJointCount
};

// A rectangle of the texture atlas in uv units (v grows downwards, as in glTF).
struct AtlasCell {
  glm::vec2 min{0.0f};
  glm::vec2 max{1.0f};
};

enum class CellId : int { Head, Torso, Arm, Leg, Neck, Foot, Cap, Spare, Count };

inline constexpr int kAtlasSize = 512;
inline constexpr int kAtlasColumns = 4;
inline constexpr int kAtlasRows = 2;

// The cell's rectangle, shrunk by a few texels so that filtering never reaches the
// neighbouring cell.
AtlasCell atlasCell(CellId cell);

// A tube swept through `points`: segment k (points k to k+1) follows joints[k], and
// at each inner point the two neighbouring joints blend over `blend` metres so the
// surface bends smoothly. The cross-section is a superellipse (exponent 2: ellipse,
// larger: boxier) with half-extents `radii` (side, front) interpolated per point.
struct BodyPart {
  std::string name;
  std::vector<glm::vec3> points;
  std::vector<glm::vec2> radii;
  std::vector<int> joints;
  float squareness = 2.0f;
  float blend = 0.05f;
  int sides = 16;
  float ringSpacing = 0.025f;
  // Which way the texture's front (u = 0.5) faces; the seam (u = 0) is opposite.
  glm::vec3 front{0.0f, 0.0f, 1.0f};
  CellId cell = CellId::Spare;
};

std::vector<Joint> robotSkeleton();
std::vector<BodyPart> robotBodyParts();

// Where along the part each point lies, as a fraction of its length (0 to 1): the v
// coordinate of that point inside the part's atlas cell.
std::vector<float> pointFractions(const BodyPart& part);

}  // namespace assetgen
