#include "contact_solver.h"

#include <algorithm>
#include <cmath>
#include <bit>
#include <numeric>
#include <tuple>

namespace softbody {

namespace {

using Key = std::tuple<std::int32_t, std::uint32_t, std::int32_t, std::uint32_t>;
Key key_of(const RigidContact& c) { return {c.soft, c.a, c.b, c.feature}; }

// A soft constraint (Box2D v3's b2MakeSoft): a spring of `hertz` with damping ratio `zeta`,
// written for one implicit step of h. bias_rate turns a depth into a velocity; mass_scale and
// impulse_scale soften the impulse so the push apart is that spring's, whatever the masses.
struct Softness {
    double bias_rate = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
};
Softness make_soft(double hertz, double zeta, double h) {
    if (hertz <= 0.0) return {};
    const double omega = 2.0 * 3.14159265358979323846 * hertz;
    const double a1 = 2.0 * zeta + h * omega, a2 = h * omega * a1, a3 = 1.0 / (1.0 + a2);
    return {omega / a1, a2 * a3, a3};
}

Mat3 rotation_of(const Quat& q) { return q.normalized().to_matrix(); }

// q turned further by the small turn theta (world axes), its length kept.
Quat turned(const Quat& q, const Vec3d& theta) {
    const double angle = length(theta);
    if (!(angle > 0.0)) return q;
    return Quat::from_axis_angle(theta / angle, angle) * q;
}

}  // namespace

void contact_tangents(const Vec3d& n, Vec3d& t1, Vec3d& t2) {
    const Vec3d axis = std::abs(n.x) < 0.57735 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
    t1 = normalize(cross(n, axis));
    t2 = cross(n, t1);
}

Vec3d contact_impulse(const RigidContact& c) {
    Vec3d t1, t2;
    contact_tangents(c.normal, t1, t2);
    return c.normal * c.normal_impulse + t1 * c.tangent_impulse[0] + t2 * c.tangent_impulse[1];
}

double effective_inverse_mass(double inv_m_a, const Mat3& J_inv_a, const Vec3d& r_a, double inv_m_b,
                              const Mat3& J_inv_b, const Vec3d& r_b, const Vec3d& n) {
    return inv_m_a + inv_m_b + dot(n, cross(J_inv_a * cross(r_a, n), r_a)) + dot(n, cross(J_inv_b * cross(r_b, n), r_b));
}

// ---------------------------------------------------------------------------------------------
// Prepare: bodies, manifolds, anchors, masses, warm starts, islands.
// ---------------------------------------------------------------------------------------------
void ContactSolver::prepare(std::vector<RigidContact>& contacts, const std::vector<RigidContact>& previous,
                            const ContactWorld& world, const ContactSettings& settings) {
    settings_ = settings;
    h_ = settings.dt / double(settings.substeps);
    energy_ = {};
    bodies_.assign(1, Body{});
    manifolds_.clear();
    points_.clear();
    rigid_index_.assign(world.bodies.size(), 0);
    if (contacts.empty()) return;

    // Solver bodies, in order of first appearance (the contacts' order: the same on every run).
    std::vector<std::vector<std::int32_t>> particle_index(world.particles.size());
    const auto rigid_body = [&](std::int64_t b) -> std::uint32_t {
        if (b < 0) return 0;
        const RigidBody& body = world.bodies[std::size_t(b)];
        if (body.fixed) return 0;
        std::int32_t& at = rigid_index_[std::size_t(b)];
        if (at == 0) {
            Body s;
            s.kind = Body::Kind::Rigid;
            s.index = std::uint32_t(b);
            s.inv_mass = body.inv_mass;
            const double* y = &world.tick_start[std::size_t(b) * rigid::kStateSize];
            s.x0 = {y[rigid::X], y[rigid::X + 1], y[rigid::X + 2]};
            s.q0 = Quat{y[rigid::Q], y[rigid::Q + 1], y[rigid::Q + 2], y[rigid::Q + 3]};
            const Mat3 R = s.q0.to_matrix();  // as Listing 9 turns q into R: the world's J_inv (Eq. 32)
            s.inv_I = R * body.J_body_inv * R.transposed();
            s.I = R * body.J_body * R.transposed();
            at = std::int32_t(bodies_.size());
            bodies_.push_back(s);
        }
        return std::uint32_t(at);
    };
    const auto particle = [&](std::int32_t soft, std::uint32_t i) -> std::uint32_t {
        std::vector<std::int32_t>& map = particle_index[std::size_t(soft)];
        const SolverParticles& p = world.particles[std::size_t(soft)];
        if (p.inv_mass[i] == 0.0f) return 0;  // pinned: it does not move
        if (map.empty()) map.assign(world.particle_step_start_v[std::size_t(soft)]->size(), 0);
        if (map[i] == 0) {
            Body s;
            s.kind = Body::Kind::Particle;
            s.index = i;
            s.soft = soft;
            s.inv_mass = p.inv_mass[i];
            s.x0 = {p.x[i], p.y[i], p.z[i]};
            map[i] = std::int32_t(bodies_.size());
            bodies_.push_back(s);
        }
        return std::uint32_t(map[i]);
    };

    // Last tick's contacts by key, to find each persisting one in log time.
    std::vector<std::uint32_t> last(previous.size());
    std::iota(last.begin(), last.end(), 0u);
    std::sort(last.begin(), last.end(), [&](std::uint32_t x, std::uint32_t y) { return key_of(previous[x]) < key_of(previous[y]); });
    const auto warm = [&](const RigidContact& c) -> const RigidContact* {
        const auto found = std::lower_bound(last.begin(), last.end(), key_of(c), [&](std::uint32_t k, const Key& key) {
            return key_of(previous[k]) < key;
        });
        return found != last.end() && key_of(previous[*found]) == key_of(c) ? &previous[*found] : nullptr;
    };

    points_.resize(contacts.size());
    for (std::size_t i = 0; i < contacts.size();) {
        const RigidContact& first = contacts[i];
        Manifold m;
        m.a = first.soft >= 0 ? particle(first.soft, first.a) : rigid_body(first.a);
        m.b = rigid_body(first.b);
        m.n = first.normal;
        contact_tangents(m.n, m.t1, m.t2);
        // A particle at rest on the surface is held by Eq. 24's mu_s (static_friction is mu_d
        // for one already sliding: particle_contacts.h); a rigid body has one mu.
        m.mu = first.soft >= 0 ? first.static_friction : first.friction;
        m.e = first.restitution;
        m.first = std::uint32_t(i);
        m.stiff = m.b == 0;
        std::size_t end = i + 1;
        if (first.soft < 0) {
            while (end < contacts.size() && end < i + kMaxManifoldPoints && contacts[end].soft < 0 &&
                   contacts[end].a == first.a && contacts[end].b == first.b) {
                ++end;
            }
        }
        m.count = std::uint32_t(end - i);
        const Body &A = bodies_[m.a], &B = bodies_[m.b];
        for (std::size_t k = i; k < end; ++k) {
            const RigidContact& c = contacts[k];
            Point& p = points_[k];
            p = Point{};
            p.contact = std::uint32_t(k);
            p.r_a = A.kind == Body::Kind::Rigid ? c.arm_a : Vec3d{};
            p.r_b = B.kind == Body::Kind::Rigid ? c.arm_b : Vec3d{};
            p.s0 = p.s = c.separation;
            const double k_n = effective_inverse_mass(A.inv_mass, A.inv_I, p.r_a, B.inv_mass, B.inv_I, p.r_b, m.n);
            const double k_1 = effective_inverse_mass(A.inv_mass, A.inv_I, p.r_a, B.inv_mass, B.inv_I, p.r_b, m.t1);
            const double k_2 = effective_inverse_mass(A.inv_mass, A.inv_I, p.r_a, B.inv_mass, B.inv_I, p.r_b, m.t2);
            p.normal_mass = k_n > 0.0 ? 1.0 / k_n : 0.0;
            p.tangent_mass[0] = k_1 > 0.0 ? 1.0 / k_1 : 0.0;
            p.tangent_mass[1] = k_2 > 0.0 ? 1.0 / k_2 : 0.0;
            if (const RigidContact* before = warm(c)) {
                // Kept as a force (impulse per second): the substep may have changed since.
                p.normal_impulse = before->warm_normal * h_;
                p.tangent_impulse[0] = before->warm_tangent[0] * h_;
                p.tangent_impulse[1] = before->warm_tangent[1] * h_;
            }
        }
        // K_ij: point i's change of normal velocity per unit impulse at point j (Eq. 38's
        // denominator when i = j).
        for (std::size_t x = i; x < end; ++x) {
            for (std::size_t y = i; y < end; ++y) {
                const Point &p = points_[x], &q = points_[y];
                m.K[x - i][y - i] = A.inv_mass + B.inv_mass + dot(cross(p.r_a, m.n), A.inv_I * cross(q.r_a, m.n)) +
                                    dot(cross(p.r_b, m.n), B.inv_I * cross(q.r_b, m.n));
            }
        }
        manifolds_.push_back(m);
        i = end;
    }

    // Islands: bodies joined by this tick's contacts (the static world joins nothing; a soft
    // body's particles are one body here). Restitution's energy is bounded per island.
    const std::size_t nodes = world.bodies.size() + world.particles.size();
    std::vector<std::uint32_t> parent(nodes);
    std::iota(parent.begin(), parent.end(), 0u);
    const auto find = [&](std::uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    const auto node = [&](const Body& s) -> std::uint32_t {
        return s.kind == Body::Kind::Rigid ? s.index : std::uint32_t(world.bodies.size() + std::size_t(s.soft));
    };
    for (const Manifold& m : manifolds_) {
        if (m.a == 0 || m.b == 0) continue;
        const std::uint32_t x = find(node(bodies_[m.a])), y = find(node(bodies_[m.b]));
        if (x != y) parent[std::max(x, y)] = std::min(x, y);
    }
    std::vector<std::int64_t> number(nodes, -1);
    island_of_.assign(bodies_.size(), 0);
    std::uint32_t islands = 0;
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
        const std::uint32_t root = find(node(bodies_[b]));
        if (number[root] < 0) number[root] = islands++;
        island_of_[b] = std::uint32_t(number[root]);
    }
    for (Manifold& m : manifolds_) m.island = island_of_[m.a != 0 ? m.a : m.b];
    absorbed_.assign(islands, 0.0);

    // The approach as the tick began, for the record (the app's Last collision panel).
    for (const Manifold& m : manifolds_) {
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
            Point& p = points_[k];
            const RigidContact& c = contacts[k];
            const auto velocity = [&](const Body& s, const Vec3d& r) -> Vec3d {
                if (s.kind == Body::Kind::Rigid) {
                    const double* y = &world.tick_start[s.index * rigid::kStateSize];
                    const Vec3d P{y[rigid::P], y[rigid::P + 1], y[rigid::P + 2]}, L{y[rigid::L], y[rigid::L + 1], y[rigid::L + 2]};
                    return P * s.inv_mass + cross(s.inv_I * L, r);
                }
                if (s.kind == Body::Kind::Particle) {
                    const SolverParticles& q = world.particles[std::size_t(s.soft)];
                    return {q.vx[s.index], q.vy[s.index], q.vz[s.index]};
                }
                return {};
            };
            p.v_n0 = dot(velocity(bodies_[m.a], p.r_a) - velocity(bodies_[m.b], p.r_b), m.n);
            (void)c;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Each substep
// ---------------------------------------------------------------------------------------------

// The velocities the integrator left, where the substep began, and how far each body has come.
void ContactSolver::load(const ContactWorld& world) {
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
        Body& s = bodies_[b];
        if (s.kind == Body::Kind::Rigid) {
            const double* y = &world.state[s.index * rigid::kStateSize];
            const double* y0 = &world.step_start[s.index * rigid::kStateSize];
            s.v_free = Vec3d{y[rigid::P], y[rigid::P + 1], y[rigid::P + 2]} * s.inv_mass;
            s.w_free = s.inv_I * Vec3d{y[rigid::L], y[rigid::L + 1], y[rigid::L + 2]};
            s.v_start = Vec3d{y0[rigid::P], y0[rigid::P + 1], y0[rigid::P + 2]} * s.inv_mass;
            s.w_start = s.inv_I * Vec3d{y0[rigid::L], y0[rigid::L + 1], y0[rigid::L + 2]};
            // Where the substep began: the positions move on from the integrator's by the contacts' share.
            s.dp = Vec3d{y0[rigid::X], y0[rigid::X + 1], y0[rigid::X + 2]} - s.x0;
            s.turn = rotation_of(Quat{y0[rigid::Q], y0[rigid::Q + 1], y0[rigid::Q + 2], y0[rigid::Q + 3]}) *
                     rotation_of(s.q0).transposed();
        } else {
            const SolverParticles& p = world.particles[std::size_t(s.soft)];
            const Vec3Array& v0 = *world.particle_step_start_v[std::size_t(s.soft)];
            s.v_free = {p.vx[s.index], p.vy[s.index], p.vz[s.index]};
            s.v_start = Vec3d(v0[s.index]);
            s.w_free = s.w_start = {};
            s.turn = Mat3::identity();
        }
        s.v = s.v_free;
        s.w = s.w_free;
    }
}

// Each point's separation where the bodies are: as the tick began, moved on by each body's
// move and turn since (the anchors turn with their bodies).
void ContactSolver::separations(const ContactWorld& world) {
    (void)world;
    for (const Manifold& m : manifolds_) {
        const Body &A = bodies_[m.a], &B = bodies_[m.b];
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
            Point& p = points_[k];
            const Vec3d da = A.dp + A.turn * p.r_a - p.r_a, db = B.dp + B.turn * p.r_b - p.r_b;
            p.s = p.s0 + dot(da - db, m.n);
        }
    }
}

// The work the contacts did on `bodies` since the integrator left them: the impulse m dv at
// the substep's middle velocity, (v + v_free) / 2 - h g / 2, and the turn's change of
// 1/2 w . J w. Zero for a body the contacts hold still under gravity.
double ContactSolver::work(const Body& s) const {
    if (s.inv_mass == 0.0) return 0.0;
    const Vec3d dv = s.v - s.v_free;
    double W = dot(dv, (s.v + s.v_free) * 0.5 - settings_.gravity * (0.5 * h_)) / s.inv_mass;
    if (s.kind == Body::Kind::Rigid) W += 0.5 * (dot(s.w, s.I * s.w) - dot(s.w_free, s.I * s.w_free));
    return W;
}

namespace {


// v + w x r of a solver body at anchor r.
template <class B>
inline Vec3d point_velocity(const B& s, const Vec3d& r) {
    return s.v + cross(s.w, r);
}

// An impulse j at anchor r: P += j (Eq. 9, 10), L += r x j (Eq. 37), as velocities.
template <class B>
inline void apply(B& s, const Vec3d& j, const Vec3d& r) {
    s.v += j * s.inv_mass;
    s.w += s.inv_I * cross(r, j);
}

// The normal impulses x >= 0 of a manifold's n <= 4 points acting together. K is their
// coupling: K_ij the change of point i's normal velocity per unit impulse at point j (Eq. 38's
// denominator on the diagonal). Each point's normal velocity, (K x)_i - b_i above its target,
// must be zero where it pushes (x_i > 0) and may be more where it does not (x_i = 0): a linear
// complementarity problem, solved exactly by trying the sets of pushing points from all of them
// down, the first whose impulses are all pushes and whose other points do not close. A face's
// four corners on a plane leave K singular (three would hold it: statically indeterminate);
// where a pivot vanishes, 1e-9 of each diagonal added picks the solution with the least
// impulses, which shares the load evenly (elsewhere the answer is exact). Returns false if no set fits (rounding at the edge of two sets).
bool solve_block(int n, const double (&K)[4][4], const double (&b)[4], double (&x)[4]) {
    constexpr double kRegular = 1e-9;
    const int full = (1 << n) - 1;
    // Sets by size, largest first: the points that pushed last time usually push now.
    for (int size = n; size >= 0; --size) {
        for (int set = full; set >= 0; --set) {
            if (std::popcount(unsigned(set)) != size) continue;
            int index[4], m = 0;
            for (int i = 0; i < n; ++i) {
                if (set & (1 << i)) index[m++] = i;
            }
            // Gaussian elimination with partial pivoting on K_SS x_S = b_S; again with the
            // diagonal raised when a pivot vanishes (K singular on this set).
            double A[4][5];
            bool singular = false;
            for (int attempt = 0; attempt < 2; ++attempt) {
                double largest = 0.0;
                for (int r = 0; r < m; ++r) {
                    for (int c = 0; c < m; ++c) A[r][c] = K[index[r]][index[c]];
                    if (attempt == 1) A[r][r] += kRegular * K[index[r]][index[r]];
                    A[r][m] = b[index[r]];
                    largest = std::max(largest, std::abs(A[r][r]));
                }
                singular = false;
                for (int c = 0; c < m && !singular; ++c) {
                    int pivot = c;
                    for (int r = c + 1; r < m; ++r) {
                        if (std::abs(A[r][c]) > std::abs(A[pivot][c])) pivot = r;
                    }
                    if (!(std::abs(A[pivot][c]) > 1e-11 * largest)) {
                        singular = true;
                        break;
                    }
                    if (pivot != c) {
                        for (int k = c; k <= m; ++k) std::swap(A[c][k], A[pivot][k]);
                    }
                    for (int r = c + 1; r < m; ++r) {
                        const double f = A[r][c] / A[c][c];
                        for (int k = c; k <= m; ++k) A[r][k] -= f * A[c][k];
                    }
                }
                if (!singular) break;
            }
            if (singular) continue;
            double y[4] = {0.0, 0.0, 0.0, 0.0};
            for (int r = m - 1; r >= 0; --r) {
                double sum = A[r][m];
                for (int k = r + 1; k < m; ++k) sum -= A[r][k] * y[k];
                y[r] = sum / A[r][r];
            }
            bool fits = true;
            double candidate[4] = {0.0, 0.0, 0.0, 0.0};
            for (int r = 0; r < m; ++r) {
                fits = fits && y[r] >= 0.0;
                candidate[index[r]] = std::max(y[r], 0.0);
            }
            for (int i = 0; i < n && fits; ++i) {
                if (set & (1 << i)) continue;
                double w = -b[i];
                for (int j = 0; j < n; ++j) w += K[i][j] * candidate[j];
                fits = w >= -1e-12 * (std::abs(b[i]) + 1e-12);
            }
            if (!fits) continue;
            for (int i = 0; i < n; ++i) x[i] = candidate[i];
            return true;
        }
    }
    return false;
}

}  // namespace

void ContactSolver::substep(std::vector<RigidContact>& contacts, const ContactWorld& world) {
    (void)contacts;
    if (manifolds_.empty()) return;
    const double h = h_, inv_h = 1.0 / h;
    const Softness soft = make_soft(std::min(settings_.contact_hertz, 0.25 * inv_h), settings_.damping_ratio, h);
    const Softness stiff = make_soft(2.0 * std::min(settings_.contact_hertz, 0.25 * inv_h), settings_.damping_ratio, h);
    load(world);
    separations(world);

    // Which points bounce in this substep: one that met its surface in the last substep, or one
    // touching now and coming in faster than a resting contact does. The bounce leaves at -e
    // times that speed plus what the substep's forces add to it (as the free step would have).
    bool bouncing = false;
    for (Manifold& m : manifolds_) {
        m.bouncing = false;
        const Body &A = bodies_[m.a], &B = bodies_[m.b];
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
            Point& p = points_[k];
            p.bounce = 0.0;
            p.bounce_impulse = 0.0;
            p.s_start = p.s;
            if (m.e <= 0.0 && p.pending == 0.0) continue;
            const double vn_start = dot((A.v_start + cross(A.w_start, p.r_a)) - (B.v_start + cross(B.w_start, p.r_b)), m.n);
            const double vn_free = dot(point_velocity(A, p.r_a) - point_velocity(B, p.r_b), m.n);
            double speed = 0.0;
            if (p.pending > 0.0) speed = p.pending;
            else if (p.s <= settings_.touching && -vn_start > settings_.bounce_speed) speed = -vn_start;
            p.pending = 0.0;
            if (speed > 0.0 && m.e > 0.0) {
                p.bounce = speed;
                p.bounce_target = m.e * speed + (vn_free - vn_start);
                m.bouncing = bouncing = true;
            }
        }
    }

