#include "render/deform.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace softbody::render {

void interpolate_positions(const BodyView& body, const glm::vec3& offset, std::vector<glm::vec3>& out) {
    const std::size_t n = body.positions.size;
    if (body.mesh && n != body.mesh->particle_count()) {
        throw std::invalid_argument("body view: " + std::to_string(n) + " positions for a mesh of " +
                                    std::to_string(body.mesh->particle_count()) + " particles");
    }
    out.resize(n);
    const Vec3Span& x = body.positions;
    if (body.previous_positions.size == n && body.alpha < 1.0f) {
        const Vec3Span& p = body.previous_positions;
        const float a = body.alpha, b = 1.0f - body.alpha;
        for (std::size_t i = 0; i < n; ++i) {
            out[i] = glm::vec3(b * p.x[i] + a * x.x[i], b * p.y[i] + a * x.y[i], b * p.z[i] + a * x.z[i]) + offset;
        }
    } else {
        for (std::size_t i = 0; i < n; ++i) out[i] = glm::vec3(x.x[i], x.y[i], x.z[i]) + offset;
    }
}

void DeformedSurface::update(const Mesh& mesh, std::span<const glm::vec3> particles, bool flip_normals) {
    if (particles.size() != mesh.particle_count()) {
        throw std::invalid_argument("deformed surface: particle count does not match the mesh");
    }
    slot_normals_.assign(mesh.normal_slot_count, glm::vec3(0.0f));
    const std::vector<RenderVertex>& rv = mesh.render_vertices;
    const std::uint32_t* t = mesh.triangles.data();
    for (std::size_t k = 0, n = mesh.triangles.size(); k + 2 < n; k += 3) {
        const RenderVertex& a = rv[t[k]];
        const RenderVertex& b = rv[t[k + 1]];
        const RenderVertex& c = rv[t[k + 2]];
        const glm::vec3 pa = particles[a.particle];
        // Twice the triangle's area times its unit normal: large faces weigh more.
        const glm::vec3 n_face = glm::cross(particles[b.particle] - pa, particles[c.particle] - pa);
        slot_normals_[a.normal_slot] += n_face;
        slot_normals_[b.normal_slot] += n_face;
        slot_normals_[c.normal_slot] += n_face;
    }
    const float sign = flip_normals ? -1.0f : 1.0f;
    for (glm::vec3& n : slot_normals_) {
        const float len2 = glm::dot(n, n);
        // A slot whose faces all collapsed keeps a harmless up normal instead of NaN.
        n = len2 > 1e-30f ? n * (sign / std::sqrt(len2)) : glm::vec3(0.0f, 0.0f, sign);
    }
    vertices_.resize(rv.size());
    for (std::size_t i = 0; i < rv.size(); ++i) {
        vertices_[i].position = particles[rv[i].particle];
        vertices_[i].normal = slot_normals_[rv[i].normal_slot];
    }
}

}  // namespace softbody::render
