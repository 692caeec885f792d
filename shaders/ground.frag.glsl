#version 330 core
// The ground where the sun's shadow map reaches: the floor with the bodies' soft shadows.
#include "floor.glsl"

in vec3 v_world;
out vec4 o_color;

void main() { o_color = floor_color(v_world, sun_visibility(v_world, vec3(0.0, 0.0, 1.0))); }
