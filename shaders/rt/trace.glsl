// The CPU tracer's ray queries on the GPU: its spheres, planes and two-level BVH8
// (gputrace/gpu_layout.h flattens them; engine/render/gpu_tracer.cpp binds them),
// closest hit and any hit, written after raytrace/shapes.h, ray.h and
// bvh_traverse.inl operation for operation. `precise` keeps the compiler from fusing
// a multiply and an add, as the CPU build does not (-ffp-contract=off): the
// watertight triangle test needs both triangles at an edge to round the same way.
//
// The program is built with RT_WIDTH (8 or 4: the node layout, GpuSceneLayout::width),
// RT_STACK_SIZE (GpuSceneLayout::stackSize()) and pbrt's
// gamma(n) in float as RT_GAMMA2 .. RT_GAMMA8 and RT_WIDEN = 1 + 2 gamma(3), computed
// by the C++ compiler, so that no GPU division rounds them differently.

#include "rt/layout.glsl"
#include "rt/math.glsl"

layout(std430, binding = BUFFER_RT_NODES) readonly buffer RtNodes { RtNode rtNodes[]; };
layout(std430, binding = BUFFER_RT_LEAVES) readonly buffer RtLeaves { RtLeaf rtLeaves[]; };
layout(std430, binding = BUFFER_RT_ORDER) readonly buffer RtOrder { uint rtOrder[]; };
layout(std430, binding = BUFFER_RT_INSTANCES) readonly buffer RtInstances { RtInstance rtInstances[]; };
layout(std430, binding = BUFFER_RT_SPHERES) readonly buffer RtSpheres { RtSphere rtSpheres[]; };
layout(std430, binding = BUFFER_RT_PLANES) readonly buffer RtPlanes { RtPlane rtPlanes[]; };
layout(std430, binding = BUFFER_RT_TRIANGLES) readonly buffer RtTriangles { RtTriangle rtTriangles[]; };

// Empty arrays are bound as a placeholder buffer; these say how many there are.
uniform int u_instanceCount;
uniform int u_sphereCount;
uniform int u_planeCount;

const int RT_NONE = 0;
const int RT_SPHERE = 1;
const int RT_PLANE = 2;
const int RT_TRIANGLE = 3;

float rtInfinity() { return uintBitsToFloat(0x7f800000u); }


struct RtHit {
  float t;
  int kind;    // RT_NONE, RT_SPHERE, RT_PLANE, RT_TRIANGLE
  uint index;  // the sphere, the plane, or the triangle's global id
  uint slot;   // a triangle's leaf slot: 4 * leaf + lane
  vec3 bary;   // a triangle's barycentrics of p0, p1, p2
};

// ---- Shapes (raytrace/shapes.h) ----

// Sphere<float>::intersect; 0 when missed.
float rtSphereT(vec3 center, float radius, vec3 o, vec3 d, float tMax) {
  precise vec3 oc = o - center;
  precise float a = rtDot(d, d);
  precise float halfB = rtDot(oc, d);
  precise float c = rtDot(oc, oc) - radius * radius;
  if (c > 0.0 && halfB > 0.0) return 0.0;
  precise vec3 l = oc - (halfB / a) * d;
  precise float dist = sqrt(rtDot(l, l));
  precise float disc = 4.0 * a * ((radius - dist) * (radius + dist));
  if (!(disc >= 0.0)) return 0.0;
  precise float b = 2.0 * halfB;
  precise float root = sqrt(disc);
  precise float q = -0.5 * (b + (b < 0.0 ? -root : root));
  float t0 = q / a;
  float t1 = q != 0.0 ? c / q : t0;
  if (t0 > t1) {
    float s = t0;
    t0 = t1;
    t1 = s;
  }
  if (t0 > 0.0 && t0 < tMax) return t0;
  if (t1 > 0.0 && t1 < tMax) return t1;
  return 0.0;
}

// Plane<float>::intersect and RtScene::onPlaneSquare (in double, as there); 0 when missed.
float rtPlaneT(int i, vec3 o, vec3 d, float tMax) {
  RtPlane p = rtPlanes[i];
  precise float denom = rtDot(p.normalD.xyz, d);
  if (denom == 0.0) return 0.0;
  precise float t = (p.normalD.w - rtDot(p.normalD.xyz, o)) / denom;
  if (!(t > 0.0 && t < tMax)) return 0.0;
  if (p.pointExtent.w <= 0.0) return t;
  precise vec3 at = o + d * t;
  dvec3 local = dvec3(at) - dvec3(p.pointExtent.xyz);
  double extent = double(p.pointExtent.w);
  if (abs(dot(local, dvec3(p.axisU.xyz))) <= extent && abs(dot(local, dvec3(p.axisV.xyz))) <= extent) return t;
  return 0.0;
}

