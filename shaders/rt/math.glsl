// glm's dot, cross, normalize, mix and refract as the CPU tracer computes them, unfused,
// and a modulo for negative operands, for every GPU tracer file (rt/trace.glsl includes it).

// glm::dot's order, (x + y) + z, unfused.
float rtDot(vec3 a, vec3 b) {
  precise float r = a.x * b.x + a.y * b.y + a.z * b.z;
  return r;
}

// glm::cross's operations, unfused.
vec3 rtCross(vec3 a, vec3 b) {
  precise vec3 r = vec3(a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y);
  return r;
}

// glm::normalize: v * (1 / sqrt(v . v)).
vec3 rtNormalize(vec3 v) {
  precise float inv = 1.0 / sqrt(rtDot(v, v));
  precise vec3 r = v * inv;
  return r;
}

// glm::mix: a (1 - t) + b t (GLSL's mix may round otherwise).
float mixAsGlm(float a, float b, float t) {
  precise float r = a * (1.0 - t) + b * t;
  return r;
}
vec3 mixAsGlm(vec3 a, vec3 b, float t) {
  precise vec3 r = a * (1.0 - t) + b * t;
  return r;
}
vec4 mixAsGlm(vec4 a, vec4 b, float t) {
  precise vec4 r = a * (1.0 - t) + b * t;
  return r;
}

// glm::refract(i, n, eta): the refracted direction, or 0 past the critical angle.
vec3 refractAsGlm(vec3 i, vec3 n, float eta) {
  precise float c = rtDot(n, i);
  precise float k = 1.0 - eta * eta * (1.0 - c * c);
  precise vec3 r = eta * i - (eta * c + sqrt(k)) * n;
  return k >= 0.0 ? r : vec3(0.0);
}

// i mod n into [0, n), negative i too (GLSL's % leaves negative operands undefined).
int wrapMod(int i, int n) { return i >= 0 ? i % n : (n - 1) - ((-i - 1) % n); }
