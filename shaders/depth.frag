#version 450 core
// Shadow passes write depth only.
void main() {}
