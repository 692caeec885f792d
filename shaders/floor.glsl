// The ground's shading: a light floor with a metre grid (finer lines in between), lit by the
// sun, darkened under each body by a contact term, and fading into the haze of the horizon with
// distance. The sun's share comes in as an argument: ground.frag.glsl looks it up in the shadow
// map where the map reaches, ground_sunlit.frag.glsl passes 1 everywhere else (renderer.cpp).
#include "lighting.glsl"

uniform vec3 u_floor_color;      // sRGB
uniform float u_grid_major;      // m between major lines
uniform float u_fog_distance;    // m: the floor is mostly haze this far from the eye
// Each body as an ellipsoid (centre and semi-axes, m): its occlusion of the sky over the floor.
const int kMaxOccluders = 16;
uniform int u_occluder_count;
uniform vec3 u_occluder_centre[kMaxOccluders];
uniform vec3 u_occluder_axes[kMaxOccluders];
uniform float u_occlusion;       // 0 without a body


// Coverage of grid lines `width_px` pixels wide every `spacing` metres, anti-aliased.
float grid(vec2 p, float spacing, float width_px) {
    vec2 q = p / spacing;
    vec2 w = fwidth(q);
    vec2 d = abs(fract(q - 0.5) - 0.5) / max(w, vec2(1e-6));
    float line = 1.0 - clamp(min(d.x, d.y) - 0.5 * width_px + 0.5, 0.0, 1.0);
    // Lines closer together than a few pixels would shimmer: fade them out.
    float fade = 1.0 - smoothstep(0.12, 0.35, max(w.x, w.y));
    return line * fade;
}

// Sky occlusion by a unit sphere seen from a point below it, in the ellipsoid's own
// coordinates: cos(angle to the centre) * (radius / distance)^2, summed over the bodies.
float body_occlusion(vec3 p) {
    if (u_occlusion <= 0.0) return 0.0;
    float total = 0.0;
    // Indexed through min(): a compiler that sees the loop index the arrays directly bounds the
    // loop by their size and may unroll all 16 passes, and a software rasterizer then runs
    // every one of them for every pixel, bodies or not.
    for (int i = 0; i < u_occluder_count; ++i) {
        int k = min(i, kMaxOccluders - 1);
        vec3 q = (p - u_occluder_centre[k]) / u_occluder_axes[k];
        float d2 = max(dot(q, q), 1.0);
        float cos_angle = clamp(-q.z * inversesqrt(d2), 0.0, 1.0);
        total += u_occlusion * cos_angle / d2;
    }
    return min(total, 0.9);
}

// The floor at `p` (world, on the plane) when the sun reaches it by the fraction `sun_seen`.
vec4 floor_color(vec3 p, float sun_seen) {
    vec3 n = vec3(0.0, 0.0, 1.0);
    vec3 base = srgb_to_linear(u_floor_color);

    float minor = grid(p.xy, u_grid_major * 0.25, 1.0);
    float major = grid(p.xy, u_grid_major, 1.6);
    base *= 1.0 - 0.16 * minor;
    base *= 1.0 - 0.38 * major;

    float sun = max(dot(n, u_sun_dir), 0.0) * sun_seen;
    float sky_seen = 1.0 - body_occlusion(p);
    vec3 lit = base * (kSunColor * sun * 0.92 + ambient(n) * 0.9 * sky_seen);
    lit *= mix(1.0, sky_seen, 0.55);  // the contact shadow also dims the sun-lit floor a little

    float dist = length(p - u_eye);
    vec3 to_eye_dir = normalize(p - u_eye);
    float haze = 1.0 - exp(-pow(dist / u_fog_distance, 2.0));
    vec3 horizon = sky(normalize(vec3(to_eye_dir.xy, 0.0)) * 0.999 + vec3(0.0, 0.0, 0.001));
    return vec4(encode(mix(lit, horizon, haze)), 1.0);
}
