#version 330 core
in vec2 v_corner;
out vec2 o_moments;

void main() {
    if (dot(v_corner, v_corner) > 1.0) discard;
    float z = gl_FragCoord.z;
    o_moments = vec2(z, z * z);
}
