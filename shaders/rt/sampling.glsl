// The path tracer's sampling routines (raytrace/sampling.h, and core/ggx_sampling.h's
// visible normals), transcribed operation for operation for the GPU: the C++ text is
// tested by sampling_test.cpp's chi-square tests, this copy by the GPU path tracer's
// image against the CPU's (tests/gl/gpu_path_test.cpp). They are transcribed, not
// shared as brdf.glsl is, because the C++ uses std::copysign, std::clamp and
// structs with methods that GLSL has no form of. Directions are local, the normal
// along +z. `precise` keeps the compiler from fusing what the CPU rounds twice.

const float RT_PI = 3.14159265358979;

// Frame (Duff et al. 2017): s, t, n orthonormal around the unit normal n.
struct Frame {
  vec3 s, t, n;
};

Frame frameAbout(vec3 n) {
  Frame f;
  f.n = n;
  float sign = (floatBitsToUint(n.z) & 0x80000000u) != 0u ? -1.0 : 1.0;  // std::copysign(1, n.z)
  precise float a = -1.0 / (sign + n.z);
  precise float b = n.x * n.y * a;
  precise vec3 s = vec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  precise vec3 t = vec3(b, sign + n.y * n.y * a, -n.y);
  f.s = s;
  f.t = t;
  return f;
}
// Frame(normal, tangent): s along the tangent made orthogonal to n, t = n x s.
Frame frameAlong(vec3 n, vec3 tangent) {
  Frame f;
  f.n = n;
  precise vec3 s = tangent - n * rtDot(n, tangent);
  f.s = rtNormalize(s);
  precise vec3 t = vec3(n.y * f.s.z - f.s.y * n.z, n.z * f.s.x - f.s.z * n.x, n.x * f.s.y - f.s.x * n.y);  // glm::cross
  f.t = t;
  return f;
}
vec3 toLocal(Frame f, vec3 w) { return vec3(rtDot(w, f.s), rtDot(w, f.t), rtDot(w, f.n)); }
vec3 toWorld(Frame f, vec3 w) {
  precise vec3 r = w.x * f.s + w.y * f.t + w.z * f.n;
  return r;
}

// Malley's method through Shirley and Chiu's concentric map; pdf cos / pi.
vec3 sampleCosineHemisphere(vec2 u) {
  precise vec2 o = 2.0 * u - 1.0;
  vec2 d = vec2(0.0);
  if (o.x != 0.0 || o.y != 0.0) {
    bool xMajor = abs(o.x) > abs(o.y);
    float r = xMajor ? o.x : o.y, other = xMajor ? o.y : o.x;
    precise float angle = (RT_PI / 4.0) * (other / r);
    precise float theta = xMajor ? angle : RT_PI / 2.0 - angle;
    precise vec2 disk = r * vec2(cos(theta), sin(theta));
    d = disk;
  }
  precise float z = sqrt(max(0.0, 1.0 - d.x * d.x - d.y * d.y));
  return vec3(d.x, d.y, z);
}
float cosineHemispherePdf(float cosTheta) { return max(cosTheta, 0.0) / RT_PI; }

// Uniform in the cone within acos(cosMax) of +z; pdf 1 / (2 pi (1 - cosMax)).
vec3 sampleUniformCone(vec2 u, float cosMax) {
  precise float cosTheta = (1.0 - u.x) + u.x * cosMax;
  precise float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  precise float phi = 2.0 * RT_PI * u.y;
  precise vec3 w = vec3(cos(phi) * sinTheta, sin(phi) * sinTheta, cosTheta);
  return w;
}
float uniformConePdf(float cosMax) {
  precise float pdf = 1.0 / (2.0 * RT_PI * (1.0 - cosMax));
  return pdf;
}

