#version 330 core
// Depth moments (z, z^2) of the body as the sun sees it; see lighting.glsl.
out vec2 o_moments;

void main() {
    float z = gl_FragCoord.z;
    o_moments = vec2(z, z * z);
}
