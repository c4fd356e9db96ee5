// The flattened scene's std430 structs (gputrace/gpu_layout.h's GpuNode, GpuNode4,
// GpuLeaf, GpuInstance, GpuSphere, GpuPlane, GpuTriangle) and its reference
// encoding (raytrace/bvh.h): what rt/trace.glsl reads and rt/refit.comp writes.
// Built with RT_WIDTH, 8 or 4.

// Four children per vec4: one side for a 4-wide node, two for an 8-wide one.
#define RT_SIDES (RT_WIDTH / 4)

struct RtNode {
  vec4 box[6 * RT_SIDES];  // box[RT_SIDES * row + side]: row min x, y, z, max x, y, z of children 4 side .. 4 side + 3
  uvec4 child[RT_SIDES];
};
struct RtLeaf {
  vec4 p[9];  // p[3 * vertex + axis][lane]
};
struct RtInstance {
  vec4 boundsMin;
  vec4 boundsMax;
  uvec4 root;
};
struct RtSphere {
  vec4 centerRadius;
  ivec4 material;
};
struct RtPlane {
  vec4 normalD;
  vec4 pointExtent;
  vec4 axisU;  // w: material
  vec4 axisV;
};
struct RtTriangle {
  vec4 n[3];  // n[0].w material, n[1].w 1 with vertex normals
};

const uint RT_LEAF_BIT = 0x80000000u;
const uint RT_NO_CHILD = 0xffffffffu;
const uint RT_MAX_TRIANGLES = 0x10000000u;
