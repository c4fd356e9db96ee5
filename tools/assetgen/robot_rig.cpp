#include "robot_rig.h"

#include <utility>

namespace assetgen {

AtlasCell atlasCell(CellId cell) {
  constexpr float kPadTexels = 4.0f;
  const int index = static_cast<int>(cell);
  const glm::vec2 size{1.0f / kAtlasColumns, 1.0f / kAtlasRows};
  const glm::vec2 origin{static_cast<float>(index % kAtlasColumns) * size.x,
                         static_cast<float>(index / kAtlasColumns) * size.y};
  const float pad = kPadTexels / static_cast<float>(kAtlasSize);
  return AtlasCell{origin + pad, origin + size - pad};
}

std::vector<Joint> robotSkeleton() {
  std::vector<Joint> joints(kJointCount);
  auto set = [&](int id, std::string name, int parent, glm::vec3 position) {
    joints[id] = Joint{std::move(name), parent, position};
  };
  set(kPelvis, "pelvis", -1, {0.0f, 0.98f, 0.0f});
  set(kSpine, "spine", kPelvis, {0.0f, 1.12f, 0.0f});
  set(kChest, "chest", kSpine, {0.0f, 1.28f, 0.0f});
  set(kNeck, "neck", kChest, {0.0f, 1.50f, 0.0f});
  set(kHead, "head", kNeck, {0.0f, 1.60f, 0.0f});
  // The robot faces +Z, so its left side is +X.
  for (int side = 0; side < 2; ++side) {
    const float x = side == 0 ? 1.0f : -1.0f;
    const char* suffix = side == 0 ? "_l" : "_r";
    const int arm = side == 0 ? kUpperArmL : kUpperArmR;
    const int leg = side == 0 ? kThighL : kThighR;
    set(arm, std::string("upperarm") + suffix, kChest, {0.22f * x, 1.43f, 0.0f});
    set(arm + 1, std::string("lowerarm") + suffix, arm, {0.265f * x, 1.16f, 0.0f});
    set(arm + 2, std::string("hand") + suffix, arm + 1, {0.30f * x, 0.91f, 0.0f});
    set(leg, std::string("thigh") + suffix, kPelvis, {0.10f * x, 0.92f, 0.0f});
    set(leg + 1, std::string("shin") + suffix, leg, {0.10f * x, 0.51f, 0.01f});
    set(leg + 2, std::string("foot") + suffix, leg + 1, {0.10f * x, 0.10f, 0.0f});
  }
  return joints;
}

namespace {

BodyPart torso() {
  BodyPart part;
  part.name = "torso";
  part.squareness = 3.0f;
  part.blend = 0.06f;
  part.sides = 24;
  part.points = {{0, 0.84f, 0}, {0, 1.12f, 0}, {0, 1.28f, 0}, {0, 1.46f, 0}, {0, 1.50f, 0}};
  part.radii = {
      {0.165f, 0.105f}, {0.145f, 0.10f}, {0.175f, 0.115f}, {0.19f, 0.12f}, {0.13f, 0.09f}};
  part.joints = {kPelvis, kSpine, kChest, kChest};
  part.cell = CellId::Torso;
  return part;
}

BodyPart neck() {
  BodyPart part;
  part.name = "neck";
  part.blend = 0.025f;
  part.sides = 12;
  part.ringSpacing = 0.015f;
  part.points = {{0, 1.44f, 0}, {0, 1.50f, 0}, {0, 1.60f, 0}, {0, 1.63f, 0}};
  part.radii = {{0.05f, 0.05f}, {0.055f, 0.055f}, {0.05f, 0.05f}, {0.05f, 0.05f}};
  part.joints = {kChest, kNeck, kHead};
  part.cell = CellId::Neck;
  return part;
}

BodyPart head() {
  BodyPart part;
  part.name = "head";
  part.squareness = 5.0f;
  part.sides = 24;
  part.ringSpacing = 0.03f;
  part.points = {{0, 1.575f, 0}, {0, 1.60f, 0}, {0, 1.84f, 0}, {0, 1.87f, 0}};
  part.radii = {{0.105f, 0.11f}, {0.125f, 0.13f}, {0.125f, 0.13f}, {0.105f, 0.11f}};
  part.joints = {kHead, kHead, kHead};
  part.cell = CellId::Head;
  return part;
}

BodyPart arm(float x, int upperArm) {
  BodyPart part;
  part.name = x > 0 ? "arm_l" : "arm_r";
  part.squareness = 2.2f;
  part.points = {{0.15f * x, 1.45f, 0}, {0.22f * x, 1.43f, 0},  {0.265f * x, 1.16f, 0},
                 {0.30f * x, 0.91f, 0}, {0.305f * x, 0.86f, 0}, {0.31f * x, 0.78f, 0}};
  // The hand is flat with the palm towards the thigh: thin along X.
  part.radii = {{0.055f, 0.055f}, {0.06f, 0.06f},   {0.045f, 0.045f},
                {0.035f, 0.04f},  {0.025f, 0.045f}, {0.02f, 0.035f}};
  part.joints = {kChest, upperArm, upperArm + 1, upperArm + 2, upperArm + 2};
  part.cell = CellId::Arm;
  return part;
}

BodyPart leg(float x, int thigh) {
  BodyPart part;
  part.name = x > 0 ? "leg_l" : "leg_r";
  part.squareness = 2.2f;
  part.blend = 0.06f;
  part.points = {{0.10f * x, 1.00f, 0},
                 {0.10f * x, 0.92f, 0},
                 {0.10f * x, 0.51f, 0.01f},
                 {0.10f * x, 0.10f, 0},
                 {0.10f * x, 0.06f, 0}};
  part.radii = {{0.07f, 0.07f}, {0.08f, 0.08f}, {0.058f, 0.06f}, {0.045f, 0.045f}, {0.04f, 0.04f}};
  part.joints = {kPelvis, thigh, thigh + 1, thigh + 2};
  part.cell = CellId::Leg;
  return part;
}

BodyPart foot(float x, int footJoint) {
  BodyPart part;
  part.name = x > 0 ? "foot_l" : "foot_r";
  part.squareness = 4.0f;
  part.points = {{0.10f * x, 0.05f, -0.07f}, {0.10f * x, 0.05f, 0.04f}, {0.10f * x, 0.045f, 0.17f}};
  part.radii = {{0.05f, 0.045f}, {0.055f, 0.05f}, {0.05f, 0.04f}};
  part.joints = {footJoint, footJoint};
  // The foot runs along Z, so its texture front is the top of the foot.
  part.front = {0.0f, 1.0f, 0.0f};
  part.cell = CellId::Foot;
  return part;
}

}  // namespace

std::vector<BodyPart> robotBodyParts() {
  return {torso(),
          neck(),
          head(),
          arm(1.0f, kUpperArmL),
          arm(-1.0f, kUpperArmR),
          leg(1.0f, kThighL),
          leg(-1.0f, kThighR),
          foot(1.0f, kFootL),
          foot(-1.0f, kFootR)};
}

std::vector<float> pointFractions(const BodyPart& part) {
  std::vector<float> fractions{0.0f};
  float length = 0.0f;
  for (size_t i = 1; i < part.points.size(); ++i) {
    length += glm::distance(part.points[i - 1], part.points[i]);
    fractions.push_back(length);
  }
  for (float& f : fractions) f /= length;
  return fractions;
}

}  // namespace assetgen
