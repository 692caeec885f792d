#version 330 core
// The body's surface: a soft, slightly glossy material. Sun with soft shadows (wrapped a
// little, as light does in a translucent jelly), sky and ground bounce, a rim of sky light at
// grazing angles, and a darkening near the ground where the floor hides the sky.
#include "lighting.glsl"

uniform vec3 u_body_color;     // sRGB
uniform float u_opacity;       // 1 solid; less for the see-through style
uniform float u_ground_height;
uniform float u_contact_range; // m over which the floor's occlusion fades out
uniform float u_pattern;       // 1: soft checks in material coordinates
uniform float u_two_sided;     // 1: light back faces as if seen from their side (see-through style)

in vec3 v_world;
in vec3 v_normal;
in vec3 v_material;
out vec4 o_color;

// Soft three-dimensional checks, three across the body's radius, carried by the material: they
// turn with the body and stretch with it. Edges are blurred over about a pixel (fwidth).
float checks(vec3 m) {
    vec3 s = sin(m * 4.71238898);  // 1.5 pi: three half-periods per radius
    float c = s.x * s.y * s.z;
    float w = fwidth(c) + 0.02;
    return smoothstep(-w, w, c);
}

void main() {
    vec3 n = normalize(v_normal);
    if (u_two_sided > 0.5 && !gl_FrontFacing) n = -n;
    vec3 v = normalize(u_eye - v_world);
    vec3 base = srgb_to_linear(u_body_color);
    if (u_pattern > 0.5) base *= mix(0.84, 1.0, checks(v_material));

    float wrap = 0.25;
    float n_dot_l = dot(n, u_sun_dir);
    float diffuse = max((n_dot_l + wrap) / (1.0 + wrap), 0.0);
    // Near the terminator the faceted surface the sun sees and the smooth normals disagree:
    // there the shadow fades out and the (wrapped) diffuse term alone darkens the surface.
    float visibility = mix(1.0, sun_visibility(v_world, n), smoothstep(0.05, 0.35, n_dot_l));
    vec3 h = normalize(u_sun_dir + v);
    float fresnel = 0.04 + 0.96 * pow(1.0 - max(dot(n, v), 0.0), 5.0);
    float specular = pow(max(dot(n, h), 0.0), 48.0) * (48.0 + 8.0) / 25.0 * step(0.0, n_dot_l);

    float height = max(v_world.z - u_ground_height, 0.0);
    float contact = mix(0.45, 1.0, smoothstep(0.0, u_contact_range, height));

    vec3 color = base * kSunColor * diffuse * visibility;
    color += base * ambient(n) * 0.85 * contact;
    color += kSunColor * specular * 0.06 * visibility;
    color += sky(reflect(-v, n)) * fresnel * 0.35 * contact;
    o_color = vec4(encode(color), u_opacity);
}
