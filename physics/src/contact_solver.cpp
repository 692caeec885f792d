#include "contact_solver.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "physics/portable_math.h"

namespace softbody {

namespace {

// One side of a contact: a rigid body's state, a particle, or nothing (the ground: 1/m = 0,
// J^-1 = 0).
struct Side {
    double* s = nullptr;               // a rigid body's thirteen numbers
    const SolverParticles* p = nullptr;  // or a soft body's particles, and which one
    std::size_t i = 0;
    double inv_mass = 0.0;
    Mat3 J_inv;  // world axes (Eq. 32), fixed for the velocity pass; zero for a particle

    bool moves() const { return inv_mass > 0.0 || !(J_inv == Mat3{}); }
    Vec3d centre() const {
        if (s) return {s[rigid::X], s[rigid::X + 1], s[rigid::X + 2]};
        if (p) return {p->x[i], p->y[i], p->z[i]};
        return {};
    }
    // Velocity of the body's material point at offset r from its centre of mass: v + w x r.
    Vec3d point_velocity(const Vec3d& r) const {
        if (p) return {p->vx[i], p->vy[i], p->vz[i]};
        if (!s || !moves()) return {};
        const Vec3d v = Vec3d{s[rigid::P], s[rigid::P + 1], s[rigid::P + 2]} * inv_mass;
        const Vec3d omega = J_inv * Vec3d{s[rigid::L], s[rigid::L + 1], s[rigid::L + 2]};
        return v + cross(omega, r);
    }
    // An impulse j at offset r: P += j (Eq. 9, 10), L += r x j (Eq. 37); a particle's v += j / m.
    void apply(const Vec3d& j, const Vec3d& r) const {
        if (inv_mass == 0.0) return;
        if (p) {
            p->vx[i] = float(double(p->vx[i]) + j.x * inv_mass);
            p->vy[i] = float(double(p->vy[i]) + j.y * inv_mass);
            p->vz[i] = float(double(p->vz[i]) + j.z * inv_mass);
            return;
        }
        const Vec3d dL = cross(r, j);
        for (int k = 0; k < 3; ++k) {
            s[rigid::P + k] += j[k];
            s[rigid::L + k] += dL[k];
        }
    }
    // The position pass's move of the centre (and, for a particle, of the particle).
    void move(const Vec3d& d) const {
        if (p) {
            p->x[i] = float(double(p->x[i]) + d.x);
            p->y[i] = float(double(p->y[i]) + d.y);
            p->z[i] = float(double(p->z[i]) + d.z);
        } else if (s) {
            for (int k = 0; k < 3; ++k) s[rigid::X + k] += d[k];
        }
    }
};

Side rigid_side(std::span<const SolverBody> bodies, std::int64_t index) {
    Side side;
    if (index < 0) return side;
    const SolverBody& b = bodies[static_cast<std::size_t>(index)];
    side.s = b.state;
    side.inv_mass = b.inv_mass;
    const Quat q{b.state[rigid::Q], b.state[rigid::Q + 1], b.state[rigid::Q + 2], b.state[rigid::Q + 3]};
    const Mat3 R = q.to_matrix();
    side.J_inv = R * b.J_body_inv * R.transposed();
    return side;
}

Side side_a(const RigidContact& c, std::span<const SolverBody> bodies, std::span<const SolverParticles> particles) {
    if (c.soft < 0) return rigid_side(bodies, c.a);
    Side side;
    side.p = &particles[std::size_t(c.soft)];
    side.i = c.a;
    side.inv_mass = side.p->inv_mass[c.a];
    return side;
}

// Two unit tangents completing n, chosen from n alone (so that a persisting contact keeps them).
void tangents(const Vec3d& n, Vec3d& t1, Vec3d& t2) {
    const Vec3d axis = std::abs(n.x) < 0.57735 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
    t1 = normalize(cross(n, axis));
    t2 = cross(n, t1);
}

struct Row {
    Side a, b;
    Vec3d r_a, r_b, t1, t2;
    double k_n = 0.0, k_t1 = 0.0, k_t2 = 0.0;  // inverse effective masses (Eq. 38's denominator)
    double target = 0.0;                      // least normal velocity allowed: 0, or -gap / h
    double v_n0 = 0.0;                        // normal velocity before any impulse (< 0: approaching)
    double mu = 0.0;                          // this step's friction coefficient
};

using Key = std::tuple<std::int32_t, std::uint32_t, std::int32_t, std::uint32_t>;
Key key_of(const RigidContact& c) { return {c.soft, c.a, c.b, c.feature}; }
// The pair of bodies a contact belongs to: a soft body's particles count as one body here.
using Pair = std::tuple<std::int32_t, std::uint32_t, std::int32_t>;
Pair pair_of(const RigidContact& c) { return {c.soft, c.soft >= 0 ? 0u : c.a, c.b}; }

// Where each manifold starts: the contacts of one pair of bodies lie next to each other (the
// ground's of one body too; each particle is a manifold of its own); the last entry is the end.
std::vector<std::size_t> manifolds(const std::vector<RigidContact>& contacts) {
    std::vector<std::size_t> start{0};
    for (std::size_t i = 1; i < contacts.size(); ++i) {
        const RigidContact &c = contacts[i], &d = contacts[i - 1];
        if (c.a != d.a || c.b != d.b || c.soft != d.soft) start.push_back(i);
    }
    start.push_back(contacts.size());
    return start;
}

// Rotates q by the small turn theta (world axes), keeping |q| as it is.
void turn(double* s, const Vec3d& theta) {
    const double angle = length(theta);
    if (angle == 0.0) return;
    const Quat q{s[rigid::Q], s[rigid::Q + 1], s[rigid::Q + 2], s[rigid::Q + 3]};
    const Quat turned = Quat::from_axis_angle(theta / angle, angle) * q;
    s[rigid::Q] = turned.w;
    s[rigid::Q + 1] = turned.x;
    s[rigid::Q + 2] = turned.y;
    s[rigid::Q + 3] = turned.z;
}

// The impulse along n that brings the contact's normal velocity to `target`, the total kept
// >= 0 (Eq. 38 with the target in place of -e v_n).
void normal_impulse(RigidContact& c, Row& row, double target) {
    const Vec3d v_rel = row.a.point_velocity(row.r_a) - row.b.point_velocity(row.r_b);
    const double lambda = std::max(c.normal_impulse + (target - dot(v_rel, c.normal)) / row.k_n, 0.0);
    const Vec3d j = c.normal * (lambda - c.normal_impulse);
    c.normal_impulse = lambda;
    row.a.apply(j, row.r_a);
    row.b.apply(-j, row.r_b);
}

}  // namespace

Vec3d contact_impulse(const RigidContact& c) {
    Vec3d t1, t2;
    tangents(c.normal, t1, t2);
    return c.normal * c.normal_impulse + t1 * c.tangent_impulse[0] + t2 * c.tangent_impulse[1];
}

double effective_inverse_mass(double inv_m_a, const Mat3& J_inv_a, const Vec3d& r_a, double inv_m_b,
                              const Mat3& J_inv_b, const Vec3d& r_b, const Vec3d& n) {
    return inv_m_a + inv_m_b + dot(n, cross(J_inv_a * cross(r_a, n), r_a)) + dot(n, cross(J_inv_b * cross(r_b, n), r_b));
}

void solve_contact_velocities(std::vector<RigidContact>& contacts, const std::vector<RigidContact>& previous,
                              std::span<const SolverBody> bodies, std::span<const SolverParticles> particles,
                              const SolverSettings& settings) {
    if (contacts.empty()) return;
    // Last step's contacts by key, to find each persisting one in log time.
    std::vector<std::size_t> last(previous.size());
    for (std::size_t k = 0; k < last.size(); ++k) last[k] = k;
    std::sort(last.begin(), last.end(), [&](std::size_t x, std::size_t y) { return key_of(previous[x]) < key_of(previous[y]); });

    std::vector<Row> rows(contacts.size());
    for (std::size_t i = 0; i < contacts.size(); ++i) {
        RigidContact& c = contacts[i];
        Row& row = rows[i];
        row.a = side_a(c, bodies, particles);
        row.b = rigid_side(bodies, c.b);
        row.r_a = c.soft >= 0 ? Vec3d{} : c.arm_a;
        row.r_b = c.b < 0 ? Vec3d{} : c.arm_b;
        tangents(c.normal, row.t1, row.t2);
        row.k_n = effective_inverse_mass(row.a.inv_mass, row.a.J_inv, row.r_a, row.b.inv_mass, row.b.J_inv, row.r_b, c.normal);
        row.k_t1 = effective_inverse_mass(row.a.inv_mass, row.a.J_inv, row.r_a, row.b.inv_mass, row.b.J_inv, row.r_b, row.t1);
        row.k_t2 = effective_inverse_mass(row.a.inv_mass, row.a.J_inv, row.r_a, row.b.inv_mass, row.b.J_inv, row.r_b, row.t2);
        const Vec3d v_rel = row.a.point_velocity(row.r_a) - row.b.point_velocity(row.r_b);
        row.v_n0 = dot(v_rel, c.normal);
        c.approach_speed = -row.v_n0;
        // Stop the approach; a contact still apart may close its gap this step, no more.
        row.target = settings.speculative ? -std::max(c.separation, 0.0) / settings.h : 0.0;
        // A particle at rest on the surface is held by Eq. 24's mu_s (static_friction is mu_d
        // for one already sliding: particle_contacts.h); a rigid body has one mu.
        row.mu = c.soft >= 0 ? c.static_friction : c.friction;
    }
    // Warm start from the same contacts last step, once every approach is measured.
    for (std::size_t i = 0; i < contacts.size(); ++i) {
        RigidContact& c = contacts[i];
        Row& row = rows[i];
        c.normal_impulse = 0.0;
        c.tangent_impulse[0] = c.tangent_impulse[1] = 0.0;
        const auto found = std::lower_bound(last.begin(), last.end(), key_of(c), [&](std::size_t k, const Key& key) {
            return key_of(previous[k]) < key;
        });
        if (found != last.end() && key_of(previous[*found]) == key_of(c)) {
            // The impulse that held it, not the bounce: starting a contact that just bounced from
            // its bounce would throw the body up again (a box landing flat then rocks for ever).
            const RigidContact& p = previous[*found];
            c.normal_impulse = p.resting_impulse;
            c.tangent_impulse[0] = p.tangent_impulse[0];
            c.tangent_impulse[1] = p.tangent_impulse[1];
            const Vec3d j = c.normal * c.normal_impulse + row.t1 * c.tangent_impulse[0] + row.t2 * c.tangent_impulse[1];
            row.a.apply(j, row.r_a);
            row.b.apply(-j, row.r_b);
        }
    }

    const std::vector<std::size_t> group_start = manifolds(contacts);
    for (int iteration = 0; iteration < settings.velocity_iterations; ++iteration) {
        for (std::size_t g = 0; g + 1 < group_start.size(); ++g) {
            const std::size_t first = group_start[g], end = group_start[g + 1];
            // The points of a manifold act on the same two bodies, and each changes what the
            // others need: a few passes over the manifold before moving on solve it nearly as a
            // whole, so that a face lands and rests on all its corners alike (one pass favours
            // the corner it visits first, and a stack of boxes leans and creeps).
            for (int pass = 0; pass < (end - first > 1 ? settings.manifold_passes : 1); ++pass) {
                for (std::size_t i = first; i < end; ++i) {
                    RigidContact& c = contacts[i];
                    Row& row = rows[i];
                    // Coulomb friction in impulse form: the tangential relative velocity brought
                    // to zero while |lambda_t| <= mu lambda_n allows, and mu lambda_n against it
                    // past that (Eq. 24's min(mu_s |F_n|, |F_t|) for a particle at rest, Eq. 25's
                    // mu_d |F_n| for one sliding; one mu for two rigid bodies).
                    if (row.mu > 0.0) {
                        const Vec3d v_rel = row.a.point_velocity(row.r_a) - row.b.point_velocity(row.r_b);
                        double t[2] = {c.tangent_impulse[0] - dot(v_rel, row.t1) / row.k_t1,
                                       c.tangent_impulse[1] - dot(v_rel, row.t2) / row.k_t2};
                        const double size = portable::hypot(t[0], t[1]);
                        const double limit = row.mu * c.normal_impulse;
                        if (size > limit) {
                            const double s = size > 0.0 ? limit / size : 0.0;
                            t[0] *= s;
                            t[1] *= s;
                        }
                        const Vec3d j = row.t1 * (t[0] - c.tangent_impulse[0]) + row.t2 * (t[1] - c.tangent_impulse[1]);
                        c.tangent_impulse[0] = t[0];
                        c.tangent_impulse[1] = t[1];
                        row.a.apply(j, row.r_a);
                        row.b.apply(-j, row.r_b);
                    }
                    normal_impulse(c, row, row.target);
                }
            }
        }
    }

    for (RigidContact& c : contacts) c.resting_impulse = c.normal_impulse;

    // Restitution: a contact hit this step (its gap closes within it) leaves at -e times the
    // speed it came in with (Eq. 38's (1 + e)), when its pair of bodies meets faster than a
    // resting contact does. Whether it was hit, not whether it took an impulse: four corners
    // of a face landing flat share the impulse in many ways (three would do), and a corner
    // left without any must bounce too. And the pair decides, not each point, by the mean
    // approach of its points hit: corners coming down at about the resting speed would
    // otherwise bounce or not by a hair, and a box would rock on them for ever. A few passes,
    // so that the points of a face bounce together.
    std::vector<char> hit(contacts.size(), 0);
    std::vector<std::pair<Pair, double>> approach;  // (pair, speed) per point hit, then averaged
    for (std::size_t i = 0; i < contacts.size(); ++i) {
        const RigidContact& c = contacts[i];
        hit[i] = settings.speculative ? c.separation + settings.h * rows[i].v_n0 <= 0.0 : c.depth >= 0.0;
        if (hit[i]) approach.emplace_back(pair_of(c), -rows[i].v_n0);
    }
    std::sort(approach.begin(), approach.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    std::vector<Pair> bouncing;
    for (std::size_t i = 0; i < approach.size();) {
        std::size_t j = i;
        double sum = 0.0;
        for (; j < approach.size() && approach[j].first == approach[i].first; ++j) sum += approach[j].second;
        if (sum / double(j - i) > settings.bounce_speed) bouncing.push_back(approach[i].first);
        i = j;
    }
    for (int iteration = 0; iteration < settings.restitution_iterations && !bouncing.empty(); ++iteration) {
        for (std::size_t i = 0; i < contacts.size(); ++i) {
            RigidContact& c = contacts[i];
            Row& row = rows[i];
            if (c.restitution == 0.0 || !hit[i] || !(row.v_n0 < 0.0) ||
                !std::binary_search(bouncing.begin(), bouncing.end(), pair_of(c))) {
                continue;
            }
            normal_impulse(c, row, -c.restitution * row.v_n0);
            if (settings.speculative) c.bounce_shift = (1.0 + c.restitution) * std::max(c.separation, 0.0);
        }
    }
}

void apply_bounce_shifts(const std::vector<RigidContact>& contacts, std::span<const SolverBody> bodies,
                         std::span<const SolverParticles> particles) {
    // Each side's largest shift; particles are keyed after the rigid bodies.
    std::vector<std::pair<double, Vec3d>> shift(bodies.size());
    std::vector<std::tuple<std::int32_t, std::uint32_t, double, Vec3d>> particle_shift;
    for (const RigidContact& c : contacts) {
        if (c.bounce_shift <= 0.0) continue;
        const Side a = side_a(c, bodies, particles), b = rigid_side(bodies, c.b);
        const double total = a.inv_mass + b.inv_mass;
        if (!(total > 0.0)) continue;
        const double on_a = c.bounce_shift * a.inv_mass / total, on_b = c.bounce_shift * b.inv_mass / total;
        if (c.soft >= 0) particle_shift.emplace_back(c.soft, c.a, on_a, c.normal * -on_a);
        else if (on_a > shift[c.a].first) shift[c.a] = {on_a, c.normal * -on_a};
        if (c.b >= 0 && on_b > shift[std::size_t(c.b)].first) shift[std::size_t(c.b)] = {on_b, c.normal * on_b};
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (shift[i].first > 0.0 && bodies[i].state) {
            for (int n = 0; n < 3; ++n) bodies[i].state[rigid::X + n] += shift[i].second[n];
        }
    }
    for (const auto& [soft, i, amount, d] : particle_shift) {
        Side side;
        side.p = &particles[std::size_t(soft)];
        side.i = i;
        side.move(d);
        (void)amount;
    }
}

// Positions: what penetration is left beyond the slop is taken out, along the normal, by
// moving and turning the bodies as an impulse would (nonlinear Gauss-Seidel). It changes x and
// q only, never P or L: no energy is added. Each body's turns within a pass are summed as a
// rotation vector and applied once at the pass's end: small rotations applied one after
// another about different axes compose into a turn about a third (their commutator), which
// would make a box resting on four corners creep about the vertical.
void solve_contact_positions(std::vector<RigidContact>& contacts, std::span<const SolverBody> bodies,
                             std::span<const SolverParticles> particles, const SolverSettings& settings) {
    if (contacts.empty()) return;
    const std::vector<std::size_t> group_start = manifolds(contacts);
    std::vector<Vec3d> turns(bodies.size());
    for (int iteration = 0; iteration < settings.position_iterations; ++iteration) {
        std::fill(turns.begin(), turns.end(), Vec3d{});
        for (std::size_t g = 0; g + 1 < group_start.size(); ++g) {
            const std::size_t first = group_start[g], end = group_start[g + 1];
            // Several passes over a manifold, as for the impulses: one pass lifts the corner it
            // visits first the most, and a stack leans.
            for (int pass = 0; pass < (end - first > 1 ? settings.manifold_passes : 1); ++pass) {
                for (std::size_t i = first; i < end; ++i) {
                    RigidContact& c = contacts[i];
                    const Side a = side_a(c, bodies, particles), b = rigid_side(bodies, c.b);
                    // Anchors where the bodies are now: R r turned further by this pass's turn so far.
                    const auto anchor = [&](const Side& side, std::int64_t index, const Vec3d& local) {
                        const Quat q{side.s[rigid::Q], side.s[rigid::Q + 1], side.s[rigid::Q + 2], side.s[rigid::Q + 3]};
                        const Vec3d r = q.to_matrix() * local;
                        return side.centre() + r + cross(turns[std::size_t(index)], r);
                    };
                    const Vec3d p_a = c.soft >= 0 ? a.centre() : anchor(a, c.a, c.local_a);
                    const Vec3d p_b = b.s ? anchor(b, c.b, c.local_b) : c.local_b;  // the ground: a point on its plane
                    const double separation = dot(p_a - p_b, c.normal);
                    const double C =
                        std::clamp(settings.position_rate * (separation + settings.slop), -settings.max_correction, 0.0);
                    if (C >= 0.0) continue;
                    const Vec3d r_a = c.soft >= 0 ? Vec3d{} : p_a - a.centre(), r_b = b.s ? p_b - b.centre() : Vec3d{};
                    const double k = effective_inverse_mass(a.inv_mass, a.J_inv, r_a, b.inv_mass, b.J_inv, r_b, c.normal);
                    if (!(k > 0.0)) continue;
                    const Vec3d j = c.normal * (-C / k);
                    if (a.inv_mass > 0.0) {
                        a.move(j * a.inv_mass);
                        if (c.soft < 0) turns[c.a] += a.J_inv * cross(r_a, j);
                    }
                    if (b.s && b.inv_mass > 0.0) {
                        b.move(j * -b.inv_mass);
                        turns[std::size_t(c.b)] += b.J_inv * cross(r_b, -j);
                    }
                }
            }
        }
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            if (bodies[i].state && bodies[i].inv_mass > 0.0) turn(bodies[i].state, turns[i]);
        }
    }
}

}  // namespace softbody
