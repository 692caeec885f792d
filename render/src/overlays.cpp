#include "overlays.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace softbody::render {

namespace {

// Overlay colours, sRGB.
constexpr glm::vec4 kParticleColor{0.93f, 0.95f, 0.98f, 1.0f};
constexpr glm::vec4 kPinColor{0.86f, 0.12f, 0.20f, 1.0f};
constexpr glm::vec4 kSpringRest{0.20f, 0.23f, 0.29f, 0.85f};
constexpr glm::vec4 kSurfaceSpringRest{0.98f, 0.96f, 0.90f, 0.75f};
constexpr glm::vec4 kSpringStretched{0.92f, 0.10f, 0.08f, 1.0f};
constexpr glm::vec4 kSpringCompressed{0.08f, 0.38f, 1.00f, 1.0f};
constexpr glm::vec4 kVelocityColor{0.10f, 0.78f, 0.52f, 0.9f};
constexpr glm::vec4 kComVelocityColor{0.02f, 0.50f, 0.30f, 1.0f};
constexpr glm::vec4 kComColor{1.00f, 0.80f, 0.10f, 1.0f};
constexpr glm::vec4 kNormalColor{0.35f, 0.45f, 0.95f, 0.9f};
constexpr glm::vec4 kForceColor{0.95f, 0.30f, 0.75f, 1.0f};
constexpr glm::vec4 kGrabColor{0.20f, 0.75f, 1.00f, 1.0f};  // the mouse's pull
constexpr glm::vec4 kComLine{0.12f, 0.12f, 0.14f, 0.75f};
constexpr glm::vec4 kOmegaColor{0.98f, 0.78f, 0.12f, 1.0f};     // angular velocity
constexpr glm::vec4 kMomentumColor{0.55f, 0.30f, 0.95f, 1.0f};  // angular momentum
constexpr glm::vec4 kContactColor{0.95f, 0.15f, 0.25f, 1.0f};
constexpr glm::vec4 kLinkColor{0.20f, 0.22f, 0.28f, 1.0f};
constexpr float kStrainForFullColor = 0.15f;  // |l / l0 - 1| that gets the full colour

glm::vec4 strain_color(const glm::vec4& rest, float strain) {
    const float s = std::clamp(std::abs(strain) / kStrainForFullColor, 0.0f, 1.0f);
    return glm::mix(rest, strain > 0.0f ? kSpringStretched : kSpringCompressed, s);
}

// A fixed sequence (a 64-bit linear congruential generator): the same sample on every run.
struct Sequence {
    std::uint64_t state;
    std::uint32_t next(std::uint32_t bound) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<std::uint32_t>((state >> 33) % bound);
    }
};

// An arrow from `from` along `v` (already scaled to metres): a line and a two-stroke head that
// faces the camera.
void arrow(const Camera& cam, const glm::vec3& from, const glm::vec3& v, float min_length, float max_head,
           const glm::vec4& color, float width, std::vector<LineInstance>& lines) {
    const glm::vec3 tip = from + v;
    const float len = glm::length(tip - from);
    if (len < min_length) return;
    const glm::vec3 dir = (tip - from) / len;
    glm::vec3 side = glm::cross(dir, glm::normalize(tip - cam.eye()));
    side = glm::dot(side, side) > 1e-8f ? glm::normalize(side) : cam.right();
    const float head = std::min(0.3f * len, max_head);
    lines.push_back({from, tip, color, width});
    lines.push_back({tip, tip - dir * head + side * (0.5f * head), color, width});
    lines.push_back({tip, tip - dir * head - side * (0.5f * head), color, width});
}

}  // namespace

