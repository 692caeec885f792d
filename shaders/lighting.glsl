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
// The sun's view of the body is stored as depth moments (z, z^2), orthographic and fitted to
// the body, and mipmapped: a lookup at a coarser level averages the moments over a wider
// square. Only the body (and the overlay spheres) are in the map; everywhere else holds the
// far plane, z = 1. Over a region where the occluders sit at depth z_b and cover a fraction f,
//     mean = f z_b + (1 - f),   mean of squares = f z_b^2 + (1 - f)
// which gives both back:  z_b = (E[z^2] - 1) / (E[z] - 1) - 1  and  f = (1 - E[z]) / (1 - z_b).
// A receiver behind z_b sees the fraction 1 - f of the sun. First a wide lookup finds the
// occluders' depth, then the penumbra's width follows from the gap between them and the
// receiver (a light of finite size), and a second lookup at that width gives the shadow:
// crisp where the body touches the ground, soft and wide when it is high above it.
uniform sampler2D u_shadow_moments;    // RG: z, z^2 (mipmapped)
uniform mat4 u_shadow_matrix;          // world -> [0,1]^3 of the shadow map
uniform float u_shadows;               // 1 on, 0 off
uniform float u_shadow_size;           // texels a side at level 0
uniform float u_penumbra_scale;        // penumbra width in uv per unit of depth gap
uniform float u_shadow_normal_offset;  // m, along the normal, against self-shadowing acne

const float kShadowBias = 0.002;       // depth units: a receiver this close to z_b is lit

// Occluders' mean depth (x) and coverage (y) from averaged moments.
vec2 occluders_from(vec2 m) {
    float open = 1.0 - m.x;  // 0 where nothing but the far plane
    if (open < 1e-5) return vec2(1.0, 0.0);
    float z_b = clamp((m.y - 1.0) / (m.x - 1.0) - 1.0, 0.0, m.x);
    return vec2(z_b, clamp(open / max(1.0 - z_b, 1e-5), 0.0, 1.0));
}

float shadow_lod(float width_uv) { return max(log2(width_uv * u_shadow_size), 0.0); }

// Over a square `width_uv` wide: four bilinear taps half a texel of that level apart, a tent
// filter, so the coarse texels of a wide penumbra do not show as steps.
vec2 occluders(vec2 uv, float width_uv) {
    float lod = shadow_lod(width_uv);
    float h = 0.5 * exp2(lod) / u_shadow_size;
    vec2 m = textureLod(u_shadow_moments, uv + vec2(-h, -h), lod).xy + textureLod(u_shadow_moments, uv + vec2(h, -h), lod).xy +
             textureLod(u_shadow_moments, uv + vec2(-h, h), lod).xy + textureLod(u_shadow_moments, uv + vec2(h, h), lod).xy;
    return occluders_from(0.25 * m);
}

float sun_visibility(vec3 p, vec3 n) {
    if (u_shadows < 0.5) return 1.0;
    vec4 s = u_shadow_matrix * vec4(p + n * u_shadow_normal_offset, 1.0);
    vec3 uvz = s.xyz / s.w;
    if (any(lessThan(uvz.xy, vec2(0.0))) || any(greaterThan(uvz.xy, vec2(1.0)))) return 1.0;
    float z = min(uvz.z, 1.0);

    // One lookup over the widest penumbra this receiver could have finds the occluders' depth
    // (and, for most of the floor, that there are none).
    float search_lod = shadow_lod(clamp(u_penumbra_scale * z, 4.0 / u_shadow_size, 0.25)) + 1.0;
    vec2 search = occluders_from(textureLod(u_shadow_moments, uvz.xy, search_lod).xy);
    if (search.y <= 0.0 || z <= search.x + kShadowBias) return 1.0;
    float width = clamp(u_penumbra_scale * (z - search.x), 1.5 / u_shadow_size, 0.25);
    vec2 here = occluders(uvz.xy, width);
    float behind = smoothstep(here.x + kShadowBias, here.x + 2.0 * kShadowBias, z);
    return 1.0 - here.y * behind;
}
