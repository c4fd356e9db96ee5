// Direct light on a surface: the sun (through its shadow map under SUN_SHADOWS) and
// the other lights: point lights and spots (the first through its cube shadow under
// POINT_SHADOWS) and further suns, unshadowed (render/frame_uniforms.h), with
// common/shading.glsl's model. Needs common/frame.glsl, shading.glsl and shadows.glsl
// included first. scene.frag and terrain.frag both use it, so that the ground is lit
// exactly like the meshes standing on it. `shadowNormal` is the geometric normal:
// the shadow lookups' offset against acne is about the geometry, not the bumps a
// normal map paints on it.
//
// The scene's lights are compile-time constants (SceneRenderer's init in
// scene_renderer_setup.cpp): SUN_LIGHT 0 or 1, POINT_LIGHTS the number of point
// lights, so that a scene pays only for the lights it has. llvmpipe runs an if's
// body whatever its condition (masked), and a loop's body once even when it makes
// no iteration: with the count a uniform, a scene without point lights shaded one,
// BRDF and all, for every fragment. A program built without these (a test's) takes
// the counts from the frame block.
// SPOT_LIGHTS, where a light has a cone, weighs each light by its cone
// (common/spot_cone.glsl); a scene without spots does not pay for it.
#ifndef SUN_LIGHT
#define SUN_LIGHT 1
#endif
#ifdef SPOT_LIGHTS
#include "common/spot_cone.glsl"
#endif
#ifndef POINT_LIGHTS
#define POINT_LIGHTS u_counts.x
#endif
vec3 shadeDirectLight(Surface s, vec3 shadowNormal) {
  vec3 color = vec3(0.0);
#if SUN_LIGHT
  if (u_sunDirection.w > 0.0) {
    float visibility = 1.0;
#ifdef SUN_SHADOWS
    visibility = sunShadow(s.position, shadowNormal);
#endif
    color += shadeLight(s, u_sunDirection.xyz, u_sunColor.rgb, visibility);
  }
#endif
  for (int i = 0; i < POINT_LIGHTS; ++i) {
    // A further sun (w = 2) is a direction: no position, no fall-off.
    bool directional = u_pointPosition[i].w > 1.5;
    vec3 toLight = directional ? u_pointPosition[i].xyz : u_pointPosition[i].xyz - s.position;
    float d2 = dot(toLight, toLight);
    float visibility = 1.0;
#ifdef POINT_SHADOWS
    if (i == 0 && u_pointColor[0].w > 0.0) visibility = pointShadow(s.position, shadowNormal);
#endif
    vec3 radiance = u_pointColor[i].rgb / (u_pointPosition[i].w > 0.5 && !directional ? max(d2, 1e-8) : 1.0);
    vec3 l = toLight * inversesqrt(max(d2, 1e-30));
#ifdef SPOT_LIGHTS
    radiance *= spotAttenuation(dot(l, u_pointAxis[i].xyz), u_pointAxis[i].w, u_pointInner[i].x);
#endif
    color += shadeLight(s, l, radiance, visibility);
  }
  return color;
}