BodyShape measure_body(std::span<const glm::vec3> particles, const Vec3Span& rest) {
    BodyShape shape;
    if (particles.empty()) return shape;
    glm::dvec3 sum(0.0);
    shape.low = shape.high = particles[0];
    for (const glm::vec3& p : particles) {
        sum += glm::dvec3(p);
        shape.low = glm::min(shape.low, p);
        shape.high = glm::max(shape.high, p);
    }
    shape.centre_of_mass = glm::vec3(sum / double(particles.size()));
    for (const glm::vec3& p : particles) shape.radius = std::max(shape.radius, glm::length(p - shape.centre_of_mass));
    shape.rest_radius = shape.radius;
    if (rest.size == particles.size()) {
        glm::dvec3 rest_sum(0.0);
        for (std::size_t i = 0; i < rest.size; ++i) rest_sum += glm::dvec3(rest[i]);
        const glm::vec3 c(rest_sum / double(rest.size));
        float r = 0.0f;
        for (std::size_t i = 0; i < rest.size; ++i) r = std::max(r, glm::length(rest[i] - c));
        shape.rest_radius = r;
    }
    return shape;
}

std::vector<SpringSample> sample_springs(const Mesh& mesh, std::size_t budget) {
    std::vector<SpringSample> springs;
    const auto n = static_cast<std::uint32_t>(mesh.particle_count());
    auto ordered = [](std::uint32_t a, std::uint32_t b) { return a < b ? std::make_pair(a, b) : std::make_pair(b, a); };

    // Surface edges, in the order the triangles give them.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    std::set<std::pair<std::uint32_t, std::uint32_t>> taken;
    const auto& t = mesh.triangles;
    const auto& rv = mesh.render_vertices;
    for (std::size_t k = 0; k + 2 < t.size(); k += 3) {
        for (std::size_t e = 0; e < 3; ++e) {
            const auto pair = ordered(rv[t[k + e]].particle, rv[t[k + (e + 1) % 3]].particle);
            if (pair.first != pair.second && taken.insert(pair).second) edges.push_back(pair);
        }
    }

    const std::uint64_t total = std::uint64_t(n) * (n > 0 ? n - 1 : 0) / 2;
    if (total <= 2 * budget) {
        for (std::uint32_t i = 0; i < n; ++i) {
            for (std::uint32_t j = i + 1; j < n; ++j) springs.push_back({i, j, taken.count({i, j}) > 0});
        }
        return springs;
    }
    // Every k-th edge when there are more than the cap.
    const std::size_t stride = (edges.size() + kMaxSurfaceSprings - 1) / kMaxSurfaceSprings;
    for (std::size_t e = 0; e < edges.size(); e += std::max<std::size_t>(stride, 1)) {
        springs.push_back({edges[e].first, edges[e].second, true});
    }
    // Then pairs from a fixed pseudo-random sequence.
    Sequence sequence{0x5eed5eedULL};
    std::size_t others = 0;
    for (std::size_t attempts = 0; others < budget && attempts < budget * 20; ++attempts) {
        const std::uint32_t i = sequence.next(n), j = sequence.next(n);
        if (i == j) continue;
        const auto pair = ordered(i, j);
        if (taken.insert(pair).second) {
            springs.push_back({pair.first, pair.second, false});
            ++others;
        }
    }
    return springs;
}

void OverlayBuilder::build(const Frame& frame, std::span<const SoftBodyDrawn> soft, float scene_size, OverlayGeometry& out) {
    out.lines.clear();
    out.spheres.clear();
    out.lines_on_top.clear();
    out.spheres_on_top.clear();
    soft_.resize(soft.size());
    for (std::size_t b = 0; b < soft.size(); ++b) build_soft(frame, frame.soft_bodies[b], soft[b], b == 0, soft_[b], out);
    build_rigid(frame, scene_size, out);
}

