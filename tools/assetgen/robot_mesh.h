#pragma once
// Sweeps the robot's body parts into one skinned triangle mesh in bind pose.
#include <cstdint>
#include <vector>

#include "character.h"
#include "robot_rig.h"

namespace assetgen {

// Weights are multiples of 1/kWeightSteps, so two of them add up to exactly 1 in
// float and the validator's normalisation check holds without tolerance.
inline constexpr int kWeightSteps = 256;

// Appends the part's tube (and a cap at each end) to the mesh.
void appendBodyPart(const BodyPart& part, std::vector<Vertex>& vertices,
                    std::vector<std::uint16_t>& indices);

}  // namespace assetgen