    // Warm start: the impulses that held the contacts in the last substep, again.
    for (Manifold& m : manifolds_) {
        Body &A = bodies_[m.a], &B = bodies_[m.b];
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
            Point& p = points_[k];
            const Vec3d j = m.n * p.normal_impulse + m.t1 * p.tangent_impulse[0] + m.t2 * p.tangent_impulse[1];
            apply(A, j, p.r_a);
            apply(B, -j, p.r_b);
            p.total_normal += p.normal_impulse;
            p.total_tangent[0] += p.tangent_impulse[0];
            p.total_tangent[1] += p.tangent_impulse[1];
        }
    }

    // One pass of Eq. 38 toward each point's target, then friction; `bias`: push overlaps apart.
    const auto solve = [&](bool bias) {
        for (Manifold& m : manifolds_) {
            if (!bias && m.bouncing) continue;  // it leaves: nothing to relax, and no turn from it
            Body &A = bodies_[m.a], &B = bodies_[m.b];
            const Softness& softness = m.stiff ? stiff : soft;
            // Each point's target normal velocity: 0 where it touches; minus the gap over h where
            // it is still apart (close it in this substep, no more); where it overlaps, what one
            // step of a soft spring pushing it out would leave (never faster than push_speed).
            const int n = int(m.count);
            double b[4], lambda[4];
            for (int i = 0; i < n; ++i) {
                const Point& p = points_[m.first + std::uint32_t(i)];
                const double v_n = dot(point_velocity(A, p.r_a) - point_velocity(B, p.r_b), m.n);
                double target = 0.0;
                if (p.s > 0.0) {
                    target = -p.s * inv_h;
                } else if (bias) {
                    const double push = std::min(-softness.bias_rate * p.s, settings_.push_speed);
                    target = (1.0 - softness.mass_scale) * v_n + softness.mass_scale * push -
                             softness.impulse_scale * p.normal_impulse / p.normal_mass;
                }
                // (K x)_i - b_i is point i's normal velocity above its target with impulses x.
                b[i] = target - v_n;
                for (int j = 0; j < n; ++j) b[i] += m.K[i][j] * points_[m.first + std::uint32_t(j)].normal_impulse;
            }
            if (!solve_block(n, m.K, b, lambda)) {
                for (int i = 0; i < n; ++i) lambda[i] = points_[m.first + std::uint32_t(i)].normal_impulse;
            }
            Vec3d J_a, L_a, L_b;
            for (int i = 0; i < n; ++i) {
                Point& p = points_[m.first + std::uint32_t(i)];
                const double applied = lambda[i] - p.normal_impulse;
                p.normal_impulse = lambda[i];
                p.total_normal += applied;
                const Vec3d j = m.n * applied;
                J_a += j;
                L_a += cross(p.r_a, j);
                L_b += cross(p.r_b, j);
            }
            A.v += J_a * A.inv_mass;
            A.w += A.inv_I * L_a;
            B.v -= J_a * B.inv_mass;
            B.w -= B.inv_I * L_b;
            // Coulomb friction in impulse form: the tangential velocity brought to zero while
            // |lambda_t| <= mu lambda_n allows (Eq. 24's min(mu_s |F_n|, |F_t|) for a particle
            // at rest, Eq. 25's mu_d |F_n| for one sliding; one mu between rigid bodies).
            if (m.mu <= 0.0) continue;
            for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
                Point& p = points_[k];
                const Vec3d dv = point_velocity(A, p.r_a) - point_velocity(B, p.r_b);
                double t[2] = {p.tangent_impulse[0] - dot(dv, m.t1) * p.tangent_mass[0],
                               p.tangent_impulse[1] - dot(dv, m.t2) * p.tangent_mass[1]};
                const double size = std::sqrt(t[0] * t[0] + t[1] * t[1]), limit = m.mu * p.normal_impulse;
                if (size > limit) {
                    const double scale = size > 0.0 ? limit / size : 0.0;
                    t[0] *= scale;
                    t[1] *= scale;
                }
                const double d0 = t[0] - p.tangent_impulse[0], d1 = t[1] - p.tangent_impulse[1];
                p.tangent_impulse[0] = t[0];
                p.tangent_impulse[1] = t[1];
                p.total_tangent[0] += d0;
                p.total_tangent[1] += d1;
                const Vec3d j = m.t1 * d0 + m.t2 * d1;
                apply(A, j, p.r_a);
                apply(B, -j, p.r_b);
            }
        }
    };
    solve(true);

    if (bouncing) restitute(false);

    // The positions: the free step's, moved on by h times what the contacts changed.
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
        Body& s = bodies_[b];
        const Vec3d dx = (s.v - s.v_free) * h;
        if (s.kind == Body::Kind::Rigid) {
            double* y = &world.state[s.index * rigid::kStateSize];
            for (int k = 0; k < 3; ++k) y[rigid::X + k] += dx[k];
            const Quat q = turned(Quat{y[rigid::Q], y[rigid::Q + 1], y[rigid::Q + 2], y[rigid::Q + 3]}, (s.w - s.w_free) * h);
            y[rigid::Q] = q.w;
            y[rigid::Q + 1] = q.x;
            y[rigid::Q + 2] = q.y;
            y[rigid::Q + 3] = q.z;
            s.dp = Vec3d{y[rigid::X], y[rigid::X + 1], y[rigid::X + 2]} - s.x0;
            s.turn = rotation_of(q) * rotation_of(s.q0).transposed();
        } else {
            SolverParticles& p = world.particles[std::size_t(s.soft)];
            p.x[s.index] = float(double(p.x[s.index]) + dx.x);
            p.y[s.index] = float(double(p.y[s.index]) + dx.y);
            p.z[s.index] = float(double(p.z[s.index]) + dx.z);
            s.dp = Vec3d{p.x[s.index], p.y[s.index], p.z[s.index]} - s.x0;
        }
    }
    separations(world);
    solve(false);  // relax

    // A point still apart as the substep began that the solve or the relax had to stop met its
    // surface in this substep: it bounces in the next, from the speed it met it with under the
    // substep's acceleration.
    for (Manifold& m : manifolds_) {
        if (m.e <= 0.0) continue;
        const Body &A = bodies_[m.a], &B = bodies_[m.b];
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
            Point& p = points_[k];
            if (p.s_start <= settings_.touching || p.normal_impulse <= 0.0) continue;
            const double vn_start = dot((A.v_start + cross(A.w_start, p.r_a)) - (B.v_start + cross(B.w_start, p.r_b)), m.n);
            const double vn_free = dot((A.v_free + cross(A.w_free, p.r_a)) - (B.v_free + cross(B.w_free, p.r_b)), m.n);
            const double a_n = (vn_free - vn_start) * inv_h;  // toward the surface: < 0
            const double speed2 = vn_start * vn_start - 2.0 * std::min(a_n, 0.0) * p.s_start;
            const bool closing = vn_start < 0.0 || a_n < 0.0;
            if (closing && speed2 > settings_.bounce_speed * settings_.bounce_speed) p.pending = std::sqrt(speed2);
        }
    }

    // The energy of this substep's contacts, island by island: what restitution may give back.
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
        const double W = work(bodies_[b]);
        absorbed_[island_of_[b]] -= W;
        energy_.total += W;
    }
    store(world, false);
}

