#include "physics/inspect.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "forces.h"
#include "physics/contact.h"

namespace softbody {

namespace {

std::string newtons(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g N", double(value));
    return text;
}

}  // namespace

ParticleInspection inspect_particle(const World& world, std::size_t b, std::uint32_t i) {
    if (b >= world.soft_body_count()) throw std::out_of_range("inspect_particle: no such soft body");
    const SoftBody& body = world.soft_body(b);
    const std::size_t n = body.particle_count();
    if (i >= n) throw std::out_of_range("inspect_particle: no such particle");
    const WorldSettings& p = world.settings();
    const float h = p.dt / float(world.substeps_in_use());

    ParticleInspection out;
    out.body = b;
    out.particle = i;
    out.x = body.x[i];
    out.v = body.v[i];
    const bool pinned = body.inv_mass[i] == 0.0f;
    out.mass = pinned ? 0.0f : body.mass;
    const auto add = [&](std::string name, std::string equation, const Vec3& F, std::string detail = {}) {
        out.terms.push_back({std::move(name), std::move(equation), F, std::move(detail)});
    };

    // Listing 8's weight.
    add("weight", "Listing 8", p.gravity * body.mass, "m g, m = " + std::to_string(body.mass).substr(0, 6) + " kg");

    // Eq. 21 and 22: every other particle, as the reference kernel computes each pair.
    Vec3 springs, dampers;
    std::vector<PairTerm> pairs;
    for (std::uint32_t j = 0; j < n; ++j) {
        if (j == i) continue;
        const Vec3 d = body.x[j] - body.x[i];
        const float l = length(d);
        if (l == 0.0f) continue;
        const Vec3 d_hat = d / l;
        const float l0 = length(body.rest[j] - body.rest[i]);
        PairTerm pair{j, l, l0, body.stiffness * (l - l0) * d_hat, body.damping * dot(body.v[j] - body.v[i], d_hat) * d_hat};
        springs += pair.spring;
        dampers += pair.damper;
        pairs.push_back(pair);
    }
    const auto strength = [](const PairTerm& t) { return length(t.spring + t.damper); };
    const std::size_t keep = std::min<std::size_t>(3, pairs.size());
    std::partial_sort(pairs.begin(), pairs.begin() + std::ptrdiff_t(keep), pairs.end(),
                      [&](const PairTerm& x, const PairTerm& y) { return strength(x) > strength(y); });
    out.strongest.assign(pairs.begin(), pairs.begin() + std::ptrdiff_t(keep));
    add("springs", "Eq. 21", springs, std::to_string(n - 1) + " pairs, k (l - l0) along each");
    add("dampers", "Eq. 22", dampers, std::to_string(n - 1) + " pairs, c (v_rel . d) along each");

    // What else pushes the whole body, for drag's implicit step (forces.h): weights, the grab,
    // the links (the springs and dampers cancel in pairs).
    Vec3Array others;
    others.resize(n);
    for (std::size_t k = 0; k < n; ++k) others.set(k, p.gravity * body.mass);
    const ParticleState s = current_state(body);
    Vec3 grab_force, link_force_here;
    if (world.grab() && !world.grab()->rigid && world.grab()->body == b) {
        Vec3Array g;
        g.resize(n);
        add_grab(g, s, *world.grab(), body.mass, h);
        const std::uint32_t k = world.grab()->particle;
        others.add(k, g[k]);
        if (k == i) grab_force = g[k];
    }
    for (const Link& link : world.links()) {
        const auto end_velocity = [&](const LinkEnd& end) {
            switch (end.kind) {
                case LinkEnd::Kind::World: return Vec3d{};
                case LinkEnd::Kind::Rigid: {
                    const RigidMotion m = world.rigid_motion(end.body);
                    return m.v + cross(m.omega, m.R * end.point);
                }
                case LinkEnd::Kind::Soft: return Vec3d(world.soft_body(end.body).v[end.particle]);
            }
            return Vec3d{};
        };
        const Vec3d F = link_force(link, world.link_end_position(link.a), end_velocity(link.a),
                                   world.link_end_position(link.b), end_velocity(link.b));
        for (const auto& [end, sign] : {std::pair{link.a, 1.0}, std::pair{link.b, -1.0}}) {
            if (end.kind != LinkEnd::Kind::Soft || end.body != b) continue;
            others.add(end.particle, to_float(F * sign));
            if (end.particle == i) link_force_here += to_float(F * sign);
        }
    }
    if (length(grab_force) > 0.0f) add("grab", "", grab_force, "the mouse's damped spring");
    if (length(link_force_here) > 0.0f) add("springs to other bodies", "Eq. 33", link_force_here);

    // Eq. 23, this particle's share, by the step's own function.
    if (body.def.drag_coefficient > 0.0f && p.air_density > 0.0f) {
        Vec3Array with = others;
        add_drag(with, s, n, p.air_density, body.def.drag_coefficient, body.rest_radius, body.mass, h);
        add("drag", "Eq. 23", with[i] - others[i], "its share of -1/2 rho C_D S |v| v (implicit over the step)");
    }

    // The ground: everything above presses the particle into it or not (F_applied . n), and
    // Coulomb friction acts as apply_ground_friction decides (Eq. 24, 25).
    Vec3 applied;
    for (const ForceTerm& t : out.terms) applied += t.force;
    constexpr float kContactTolerance = 1e-5f, kStaticSpeed = 1e-4f;  // as in ground_contact.cpp
    if (p.ground && !pinned && out.x.z <= p.ground_height + kContactTolerance && applied.z < 0.0f) {
        out.on_ground = true;
        const float F_n = -applied.z;
        add("ground", "contact", Vec3{0.0f, 0.0f, F_n}, "holds it up: " + newtons(F_n) + " against the push into it");
        const Vec3 F_t{applied.x, applied.y, 0.0f};
        const Vec3 v_t{out.v.x, out.v.y, 0.0f};
        if (length(v_t) < kStaticSpeed) {
            const float limit = p.static_friction * F_n;
            if (length(F_t) <= limit) {
                out.friction = FrictionRegime::Held;
                add("friction", "Eq. 24", -F_t, "static, held: |F_t| " + newtons(length(F_t)) + " <= mu_s |F_n| " + newtons(limit));
            } else {
                out.friction = FrictionRegime::Slipping;
                add("friction", "Eq. 24", F_t * (-limit / length(F_t)),
                    "static, slipping: |F_t| " + newtons(length(F_t)) + " > mu_s |F_n| " + newtons(limit));
            }
        } else {
            out.friction = FrictionRegime::Sliding;
            const float magnitude = p.dynamic_friction * F_n;
            add("friction", "Eq. 25", v_t * (-magnitude / length(v_t)),
                "dynamic: mu_d |F_n| " + newtons(magnitude) + " against the slide");
        }
    }

    // Rigid bodies it touched in the last step: the impulse of Eq. 38 over that step.
    for (const RigidContact& c : world.contacts()) {
        if (c.soft != std::int32_t(b) || c.a != i || (c.normal_impulse == 0.0 && c.tangent_impulse[0] == 0.0 &&
                                                      c.tangent_impulse[1] == 0.0)) {
            continue;
        }
        const Vec3d J = contact_impulse(c);
        char detail[96];
        std::snprintf(detail, sizeof detail, "lambda %.3g N s over the step (h = %.3g s)", c.normal_impulse, double(h));
        add("contact with '" + world.rigid_body(std::size_t(c.b)).name + "'", "Eq. 38", to_float(J / double(h)), detail);
    }

    // Other soft bodies (or its own, with self_collision) in the last substep: as the particle
    // against their surface, and as a corner of a triangle another body's particle pressed on.
    for (const SoftContact& c : world.soft_contacts()) {
        const std::string other = "'" + world.soft_body(c.body_a == b ? c.body_b : c.body_a).name() + "'";
        char detail[128];
        if (c.body_a == b && c.particle == i) {
            std::snprintf(detail, sizeof detail, "against its surface: lambda %.3g N s over the substep, friction %.3g N s",
                          c.normal_impulse, c.tangent_impulse);
            add("contact with " + other, "Eq. 38", to_float(c.impulse / double(h)), detail);
        }
        for (int k = 0; k < 3; ++k) {
            if (c.body_b != b || c.other[k] != i || c.weight[k] == 0.0f || (k > 0 && c.other[k] == c.other[0])) continue;
            std::snprintf(detail, sizeof detail, "a particle of it on a triangle here: weight %.2f of %.3g N s", double(c.weight[k]),
                          length(c.impulse));
            add("contact from " + other, "Eq. 38", to_float(c.impulse * -double(c.weight[k]) / double(h)), detail);
        }
    }

    for (const ForceTerm& t : out.terms) out.net += t.force;
    out.a = pinned ? Vec3{} : out.net / body.mass;
    return out;
}

RigidInspection inspect_rigid(const World& world, std::size_t b) {
    if (b >= world.rigid_body_count()) throw std::out_of_range("inspect_rigid: no such rigid body");
    const RigidBody& body = world.rigid_body(b);
    const RigidMotion m = world.rigid_motion(b);
    const WorldSettings& p = world.settings();
    const float h = p.dt / float(world.substeps_in_use());
    RigidInspection out;
    out.body = b;
    if (body.fixed) return out;  // scenery: nothing moves it
    const auto add = [&](std::string name, std::string equation, const Vec3d& F, const Vec3d& tau, std::string detail = {},
                         const Vec3d& impulse = {}) {
        out.terms.push_back({std::move(name), std::move(equation), F, tau, impulse, std::move(detail)});
    };
    add("weight", "Listing 9", Vec3d(p.gravity) * body.mass, {}, "at the centre of mass: no torque");
    Wrench others;
    others.F = Vec3d(p.gravity) * body.mass;
    if (world.grab() && world.grab()->rigid && world.grab()->body == b) {
        Wrench w;
        add_rigid_grab(w, body, m, *world.grab(), h);
        others.F += w.F;
        add("grab", "Eq. 27", w.F, w.tau, "the mouse's damped spring at the grabbed point");
    }
    for (const Link& link : world.links()) {
        for (const auto& [end, sign] : {std::pair{link.a, 1.0}, std::pair{link.b, -1.0}}) {
            if (end.kind != LinkEnd::Kind::Rigid || end.body != b) continue;
            const auto velocity = [&](const LinkEnd& e) {
                if (e.kind == LinkEnd::Kind::Rigid) {
                    const RigidMotion em = world.rigid_motion(e.body);
                    return em.v + cross(em.omega, em.R * e.point);
                }
                if (e.kind == LinkEnd::Kind::Soft) return Vec3d(world.soft_body(e.body).v[e.particle]);
                return Vec3d{};
            };
            const Vec3d F = link_force(link, world.link_end_position(link.a), velocity(link.a), world.link_end_position(link.b),
                                       velocity(link.b)) * sign;
            const Vec3d r = world.link_end_position(end) - m.x;
            others.F += F;
            add("spring to another body", "Eq. 33", F, cross(r, F), "at r from the centre of mass: tau = r x F (Eq. 27)");
        }
    }
    if (body.drag_coefficient > 0.0f && p.air_density > 0.0f) {
        Wrench w = others;
        add_rigid_drag(w, body, m, p.air_density, h);
        add("drag", "Eq. 23", w.F - others.F, {}, "at the centre of mass (implicit over the step)");
    }
    for (const RigidContact& c : world.contacts()) {
        const bool a_side = c.soft < 0 && c.a == b, b_side = c.b == std::int32_t(b);
        if (!a_side && !b_side) continue;
        const Vec3d J = contact_impulse(c) * (a_side ? 1.0 : -1.0);
        if (J == Vec3d{}) continue;
        const Vec3d r = a_side ? c.arm_a : c.arm_b;
        const std::string other = c.soft >= 0 ? "a particle of '" + world.soft_body(std::size_t(c.soft)).name() + "'"
                                  : c.b < 0          ? "the ground"
                                  : a_side           ? "'" + world.rigid_body(std::size_t(c.b)).name + "'"
                                                     : "'" + world.rigid_body(c.a).name + "'";
        char detail[96];
        std::snprintf(detail, sizeof detail, "impulse %.3g N s; dL = r x J", length(J));
        add("contact with " + other, "Eq. 37", J / double(h), cross(r, J) / double(h), detail, J);
    }
    for (const WrenchTerm& t : out.terms) {
        out.force += t.force;
        out.torque += t.torque;
    }
    return out;
}

}  // namespace softbody
