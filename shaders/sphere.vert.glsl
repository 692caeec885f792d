#version 330 core
// Small spheres (particles, pins, the centre of mass), each instance a camera-facing quad; the
// fragment shader intersects the view ray with the true sphere.
uniform mat4 u_view;
uniform mat4 u_projection;
layout(location = 0) in vec3 a_centre;
layout(location = 1) in float a_radius;
layout(location = 2) in vec4 a_color;  // sRGB and opacity
out vec3 v_view_pos;                  // this corner of the quad, in view space
flat out vec3 v_centre;               // sphere centre, view space
flat out float v_radius;
flat out vec4 v_color;

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1)) * 2.0 - 1.0;
    vec3 c = (u_view * vec4(a_centre, 1.0)).xyz;
    // A quad a little larger than the sphere and moved in front of it covers its outline
    // under perspective.
    float grow = 1.0 + a_radius / max(-c.z, 1e-3);
    vec3 p = c + vec3(corner * a_radius * 1.15 * grow, a_radius);
    v_view_pos = p;
    v_centre = c;
    v_radius = a_radius;
    v_color = a_color;
    gl_Position = u_projection * vec4(p, 1.0);
}
