#version 330 core
// A large square of the plane z = u_height, centred under the camera's target.
uniform mat4 u_view_projection;
uniform vec2 u_centre;
uniform float u_half_size;
uniform float u_height;
out vec3 v_world;

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1)) * 2.0 - 1.0;
    v_world = vec3(u_centre + corner * u_half_size, u_height);
    gl_Position = u_view_projection * vec4(v_world, 1.0);
}
