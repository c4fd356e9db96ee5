#pragma once
// Four rotations interpolated at once (SoA, SSE): the normalisation that ends nlerp
// and slerp (a square root and a division per rotation) is most of their cost, and
// four lanes do it for the price of one. Each lane computes glm's operations in
// glm's order, so every lane gives the bits of the scalar nlerp / slerpAt.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace engine {

class QuatBatch {
 public:
  // Queues out = safeNormalize(a * wa + b' * wb), where b' is b flipped into a's
  // hemisphere (as nlerp does; a no-op for a slerp arc's b, which is flipped
  // already). Writes the queue when it holds four.
  void add(const glm::vec4& a, const glm::quat& b, float wa, float wb, glm::quat& out) {
    const int i = count_++;
    a_[i] = a;
    b_[i] = glm::vec4(b.x, b.y, b.z, b.w);
    wa_[i] = wa, wb_[i] = wb;
    out_[i] = &out;
    if (count_ == 4) flush();
  }
  // Writes what is queued.
  void flush();

 private:
  // Whole quaternions (x, y, z, w), transposed to SoA in registers: loading lanes
  // stored one float at a time would stall on store forwarding.
  alignas(16) glm::vec4 a_[4] = {}, b_[4] = {};
  float wa_[4] = {}, wb_[4] = {};
  glm::quat* out_[4] = {};
  int count_ = 0;
};

}  // namespace engine