// ---- The watertight triangle test (shapes.h intersectTriangle) ----

struct RtTriangleRay {
  vec3 o;
  int kx, ky, kz;
  float sx, sy, sz;
};

// v's components kx, ky, kz by selects: a vector indexed at run time is an array a
// GPU compiler may keep in local memory, and this runs for every triangle tested.
float rtPick(vec3 v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }
vec3 rtPermute(vec3 v, RtTriangleRay r) { return vec3(rtPick(v, r.kx), rtPick(v, r.ky), rtPick(v, r.kz)); }

RtTriangleRay rtTriangleRay(vec3 o, vec3 d) {
  RtTriangleRay r;
  r.o = o;
  vec3 ad = abs(d);
  r.kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  r.kx = r.kz == 2 ? 0 : r.kz + 1;
  r.ky = r.kx == 2 ? 0 : r.kx + 1;
  vec3 dt = rtPermute(d, r);
  r.sx = -dt.x / dt.z;
  r.sy = -dt.y / dt.z;
  r.sz = 1.0 / dt.z;
  return r;
}

float rtEdge(float ax, float ay, float bx, float by) {
  precise float e = ax * by - ay * bx;
  return e;
}

// Products of floats are exact in double: the sign of a zero edge function settled.
float rtEdgeExact(float ax, float ay, float bx, float by) {
  precise double e = double(ax) * double(by) - double(ay) * double(bx);
  return float(e);
}

// The hit's t (0 when missed, as t > 0 always for a hit) and barycentrics.
float rtTriangleT(RtTriangleRay r, float tMax, vec3 p0, vec3 p1, vec3 p2, out vec3 bary) {
  precise vec3 a = p0 - r.o, b = p1 - r.o, c = p2 - r.o;
  precise vec3 p0t = rtPermute(a, r);
  precise vec3 p1t = rtPermute(b, r);
  precise vec3 p2t = rtPermute(c, r);
  p0t.x += r.sx * p0t.z;
  p0t.y += r.sy * p0t.z;
  p1t.x += r.sx * p1t.z;
  p1t.y += r.sy * p1t.z;
  p2t.x += r.sx * p2t.z;
  p2t.y += r.sy * p2t.z;
  float e0 = rtEdge(p1t.x, p1t.y, p2t.x, p2t.y);
  float e1 = rtEdge(p2t.x, p2t.y, p0t.x, p0t.y);
  float e2 = rtEdge(p0t.x, p0t.y, p1t.x, p1t.y);
  if (e0 == 0.0 || e1 == 0.0 || e2 == 0.0) {
    e0 = rtEdgeExact(p1t.x, p1t.y, p2t.x, p2t.y);
    e1 = rtEdgeExact(p2t.x, p2t.y, p0t.x, p0t.y);
    e2 = rtEdgeExact(p0t.x, p0t.y, p1t.x, p1t.y);
  }
  bary = vec3(0.0);
  if ((e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0)) return 0.0;
  precise float det = e0 + e1 + e2;
  if (det == 0.0) return 0.0;
  p0t.z *= r.sz;
  p1t.z *= r.sz;
  p2t.z *= r.sz;
  precise float tScaled = e0 * p0t.z + e1 * p1t.z + e2 * p2t.z;
  if (det < 0.0 && (tScaled >= 0.0 || tScaled < tMax * det)) return 0.0;
  if (det > 0.0 && (tScaled <= 0.0 || tScaled > tMax * det)) return 0.0;
  precise float invDet = 1.0 / det;
  precise float t = tScaled * invDet;
  // pbrt's conservative bound on t's error: a hit must lie beyond it.
  precise float maxZt = max(max(abs(p0t.z), abs(p1t.z)), abs(p2t.z));
  precise float deltaZ = RT_GAMMA3 * maxZt;
  precise float maxXt = max(max(abs(p0t.x), abs(p1t.x)), abs(p2t.x));
  precise float maxYt = max(max(abs(p0t.y), abs(p1t.y)), abs(p2t.y));
  precise float deltaX = RT_GAMMA5 * (maxXt + maxZt);
  precise float deltaY = RT_GAMMA5 * (maxYt + maxZt);
  precise float deltaE = 2.0 * (RT_GAMMA2 * maxXt * maxYt + deltaY * maxXt + deltaX * maxYt);
  precise float maxE = max(max(abs(e0), abs(e1)), abs(e2));
  precise float deltaT = 3.0 * (RT_GAMMA3 * maxE * maxZt + deltaE * maxZt + deltaZ * maxE) * abs(invDet);
  if (t <= deltaT) return 0.0;
  bary = vec3(e0 * invDet, e1 * invDet, e2 * invDet);
  return t;
}

