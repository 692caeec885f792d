#version 330 core
// A rectangle of the plane z = u_height: the floor, a large square centred under the camera's
// target, or the part of it the sun's shadow map reaches (renderer.cpp, draw_ground).
uniform mat4 u_view_projection;
uniform vec2 u_centre;
uniform vec2 u_half_size;
uniform float u_height;
out vec3 v_world;

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1)) * 2.0 - 1.0;
    v_world = vec3(u_centre + corner * u_half_size, u_height);
    gl_Position = u_view_projection * vec4(v_world, 1.0);
}
