#include "particle_contacts.h"

#include <algorithm>
#include <cmath>

#include "ground_contact.h"

namespace softbody {

namespace {
constexpr double kStaticSpeed = 1e-4;  // m/s across the surface: below it, the particle is at rest (Eq. 24)
}  // namespace

void particle_rigid_contacts(const SoftBody& body, std::int32_t soft, std::span<const RigidBody> bodies, std::span<const CollisionShape> shapes,
                             std::span<const double> start, const Params& world, double h, std::vector<RigidContact>& out) {
    const std::size_t n = body.particle_count();
    if (n == 0 || bodies.empty()) return;
    const Vec3Array &x_start = body.x_step_start, &v_start = body.v_step_start;
    // How far any particle moved this step, and the box that holds the body's start with it.
    float reach = 0.0f;
    Vec3 lo = x_start[0], hi = x_start[0];
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 p = x_start[i];
        reach = std::max(reach, length(body.x[i] - p));
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const double g = length(Vec3d(world.gravity));
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const RigidBody& rigid = bodies[b];
        const double* s = &start[b * rigid::kStateSize];
        const RigidMotion m = rigid_motion(rigid, s);
        const double margin = rigid.fixed ? 1e-3 : speculative_margin(rigid, m, h, g);
        // Broad phase: the body's box against the rigid body's bounding sphere, grown by both reaches.
        const double r = shapes[b].bounding_radius + margin + double(reach);
        const Vec3d low(lo), high(hi);
        bool apart = false;
        for (int k = 0; k < 3; ++k) apart = apart || m.x[k] + r < low[k] || m.x[k] - r > high[k];
        if (apart) continue;
        const Pose pose = pose_of(s);
        RigidContact c;
        c.soft = soft;
        c.b = std::int32_t(b);
        c.restitution = std::max(world.restitution, rigid.restitution.value_or(world.restitution));
        c.friction = rigid.friction.value_or(world.dynamic_friction);
        const double mu_s = rigid.friction.value_or(world.static_friction);
        for (std::size_t i = 0; i < n; ++i) {
            if (rigid.fixed && body.inv_mass[i] == 0.0f) continue;  // nothing there can move
            const Vec3d p(x_start[i]);
            if (dot(p - m.x, p - m.x) > r * r) continue;
            // Each particle's own reach: how far it moved, and how far the body's surface can.
            const double own = margin + double(length(body.x[i] - x_start[i]));
            const std::optional<SurfacePoint> hit = point_contact(shapes[b], pose, p, own);
            if (!hit) continue;
            c.a = std::uint32_t(i);
            c.feature = 0;
            c.point = hit->point;
            c.normal = hit->normal;
            c.separation = -hit->depth;
            c.depth = hit->depth;
            c.arm_a = {};
            c.arm_b = hit->point - m.x;
            c.local_a = {};
            c.local_b = m.R.transposed() * c.arm_b;
            const Vec3d v_rel = Vec3d(v_start[i]) - (m.v + cross(m.omega, c.arm_b));
            const Vec3d v_t = v_rel - c.normal * dot(v_rel, c.normal);
            c.static_friction = length(v_t) < kStaticSpeed ? mu_s : c.friction;
            out.push_back(c);
        }
    }
}

double particle_separation(const RigidContact& c, const Vec3Array& x, std::span<const RigidBody> bodies,
                           std::span<const double> state) {
    const RigidMotion m = rigid_motion(bodies[std::size_t(c.b)], &state[std::size_t(c.b) * rigid::kStateSize]);
    return dot(Vec3d(x[c.a]) - (m.x + m.R * c.local_b), c.normal);
}

}  // namespace softbody
