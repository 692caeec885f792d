#include "particle_contacts.h"

#include <algorithm>
#include <cmath>

#include "ground_contact.h"

namespace softbody {

namespace {
constexpr double kParticleRestSpeed = 1e-4;  // m/s across the surface: below it, the particle is at rest (Eq. 24)
}  // namespace

void particle_rigid_contacts(const SoftBody& body, std::int32_t soft, std::span<const RigidBody> bodies, std::span<const CollisionShape> shapes,
                             std::span<const double> start, const WorldSettings& world, double h, std::vector<RigidContact>& out) {
    const std::size_t n = body.particle_count();
    if (n == 0 || bodies.empty()) return;
    const double g = length(Vec3d(world.gravity));
    // How far each particle can go in the tick: at its speed, with gravity, twice what its
    // last tick's forces added to the way it went (x - x_prev - v h, about a h^2 / 2), and a
    // millimetre; the box that holds the body with it.
    std::vector<double> reach(n);
    double most = 0.0;
    Vec3 lo = body.x[0], hi = body.x[0];
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 p = body.x[i];
        const double pushed = double(length(p - body.x_tick_prev[i] - body.v[i] * float(h)));
        reach[i] = h * double(length(body.v[i])) + 2.0 * pushed + h * h * g + 1e-3;
        most = std::max(most, reach[i]);
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const RigidBody& rigid = bodies[b];
        const double* s = &start[b * rigid::kStateSize];
        const RigidMotion m = rigid_motion(rigid, s);
        const double margin = rigid.fixed ? 0.0 : speculative_margin(rigid, m, h, g);
        // Broad phase: the body's box against the rigid body's bounding sphere, grown by both reaches.
        const double r = shapes[b].bounding_radius + margin + most;
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
            const Vec3d p(body.x[i]);
            if (dot(p - m.x, p - m.x) > r * r) continue;
            // Each particle's own reach, and how far the body's surface can come.
            const std::optional<SurfacePoint> hit = point_contact(shapes[b], pose, p, margin + reach[i]);
            if (!hit) continue;
            c.a = std::uint32_t(i);
            c.feature = 0;
            c.point = hit->point;
            c.normal = hit->normal;
            c.separation = -hit->depth;
            c.depth = hit->depth;
            c.arm_a = {};
            c.arm_b = hit->point - m.x;
            const Vec3d v_rel = Vec3d(body.v[i]) - (m.v + cross(m.omega, c.arm_b));
            const Vec3d v_t = v_rel - c.normal * dot(v_rel, c.normal);
            c.static_friction = length(v_t) < kParticleRestSpeed ? mu_s : c.friction;
            out.push_back(c);
        }
    }
}

void hold_stage_off_rigid(std::span<SoftBody> soft, std::span<const RigidContact> contacts, std::span<const RigidBody> bodies,
                          std::span<const double> found, std::span<const double> stage) {
    for (const RigidContact& c : contacts) {
        if (c.soft < 0 || c.b < 0) continue;
        SoftBody& body = soft[std::size_t(c.soft)];
        const std::uint32_t i = c.a;
        if (body.inv_mass[i] == 0.0f) continue;
        const RigidBody& rigid = bodies[std::size_t(c.b)];
        const RigidMotion m0 = rigid_motion(rigid, &found[std::size_t(c.b) * rigid::kStateSize]);
        const RigidMotion m = rigid_motion(rigid, &stage[std::size_t(c.b) * rigid::kStateSize]);
        // The contact's plane, turned and moved with the body (q made unit: rigid_motion's R is
        // Listing 9's, from q as it is).
        const Mat3 turn = m.q.normalized().to_matrix() * m0.q.normalized().to_matrix().transposed();
        const Vec3d n = turn * c.normal, p = m.x + turn * (c.point - m0.x);
        const Vec3d x(body.x_tmp[i]);
        const double d = dot(x - p, n);
        if (!(d < 0.0)) continue;
        body.x_tmp.set(i, to_float(x - n * d));
        const Vec3d v(body.v_stage[i]);
        const double v_n = dot(v - (m.v + cross(m.omega, p - m.x)), n);
        if (v_n < 0.0) body.v_stage.set(i, to_float(v - n * v_n));
    }
}

}  // namespace softbody
