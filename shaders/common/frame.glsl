// Per-frame data shared by every scene program (uniform block BLOCK_FRAME), filled
// once per frame by engine/render/frame_uniforms.cpp. Positions are camera-relative.
// C++ compiles this very block as its struct (engine/render/frame_block.h), so its
// members are vec4, ivec4 and mat4 alone, whose std140 layout is C++'s: a float or
// vec3 member would be laid out otherwise by the two. FrameBlockText.* compares the
// GL's offsets with C++'s.
//
// Texture units and binding points are engine/gl/bindings.h's, which every program
// receives as #defines (UNIT_BASE_COLOR, ...): one owner each, as a unit shared by
// two sampler types is a draw-time GL error.
#define MAX_POINT_LIGHTS 8
layout(std140, binding = BLOCK_FRAME) uniform Frame {
  mat4 u_viewProjection;
  mat4 u_sunShadowMatrix;   // camera-relative world -> shadow map [0,1]^3
  vec4 u_sunDirection;      // toward the sun; w = 1 when there is a sun
  vec4 u_sunColor;          // colour * intensity
  // The lights but the sun (render/frame_uniforms.h, CompiledLights::others):
  vec4 u_pointPosition[MAX_POINT_LIGHTS];  // xyz: a position, w = 0 (no fall-off) or 1 (1/d^2); or
                                           // a unit direction toward a further sun, w = 2
  vec4 u_pointColor[MAX_POINT_LIGHTS];     // colour * intensity; w = 1: casts shadows
  // Each light's cone (scene/environment.h's LightCone): xyz the axis toward the
  // light, w the cosine of the outer half-angle; and x the cosine of the inner one.
  // Read under SPOT_LIGHTS alone (common/direct_light.glsl).
  vec4 u_pointAxis[MAX_POINT_LIGHTS];
  vec4 u_pointInner[MAX_POINT_LIGHTS];
  vec4 u_ambientSky;        // hemispheric ambient (PBR); w = classic ambient weight
  vec4 u_ambientGround;
  vec4 u_fog;               // rgb colour, w = density (0 = none)
  vec4 u_shadowParams;      // x: sun texel size, y: PCF radius in texels, z: point far, w: point texel angle
  ivec4 u_counts;           // x: point lights
  mat4 u_sunShadowMatrixFar;  // the far sun map (terrain scenes): as u_sunShadowMatrix
  vec4 u_sunFarParams;      // x: far map texel size (uv), y: its texel's world size
  vec4 u_shIrradiance[9];   // rgb: SH irradiance of the environment (AMBIENT_SH, AMBIENT_IBL)
  vec4 u_iblParams;         // x: the prefiltered chain's last level (AMBIENT_IBL)
};