// Restitution: each bouncing point toward its bounce_target, a few passes (the points of a face
// bounce together), then no more energy than the island's contacts took this tick.
void ContactSolver::restitute(bool end_of_tick) {
    std::vector<std::uint32_t> islands;
    for (const Manifold& m : manifolds_) {
        if (m.bouncing) islands.push_back(m.island);
    }
    std::sort(islands.begin(), islands.end());
    islands.erase(std::unique(islands.begin(), islands.end()), islands.end());
    // The bodies of those islands and their velocities before the bounce.
    std::vector<std::uint32_t> touched;
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
        if (std::binary_search(islands.begin(), islands.end(), island_of_[b])) touched.push_back(std::uint32_t(b));
    }
    std::vector<std::pair<Vec3d, Vec3d>> before(touched.size());
    std::vector<double> W_before(absorbed_.size(), 0.0);
    for (std::size_t k = 0; k < touched.size(); ++k) {
        const Body& s = bodies_[touched[k]];
        before[k] = {s.v, s.w};
        if (!end_of_tick) W_before[island_of_[touched[k]]] += work(s);
    }
    // Each manifold's bouncing points together (solve_block), the round of manifolds a few
    // times for manifolds that share a body.
    for (int round = 0; round < settings_.restitution_passes; ++round) {
        for (Manifold& m : manifolds_) {
            if (!m.bouncing) continue;
            Body &A = bodies_[m.a], &B = bodies_[m.b];
            // The bouncing points only: the others stay as the solve left them.
            int index[4], n = 0;
            for (std::uint32_t k = 0; k < m.count; ++k) {
                if (points_[m.first + k].bounce > 0.0) index[n++] = int(k);
            }
            double K[4][4], b[4], lambda[4];
            for (int i = 0; i < n; ++i) {
                const Point& p = points_[m.first + std::uint32_t(index[i])];
                const double v_n = dot(point_velocity(A, p.r_a) - point_velocity(B, p.r_b), m.n);
                b[i] = p.bounce_target - v_n;
                for (int j = 0; j < n; ++j) {
                    K[i][j] = m.K[index[i]][index[j]];
                    b[i] += K[i][j] * points_[m.first + std::uint32_t(index[j])].bounce_impulse;
                }
            }
            if (!solve_block(n, K, b, lambda)) continue;
            for (int i = 0; i < n; ++i) {
                Point& p = points_[m.first + std::uint32_t(index[i])];
                const Vec3d j = m.n * (lambda[i] - p.bounce_impulse);
                p.bounce_impulse = lambda[i];
                apply(A, j, p.r_a);
                apply(B, -j, p.r_b);
            }
        }
    }
    // What the bounce gave each island, against what its contacts took: scaled down to fit.
    for (std::uint32_t island : islands) {
        double B_lin = 0.0, C = 0.0, W_after = 0.0;
        const Vec3d half_hg = settings_.gravity * (end_of_tick ? 0.0 : 0.5 * h_);
        for (std::size_t k = 0; k < touched.size(); ++k) {
            if (island_of_[touched[k]] != island) continue;
            const Body& s = bodies_[touched[k]];
            const double m = 1.0 / s.inv_mass;
            const Vec3d dv = s.v - before[k].first, dw = s.w - before[k].second;
            // W(alpha) = alpha B + alpha^2 C for the bounce scaled by alpha.
            B_lin += m * dot(dv, before[k].first - half_hg) + dot(before[k].second, s.I * dw);
            C += 0.5 * (m * dot(dv, dv) + dot(dw, s.I * dw));
        }
        W_after = B_lin + C;
        const double allowed = absorbed_[island] - W_before[island];
        double alpha = 1.0;
        if (W_after > allowed) {
            alpha = 0.0;
            if (allowed > 0.0 && C > 0.0) {
                const double disc = B_lin * B_lin + 4.0 * C * allowed;
                alpha = std::clamp((-B_lin + std::sqrt(std::max(disc, 0.0))) / (2.0 * C), 0.0, 1.0);
            }
            for (std::size_t k = 0; k < touched.size(); ++k) {
                if (island_of_[touched[k]] != island) continue;
                Body& s = bodies_[touched[k]];
                s.v = before[k].first + (s.v - before[k].first) * alpha;
                s.w = before[k].second + (s.w - before[k].second) * alpha;
            }
        }
        for (Manifold& m : manifolds_) {
            if (!m.bouncing || m.island != island) continue;
            for (std::uint32_t k = m.first; k < m.first + m.count; ++k) points_[k].bounce_impulse *= alpha;
        }
        const double W = alpha * B_lin + alpha * alpha * C;
        energy_.restitution += W;
        if (end_of_tick) {
            absorbed_[island] -= W;
            energy_.total += W;
        }
    }
    for (Point& p : points_) p.total_bounce += p.bounce_impulse;
}

