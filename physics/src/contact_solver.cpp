#include "contact_solver.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace softbody {

namespace {

// One side of a contact: a body's velocity state, or nothing (the ground, 1/m = 0, J^-1 = 0).
struct Side {
    double* s = nullptr;
    double inv_mass = 0.0;
    Mat3 J_inv;  // world axes (Eq. 32), fixed for the velocity pass

    Vec3d x() const { return s ? Vec3d{s[rigid::X], s[rigid::X + 1], s[rigid::X + 2]} : Vec3d{}; }
    // Velocity of the body's material point at offset r from its centre of mass: v + w x r.
    Vec3d point_velocity(const Vec3d& r) const {
        if (!s || (inv_mass == 0.0 && J_inv == Mat3{})) return {};
        const Vec3d v = Vec3d{s[rigid::P], s[rigid::P + 1], s[rigid::P + 2]} * inv_mass;
        const Vec3d omega = J_inv * Vec3d{s[rigid::L], s[rigid::L + 1], s[rigid::L + 2]};
        return v + cross(omega, r);
    }
    // An impulse j at offset r: P += j (Eq. 9, 10), L += r x j (Eq. 37).
    void apply(const Vec3d& j, const Vec3d& r) {
        if (!s || inv_mass == 0.0) return;
        const Vec3d dL = cross(r, j);
        for (int k = 0; k < 3; ++k) {
            s[rigid::P + k] += j[k];
            s[rigid::L + k] += dL[k];
        }
    }
};

Side side_of(std::span<const SolverBody> bodies, std::int64_t index) {
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
};

using Key = std::tuple<std::uint32_t, std::int32_t, std::uint32_t>;
Key key_of(const RigidContact& c) { return {c.a, c.b, c.feature}; }

// Where each manifold starts: the contacts of one pair of bodies lie next to each other (the
// ground's of one body too); the last entry is the end.
std::vector<std::size_t> manifolds(const std::vector<RigidContact>& contacts) {
    std::vector<std::size_t> start{0};
    for (std::size_t i = 1; i < contacts.size(); ++i) {
        if (contacts[i].a != contacts[i - 1].a || contacts[i].b != contacts[i - 1].b) start.push_back(i);
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

}  // namespace

double effective_inverse_mass(double inv_m_a, const Mat3& J_inv_a, const Vec3d& r_a, double inv_m_b,
                              const Mat3& J_inv_b, const Vec3d& r_b, const Vec3d& n) {
    return inv_m_a + inv_m_b + dot(n, cross(J_inv_a * cross(r_a, n), r_a)) + dot(n, cross(J_inv_b * cross(r_b, n), r_b));
}

void solve_contact_velocities(std::vector<RigidContact>& contacts, const std::vector<RigidContact>& previous,
                              std::span<const SolverBody> bodies, const SolverSettings& settings) {
    if (contacts.empty()) return;
    // Last step's contacts by (a, b, feature), to find each persisting one in log time.
    std::vector<std::size_t> last(previous.size());
    for (std::size_t k = 0; k < last.size(); ++k) last[k] = k;
    std::sort(last.begin(), last.end(), [&](std::size_t x, std::size_t y) { return key_of(previous[x]) < key_of(previous[y]); });
    std::vector<Row> rows(contacts.size());
    for (std::size_t i = 0; i < contacts.size(); ++i) {
        RigidContact& c = contacts[i];
        Row& row = rows[i];
        row.a = side_of(bodies, c.a);
        row.b = side_of(bodies, c.b);
        row.r_a = c.arm_a;
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
                    // Coulomb friction in impulse form: |lambda_t| <= mu lambda_n, the tangential
                    // relative velocity brought to zero while that allows.
                    if (c.friction > 0.0) {
                        const Vec3d v_rel = row.a.point_velocity(row.r_a) - row.b.point_velocity(row.r_b);
                        double t[2] = {c.tangent_impulse[0] - dot(v_rel, row.t1) / row.k_t1,
                                       c.tangent_impulse[1] - dot(v_rel, row.t2) / row.k_t2};
                        const double limit = c.friction * c.normal_impulse, size = std::hypot(t[0], t[1]);
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
                    // Eq. 38: lambda = (target - v_n) / (1/m_a + 1/m_b + rotational terms), the total kept >= 0.
                    const Vec3d v_rel = row.a.point_velocity(row.r_a) - row.b.point_velocity(row.r_b);
                    const double lambda = std::max(c.normal_impulse + (row.target - dot(v_rel, c.normal)) / row.k_n, 0.0);
                    const Vec3d j = c.normal * (lambda - c.normal_impulse);
                    c.normal_impulse = lambda;
                    row.a.apply(j, row.r_a);
                    row.b.apply(-j, row.r_b);
                }
            }
        }
    }

    for (RigidContact& c : contacts) c.resting_impulse = c.normal_impulse;

