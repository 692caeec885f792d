// Shared lighting: the sun (a key light with soft shadows), the sky it sits in, and the
// final encoding to the screen. Included by the passes that shade surfaces.
//
// Colours are linear until encode(); inputs given in sRGB go through srgb_to_linear().

uniform vec3 u_sun_dir;              // unit vector towards the sun
uniform vec3 u_eye;                  // camera position, m

const vec3 kSunColor = vec3(1.00, 0.93, 0.82) * 2.6;
const vec3 kSkyZenith = vec3(0.18, 0.36, 0.68);
const vec3 kSkyHorizon = vec3(0.72, 0.80, 0.88);
const vec3 kGroundBounce = vec3(0.34, 0.31, 0.27);

vec3 srgb_to_linear(vec3 c) { return pow(max(c, vec3(0.0)), vec3(2.2)); }

// Filmic curve (a rational fit that rolls highlights off smoothly), then gamma 2.2.
vec3 encode(vec3 c) {
    c *= 0.85;
    c = clamp((c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14), 0.0, 1.0);
    return pow(c, vec3(1.0 / 2.2));
}

// Radiance of the sky seen along `dir` (unit): a gradient from a pale horizon to a deep zenith,
// a warm glow around the sun, and a flat haze below the horizon.
vec3 sky(vec3 dir) {
    float up = clamp(dir.z, -1.0, 1.0);
    vec3 c = up > 0.0 ? mix(kSkyHorizon, kSkyZenith, pow(up, 0.4)) : kSkyHorizon * 0.92;
    float sun = max(dot(dir, u_sun_dir), 0.0);
    c += vec3(1.0, 0.85, 0.65) * (0.18 * pow(sun, 8.0) + 0.6 * pow(sun, 256.0));
    return c;
}

// Light from the sky dome on a surface with normal n: the sky above, bounce from the ground
// below, blended by how much the surface faces up.
vec3 ambient(vec3 n) {
    float up = 0.5 + 0.5 * n.z;
    return mix(kGroundBounce, mix(kSkyHorizon, kSkyZenith, 0.4), up);
}

// ---- Soft shadows from the sun ------------------------------------------------------------
// A depth map rendered from the sun (orthographic, fitted to the body). Percentage-closer
// soft shadows: a blocker search finds how far the occluder is above the receiver, and the
// filter widens with that gap, so a shadow is crisp where the body touches the ground and
// soft and wide when the body is high above it.
uniform sampler2DShadow u_shadow_map;  // compare lookups (bilinear PCF)
uniform sampler2D u_shadow_depth;      // the same texture, raw depth (blocker search)
uniform mat4 u_shadow_matrix;          // world -> [0,1]^3 of the shadow map
uniform float u_shadows;               // 1 on, 0 off
uniform float u_shadow_texel;          // one texel, in shadow-map uv
uniform float u_penumbra_scale;        // penumbra width in uv per unit of depth gap
uniform float u_shadow_normal_offset;  // m, along the normal, against acne

const vec2 kDisk[16] = vec2[](
    vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725), vec2(-0.09418410, -0.92938870),
    vec2(0.34495938, 0.29387760), vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
    vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379), vec2(0.44323325, -0.97511554),
    vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
    vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590), vec2(0.19984126, 0.78641367),
    vec2(0.14383161, -0.14100790));

float sun_visibility(vec3 p, vec3 n) {
    if (u_shadows < 0.5) return 1.0;
    vec4 s = u_shadow_matrix * vec4(p + n * u_shadow_normal_offset, 1.0);
    vec3 uvz = s.xyz / s.w;
    if (any(lessThan(uvz.xy, vec2(0.0))) || any(greaterThan(uvz.xy, vec2(1.0)))) return 1.0;
    float z = min(uvz.z, 0.9999);

    // Blocker search over a region as wide as the largest penumbra this gap could give.
    float search = clamp(u_penumbra_scale * z, 2.0 * u_shadow_texel, 0.08);
    float blockers = 0.0, blocker_depth = 0.0;
    for (int i = 0; i < 16; ++i) {
        float d = texture(u_shadow_depth, uvz.xy + kDisk[i] * search).r;
        if (d < z - 0.0005) {
            blockers += 1.0;
            blocker_depth += d;
        }
    }
    if (blockers < 0.5) return 1.0;
    blocker_depth /= blockers;

    float radius = clamp(u_penumbra_scale * (z - blocker_depth), 1.5 * u_shadow_texel, 0.08);
    float lit = 0.0;
    for (int i = 0; i < 16; ++i) lit += texture(u_shadow_map, vec3(uvz.xy + kDisk[i] * radius, z - 0.0005));
    return lit / 16.0;
}
