// Picking (view.h): what is under the mouse, a soft body's particle or a point of a rigid body.
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "body_view.h"
#include "gui/view.h"

namespace softbody::app {

namespace {

// Where a ray first meets a mesh's triangles (Moller-Trumbore): the distance along it and the
// triangle's three particles; none when it misses. `at(particle)` is where a particle is.
struct RayHit {
    float t = 0.0f;
    std::uint32_t corners[3] = {0, 0, 0};
};

template <class Position>
std::optional<RayHit> ray_surface(const Mesh& mesh, Position at, const glm::vec3& origin, const glm::vec3& direction) {
    std::optional<RayHit> nearest;
    for (std::size_t k = 0; k + 2 < mesh.triangles.size(); k += 3) {
        const std::uint32_t i = mesh.render_vertices[mesh.triangles[k]].particle;
        const std::uint32_t j = mesh.render_vertices[mesh.triangles[k + 1]].particle;
        const std::uint32_t l = mesh.render_vertices[mesh.triangles[k + 2]].particle;
        const glm::vec3 p0 = at(i), e1 = at(j) - p0, e2 = at(l) - p0;
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
        if (t > 0.0f && (!nearest || t < nearest->t)) nearest = RayHit{t, {i, j, l}};
    }
    return nearest;
}

}  // namespace

std::optional<Pick> View::pick(const World& world, float x, float y, float width, float height, float radius) const {
    const glm::mat4 clip = camera.projection(width / height) * camera.view();
    std::optional<Pick> best;
    glm::vec3 origin, direction;
    mouse_ray(camera, x, y, width, height, origin, direction);
    for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
        const SoftBody& body = world.soft_body(b);
        const auto& p = body.x;
        // A body with a surface: the ray against its triangles as they are now, and of the
        // triangle it meets first, the corner nearest the hit (a finger in the middle of a ball
        // lands on the ball, however far its particles are from that point on the screen).
        const Mesh& surface = body.reduced ? body.particle_mesh : body.mesh;
        const auto position = [&](std::uint32_t i) { return to_glm(p[i]); };
        if (const auto hit = ray_surface(surface, position, origin, direction)) {
            const glm::vec3 point = origin + direction * hit->t;
            std::uint32_t corner = hit->corners[0];
            for (const std::uint32_t c : hit->corners) {
                if (glm::distance(position(c), point) < glm::distance(position(corner), point)) corner = c;
            }
            const float depth = glm::dot(point - camera.eye(), camera.forward());
            if (!best || depth < best->depth) best = Pick{false, static_cast<std::uint32_t>(b), corner, {}, depth};
            continue;
        }
        // Else (a point cloud, or the ray passing by the edge): a particle within `radius` on
        // the screen, the nearest to the eye.
        for (std::size_t i = 0; i < p.size(); ++i) {
            const glm::vec4 c = clip * glm::vec4(to_glm(p[i]), 1.0f);
            if (c.w <= 0.0f) continue;
            const float sx = (c.x / c.w * 0.5f + 0.5f) * width, sy = (0.5f - c.y / c.w * 0.5f) * height;
            const float d2 = (sx - x) * (sx - x) + (sy - y) * (sy - y);
            if (d2 > radius * radius) continue;
            if (!best || c.w < best->depth) {
                best = Pick{false, static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(i), {}, c.w};
            }
        }
    }
    // Rigid bodies: the ray against each body's own mesh, in its own axes.
    for (std::size_t b = 0; b < world.rigid_body_count(); ++b) {
        if (world.rigid_body(b).fixed) continue;
        const glm::mat4 model = render::model_matrix(rigid_body_view(world, b));
        const glm::mat4 to_body = glm::inverse(model);
        const glm::vec3 o(to_body * glm::vec4(origin, 1.0f));
        const glm::vec3 d(to_body * glm::vec4(direction, 0.0f));
        const Mesh& mesh = world.rigid_body(b).render_mesh;
        const auto hit = ray_surface(mesh, [&](std::uint32_t i) { return to_glm(mesh.positions[i]); }, o, d);
        if (!hit) continue;
        // The map to body axes is affine, so one distance t serves both rays.
        const glm::vec3 hit_world = origin + direction * hit->t;
        const glm::vec3 hit_body = o + d * hit->t;
        const float depth = glm::dot(hit_world - camera.eye(), camera.forward());
        if (!best || depth < best->depth) {
            best = Pick{true, static_cast<std::uint32_t>(b), 0, Vec3d{hit_body.x, hit_body.y, hit_body.z}, depth};
        }
    }
    return best;
}

}  // namespace softbody::app
