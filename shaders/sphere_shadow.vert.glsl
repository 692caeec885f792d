#version 330 core
// The overlay spheres (a point cloud's particles) as discs in the sun's depth map, so they cast
// shadows like the body does. The sun's projection is orthographic: a sphere's outline is a
// circle of its own radius.
uniform mat4 u_light_view;
uniform mat4 u_light_projection;
layout(location = 0) in vec3 a_centre;
layout(location = 1) in float a_radius;
out vec2 v_corner;

void main() {
    v_corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1)) * 2.0 - 1.0;
    vec4 c = u_light_view * vec4(a_centre, 1.0);
    gl_Position = u_light_projection * vec4(c.xy + v_corner * a_radius, c.z, 1.0);
}
