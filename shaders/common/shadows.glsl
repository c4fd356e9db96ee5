// Shadow-map lookups. The sun uses one 2D map fitted to the view; the first point
// light uses a depth cube map. Both compare in hardware (sampler*Shadow) and filter
// with an N x N PCF kernel (radius PCF_RADIUS texels; 0 = one hard sample).
// Acne is kept away by slope-scaled depth offset in the shadow pass and by moving
// the lookup point along the normal by about one shadow texel, which grows with the
// texel's world size instead of a fixed epsilon.

// The kernel's radius is compile-time (SceneRenderer's init), so that its loops
// unroll: llvmpipe keeps a loop of a uniform's count as a loop, with its bookkeeping
// at every tap. A program built without it (a test's) reads it from the frame block.
#ifndef PCF_RADIUS
#define PCF_RADIUS int(u_shadowParams.y)
#endif

#ifdef SUN_SHADOWS
layout(binding = UNIT_SUN_SHADOW) uniform sampler2DShadow u_sunShadowMap;
uniform float u_sunTexelWorld;  // world size of one shadow texel
#ifdef SUN_FAR_SHADOWS
// Terrain scenes: a second, coarse map of the terrain over the view out to a few
// kilometres, so mountains shade valleys beyond the near map's reach.
layout(binding = UNIT_SUN_SHADOW_FAR) uniform sampler2DShadow u_sunShadowMapFar;
#endif

// Visibility through one map with an N x N PCF kernel (radius `r` texels), and in
// `inside` how far within the map the point lies: 1 inside, fading to 0 over the
// map's outer tenth (beyond it nothing is known), 0 outside.
float sunMapVisibility(sampler2DShadow map, mat4 shadowMatrix, vec3 position, vec3 n, float texelWorld,
                       float texel, int r, out float inside) {
  vec4 p = shadowMatrix * vec4(position + n * texelWorld * 1.5, 1.0);
  vec3 uvz = p.xyz / p.w;
  vec2 edge = min(uvz.xy, 1.0 - uvz.xy);
  inside = uvz.z < 0.0 || uvz.z > 1.0 ? 0.0 : smoothstep(0.0, 0.1, min(edge.x, edge.y));
  if (inside <= 0.0) return 1.0;
  float sum = 0.0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) sum += texture(map, vec3(uvz.xy + vec2(x, y) * texel, uvz.z));
  return sum / float((2 * r + 1) * (2 * r + 1));
}

float sunShadow(vec3 position, vec3 n) {
  float nDotL = dot(n, u_sunDirection.xyz);
  // Faces turned away are dark anyway; no lookup, no acne on them.
  if (nDotL <= 0.0) return 0.0;
  float inside;
  float near = sunMapVisibility(u_sunShadowMap, u_sunShadowMatrix, position, n, u_sunTexelWorld,
                                u_shadowParams.x, PCF_RADIUS, inside);
  float far = 1.0;
#ifdef SUN_FAR_SHADOWS
  if (inside < 1.0) {
    float insideFar;
    far = sunMapVisibility(u_sunShadowMapFar, u_sunShadowMatrixFar, position, n, u_sunFarParams.y,
                           u_sunFarParams.x, 1, insideFar);
    far = mix(1.0, far, insideFar);
  }
#endif
  return mix(far, near, inside);
}
#endif

#ifdef POINT_SHADOWS
layout(binding = UNIT_POINT_SHADOW) uniform samplerCubeShadow u_pointShadowMap;
uniform float u_pointNear;

// Depth the cube face's projection (90 degrees, zero-to-one) gives a point at
// distance `z` along the face's axis.
float cubeDepth(float z) {
  float far = u_shadowParams.z;
  return far / (far - u_pointNear) - far * u_pointNear / ((far - u_pointNear) * z);
}

float pointShadow(vec3 position, vec3 n) {
  vec3 toLight = u_pointPosition[0].xyz - position;
  if (dot(n, toLight) <= 0.0) return 0.0;
  float distance = length(toLight);
  // One cube texel at this distance, in world units.
  float texelWorld = distance * u_shadowParams.w;
  vec3 v = (position + n * texelWorld * 1.5) - u_pointPosition[0].xyz;
  float z = max(abs(v.x), max(abs(v.y), abs(v.z)));
  float reference = cubeDepth(z);
  int r = PCF_RADIUS;
  if (r == 0) return texture(u_pointShadowMap, vec4(v, reference));
  // PCF on the cube: sample points spread in the surface's own tangent plane, so
  // that none of them dips behind the surface and shadows it.
  vec3 axisU = normalize(cross(abs(n.y) < 0.99 ? vec3(0, 1, 0) : vec3(1, 0, 0), n));
  vec3 axisV = cross(n, axisU);
  float sum = 0.0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) {
      vec3 d = v + (axisU * float(x) + axisV * float(y)) * texelWorld;
      float dz = max(abs(d.x), max(abs(d.y), abs(d.z)));
      sum += texture(u_pointShadowMap, vec4(d, cubeDepth(dz)));
    }
  return sum / float((2 * r + 1) * (2 * r + 1));
}
#endif
