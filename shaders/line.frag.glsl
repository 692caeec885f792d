#version 330 core
in vec4 v_color;
in float v_across;
out vec4 o_color;

void main() {
    // Full inside the nominal width, fading over the last pixel or so.
    float edge = 1.0 - smoothstep(1.0, 1.0 + 1.5 * fwidth(v_across) + 1e-4, abs(v_across));
    o_color = vec4(v_color.rgb, v_color.a * edge);
}
