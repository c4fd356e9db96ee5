#pragma once
// Paints the robot's base-colour atlas: one cell per kind of body part, coloured in
// bands that follow the joints (read from the same body parts as the mesh), with
// panel lines, a face, a chest emblem and knee pads so texturing is easy to see.
#include <vector>

#include "core/image.h"
#include "robot_rig.h"

namespace assetgen {

engine::Image paintRobotAlbedo(const std::vector<BodyPart>& parts);

}  // namespace assetgen
