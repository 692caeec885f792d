#include "ground_contact.h"

#include <algorithm>
#include <cmath>

namespace softbody {

namespace {

constexpr float kContactTolerance = 1e-5f;  // m: a particle this close to the ground touches it
constexpr float kStaticSpeed = 1e-4f;       // m/s: below this tangential speed, friction is static

}  // namespace

void apply_ground_friction(SoftBody& body, const ParticleState& s, const WorldSettings& world, bool record) {
    if (record) body.contacts.clear();
    if (!world.ground) return;
    Vec3Array& force = body.force;
    const std::size_t n = body.particle_count();
    const float mu_s = world.static_friction, mu_d = world.dynamic_friction;
    if (!record) {
        // RK4's later stages: friction as the step's start found it, for the particles in
        // contact then (held on the ground in these stages: hold_stage_on_ground). Found again
        // from each stage's state, it came and went with the stage's normal force and turned
        // with the stage's v_t, so the stages disagreed on the slide: a particle creeping at
        // 7 mm/s under a stack of cubes reported 80 mm/s the other way.
        for (const ParticleContact& c : body.contacts) {
            const std::uint32_t i = c.particle;
            if (c.held) {
                force.x[i] = 0.0f;  // Eq. 24: held through the step
                force.y[i] = 0.0f;
            } else {
                force.x[i] += c.fx;
                force.y[i] += c.fy;
            }
        }
        return;
    }
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
                contact.fx = -F_tx / F_t * limit;
                contact.fy = -F_ty / F_t * limit;
            }
        } else {
            // Eq. 25: F_friction = -(v_t/|v_t|) mu_d |F_n|.
            const float magnitude = mu_d * -F_n;
            contact.fx = -v_tx / v_t * magnitude;
            contact.fy = -v_ty / v_t * magnitude;
            contact.sliding = true;
        }
        force.x[i] += contact.fx;
        force.y[i] += contact.fy;
        if (record) body.contacts.push_back(contact);
    }
}

void hold_stage_on_ground(SoftBody& body, const WorldSettings& world) {
    if (!world.ground) return;
    const float ground = world.ground_height;
    for (const ParticleContact& c : body.contacts) {
        const std::uint32_t i = c.particle;
        body.x_tmp.z[i] = std::max(body.x_tmp.z[i], ground);
        body.v_stage.z[i] = std::max(body.v_stage.z[i], 0.0f);
    }
}

void resolve_ground_contacts(SoftBody& body, const WorldSettings& world, float h) {
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
    const Vec3Array &x0 = body.x_step_start, &v0 = body.v_step_start;
    std::size_t next = 0;  // body.contacts is in the particles' order
    for (std::size_t i = 0; i < body.particle_count(); ++i) {
        // Pressed into the ground as the step began (it held the particle through the step).
        bool pressed = false;
        if (next < body.contacts.size() && body.contacts[next].particle == i) {
            pressed = true;
            ++next;
        }
        // Below the ground, or on it (or held by it) and moving into it: the next step would
        // take it below.
        if (!(x.z[i] <= ground || pressed) || body.inv_mass[i] == 0.0f) continue;
        const bool below = x.z[i] < ground;
        if (!below && !(v.z[i] < 0.0f)) continue;
        x.z[i] = ground;
        // v_n' = -e v_n, v_n the velocity it met the ground with: as the step ended for a
        // particle in the air as the step began (the step's whole fall, so that a bounce at e = 1
        // climbs back as high as it fell, step for step), but as the step began for one on the
        // ground then. Its velocity at the step's end holds a whole step of every force pressing
        // it in, and a particle at rest under a stack (its springs pressing it down at many g)
        // counted as an impact every step, bounced up at e times that, and reported 0.04 to
        // 0.2 m/s upward for as long as it lay there, unmoving.
        const float v_n = v.z[i];
        const bool on_ground = pressed || x0.z[i] <= ground + kContactTolerance;
        const float v_in = on_ground ? v0.z[i] : v_n;
        if (v_in < -bounce_speed) v.z[i] = -world.restitution * v_in;
        else if (v_n < 0.0f) v.z[i] = 0.0f;
        if (verlet) body.verlet_step.set(i, v[i] * h);
    }
}

double speculative_margin(const RigidBody& body, const RigidMotion& start, double h, double g) {
    return h * (length(start.v) + length(start.omega) * body.bounding_radius) + h * h * g + 1e-3;
}

void rigid_ground_contacts(const RigidBody& body, std::uint32_t index, const double* start, const WorldSettings& world, double h,
                           std::vector<RigidContact>& out) {
    if (!world.ground || body.fixed) return;
    rigid_ground_contacts(body, index, rigid_motion(body, start), world, h, out);
}

void rigid_ground_contacts(const RigidBody& body, std::uint32_t index, const RigidMotion& m0, const WorldSettings& world, double h,
                           std::vector<RigidContact>& out) {
    if (!world.ground || body.fixed) return;
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
