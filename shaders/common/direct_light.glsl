// Direct light on a surface: the sun (through its shadow map under SUN_SHADOWS) and
// the point lights (the first through its cube shadow under POINT_SHADOWS), with
// common/shading.glsl's model. Needs common/frame.glsl, shading.glsl and shadows.glsl
// included first. scene.frag and terrain.frag both use it, so that the ground is lit
// exactly like the meshes standing on it. `shadowNormal` is the geometric normal:
// the shadow lookups' offset against acne is about the geometry, not the bumps a
// normal map paints on it.
vec3 shadeDirectLight(Surface s, vec3 shadowNormal) {
  vec3 color = vec3(0.0);
  if (u_sunDirection.w > 0.0) {
    float visibility = 1.0;
#ifdef SUN_SHADOWS
    visibility = sunShadow(s.position, shadowNormal);
#endif
    color += shadeLight(s, u_sunDirection.xyz, u_sunColor.rgb, visibility);
  }
  for (int i = 0; i < u_counts.x; ++i) {
    vec3 toLight = u_pointPosition[i].xyz - s.position;
    float d2 = dot(toLight, toLight);
    float visibility = 1.0;
#ifdef POINT_SHADOWS
    if (i == 0 && u_pointColor[0].w > 0.0) visibility = pointShadow(s.position, shadowNormal);
#endif
    vec3 radiance = u_pointColor[i].rgb / (u_pointPosition[i].w > 0.0 ? max(d2, 1e-8) : 1.0);
    color += shadeLight(s, toLight * inversesqrt(max(d2, 1e-30)), radiance, visibility);
  }
  return color;
}
