// EnvironmentLight (raytrace/path_tracer.h) on the GPU: the environment sampled
// through its piecewise-constant 2D distribution over the lat-long grid, whose tables
// the CPU builds (preparePathLights) and uploads as they are (GpuTracer's path
// kernel, engine/gputrace/path_kernel.cpp). Distribution1D and Distribution2D of
// raytrace/sampling.cpp transcribed. After common/brdf.glsl (BRDF_PI), rt/sky.glsl
// and common/latlong.glsl.
//
// rtEnv holds, for a grid of w x h cells: the marginal's h weights, its h + 1 CDF
// entries and its integral; then each row's w weights (row after row), each row's
// w + 1 CDF entries, and each row's integral.

layout(std430, binding = BUFFER_RT_ENVIRONMENT) readonly buffer RtEnvironment { float rtEnv[]; };

uniform ivec2 u_envSize;  // w, h
uniform int u_envBlack;   // nothing to sample: EnvironmentLight::black()

struct Distribution1D {
  int func, cdf;  // offsets into rtEnv
  int n;
  float integral;
};

Distribution1D envMarginal() {
  int h = u_envSize.y;
  return Distribution1D(0, h, h, rtEnv[2 * h + 1]);
}
Distribution1D envRow(int row) {
  int w = u_envSize.x, h = u_envSize.y;
  int funcs = 2 * h + 2, cdfs = funcs + w * h, integrals = cdfs + (w + 1) * h;
  return Distribution1D(funcs + row * w, cdfs + row * (w + 1), w, rtEnv[integrals + row]);
}

float distributionPdf(Distribution1D d, int index) { return d.integral > 0.0 ? rtEnv[d.func + index] / d.integral : 0.0; }

// Distribution1D::sample: the cell by upper_bound on the CDF, then the position in it.
float distributionSample(Distribution1D d, float u, out int index) {
  int first = 0, count = d.n + 1;
  while (count > 0) {
    int step = count / 2;
    if (!(u < rtEnv[d.cdf + first + step])) {
      first += step + 1;
      count -= step + 1;
    } else {
      count = step;
    }
  }
  int i = clamp(first - 1, 0, d.n - 1);
  while (i < d.n - 1 && rtEnv[d.cdf + i + 1] <= u) ++i;
  index = i;
  float lo = rtEnv[d.cdf + i];
  precise float width = rtEnv[d.cdf + i + 1] - lo;
  precise float du = (u - lo) / width;
  precise float x = (float(i) + clamp(width > 0.0 ? du : 0.5, 0.0, 1.0)) / float(d.n);
  return min(x, uintBitsToFloat(0x3f7fffffu));  // std::nextafter(1.0f, 0.0f)
}

// EnvironmentLight::sample: a unit direction and its solid-angle density.
vec3 envSample(vec2 u, out float pdf) {
  pdf = 0.0;
  if (u_envBlack != 0) return vec3(0.0, 1.0, 0.0);
  Distribution1D marginal = envMarginal();
  int row, column;
  float v = distributionSample(marginal, u.y, row);
  Distribution1D rowDistribution = envRow(row);
  float x = distributionSample(rowDistribution, u.x, column);
  precise float uvPdf = distributionPdf(marginal, row) * distributionPdf(rowDistribution, column);
  float sinTheta = sin(BRDF_PI * v);
  if (sinTheta <= 0.0) return vec3(0.0, 1.0, 0.0);
  precise float solidAngle = uvPdf / (2.0 * BRDF_PI * BRDF_PI * sinTheta);
  pdf = solidAngle;
  return latLongDirection(vec2(x, v));
}

// EnvironmentLight::pdf.
float envPdf(vec3 dir) {
  if (u_envBlack != 0) return 0.0;
  vec2 uv = latLongUv(dir);
  float sinTheta = sin(BRDF_PI * uv.y);
  if (sinTheta <= 0.0) return 0.0;
  int row = clamp(int(uv.y * float(u_envSize.y)), 0, u_envSize.y - 1);
  int column = clamp(int(uv.x * float(u_envSize.x)), 0, u_envSize.x - 1);
  precise float uvPdf = distributionPdf(envMarginal(), row) * distributionPdf(envRow(row), column);
  precise float solidAngle = uvPdf / (2.0 * BRDF_PI * BRDF_PI * sinTheta);
  return solidAngle;
}
