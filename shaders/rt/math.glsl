// glm's dot and normalize as the CPU tracer computes them, unfused, for every GPU
// tracer file (rt/trace.glsl includes it).

// glm::dot's order, (x + y) + z, unfused.
float rtDot(vec3 a, vec3 b) {
  precise float r = a.x * b.x + a.y * b.y + a.z * b.z;
  return r;
}

// glm::normalize: v * (1 / sqrt(v . v)).
vec3 rtNormalize(vec3 v) {
  precise float inv = 1.0 / sqrt(rtDot(v, v));
  precise vec3 r = v * inv;
  return r;
}
