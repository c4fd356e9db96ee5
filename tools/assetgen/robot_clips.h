#pragma once
// The robot's animation clips: "Idle", "Walk" and "Wave". Every clip is a seamless
// loop (each channel's last key equals its first), so a player may wrap it.
#include <vector>

#include "character.h"

namespace assetgen {

std::vector<Clip> robotClips(const std::vector<Joint>& skeleton);

}  // namespace assetgen
