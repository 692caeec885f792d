#version 330 core
// The background: the sky along each pixel's view ray.
#include "lighting.glsl"

uniform mat4 u_inverse_view_projection;
in vec2 v_ndc;
out vec4 o_color;

void main() {
    vec4 far_point = u_inverse_view_projection * vec4(v_ndc, 1.0, 1.0);
    vec3 dir = normalize(far_point.xyz / far_point.w - u_eye);
    o_color = vec4(encode(sky(dir)), 1.0);
}
