#version 330 core
#include "lighting.glsl"

uniform mat4 u_projection;
uniform mat3 u_view_to_world;  // rotation only
in vec3 v_view_pos;
flat in vec3 v_centre;
flat in float v_radius;
flat in vec4 v_color;
out vec4 o_color;

void main() {
    // Ray from the eye (the origin in view space) through this pixel, against the sphere.
    vec3 d = normalize(v_view_pos);
    float b = dot(d, v_centre);
    float disc = b * b - dot(v_centre, v_centre) + v_radius * v_radius;
    if (disc < 0.0) discard;
    float t = b - sqrt(disc);
    vec3 hit = d * t;
    vec3 n_view = (hit - v_centre) / v_radius;
    vec3 n = u_view_to_world * n_view;

    vec4 clip = u_projection * vec4(hit, 1.0);
    gl_FragDepth = 0.5 + 0.5 * clip.z / clip.w;

    vec3 base = srgb_to_linear(v_color.rgb);
    float diffuse = max(dot(n, u_sun_dir) * 0.8 + 0.2, 0.0);
    vec3 h = normalize(u_sun_dir - u_view_to_world * d);
    float specular = pow(max(dot(n, h), 0.0), 40.0);
    vec3 color = base * (kSunColor * diffuse * 0.8 + ambient(n)) + kSunColor * specular * 0.12;
    // A darker outline keeps small spheres readable against any background.
    float rim = smoothstep(0.55, 0.95, 1.0 - max(-dot(n_view, d), 0.0));
    color *= 1.0 - 0.45 * rim;
    o_color = vec4(encode(color), v_color.a);
}
