#version 450 core
// GPU culling (render/gpu_cull.h): one workgroup per job (an instance of a mesh).
// The instance's sphere, then each of its clusters (runs of at most 128 triangles
// of its index buffer, render/cull_math.h), against the view's frustum and the
// hierarchical-Z pyramid of the depth drawn so far (shaders/cull/hiz.comp); each
// run of visible clusters becomes one glMultiDrawElementsIndirect command at its
// first cluster's slot, every other slot an empty command. The order of the
// indices is kept, so depth ties resolve as without culling. cull_math.cpp's
// cullJobs is the CPU twin: keep the two alike, line for line.
layout(local_size_x = 64) in;

struct Cluster {
  vec3 lo;
  uint firstIndex;
  vec3 hi;
  uint indexCount;
};
struct Job {
  mat4 model;   // mesh -> camera-relative world: the draw's u_model
  vec4 sphere;  // instance bounds, camera-relative; w < 0: none
  uint firstCluster;
  uint clusterCount;  // the whole range's entry follows them
  uint firstCommand;
  uint flags;
  uint firstInstance;  // kInstances: the instance of its first cluster
  uint pad0, pad1, pad2;
};
struct Command {
  uint count;
  uint instanceCount;
  uint firstIndex;
  int baseVertex;
  uint baseInstance;
};

layout(std430, binding = BUFFER_CULL_CLUSTERS) readonly buffer Clusters { Cluster clusters[]; };
layout(std430, binding = BUFFER_CULL_JOBS) readonly buffer Jobs { Job jobs[]; };
layout(std430, binding = BUFFER_CULL_COMMANDS) writeonly buffer Commands { Command commands[]; };
// instances tested, frustum, occluded; clusters tested, frustum, occluded (cull::Counters)
layout(std430, binding = BUFFER_CULL_COUNTERS) buffer Counters { uint counters[8]; };
layout(binding = UNIT_HIZ) uniform sampler2D u_hiz;

uniform mat4 u_viewProjection;  // camera-relative world -> clip (zero-to-one, reverse-Z)
uniform ivec2 u_size;           // the depth's (level 0, not kept: the texture's mip k - 1 is level k)
uniform int u_levels;           // levels 1 to u_levels; 0: frustum only
uniform uint u_firstJob;
uniform float u_depthMargin;    // cull::kDepthMargin (tests break it on purpose: cull::View)

const uint kInstanceOnly = 1u;
const uint kInstances = 2u;  // clusters are instances of one mesh (the terrain's patches)
const uint kMergeChunk = 1024u;
const float kClipMargin = 1e-4;
const uint kVisible = 0u, kFrustum = 1u, kOccluded = 2u;
const int kHiZSpan = 8;  // cull::kHiZSpan: texels a side read at most

shared uint s_visible[kMergeChunk];

bool outsideFrustum(vec4 c[8]) {
  bool out0 = true, out1 = true, out2 = true, out3 = true, out4 = true, out5 = true;
  for (int i = 0; i < 8; ++i) {
    const vec4 p = c[i];
    const float mx = kClipMargin * (abs(p.x) + abs(p.w));
    const float my = kClipMargin * (abs(p.y) + abs(p.w));
    const float mz = kClipMargin * (abs(p.z) + abs(p.w));
    out0 = out0 && p.x < -p.w - mx;
    out1 = out1 && p.x > p.w + mx;
    out2 = out2 && p.y < -p.w - my;
    out3 = out3 && p.y > p.w + my;
    out4 = out4 && p.z < -mz;
    out5 = out5 && p.z > p.w + mz;
  }
  return out0 || out1 || out2 || out3 || out4 || out5;
}

int pixelOf(float ndc, int size, int widen) {
  const float window = clamp((ndc * 0.5 + 0.5) * float(size), -4.0, float(size) + 4.0);
  return clamp(int(floor(window)) + widen, 0, size - 1);
}

float hizAt(int level, int x, int y) { return texelFetch(u_hiz, ivec2(x, y), level - 1).r; }