void OverlayBuilder::build_soft(const Frame& frame, const BodyView& body, const SoftBodyDrawn& drawn, bool first,
                                SoftCache& cache, OverlayGeometry& out) {
    const std::span<const glm::vec3> x = drawn.particles;
    const std::span<const SurfaceVertex> surface = drawn.surface;
    const BodyShape& shape = drawn.shape;
    const Overlays& on = frame.overlays;
    if (!body.mesh || x.empty()) return;
    const std::size_t n = x.size();

    // Marker sizes follow the body's size at rest and its particle spacing.
    const float r_body = std::max(shape.rest_radius, 1e-3f);
    const float spacing = r_body * std::sqrt(12.566f / float(n));  // surface area shared out
    const float particle_radius = std::min(0.05f * r_body, 0.22f * spacing);

    if (on.springs) {
        const std::size_t triangles = body.mesh->triangle_count();
        if (cache.spring_mesh != body.mesh || cache.spring_mesh_particles != n || cache.spring_mesh_triangles != triangles ||
            cache.spring_budget != frame.appearance.max_springs) {
            cache.springs = sample_springs(*body.mesh, frame.appearance.max_springs);
            cache.spring_mesh = body.mesh;
            cache.spring_mesh_particles = n;
            cache.spring_mesh_triangles = triangles;
            cache.spring_budget = frame.appearance.max_springs;
        }
        const bool strain = body.rest_positions.size == n;
        for (const SpringSample& spring : cache.springs) {
            // Surface springs light and fine: they outline; the ones across the body stand out.
            const glm::vec4 rest = spring.surface ? kSurfaceSpringRest : kSpringRest;
            glm::vec4 color = rest;
            if (strain) {
                const float l0 = glm::length(body.rest_positions[spring.j] - body.rest_positions[spring.i]);
                if (l0 > 0.0f) color = strain_color(rest, glm::length(x[spring.j] - x[spring.i]) / l0 - 1.0f);
            }
            out.lines.push_back({x[spring.i], x[spring.j], color, spring.surface ? 1.0f : 1.6f});
        }
    }

    // A mesh without faces (a point cloud) has no surface to draw: its particles are the body,
    // drawn whether or not the particles overlay is on (unless the body is hidden).
    const bool faceless = (body.surface ? body.surface : body.mesh)->triangle_count() == 0;
    if (on.particles || (faceless && frame.appearance.body != BodyStyle::Hidden)) {
        // When no surface is drawn the particles are the body, and take its colour.
        const bool are_body = frame.appearance.body == BodyStyle::Hidden || faceless;
        const glm::vec4 color = are_body ? glm::vec4(frame.appearance.body_color, 1.0f) : kParticleColor;
        const float radius = are_body ? 1.4f * particle_radius : particle_radius;
        for (std::size_t i = 0; i < n; ++i) out.spheres.push_back({x[i], radius, color});
    }

    if (on.pins && body.inverse_masses.size() == n) {
        const float pin_radius = std::max(1.5f * particle_radius, 0.03f * r_body);
        for (std::size_t i = 0; i < n; ++i) {
            if (body.inverse_masses[i] != 0.0f) continue;
            out.spheres.push_back({x[i], pin_radius, kPinColor});
            // A short stem upward: the particle is held from above.
            out.lines.push_back({x[i], x[i] + glm::vec3(0.0f, 0.0f, 3.0f * pin_radius), glm::vec4(0.25f, 0.25f, 0.28f, 1.0f), 2.0f});
        }
    }

    if (on.velocities && body.velocities.size == n) {
        const float scale = frame.appearance.velocity_scale;
        const auto velocity_arrow = [&](const glm::vec3& from, const glm::vec3& v, const glm::vec4& color, float width,
                                        std::vector<LineInstance>& lines) {
            arrow(frame.camera, from, v * scale, 0.02f * r_body, 0.15f * r_body, color, width, lines);
        };
        // A sample of the particles' own velocities, thin...
        const std::size_t budget = std::max<std::size_t>(1, frame.appearance.max_arrows);
        const std::size_t stride = (n + budget - 1) / budget;
        glm::dvec3 mean(0.0);
        for (std::size_t i = 0; i < n; ++i) mean += glm::dvec3(body.velocities[i]);
        for (std::size_t i = 0; i < n; i += stride) velocity_arrow(x[i], body.velocities[i], kVelocityColor, 1.6f, out.lines);
        // ...and the centre of mass's, bold and always in view.
        velocity_arrow(shape.centre_of_mass, glm::vec3(mean / double(n)), kComVelocityColor, 3.5f, out.lines_on_top);
    }

    if (frame.appearance.body == BodyStyle::Wireframe && body.mesh->triangle_count() > 0) {
        // Every edge of the surface once, in the body's colour.
        if (cache.edge_mesh != body.mesh || cache.edge_mesh_triangles != body.mesh->triangle_count()) {
            auto& edges_ = cache.edges;
            edges_.clear();
            const auto& rv = body.mesh->render_vertices;
            const auto& t = body.mesh->triangles;
            for (std::size_t k = 0; k + 2 < t.size(); k += 3) {
                for (int e = 0; e < 3; ++e) {
                    std::uint32_t a = rv[t[k + e]].particle, b = rv[t[k + (e + 1) % 3]].particle;
                    if (a > b) std::swap(a, b);
                    edges_.emplace_back(a, b);
                }
            }
            std::sort(edges_.begin(), edges_.end());
            edges_.erase(std::unique(edges_.begin(), edges_.end()), edges_.end());
            cache.edge_mesh = body.mesh;
            cache.edge_mesh_triangles = body.mesh->triangle_count();
        }
        const glm::vec4 color(frame.appearance.body_color, 1.0f);
        for (const auto& [a, b] : cache.edges) {
            if (a < n && b < n) out.lines.push_back({x[a], x[b], color, 1.4f});
        }
    }

    if (on.normals && !surface.empty()) {
        // A fixed sample of the render vertices, each with its normal: the shading's input.
        const std::size_t budget = std::max<std::size_t>(1, 4 * frame.appearance.max_arrows);
        const std::size_t stride = (surface.size() + budget - 1) / budget;
        const float length = 0.12f * r_body;
        for (std::size_t i = 0; i < surface.size(); i += stride) {
            out.lines.push_back({surface[i].position, surface[i].position + surface[i].normal * length, kNormalColor, 1.4f});
        }
    }

    if (on.forces && body.forces.size == n) {
        // Net force per particle, the longest drawn at half the body's rest radius.
        float largest = 0.0f;
        for (std::size_t i = 0; i < n; ++i) largest = std::max(largest, glm::length(body.forces[i]));
        if (largest > 0.0f) {
            const float scale = 0.5f * r_body / largest;
            const std::size_t budget = std::max<std::size_t>(1, frame.appearance.max_arrows);
            const std::size_t stride = (n + budget - 1) / budget;
            for (std::size_t i = 0; i < n; i += stride) {
                const glm::vec3 tip = x[i] + body.forces[i] * scale;
                if (glm::length(tip - x[i]) < 0.02f * r_body) continue;
                out.lines_on_top.push_back({x[i], tip, kForceColor, 2.0f});
                out.spheres_on_top.push_back({tip, 0.5f * particle_radius, kForceColor});
            }
        }
    }

    if (first && on.grab && !on.grab_on_rigid && on.grab_particle < n) {
        const glm::vec3 from = x[on.grab_particle];
        out.lines_on_top.push_back({from, on.grab_target, kGrabColor, 2.5f});
        out.spheres_on_top.push_back({from, 1.6f * particle_radius, kGrabColor});
        out.spheres_on_top.push_back({on.grab_target, 1.0f * particle_radius, kGrabColor});
    }

    if (on.center_of_mass) {
        const glm::vec3 c = shape.centre_of_mass;
        const float r = 0.06f * r_body;
        out.spheres_on_top.push_back({c, r, kComColor});
        if (frame.appearance.ground) {
            // A plumb line to the floor and a cross where it lands: the height at a glance.
            const glm::vec3 foot(c.x, c.y, frame.appearance.ground_height);
            out.lines_on_top.push_back({c, foot, kComLine, 1.5f});
            const float a = 2.0f * r;
            out.lines_on_top.push_back({foot - glm::vec3(a, 0, 0), foot + glm::vec3(a, 0, 0), kComLine, 2.0f});
            out.lines_on_top.push_back({foot - glm::vec3(0, a, 0), foot + glm::vec3(0, a, 0), kComLine, 2.0f});
        }
    }
}

