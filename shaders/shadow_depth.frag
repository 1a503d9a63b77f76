#version 430 core
// shadow_depth: the shadow pass writes depth only (renderer.cpp); the colour is never stored.
void main() {}
