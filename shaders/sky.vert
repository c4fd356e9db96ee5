#version 450 core
// One triangle that covers the screen, on the far plane: the sky is drawn behind
// everything, after it (kSkyBehindPass), or alone into a cube map.
uniform mat4 u_inverseViewProjection;
out vec3 v_direction;

void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
  vec4 far = u_inverseViewProjection * vec4(p, 1.0, 1.0);
  v_direction = far.xyz / far.w;
  gl_Position = vec4(p, 0.0, 1.0);  // the far plane: depth 0 in reverse-Z
}