// GGX's Smith Lambda and G1 (core/ggx_sampling.h).
float ggxSmithG1(float cosTheta, float alpha) {
  precise float c2 = max(cosTheta * cosTheta, 1e-12);
  precise float tan2 = max(0.0, 1.0 - c2) / c2;
  precise float lambda = 0.5 * (sqrt(1.0 + alpha * alpha * tan2) - 1.0);
  precise float g1 = 1.0 / (1.0 + lambda);
  return g1;
}

// Heitz 2018's visible normals (sampleGgxAnisotropicVisibleNormal: alpha.x along x,
// alpha.y along y; with equal alphas it is sampleGgxVisibleNormal, on the CPU too).
vec3 sampleGgxVisibleNormal(vec3 wo, vec2 alpha, vec2 u) {
  vec3 vh = rtNormalize(vec3(alpha.x * wo.x, alpha.y * wo.y, wo.z));
  precise float lensq = vh.x * vh.x + vh.y * vh.y;
  precise vec3 t1 = lensq > 0.0 ? vec3(-vh.y, vh.x, 0.0) / sqrt(lensq) : vec3(1.0, 0.0, 0.0);
  precise vec3 t2 = cross(vh, t1);
  precise float r = sqrt(u.x);
  precise float phi = 2.0 * RT_PI * u.y;
  precise float p1 = r * cos(phi);
  precise float s = 0.5 * (1.0 + vh.z);
  precise float p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * r * sin(phi);
  precise vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
  return rtNormalize(vec3(alpha.x * nh.x, alpha.y * nh.y, max(1e-6, nh.z)));
}

// D(h) in brdf.glsl's stable form, for a local h.
float ggxD(vec3 h, float alpha) {
  precise float a = h.z * alpha;
  precise float k = alpha / max(h.x * h.x + h.y * h.y + a * a, 1e-30);
  precise float d = k * k / RT_PI;
  return d;
}

// The density of wi = reflect(-wo, h), h a visible normal: G1(wo) D(h) / (4 wo.z).
float ggxReflectionPdf(vec3 wo, vec3 wi, float alpha) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  precise vec3 sum = wo + wi;
  vec3 h = rtNormalize(sum);
  precise float pdf = ggxSmithG1(wo.z, alpha) * ggxD(h, alpha) / (4.0 * wo.z);
  return pdf;
}

// KHR_materials_anisotropy's GGX (core/ggx_sampling.h, raytrace/sampling.h): Lambda
// and G1 of a local direction, D of a local h, and the visible-normal pdf.
float ggxAnisotropicG1(vec3 w, vec2 alpha) {
  precise float z2 = max(w.z * w.z, 1e-12);
  precise float a2Tan2 = (alpha.x * alpha.x * w.x * w.x + alpha.y * alpha.y * w.y * w.y) / z2;
  precise float lambda = 0.5 * (sqrt(1.0 + a2Tan2) - 1.0);
  precise float g1 = 1.0 / (1.0 + lambda);
  return g1;
}
float ggxAnisotropicD(vec3 h, vec2 alpha) {
  precise float a2 = alpha.x * alpha.y;
  precise vec3 f = vec3(alpha.y * h.x, alpha.x * h.y, a2 * h.z);
  precise float w2 = a2 / max(rtDot(f, f), 1e-30);
  precise float d = a2 * w2 * w2 / RT_PI;
  return d;
}
float ggxAnisotropicReflectionPdf(vec3 wo, vec3 wi, vec2 alpha) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  precise vec3 sum = wo + wi;
  vec3 h = rtNormalize(sum);
  precise float pdf = ggxAnisotropicG1(wo, alpha) * ggxAnisotropicD(h, alpha) / (4.0 * wo.z);
  return pdf;
}

vec3 reflectAbout(vec3 w, vec3 h) {
  precise vec3 r = 2.0 * rtDot(w, h) * h - w;
  return r;
}

// Veach's power heuristic, beta = 2.
float powerHeuristic(float fPdf, float gPdf) {
  precise float f2 = fPdf * fPdf, g2 = gPdf * gPdf;
  precise float sum = f2 + g2;
  return sum > 0.0 ? f2 / sum : 0.0;
}
