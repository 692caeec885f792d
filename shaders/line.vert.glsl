#version 330 core
// Lines of a constant width in pixels, whatever the driver's line width limits: each
// instance is one segment, widened on screen into a quad of four vertices.
uniform mat4 u_view_projection;
uniform vec2 u_viewport;   // pixels
layout(location = 0) in vec3 a_from;
layout(location = 1) in vec3 a_to;
layout(location = 2) in vec4 a_color;   // sRGB and opacity
layout(location = 3) in float a_width;  // pixels
out vec4 v_color;
out float v_across;  // -1..1 across the line, for a soft edge

void main() {
    vec4 a = u_view_projection * vec4(a_from, 1.0);
    vec4 b = u_view_projection * vec4(a_to, 1.0);
    // Keep both ends in front of the eye so the direction on screen is defined.
    a.w = max(a.w, 1e-4);
    b.w = max(b.w, 1e-4);
    vec2 sa = a.xy / a.w * u_viewport, sb = b.xy / b.w * u_viewport;
    vec2 dir = sb - sa;
    dir = dot(dir, dir) > 1e-8 ? normalize(dir) : vec2(1.0, 0.0);
    vec2 normal = vec2(-dir.y, dir.x);
    float side = (gl_VertexID & 2) != 0 ? 1.0 : -1.0;
    vec4 p = (gl_VertexID & 1) != 0 ? b : a;
    float half_width = 0.5 * a_width + 0.75;  // room for the soft edge
    p.xy += normal * side * half_width * 2.0 / u_viewport * p.w;
    gl_Position = p;
    v_color = a_color;
    v_across = side * half_width / max(0.5 * a_width, 0.5);
}
