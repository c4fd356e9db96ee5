// A hit as the shading sees it (raytrace/shapes.h's SurfaceInteraction): the point
// with its error bound, the geometric and shading normals, the material, the texture
// coordinates and their density (RtScene::intersect's, worked out only for a material
// that reads them); and the ray origins spawned from it, offset as the CPU offsets
// them. After rt/trace.glsl and rt/materials.glsl.

struct Surface {
  vec3 p, pError, n, ns;
  int material;
  vec2 uv0, uv1;     // TEXCOORD_0 and _1 (the same on spheres and planes)
  float uvPerMetre;  // uv units per metre of surface, for the ray cone's footprint
  vec4 color;        // COLOR_0 (white where the mesh has none)
  vec3 dpdu, dpdv;   // a triangle's uv gradient, for an anisotropic material (else 0)
};

// The triangles' uvs and colours (gputrace/gpu_layout.h's triangleAttributes,
// RT_ATTRIBUTE_SLOTS vec4 a triangle), built with RT_TRIANGLE_UVS where a material
// reads a texture and with RT_TRIANGLE_COLORS where a mesh has vertex colours.
#if defined(RT_TRIANGLE_UVS) || defined(RT_TRIANGLE_COLORS)
layout(std430, binding = BUFFER_RT_TRIANGLE_ATTRIBUTES) readonly buffer RtTriangleAttributes { vec4 rtTriangleAttributes[]; };
#endif

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


// float(pi) and std::sqrt(2.0f), as the C++ rounds them.
const float RT_PI_F = uintBitsToFloat(0x40490fdbu);
const float RT_SQRT2_F = uintBitsToFloat(0x3fb504f3u);

// The sphere's uv (rt_scene.cpp's sphereUv, in float here where the CPU works in
// double): n = (sin t sin p, cos t, sin t cos p) at uv = (p / 2 pi, t / pi).
vec2 rtSphereUv(vec3 n) {
  float theta = acos(clamp(n.y, -1.0, 1.0));
  float phi = atan(n.x, n.z);
  if (phi < 0.0) phi += 2.0 * RT_PI_F;
  return vec2(phi / (2.0 * RT_PI_F), theta / RT_PI_F);
}

// A triangle's uv at the hit and its density (RtScene::meshInteraction): the square
// root of the uv area over the area in space.
#ifdef RT_TRIANGLE_UVS
void rtTriangleUv(inout Surface s, RtHit hit, vec3 p0, vec3 p1, vec3 p2, float area) {
  uint first = hit.index * uint(RT_ATTRIBUTE_SLOTS);
  vec4 t0 = rtTriangleAttributes[first], t1 = rtTriangleAttributes[first + 1u], t2 = rtTriangleAttributes[first + 2u];
  vec3 b = hit.bary;
  precise vec4 uv = b.x * t0 + b.y * t1 + b.z * t2;
  s.uv0 = uv.xy;
  s.uv1 = uv.zw;
  precise vec2 du = t1.xy - t0.xy, dv = t2.xy - t0.xy;
  precise float uvArea = abs(du.x * dv.y - du.y * dv.x);
  s.uvPerMetre = area > 0.0 ? sqrt(uvArea / area) : 0.0;
  // KHR_materials_anisotropy's tangent frame: dP/du and dP/dv across the triangle.
  precise float det = du.x * dv.y - dv.x * du.y;
  if (rtMaterials[s.material].anisotropy.x > 0.0 && abs(det) > 0.0) {
    precise vec3 e1 = p1 - p0, e2 = p2 - p0;
    precise vec3 dpdu = (dv.y * e1 - du.y * e2) / det;
    precise vec3 dpdv = (du.x * e2 - dv.x * e1) / det;
    s.dpdu = dpdu;
    s.dpdv = dpdv;
  }
}
#endif

Surface surfaceAt(RtHit hit, vec3 o, vec3 d) {
  Surface s;
  s.uv0 = vec2(0.0);
  s.uv1 = vec2(0.0);
  s.uvPerMetre = 0.0;
  s.color = vec4(1.0);
  s.dpdu = vec3(0.0);
  s.dpdv = vec3(0.0);
  precise vec3 at = o + d * hit.t;
  if (hit.kind == RT_SPHERE) {
    RtSphere sp = rtSpheres[hit.index];
    precise vec3 local = at - sp.centerRadius.xyz;
    s.n = local / sqrt(rtDot(local, local));
    s.p = sp.centerRadius.xyz + s.n * sp.centerRadius.w;
    s.pError = RT_GAMMA8 * (abs(sp.centerRadius.xyz) + vec3(sp.centerRadius.w));
    s.ns = s.n;
    s.material = sp.material.x;
    vec4 surface = rtMaterials[s.material].surface;
    if (surface.y != 0.0) {
      precise vec2 uv = rtSphereUv(s.n) * surface.x;
      s.uv0 = uv;
      s.uv1 = uv;
    }
    // u runs once around (2 pi r), v from pole to pole (pi r): their geometric mean.
    precise float around = RT_PI_F * RT_SQRT2_F * sp.centerRadius.w;
    s.uvPerMetre = surface.x / around;
  } else if (hit.kind == RT_PLANE) {
    RtPlane pl = rtPlanes[hit.index];
    precise vec3 p = at - (rtDot(pl.normalD.xyz, at) - pl.normalD.w) * pl.normalD.xyz;
    s.p = p;
    s.pError = RT_GAMMA8 * (abs(p) + vec3(abs(pl.normalD.w)));
    s.n = pl.normalD.xyz;
    s.ns = s.n;
    s.material = int(pl.axisU.w);
    vec4 surface = rtMaterials[s.material].surface;
    if (surface.y != 0.0) {
      // In double, as the CPU: the square's uv from its corner, times the texture scale.
      precise dvec3 local = dvec3(s.p) - dvec3(pl.pointExtent.xyz);
      dvec3 u = dvec3(pl.axisU.xyz), v = dvec3(pl.axisV.xyz);
      double extent = double(pl.pointExtent.w);
      precise dvec2 uv = dvec2(local.x * u.x + local.y * u.y + local.z * u.z + extent,
                               local.x * v.x + local.y * v.y + local.z * v.z + extent) * double(surface.x);
      s.uv0 = vec2(uv);
      s.uv1 = s.uv0;
    }
    s.uvPerMetre = surface.x;
  } else {
    vec3 p0, p1, p2;
    rtLeafTriangle(hit.slot / 4u, int(hit.slot % 4u), p0, p1, p2);
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
#ifdef RT_TRIANGLE_UVS
    rtTriangleUv(s, hit, p0, p1, p2, len);
#endif
#ifdef RT_TRIANGLE_COLORS
    if (tri.n[2].w > 0.0) {
      // After the uvs' three slots, where there are uvs.
      uint first = hit.index * uint(RT_ATTRIBUTE_SLOTS) + uint(RT_ATTRIBUTE_SLOTS) - 3u;
      precise vec4 color = b.x * rtTriangleAttributes[first] + b.y * rtTriangleAttributes[first + 1u] +
                           b.z * rtTriangleAttributes[first + 2u];
      s.color = color;
    }
#endif
  }
  return s;
}
