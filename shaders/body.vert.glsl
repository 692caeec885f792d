#version 330 core
// A body's surface. A soft body's positions and normals are streamed in every frame, already
// in world space (recomputed from the deformed triangles), and its model matrix is the
// identity; a rigid body's are fixed in its own axes and placed by its model matrix.
uniform mat4 u_view_projection;
uniform mat4 u_model;
uniform mat3 u_normal_matrix;  // inverse transpose of the model matrix's 3x3 part
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_material;  // fixed: where this vertex sits in the body at rest
out vec3 v_world;
out vec3 v_normal;
out vec3 v_material;

void main() {
    v_world = (u_model * vec4(a_position, 1.0)).xyz;
    v_normal = u_normal_matrix * a_normal;
    v_material = a_material;
    gl_Position = u_view_projection * vec4(v_world, 1.0);
}
