#version 450 core
// tests/render/frame_block_test.cpp: the frame block as the GPU's compiler lays it
// out (std140: every member active), for the test to hold against C++'s struct of
// the same text (render/frame_block.h).
#include "common/frame.glsl"

layout(local_size_x = 1) in;
layout(std430, binding = 1) buffer Out { ivec4 outCounts; };

void main() { outCounts = u_counts; }
