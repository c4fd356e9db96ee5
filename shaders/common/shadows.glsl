// Shadow-map lookups. The sun uses one 2D map fitted to the view; the first point
// light uses a depth cube map. Both compare in hardware (sampler*Shadow) and filter
// with an N x N PCF kernel (radius u_shadowParams.y texels; 0 = one hard sample).
// Acne is kept away by slope-scaled depth offset in the shadow pass and by moving
// the lookup point along the normal by about one shadow texel, which grows with the
// texel's world size instead of a fixed epsilon.
#ifdef SUN_SHADOWS
layout(binding = 4) uniform sampler2DShadow u_sunShadowMap;
uniform float u_sunTexelWorld;  // world size of one shadow texel

float sunShadow(vec3 position, vec3 n) {
  float nDotL = dot(n, u_sunDirection.xyz);
  // Faces turned away are dark anyway; no lookup, no acne on them.
  if (nDotL <= 0.0) return 0.0;
  vec3 offset = n * u_sunTexelWorld * 1.5;
  vec4 p = u_sunShadowMatrix * vec4(position + offset, 1.0);
  vec3 uvz = p.xyz / p.w;
  if (any(lessThan(uvz, vec3(0.0))) || any(greaterThan(uvz, vec3(1.0)))) return 1.0;
  int r = int(u_shadowParams.y);
  float texel = u_shadowParams.x;
  float sum = 0.0;
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x) sum += texture(u_sunShadowMap, vec3(uvz.xy + vec2(x, y) * texel, uvz.z));
  // Fade to lit over the map's outer tenth: beyond it nothing is known, and a
  // terrain shadow (a mountain's, at low sun) would otherwise stop at a straight edge.
  vec2 edge = min(uvz.xy, 1.0 - uvz.xy);
  float known = smoothstep(0.0, 0.1, min(edge.x, edge.y));
  return mix(1.0, sum / float((2 * r + 1) * (2 * r + 1)), known);
}
#endif

#ifdef POINT_SHADOWS
layout(binding = 5) uniform samplerCubeShadow u_pointShadowMap;
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
  int r = int(u_shadowParams.y);
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