    // Restitution: a contact hit this step (its gap closes within it) leaves at -e times the
    // speed it came in with (Eq. 38's (1 + e)), when its pair of bodies meets faster than a
    // resting contact does. Whether it was hit, not whether it took an impulse: four corners
    // of a face landing flat share the impulse in many ways (three would do), and a corner
    // left without any must bounce too. And the pair decides, not each point: corners coming
    // down at about the resting speed would otherwise bounce or not by a hair, and a box would
    // rock on them for ever. A few passes, so that the points of a face bounce together.
    // The pair's approach speed is the mean over its points hit: a face coming down while it
    // turns has some corners faster and some slower, and the turn alone is no impact.
    std::vector<char> hit(contacts.size(), 0);
    std::vector<std::pair<Key, double>> approach;  // (pair, speed) per point hit, then summed
    for (std::size_t i = 0; i < contacts.size(); ++i) {
        const RigidContact& c = contacts[i];
        hit[i] = settings.speculative ? c.separation + settings.h * rows[i].v_n0 <= 0.0 : c.depth >= 0.0;
        if (hit[i]) approach.emplace_back(Key{c.a, c.b, 0}, -rows[i].v_n0);
    }
    std::sort(approach.begin(), approach.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    std::vector<Key> bouncing;
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
                !std::binary_search(bouncing.begin(), bouncing.end(), Key{c.a, c.b, 0})) {
                continue;
            }
            const Vec3d v_rel = row.a.point_velocity(row.r_a) - row.b.point_velocity(row.r_b);
            const double target = -c.restitution * row.v_n0;
            const double lambda = std::max(c.normal_impulse + (target - dot(v_rel, c.normal)) / row.k_n, 0.0);
            const Vec3d j = c.normal * (lambda - c.normal_impulse);
            c.normal_impulse = lambda;
            row.a.apply(j, row.r_a);
            row.b.apply(-j, row.r_b);
            if (settings.speculative) c.bounce_shift = (1.0 + c.restitution) * std::max(c.separation, 0.0);
        }
    }
}

void apply_bounce_shifts(const std::vector<RigidContact>& contacts, std::span<const SolverBody> bodies) {
    std::vector<Vec3d> shift(bodies.size());
    std::vector<double> largest(bodies.size(), 0.0);
    for (const RigidContact& c : contacts) {
        if (c.bounce_shift <= 0.0) continue;
        const double inv_a = bodies[c.a].inv_mass, inv_b = c.b < 0 ? 0.0 : bodies[std::size_t(c.b)].inv_mass;
        if (!(inv_a + inv_b > 0.0)) continue;
        const auto take = [&](std::size_t body, double share, double sign) {
            const double amount = c.bounce_shift * share;
            if (amount > largest[body]) {
                largest[body] = amount;
                shift[body] = c.normal * (sign * amount);
            }
        };
        take(c.a, inv_a / (inv_a + inv_b), -1.0);
        if (c.b >= 0) take(std::size_t(c.b), inv_b / (inv_a + inv_b), 1.0);
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (largest[i] == 0.0 || !bodies[i].state) continue;
        for (int n = 0; n < 3; ++n) bodies[i].state[rigid::X + n] += shift[i][n];
    }
}

// Positions: what penetration is left beyond the slop is taken out, along the normal, by
// moving and turning the bodies as an impulse would (nonlinear Gauss-Seidel). It changes x and
// q only, never P or L: no energy is added. Each body's turns within a pass are summed as a
// rotation vector and applied once at the pass's end: small rotations applied one after
// another about different axes compose into a turn about a third (their commutator), which
// would make a box resting on four corners creep about the vertical.
void solve_contact_positions(std::vector<RigidContact>& contacts, std::span<const SolverBody> bodies,
                             const SolverSettings& settings) {
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
                    const Side a = side_of(bodies, c.a), b = side_of(bodies, c.b);
                    // Anchors where the body is now: R r turned further by this pass's turn so far.
                    const auto anchor = [&](const Side& side, std::int64_t index, const Vec3d& local) {
                        const Quat q{side.s[rigid::Q], side.s[rigid::Q + 1], side.s[rigid::Q + 2], side.s[rigid::Q + 3]};
                        const Vec3d r = q.to_matrix() * local;
                        return side.x() + r + cross(turns[std::size_t(index)], r);
                    };
                    const Vec3d p_a = anchor(a, c.a, c.local_a);
                    const Vec3d p_b = b.s ? anchor(b, c.b, c.local_b) : c.local_b;  // the ground: a point on its plane
                    const double separation = dot(p_a - p_b, c.normal);
                    const double C =
                        std::clamp(settings.position_rate * (separation + settings.slop), -settings.max_correction, 0.0);
                    if (C >= 0.0) continue;
                    const Vec3d r_a = p_a - a.x(), r_b = b.s ? p_b - b.x() : Vec3d{};
                    const double k = effective_inverse_mass(a.inv_mass, a.J_inv, r_a, b.inv_mass, b.J_inv, r_b, c.normal);
                    if (!(k > 0.0)) continue;
                    const Vec3d j = c.normal * (-C / k);
                    if (a.s && a.inv_mass > 0.0) {
                        for (int n = 0; n < 3; ++n) a.s[rigid::X + n] += j[n] * a.inv_mass;
                        turns[c.a] += a.J_inv * cross(r_a, j);
                    }
                    if (b.s && b.inv_mass > 0.0) {
                        for (int n = 0; n < 3; ++n) b.s[rigid::X + n] -= j[n] * b.inv_mass;
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