// ---- Boxes (ray.h intersectBounds; bvh_traverse.cpp's SIMD rows) ----

struct RtBoxRay {
  vec3 o;
  vec3 inv;
  ivec3 nearRow, farRow;  // per axis: min (0-2) or max (3-5) row
};

RtBoxRay rtBoxRay(vec3 o, vec3 d) {
  RtBoxRay r;
  r.o = o;
  r.inv = vec3(1.0) / d;
  for (int axis = 0; axis < 3; ++axis) {
    int neg = r.inv[axis] < 0.0 ? 1 : 0;
    r.nearRow[axis] = axis + 3 * neg;
    r.farRow[axis] = axis + 3 * (1 - neg);
  }
  return r;
}

// Four children's boxes of node `ref`: which the ray enters before tMax, and where.
// The rows are read from the buffer where the ray's signs pick them: a copy of the
// node indexed by those signs would be an array indexed at run time, which a GPU
// compiler keeps in each thread's local memory, node after node.
bvec4 rtBoxes4(RtBoxRay r, uint ref, int side, float tMax, out vec4 tEntry) {
  precise vec4 t0 = vec4(-rtInfinity());
  precise vec4 t1 = vec4(rtInfinity());
  for (int axis = 0; axis < 3; ++axis) {
    precise vec4 n = (rtNodes[ref].box[RT_SIDES * r.nearRow[axis] + side] - vec4(r.o[axis])) * r.inv[axis];
    precise vec4 f = (rtNodes[ref].box[RT_SIDES * r.farRow[axis] + side] - vec4(r.o[axis])) * r.inv[axis];
    // NaN (a ray in a slab's plane) keeps the interval, as the CPU's max and min do.
    t0 = mix(max(n, t0), t0, isnan(n));
    t1 = mix(min(f, t1), t1, isnan(f));
  }
  t1 *= RT_WIDEN;
  tEntry = t0;
  return bvec4(uvec4(lessThanEqual(t0, t1)) & uvec4(greaterThan(t1, vec4(0.0))) & uvec4(lessThan(t0, vec4(tMax))));
}

// One box (an instance's bounds), the same test.
bool rtBox(RtBoxRay r, vec3 lo, vec3 hi, float tMax) {
  precise float t0 = -rtInfinity(), t1 = rtInfinity();
  for (int axis = 0; axis < 3; ++axis) {
    precise float n = ((r.nearRow[axis] < 3 ? lo[axis] : hi[axis]) - r.o[axis]) * r.inv[axis];
    precise float f = ((r.farRow[axis] < 3 ? lo[axis] : hi[axis]) - r.o[axis]) * r.inv[axis];
    if (!isnan(n)) t0 = max(n, t0);
    if (!isnan(f)) t1 = min(f, t1);
  }
  t1 *= RT_WIDEN;
  return t0 <= t1 && t1 > 0.0 && t0 < tMax;
}

// Triangle `lane` of leaf `leaf`, read from the buffer: a copy of the leaf indexed
// by `lane` at run time would be kept in each thread's local memory.
void rtLeafTriangle(uint leaf, int lane, out vec3 p0, out vec3 p1, out vec3 p2) {
  p0 = vec3(rtLeaves[leaf].p[0][lane], rtLeaves[leaf].p[1][lane], rtLeaves[leaf].p[2][lane]);
  p1 = vec3(rtLeaves[leaf].p[3][lane], rtLeaves[leaf].p[4][lane], rtLeaves[leaf].p[5][lane]);
  p2 = vec3(rtLeaves[leaf].p[6][lane], rtLeaves[leaf].p[7][lane], rtLeaves[leaf].p[8][lane]);
}

// ---- The BVH8 traversal (bvh_traverse.inl) ----

