#pragma once
// Vocabulary shared by the loader (asset) and the runtime (anim) for keyframed
// tracks, so both speak of the same interpolation without depending on each other.

namespace engine {

// Which part of a node's Srt a track drives.
enum class AnimPath { Translation, Rotation, Scale };

// glTF sampler interpolation. CubicSpline keys carry three values each:
// in-tangent, value, out-tangent.
enum class Interpolation { Step, Linear, CubicSpline };

}  // namespace engine