// The solved velocities back into the bodies: P and L by what the contacts changed (Eq. 37's
// L += r x j, as J_world dw), a particle's v, and Verlet's step with it.
void ContactSolver::store(const ContactWorld& world, bool) {
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
        const Body& s = bodies_[b];
        if (s.kind == Body::Kind::Rigid) {
            double* y = &world.state[s.index * rigid::kStateSize];
            const Vec3d dP = (s.v - s.v_free) / s.inv_mass, dL = s.I * (s.w - s.w_free);
            for (int k = 0; k < 3; ++k) {
                y[rigid::P + k] += dP[k];
                y[rigid::L + k] += dL[k];
            }
        } else {
            SolverParticles& p = world.particles[std::size_t(s.soft)];
            p.vx[s.index] = float(s.v.x);
            p.vy[s.index] = float(s.v.y);
            p.vz[s.index] = float(s.v.z);
            if (p.verlet_x) {
                const float h = float(h_);
                p.verlet_x[s.index] = p.vx[s.index] * h;
                p.verlet_y[s.index] = p.vy[s.index] * h;
                p.verlet_z[s.index] = p.vz[s.index] * h;
            }
        }
    }
}

void ContactSolver::finish(std::vector<RigidContact>& contacts, const ContactWorld& world) {
    if (manifolds_.empty()) return;
    // The bounces still due: points that met their surface in the last substep, from there.
    bool due = false;
    for (Manifold& m : manifolds_) {
        m.bouncing = false;
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
            Point& p = points_[k];
            p.bounce = 0.0;
            p.bounce_impulse = 0.0;
            if (p.pending > 0.0 && m.e > 0.0) {
                p.bounce = p.pending;
                p.bounce_target = m.e * p.pending;
                m.bouncing = due = true;
            }
            p.pending = 0.0;
        }
    }
    if (due) {
        for (std::size_t b = 1; b < bodies_.size(); ++b) {
            Body& s = bodies_[b];
            if (s.kind == Body::Kind::Rigid) {
                const double* y = &world.state[s.index * rigid::kStateSize];
                s.v_free = Vec3d{y[rigid::P], y[rigid::P + 1], y[rigid::P + 2]} * s.inv_mass;
                s.w_free = s.inv_I * Vec3d{y[rigid::L], y[rigid::L + 1], y[rigid::L + 2]};
            } else {
                const SolverParticles& p = world.particles[std::size_t(s.soft)];
                s.v_free = {p.vx[s.index], p.vy[s.index], p.vz[s.index]};
                s.w_free = {};
            }
            s.v = s.v_free;
            s.w = s.w_free;
        }
        restitute(true);
        store(world, false);
    }
    // The record: what each point took over the tick, and what the next tick starts from.
    for (const Manifold& m : manifolds_) {
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
            const Point& p = points_[k];
            RigidContact& c = contacts[p.contact];
            c.approach_speed = -p.v_n0;
            c.normal_impulse = p.total_normal + p.total_bounce;
            c.bounce_impulse = p.total_bounce;
            c.tangent_impulse[0] = p.total_tangent[0];
            c.tangent_impulse[1] = p.total_tangent[1];
            c.warm_normal = p.normal_impulse / h_;
            c.warm_tangent[0] = p.tangent_impulse[0] / h_;
            c.warm_tangent[1] = p.tangent_impulse[1] / h_;
            c.depth = -p.s;
        }
    }
}

}  // namespace softbody