bool hidden(vec4 c[8]) {
  float nearest = 0.0;
  vec2 lo = vec2(3.4e38), hi = vec2(-3.4e38);
  for (int i = 0; i < 8; ++i) {
    const vec4 p = c[i];
    if (!(p.w > 0.0)) return false;
    const vec2 ndc = vec2(p.x / p.w, p.y / p.w);
    lo = min(lo, ndc);
    hi = max(hi, ndc);
    nearest = max(nearest, p.z / p.w);
  }
  const int x0 = pixelOf(lo.x, u_size.x, -1), x1 = pixelOf(hi.x, u_size.x, 1);
  const int y0 = pixelOf(lo.y, u_size.y, -1), y1 = pixelOf(hi.y, u_size.y, 1);
  const int last = u_levels;
  int level = 1;
  while (level < last && ((x1 >> level) - (x0 >> level) >= kHiZSpan || (y1 >> level) - (y0 >> level) >= kHiZSpan))
    ++level;
  const int w = max(1, u_size.x >> level), h = max(1, u_size.y >> level);
  const int tx0 = min(x0 >> level, w - 1), tx1 = min(x1 >> level, w - 1);
  const int ty0 = min(y0 >> level, h - 1), ty1 = min(y1 >> level, h - 1);
  float farthest = hizAt(level, tx0, ty0);
  for (int ty = ty0; ty <= ty1; ++ty)
    for (int tx = tx0; tx <= tx1; ++tx) farthest = min(farthest, hizAt(level, tx, ty));
  return nearest * (1.0 + u_depthMargin) < farthest;
}

uint testBox(mat4 model, vec3 lo, vec3 hi) {
  vec4 corners[8];
  for (int i = 0; i < 8; ++i) {
    const vec3 p = vec3((i & 1) != 0 ? hi.x : lo.x, (i & 2) != 0 ? hi.y : lo.y, (i & 4) != 0 ? hi.z : lo.z);
    corners[i] = u_viewProjection * (model * vec4(p, 1.0));  // scene.vert's order
  }
  if (outsideFrustum(corners)) return kFrustum;
  if (u_levels > 0 && hidden(corners)) return kOccluded;
  return kVisible;
}

void count(uint counter) { atomicAdd(counters[counter], 1u); }

void main() {
  const Job job = jobs[u_firstJob + gl_WorkGroupID.x];
  const uint tid = gl_LocalInvocationID.x;
  const uint commandCount = (job.flags & kInstanceOnly) != 0u ? 1u : job.clusterCount;
  // The instance: the same answer in every invocation (uniform control flow).
  uint instance = kVisible;
  if (job.sphere.w >= 0.0) instance = testBox(mat4(1.0), job.sphere.xyz - vec3(job.sphere.w), job.sphere.xyz + vec3(job.sphere.w));
  if (tid == 0u) {
    count(0u);
    if (instance == kFrustum) count(1u);
    if (instance == kOccluded) count(2u);
  }
  if (instance != kVisible) {
    for (uint i = tid; i < commandCount; i += gl_WorkGroupSize.x) commands[job.firstCommand + i] = Command(0u, 0u, 0u, 0, 0u);
    return;
  }
  if ((job.flags & kInstanceOnly) != 0u) {
    const Cluster whole = clusters[job.firstCluster + job.clusterCount];
    if (tid == 0u) commands[job.firstCommand] = Command(whole.indexCount, 1u, whole.firstIndex, 0, 0u);
    return;
  }
  for (uint chunk = 0u; chunk < job.clusterCount; chunk += kMergeChunk) {
    const uint n = min(kMergeChunk, job.clusterCount - chunk);
    for (uint i = tid; i < n; i += gl_WorkGroupSize.x) {
      const Cluster c = clusters[job.firstCluster + chunk + i];
      const uint v = testBox(job.model, c.lo, c.hi);
      count(3u);
      if (v == kFrustum) count(4u);
      if (v == kOccluded) count(5u);
      s_visible[i] = v == kVisible ? 1u : 0u;
    }
    barrier();
    // Each run of visible clusters: one command at its first cluster's slot.
    for (uint i = tid; i < n; i += gl_WorkGroupSize.x) {
      Command command = Command(0u, 0u, 0u, 0, 0u);
      if (s_visible[i] != 0u && (i == 0u || s_visible[i - 1u] == 0u)) {
        uint total = 0u, run = 0u;
        for (uint j = i; j < n && s_visible[j] != 0u; ++j, ++run) total += clusters[job.firstCluster + chunk + j].indexCount;
        const Cluster head = clusters[job.firstCluster + chunk + i];
        command = (job.flags & kInstances) != 0u
                      ? Command(head.indexCount, run, head.firstIndex, 0, job.firstInstance + chunk + i)
                      : Command(total, 1u, head.firstIndex, 0, 0u);
      }
      commands[job.firstCommand + chunk + i] = command;
    }
    barrier();  // before the next chunk overwrites s_visible
  }
}
