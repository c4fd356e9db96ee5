#version 450 core
// Shadow passes write depth only; alpha-masked materials (ALPHA_MASK) cut their
// holes here too, so cut-out leaves cast cut-out shadows.
#ifdef ALPHA_MASK
#include "common/material.glsl"
in vec2 v_uv;
void main() { materialAlphaTest(materialBaseColor(v_uv).a); }
#else
void main() {}
#endif