// The nearest hit (anyHit: the first) in the BVH under `root` before hit.t, which it
// shortens; whether one was found.
bool rtTraverse(uint root, vec3 o, vec3 d, bool anyHit, inout RtHit hit) {
  RtBoxRay boxRay = rtBoxRay(o, d);
  RtTriangleRay triRay = rtTriangleRay(o, d);
  uint stackRef[RT_STACK_SIZE];
  float stackT[RT_STACK_SIZE];
  int top = 0;
  bool found = false;
  uint ref = root;
  for (;;) {
    bool popNext = false;
    while ((ref & RT_LEAF_BIT) == 0u) {
      vec4 tEntry[RT_SIDES];
      bvec4 hits[RT_SIDES];
      for (int side = 0; side < RT_SIDES; ++side) hits[side] = rtBoxes4(boxRay, ref, side, hit.t, tEntry[side]);
      // Every child hit, pushed sorted with the nearest on top (ties: lower slot on
      // top), then the top popped: Embree's order, as the CPU's. Each child's place
      // is its rank, the number of hit children that go below it (farther, or as far
      // and of a higher slot), counted in registers: no insertion loop shifting the
      // stack in local memory, and the nearest goes straight to `ref`, unstored.
      int count = 0;
      for (int k = 0; k < RT_WIDTH; ++k) count += hits[k / 4][k % 4] ? 1 : 0;
      if (count == 0) {
        popNext = true;
        break;
      }
      uint nearest = 0u;
      for (int k = 0; k < RT_WIDTH; ++k) {
        if (!hits[k / 4][k % 4]) continue;
        float tk = tEntry[k / 4][k % 4];
        int rank = 0;
        for (int j = 0; j < RT_WIDTH; ++j) {
          float tj = tEntry[j / 4][j % 4];
          rank += hits[j / 4][j % 4] && (tj > tk || (tj == tk && j > k)) ? 1 : 0;
        }
        uint child = rtNodes[ref].child[k / 4][k % 4];
        if (rank == count - 1) {
          nearest = child;
        } else {
          stackRef[top + rank] = child;
          stackT[top + rank] = tk;
        }
      }
      top += count - 1;
      ref = nearest;
    }
    if (!popNext) {
      uint leaf = ref & (RT_MAX_TRIANGLES - 1u);
      int count = int((ref >> 28) & 3u) + 1;
      for (int lane = 0; lane < count; ++lane) {
        vec3 p0, p1, p2;
        rtLeafTriangle(leaf, lane, p0, p1, p2);
        vec3 bary;
        float t = rtTriangleT(triRay, hit.t, p0, p1, p2, bary);
        if (t > 0.0) {
          hit.t = t;
          hit.kind = RT_TRIANGLE;
          hit.slot = 4u * leaf + uint(lane);
          hit.index = rtOrder[hit.slot];
          hit.bary = bary;
          found = true;
          if (anyHit) return true;
        }
      }
    }
    // The next box the ray still enters before its nearest hit.
    do {
      if (top == 0) return found;
      --top;
    } while (!(stackT[top] < hit.t));
    ref = stackRef[top];
  }
  return found;
}

RtHit rtNoHit(float tMax) {
  RtHit h;
  h.t = tMax;
  h.kind = RT_NONE;
  h.index = 0u;
  h.slot = 0u;
  h.bary = vec3(0.0);
  return h;
}

// RtScene::intersect: spheres, planes, then each instance whose bounds the ray
// enters before the nearest hit so far. kind RT_NONE when nothing is hit.
RtHit rtClosestHit(vec3 o, vec3 d, float tMax) {
  RtHit hit = rtNoHit(tMax);
  for (int i = 0; i < u_sphereCount; ++i) {
    float t = rtSphereT(rtSpheres[i].centerRadius.xyz, rtSpheres[i].centerRadius.w, o, d, hit.t);
    if (t > 0.0) {
      hit.t = t;
      hit.kind = RT_SPHERE;
      hit.index = uint(i);
    }
  }
  for (int i = 0; i < u_planeCount; ++i) {
    float t = rtPlaneT(i, o, d, hit.t);
    if (t > 0.0) {
      hit.t = t;
      hit.kind = RT_PLANE;
      hit.index = uint(i);
    }
  }
  RtBoxRay boxRay = rtBoxRay(o, d);
  for (int i = 0; i < u_instanceCount; ++i) {
    if (rtBox(boxRay, rtInstances[i].boundsMin.xyz, rtInstances[i].boundsMax.xyz, hit.t)) {
      rtTraverse(rtInstances[i].root.x, o, d, false, hit);
    }
  }
  return hit;
}

// RtScene::intersectAny.
bool rtAnyHit(vec3 o, vec3 d, float tMax) {
  for (int i = 0; i < u_sphereCount; ++i) {
    if (rtSphereT(rtSpheres[i].centerRadius.xyz, rtSpheres[i].centerRadius.w, o, d, tMax) > 0.0) return true;
  }
  for (int i = 0; i < u_planeCount; ++i) {
    if (rtPlaneT(i, o, d, tMax) > 0.0) return true;
  }
  RtBoxRay boxRay = rtBoxRay(o, d);
  RtHit hit = rtNoHit(tMax);
  for (int i = 0; i < u_instanceCount; ++i) {
    if (rtBox(boxRay, rtInstances[i].boundsMin.xyz, rtInstances[i].boundsMax.xyz, tMax) &&
        rtTraverse(rtInstances[i].root.x, o, d, true, hit)) {
      return true;
    }
  }
  return false;
}
