#version 330 core
in vec2 v_corner;

void main() {
    if (dot(v_corner, v_corner) > 1.0) discard;
}