// Rigid bodies' markers (centre of mass, velocity, omega and L), the springs between bodies,
// the contacts, and the pull on a rigid body.
void OverlayBuilder::build_rigid(const Frame& frame, float scene_size, OverlayGeometry& out) {
    const Overlays& on = frame.overlays;
    const Camera& cam = frame.camera;
    const float size = std::max(scene_size, 1e-3f);
    for (const RigidBodyView& body : frame.rigid_bodies) {
        if (body.fixed) continue;
        const glm::vec3 c(model_matrix(body)[3]);
        const float r = std::max(body.radius, 1e-3f);
        if (on.center_of_mass) {
            out.spheres_on_top.push_back({c, 0.06f * r, kComColor});
            if (frame.appearance.ground) {
                out.lines_on_top.push_back({c, glm::vec3(c.x, c.y, frame.appearance.ground_height), kComLine, 1.5f});
            }
        }
        if (on.velocities) {
            arrow(cam, c, body.velocity * frame.appearance.velocity_scale, 0.02f * r, 0.15f * r, kComVelocityColor, 3.0f,
                  out.lines_on_top);
        }
        if (on.angular) {
            // omega: one body radius per half turn a second (pi rad/s); L the same, per the
            // angular momentum of that spin about an axis through a point mass at the radius.
            const float per_omega = r / 3.14159265f;
            arrow(cam, c, body.angular_velocity * per_omega, 0.02f * r, 0.2f * r, kOmegaColor, 3.0f, out.lines_on_top);
            const float unit_L = body.mass * r * r;
            if (unit_L > 0.0f) {
                arrow(cam, c, body.angular_momentum * (per_omega / unit_L), 0.02f * r, 0.2f * r, kMomentumColor, 2.0f,
                      out.lines_on_top);
            }
        }
    }
    if (on.links) {
        for (const LinkView& link : frame.links) {
            glm::vec4 color = kLinkColor;
            if (link.rest_length > 0.0f) color = strain_color(kLinkColor, glm::length(link.b - link.a) / link.rest_length - 1.0f);
            out.lines.push_back({link.a, link.b, color, 2.5f});
            out.spheres.push_back({link.a, 0.025f * size, color});
            out.spheres.push_back({link.b, 0.025f * size, color});
        }
    }
    if (on.contacts && !frame.contacts.empty()) {
        // The normal at each contact, as long as its impulse relative to the largest this step.
        float largest = 0.0f;
        for (const ContactView& c : frame.contacts) largest = std::max(largest, c.impulse);
        for (const ContactView& c : frame.contacts) {
            out.spheres_on_top.push_back({c.point, 0.02f * size, kContactColor});
            const float len = largest > 0.0f ? 0.4f * size * c.impulse / largest : 0.0f;
            arrow(cam, c.point, c.normal * std::max(len, 0.08f * size), 0.0f, 0.06f * size, kContactColor, 2.0f,
                  out.lines_on_top);
        }
    }
    for (const ArrowView& a : frame.arrows) {
        arrow(cam, a.from, a.vector, 0.0f, 0.25f * glm::length(a.vector), glm::vec4(a.color, 1.0f), a.width, out.lines_on_top);
    }
    if (on.grab && on.grab_on_rigid) {
        out.lines_on_top.push_back({on.grab_point, on.grab_target, kGrabColor, 2.5f});
        out.spheres_on_top.push_back({on.grab_point, 0.03f * size, kGrabColor});
        out.spheres_on_top.push_back({on.grab_target, 0.02f * size, kGrabColor});
    }
}

}  // namespace softbody::render
