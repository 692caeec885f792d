#version 330 core
// A body as the sun sees it (for the shadow map).
uniform mat4 u_shadow_view_projection;
uniform mat4 u_model;
layout(location = 0) in vec3 a_position;

void main() { gl_Position = u_shadow_view_projection * (u_model * vec4(a_position, 1.0)); }
