#version 330 core
// The ground beyond the sun's shadow map, where nothing shades it from the sun (sun_visibility
// would give 1): the same floor without the lookups, which a software rasterizer would make
// for every pixel whatever their outcome.
#include "floor.glsl"

in vec3 v_world;
out vec4 o_color;

void main() { o_color = floor_color(v_world, 1.0); }
