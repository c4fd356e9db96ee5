// GPU skinning. The palette lives in a buffer texture (gl::Texture::ofBuffer says
// why not a storage buffer), so a skin may have any number of joints. Variants,
// chosen per mesh by the renderer:
//   INFLUENCES 4 or 8      joints per vertex (8 when the file has JOINTS_1)
//   DUAL_QUAT              dual-quaternion skinning instead of linear blend
// LBS: a joint's matrix is three texels (the rows of its affine part,
// render/model_renderer.h's lbsPaletteRows); DQS: two, the real part (rotation) and
// the dual part (translation).
layout(binding = UNIT_SKIN_PALETTE) uniform samplerBuffer u_palette;

// The vertex's joints and weights: attributes here; skin.comp (SKIN_COMPUTE)
// defines a_joints0... as reads of the same buffers by invocation.
#ifndef SKIN_COMPUTE
layout(location = 3) in uvec4 a_joints0;
layout(location = 4) in vec4 a_weights0;
#if INFLUENCES == 8
layout(location = 5) in uvec4 a_joints1;
layout(location = 6) in vec4 a_weights1;
#endif
#endif

// The blended transform of a vertex is computed once and applied to the
// position, the normal and (for normal maps) the tangent: skin() below.
#ifdef DUAL_QUAT
void addDualQuat(inout vec4 real, inout vec4 dual, uint joint, float weight) {
  vec4 r = texelFetch(u_palette, int(2u * joint));
  vec4 d = texelFetch(u_palette, int(2u * joint + 1u));
  // q and -q are the same rotation; keep every one in the hemisphere of the sum
  // so far (as the CPU path does), or opposite signs cancel out.
  if (dot(real, r) < 0.0) weight = -weight;
  real += weight * r;
  dual += weight * d;
}

vec3 rotateByQuat(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }

// The blended, normalised dual quaternion as a rotation and a translation.
struct SkinTransform {
  vec4 rotation;
  vec3 translation;
};

SkinTransform skinTransform() {
  vec4 real = vec4(0.0), dual = vec4(0.0);
  addDualQuat(real, dual, a_joints0.x, a_weights0.x);
  addDualQuat(real, dual, a_joints0.y, a_weights0.y);
  addDualQuat(real, dual, a_joints0.z, a_weights0.z);
  addDualQuat(real, dual, a_joints0.w, a_weights0.w);
#if INFLUENCES == 8
  addDualQuat(real, dual, a_joints1.x, a_weights1.x);
  addDualQuat(real, dual, a_joints1.y, a_weights1.y);
  addDualQuat(real, dual, a_joints1.z, a_weights1.z);
  addDualQuat(real, dual, a_joints1.w, a_weights1.w);
#endif
  float len = length(real);
  real /= len;
  dual /= len;
  // Translation t = 2 * dual * conjugate(real).
  vec3 t = 2.0 * (real.w * dual.xyz - dual.w * real.xyz + cross(real.xyz, dual.xyz));
  return SkinTransform(real, t);
}

vec3 skinPoint(SkinTransform s, vec3 p) { return rotateByQuat(s.rotation, p) + s.translation; }
vec3 skinDirection(SkinTransform s, vec3 v) { return rotateByQuat(s.rotation, v); }
#else
// Linear blend skinning: the weighted sum of the joints' palette matrices, kept as
// rows (m[r] is row r of the affine matrix).
struct SkinTransform {
  mat3x4 m;
};

mat3x4 paletteMatrix(uint joint) {
  int i = int(3u * joint);
  return mat3x4(texelFetch(u_palette, i), texelFetch(u_palette, i + 1), texelFetch(u_palette, i + 2));
}

SkinTransform skinTransform() {
  mat3x4 m = a_weights0.x * paletteMatrix(a_joints0.x) + a_weights0.y * paletteMatrix(a_joints0.y) +
           a_weights0.z * paletteMatrix(a_joints0.z) + a_weights0.w * paletteMatrix(a_joints0.w);
#if INFLUENCES == 8
  m += a_weights1.x * paletteMatrix(a_joints1.x) + a_weights1.y * paletteMatrix(a_joints1.y) +
       a_weights1.z * paletteMatrix(a_joints1.z) + a_weights1.w * paletteMatrix(a_joints1.w);
#endif
  return SkinTransform(m);
}

vec3 skinPoint(SkinTransform s, vec3 p) { return vec4(p, 1.0) * s.m; }
// Inverse transpose would be exact for normals under non-uniform scale; skins
// rarely scale non-uniformly and the cost is per vertex. Tangents lie in the
// surface and take the matrix itself.
vec3 skinDirection(SkinTransform s, vec3 v) { return vec4(v, 0.0) * s.m; }
#endif

void skin(inout vec3 position, inout vec3 normal) {
  SkinTransform s = skinTransform();
  position = skinPoint(s, position);
  normal = skinDirection(s, normal);
}

void skin(inout vec3 position, inout vec3 normal, inout vec3 tangent) {
  SkinTransform s = skinTransform();
  position = skinPoint(s, position);
  normal = skinDirection(s, normal);
  tangent = skinDirection(s, tangent);
}
