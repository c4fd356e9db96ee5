// A hit as the shading sees it (raytrace/shapes.h's SurfaceInteraction): the point
// with its error bound, the geometric and shading normals, the material; and the ray
// origins spawned from it, offset as the CPU offsets them. After rt/trace.glsl.

struct Surface {
  vec3 p, pError, n, ns;
  int material;
};

float nextUp(float v) {
  if (isinf(v) && v > 0.0) return v;
  if (v == 0.0) return uintBitsToFloat(1u);
  uint bits = floatBitsToUint(v);
  return uintBitsToFloat(v > 0.0 ? bits + 1u : bits - 1u);
}
float nextDown(float v) {
  if (isinf(v) && v < 0.0) return v;
  if (v == 0.0) return -uintBitsToFloat(1u);
  uint bits = floatBitsToUint(v);
  return uintBitsToFloat(v > 0.0 ? bits - 1u : bits + 1u);
}

// offsetRayOrigin (ray.h): off the surface by more than the point's error bound.
vec3 offsetRayOrigin(Surface s, vec3 w) {
  precise float d = rtDot(abs(s.n), s.pError);
  precise vec3 offset = s.n * d;
  if (rtDot(w, s.n) < 0.0) offset = -offset;
  precise vec3 po = s.p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0.0) po[i] = nextUp(po[i]);
    else if (offset[i] < 0.0) po[i] = nextDown(po[i]);
  }
  return po;
}

// glm::normalize: v * (1 / sqrt(v . v)).
vec3 rtNormalize(vec3 v) {
  precise float inv = 1.0 / sqrt(rtDot(v, v));
  precise vec3 r = v * inv;
  return r;
}

Surface surfaceAt(RtHit hit, vec3 o, vec3 d) {
  Surface s;
  precise vec3 at = o + d * hit.t;
  if (hit.kind == RT_SPHERE) {
    RtSphere sp = rtSpheres[hit.index];
    precise vec3 local = at - sp.centerRadius.xyz;
    s.n = local / sqrt(rtDot(local, local));
    s.p = sp.centerRadius.xyz + s.n * sp.centerRadius.w;
    s.pError = RT_GAMMA8 * (abs(sp.centerRadius.xyz) + vec3(sp.centerRadius.w));
    s.ns = s.n;
    s.material = sp.material.x;
  } else if (hit.kind == RT_PLANE) {
    RtPlane pl = rtPlanes[hit.index];
    precise vec3 p = at - (rtDot(pl.normalD.xyz, at) - pl.normalD.w) * pl.normalD.xyz;
    s.p = p;
    s.pError = RT_GAMMA8 * (abs(p) + vec3(abs(pl.normalD.w)));
    s.n = pl.normalD.xyz;
    s.ns = s.n;
    s.material = int(pl.axisU.w);
  } else {
    RtLeaf l = rtLeaves[hit.slot / 4u];
    int lane = int(hit.slot % 4u);
    vec3 p0 = vec3(l.p[0][lane], l.p[1][lane], l.p[2][lane]);
    vec3 p1 = vec3(l.p[3][lane], l.p[4][lane], l.p[5][lane]);
    vec3 p2 = vec3(l.p[6][lane], l.p[7][lane], l.p[8][lane]);
    vec3 b = hit.bary;
    precise vec3 p = b.x * p0 + b.y * p1 + b.z * p2;
    s.p = p;
    s.pError = RT_GAMMA7 * (abs(b.x * p0) + abs(b.y * p1) + abs(b.z * p2));
    precise vec3 n = cross(p1 - p0, p2 - p0);
    float len = sqrt(rtDot(n, n));
    s.n = len > 0.0 ? n / len : vec3(0.0, 1.0, 0.0);
    s.ns = s.n;
    RtTriangle tri = rtTriangles[hit.index];
    if (tri.n[1].w > 0.0) {
      precise vec3 ns = b.x * tri.n[0].xyz + b.y * tri.n[1].xyz + b.z * tri.n[2].xyz;
      float nsLen = sqrt(rtDot(ns, ns));
      if (nsLen > 0.0) s.ns = ns / nsLen;
    }
    s.material = int(tri.n[0].w);
  }
  return s;
}
