#version 330 core
// The body as the sun sees it (for the shadow map).
uniform mat4 u_shadow_view_projection;
layout(location = 0) in vec3 a_position;

void main() { gl_Position = u_shadow_view_projection * vec4(a_position, 1.0); }
