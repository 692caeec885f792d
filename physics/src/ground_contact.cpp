#include "ground_contact.h"

#include <algorithm>
#include <cmath>

namespace softbody {

namespace {

constexpr float kContactTolerance = 1e-5f;  // m: a particle this close to the ground touches it
constexpr float kStaticSpeed = 1e-4f;       // m/s: below this tangential speed, friction is static

}  // namespace

void apply_ground_friction(SoftBody& body, const ParticleState& s, const Params& world, bool record) {
    if (record) body.contacts.clear();
    if (!world.ground) return;
    Vec3Array& force = body.force;
    const std::size_t n = body.particle_count();
    const float mu_s = world.static_friction, mu_d = world.dynamic_friction;
    for (std::size_t i = 0; i < n; ++i) {
        if (s.z[i] > world.ground_height + kContactTolerance || body.inv_mass[i] == 0.0f) continue;
        const float F_n = force.z[i];  // F_applied . n; < 0 presses into the ground
        if (!(F_n < 0.0f)) continue;
        const float F_tx = force.x[i], F_ty = force.y[i];
        const float F_t = std::sqrt(F_tx * F_tx + F_ty * F_ty);
        const float v_tx = s.vx[i], v_ty = s.vy[i];
        const float v_t = std::sqrt(v_tx * v_tx + v_ty * v_ty);
        ParticleContact contact{static_cast<std::uint32_t>(i), false, false, s.x[i], s.y[i], v_tx, v_ty};
        if (v_t < kStaticSpeed) {
            // Eq. 24: F_friction = -(F_t/|F_t|) min(mu_s |F_n|, |F_t|).
            const float limit = mu_s * -F_n;
            if (F_t <= limit) {
                force.x[i] = 0.0f;  // cancels F_t exactly: the particle stays put
                force.y[i] = 0.0f;
                contact.held = true;
            } else {
                force.x[i] -= F_tx / F_t * limit;
                force.y[i] -= F_ty / F_t * limit;
            }
        } else {
            // Eq. 25: F_friction = -(v_t/|v_t|) mu_d |F_n|.
            const float magnitude = mu_d * -F_n;
            force.x[i] -= v_tx / v_t * magnitude;
            force.y[i] -= v_ty / v_t * magnitude;
            contact.sliding = true;
        }
        if (record) body.contacts.push_back(contact);
    }
}

void resolve_ground_contacts(SoftBody& body, const Params& world, float h) {
    const bool verlet = world.integrator == Integrator::Verlet;
    Vec3Array &x = body.x, &v = body.v;
    for (const ParticleContact& c : body.contacts) {
        const std::uint32_t i = c.particle;
        const bool reversed = c.sliding && (v.x[i] * c.vx0 + v.y[i] * c.vy0) <= 0.0f;
        if (c.held || reversed) {
            // The slide ends within this step: v_t = 0, and x_t = x_t(start) + v_t h.
            v.x[i] = 0.0f;
            v.y[i] = 0.0f;
            x.x[i] = c.x0;
            x.y[i] = c.y0;
            if (verlet) {
                body.verlet_step.x[i] = 0.0f;
                body.verlet_step.y[i] = 0.0f;
            }
        }
    }
    if (!world.ground) return;
    const float ground = world.ground_height;
    // Impacts slower than two steps of gravity are resting contact, not a bounce.
    const float bounce_speed = 2.0f * std::abs(world.gravity.z) * h;
    for (std::size_t i = 0; i < body.particle_count(); ++i) {
        if (!(x.z[i] < ground) || body.inv_mass[i] == 0.0f) continue;
        x.z[i] = ground;
        const float v_n = v.z[i];
        if (v_n < -bounce_speed) v.z[i] = -world.restitution * v_n;  // v_n' = -e v_n
        else if (v_n < 0.0f) v.z[i] = 0.0f;
        if (verlet) body.verlet_step.set(i, v[i] * h);
    }
}

double speculative_margin(const RigidBody& body, const RigidMotion& start, double h, double g) {
    return h * (length(start.v) + length(start.omega) * body.bounding_radius) + h * h * g + 1e-3;
}

void rigid_ground_contacts(const RigidBody& body, std::uint32_t index, const double* start, const Params& world, double h,
                           std::vector<RigidContact>& out) {
    if (!world.ground || body.fixed) return;
    const RigidMotion m0 = rigid_motion(body, start);
    const Vec3d n{0.0, 0.0, 1.0};
    const double ground = world.ground_height;
    const double margin = speculative_margin(body, m0, h, length(Vec3d(world.gravity)));
    RigidContact c;
    c.a = index;
    c.b = -1;
    c.normal = n;
    c.restitution = body.restitution.value_or(world.restitution);
    c.friction = body.friction.value_or(world.dynamic_friction);
    c.rolling = double(body.rolling_resistance) * body.rolling_radius;
    // `local`: the point in body axes.
    const auto add = [&](const Vec3d& local, std::uint32_t feature, std::vector<RigidContact>& into) {
        const Vec3d p0 = m0.x + m0.R * local;
        if (p0.z - ground > margin) return;
        c.feature = feature;
        c.point = p0;
        c.arm_a = p0 - m0.x;
        c.separation = p0.z - ground;
        c.depth = -c.separation;
        into.push_back(c);
    };
    if (body.shape == ShapeKind::Sphere) {
        // Its lowest point, r below the centre whichever way the ball has turned: a ball is round
        // however its quaternion has drifted (m0.R, from a q longer than 1 under explicit Euler
        // or RK4, is no rotation, and R R^T (-r n) would put the point below the ball's surface:
        // a rolling ball was pushed up out of a ground it did not touch).
        const Vec3d p0 = m0.x - n * body.radius;
        if (p0.z - ground > margin) return;
        c.feature = 0;
        c.point = p0;
        c.arm_a = p0 - m0.x;
        c.separation = p0.z - ground;
        c.depth = -c.separation;
        out.push_back(c);
        return;
    }
    std::vector<RigidContact> points;
    for (std::size_t v = 0; v < body.hull->vertices.size(); ++v) add(body.hull->vertices[v], std::uint32_t(v), points);
    // Cut to four by how deep each point will be by the end of `h`, coming in at its own speed
    // (v + w x r) . n and by how far the body's turn bends its path in (half the turn squared
    // times its arm), where that is more than the touching band (a body at rest ranks its
    // points by their gaps alone, as before). Then the points the four left out that will touch
    // within `h` all the same make a manifold of their own (the solver takes each four of a pair
    // as one manifold), and so on. By the gap alone, the four kept under a cylinder rolling on
    // its side were its two on the ground and, by area, two rising behind it 3 cm up; the two
    // coming down ahead were left out, met the ground unheld and went 1 mm into it every facet.
    // A rolling prism can bring three lines of points to the ground in a tick: six points.
    const double turn = length(m0.omega) * h;
    for (RigidContact& point : points) {
        const double coming = h * -dot(m0.v + cross(m0.omega, point.arm_a), n) + 0.5 * turn * turn * length(point.arm_a);
        if (coming > kManifoldTouching) point.depth += coming;
    }
    while (!points.empty()) {
        std::vector<RigidContact> manifold = points;
        reduce_manifold(manifold, n);
        std::erase_if(points, [&](const RigidContact& p) {
            if (p.depth < -kManifoldTouching) return true;  // apart as far as `h` reaches
            for (const RigidContact& kept : manifold) {
                if (kept.feature == p.feature) return true;
            }
            return false;
        });
        for (RigidContact& point : manifold) point.depth = -point.separation;
        out.insert(out.end(), manifold.begin(), manifold.end());
    }
}

}  // namespace softbody
