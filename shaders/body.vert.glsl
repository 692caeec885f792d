#version 330 core
// The deformable body: positions and normals are streamed in every frame (already in world
// space, recomputed from the deformed triangles).
uniform mat4 u_view_projection;
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_material;  // fixed: where this vertex sits in the body at rest
out vec3 v_world;
out vec3 v_normal;
out vec3 v_material;

void main() {
    v_world = a_position;
    v_normal = a_normal;
    v_material = a_material;
    gl_Position = u_view_projection * vec4(a_position, 1.0);
}
