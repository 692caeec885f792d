// Picking (view.h): what is under the mouse, a soft body's particle or a point of a rigid body.
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "body_view.h"
#include "gui/view.h"

namespace softbody::app {

namespace {

// Where a ray first meets a mesh's triangles (Moller-Trumbore), as a distance along it; none
// when it misses.
std::optional<float> ray_mesh(const Mesh& mesh, const glm::vec3& origin, const glm::vec3& direction) {
    std::optional<float> nearest;
    for (std::size_t k = 0; k + 2 < mesh.triangles.size(); k += 3) {
        const Vec3 a = mesh.positions[mesh.render_vertices[mesh.triangles[k]].particle];
        const Vec3 b = mesh.positions[mesh.render_vertices[mesh.triangles[k + 1]].particle];
        const Vec3 c = mesh.positions[mesh.render_vertices[mesh.triangles[k + 2]].particle];
        const glm::vec3 p0 = to_glm(a), e1 = to_glm(b) - p0, e2 = to_glm(c) - p0;
        const glm::vec3 h = glm::cross(direction, e2);
        const float det = glm::dot(e1, h);
        if (std::abs(det) < 1e-12f) continue;
        const glm::vec3 s = origin - p0;
        const float u = glm::dot(s, h) / det;
        if (u < 0.0f || u > 1.0f) continue;
        const glm::vec3 q = glm::cross(s, e1);
        const float v = glm::dot(direction, q) / det;
        if (v < 0.0f || u + v > 1.0f) continue;
        const float t = glm::dot(e2, q) / det;
        if (t > 0.0f && (!nearest || t < *nearest)) nearest = t;
    }
    return nearest;
}

}  // namespace

std::optional<Pick> View::pick(const World& world, float x, float y, float width, float height, float radius) const {
    const glm::mat4 clip = camera.projection(width / height) * camera.view();
    std::optional<Pick> best;
    for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
        const auto& p = world.soft_body(b).x;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const glm::vec4 c = clip * glm::vec4(to_glm(p[i]), 1.0f);
            if (c.w <= 0.0f) continue;
            const float sx = (c.x / c.w * 0.5f + 0.5f) * width, sy = (0.5f - c.y / c.w * 0.5f) * height;
            const float d2 = (sx - x) * (sx - x) + (sy - y) * (sy - y);
            if (d2 > radius * radius) continue;
            // Within reach: the nearest to the eye wins (it is the one drawn in front).
            if (!best || c.w < best->depth) {
                best = Pick{false, static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(i), {}, c.w};
            }
        }
    }
    // Rigid bodies: the ray against each body's own mesh, in its own axes.
    glm::vec3 origin, direction;
    mouse_ray(camera, x, y, width, height, origin, direction);
    for (std::size_t b = 0; b < world.rigid_body_count(); ++b) {
        if (world.rigid_body(b).fixed) continue;
        const glm::mat4 model = render::model_matrix(rigid_body_view(world, b));
        const glm::mat4 to_body = glm::inverse(model);
        const glm::vec3 o(to_body * glm::vec4(origin, 1.0f));
        const glm::vec3 d(to_body * glm::vec4(direction, 0.0f));
        const auto t = ray_mesh(world.rigid_body(b).render_mesh, o, d);
        if (!t) continue;
        // The map to body axes is affine, so one distance t serves both rays.
        const glm::vec3 hit_world = origin + direction * *t;
        const glm::vec3 hit_body = o + d * *t;
        const float depth = glm::dot(hit_world - camera.eye(), camera.forward());
        if (!best || depth < best->depth) {
            best = Pick{true, static_cast<std::uint32_t>(b), 0, Vec3d{hit_body.x, hit_body.y, hit_body.z}, depth};
        }
    }
    return best;
}

}  // namespace softbody::app
