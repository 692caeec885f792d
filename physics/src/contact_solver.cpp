#include "contact_solver.h"

#include "integrators.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <thread>
#include <tuple>

#include "kept_memory.h"
#include "nearly_sorted.h"
#include "physics/portable_math.h"

namespace softbody {

namespace {

using Key = ContactKey;

// The least contacts worth a chunk of a scan of the list on another thread (sorted_keys(),
// prepare()); such a scan keeps a list of what it found per chunk (for_chunks: at most four a
// thread).
constexpr std::size_t kScanGrain = 1024;

// For each set of a manifold's points (bit i: point i), how many and which, in order
// (solve_manifold).
struct PointsOf {
    int count = 0;
    std::array<int, 4> index{};
};
constexpr std::array<PointsOf, 16> kPointsOf = [] {
    std::array<PointsOf, 16> lists{};
    for (unsigned set = 0; set < 16; ++set) {
        for (int i = 0; i < 4; ++i) {
            if (set & (1u << i)) lists[set].index[std::size_t(lists[set].count++)] = i;
        }
    }
    return lists;
}();
// The manifolds are laid out in the passes' order, their contacts in the order they were found:
// a walk through the manifolds reads (prepare) or writes (finish) the contacts of each at another
// place, 256 bytes a point, and in a pile they are tens of megabytes, out of the cache. So the
// contacts of the manifold kFetchAhead on are asked for while one is worked on.
constexpr std::size_t kFetchAhead = 4;
template <bool kWrite>
void fetch_contacts(const RigidContact* first, std::uint32_t count) {
    const char* at = reinterpret_cast<const char*>(first);
    for (std::size_t byte = 0; byte < count * sizeof(RigidContact); byte += 64) __builtin_prefetch(at + byte, kWrite ? 1 : 0);
}
std::size_t most_chunks(const ThreadPool* pool) { return 4 * std::size_t(pool ? pool->threads() : 1); }
Key key_of(const RigidContact& c) { return {c.soft, c.a, c.b, c.feature}; }

// The contacts' keys with their places, sorted (by key, then place). A list of contacts comes as
// runs of one pair's points (RigidContact's order), a few points each: the runs are sorted by
// their pair, then each pair's points by feature, a few at a time. The same order as sorting
// every point at once, with a quarter of the items to sort; and each pair's keys are written and
// sorted in their own place, on every thread (`at`: where each run's keys begin). Into `keys`,
// with `runs` and `at` to work in (all kept from call to call).
void sorted_keys(const std::vector<RigidContact>& contacts, std::vector<ContactRun>& runs, std::vector<std::vector<ContactRun>>& parts,
                 std::vector<std::uint32_t>& at, std::vector<std::pair<Key, std::uint32_t>>& keys, ThreadPool* pool) {
    using Run = ContactRun;
    // The runs, on every thread: each chunk of the list takes the runs that begin in it (the last
    // may go on into the next chunk, which leaves that run's points to it).
    const auto same_pair = [&](std::size_t j, std::size_t k) {
        return contacts[j].soft == contacts[k].soft && contacts[j].a == contacts[k].a && contacts[j].b == contacts[k].b;
    };
    if (parts.size() < most_chunks(pool)) parts.resize(most_chunks(pool));
    const std::size_t chunks = for_chunks(pool, contacts.size(), kScanGrain, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        ChunkList taken(parts[chunk]);
        std::vector<Run>& part = *taken;
        std::size_t k = begin;
        while (k > 0 && k < end && same_pair(k, k - 1)) ++k;  // a run begun before this chunk
        while (k < end) {
            const RigidContact& c = contacts[k];
            std::size_t run_end = k + 1;
            while (run_end < contacts.size() && same_pair(run_end, k)) ++run_end;
            part.push_back({{c.soft, c.a, c.b}, std::uint32_t(k), std::uint32_t(run_end - k)});
            k = run_end;
        }
    });
    runs.resize(place_chunks(runs, 0, parts, chunks, pool));
    sort_nearly_sorted(runs, [](const Run& x, const Run& y) { return std::tie(x.pair, x.first) < std::tie(y.pair, y.first); });
    resize_with_room(at, runs.size() + 1);
    at[0] = 0;
    for (std::size_t r = 0; r < runs.size(); ++r) at[r + 1] = at[r] + runs[r].count;
    resize_with_room(keys, contacts.size());
    // Each pair from the run it starts at (one run, unless its points were more than a manifold
    // holds), by the thread whose chunk holds that run.
    for_chunks(pool, runs.size(), 256, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t r = begin; r < end; ++r) {
            if (r > 0 && runs[r - 1].pair == runs[r].pair) continue;  // not where its pair starts
            std::size_t last = r;
            for (; last < runs.size() && runs[last].pair == runs[r].pair; ++last) {
                for (std::uint32_t j = 0; j < runs[last].count; ++j) {
                    const std::uint32_t k = runs[last].first + j;
                    keys[at[last] + j] = {key_of(contacts[k]), k};
                }
            }
            std::sort(keys.begin() + at[r], keys.begin() + at[last]);
        }
    });
}

// A body whose angular velocity would be wrong by more than this (m/s, at its surface) with its
// inertia as it was found has it found again (load()).
constexpr double kStaleSpeed = 1e-4;

// Passes of a manifold's normal impulses and its friction in turn in the solve, at most; the
// relax makes one (solve_manifold).
constexpr int kCouplingPasses = 8;

// A point closer than this (m) touches: pushed apart softly where it overlaps (solve()).
constexpr double kSpeculative = 1e-6;

// m/s: a point apart that stays this much short of closing its gap within the substep, held
// by nothing, needs no impulse in the solve (solve_manifold): well above the block solve's
// tolerances (solve_block), so that its answer would be none too.
constexpr double kClearlyApart = 1e-9;

// Two points of a pair of bodies, a tick apart, this close are the same contact (m).
constexpr double kSameContact = 5e-3;

// The least work worth handing to another thread: bodies (a free turn each, in the positions),
// manifolds (one pass of a block solve each; the slabs go to the threads from kManifoldGrain
// a slab) and points (a field or two each). Fewer run on the calling thread. Which thread runs
// what never changes the bits.
constexpr std::size_t kBodyGrain = 32;
constexpr std::size_t kManifoldGrain = 16;
constexpr std::size_t kPointGrain = 64;

// Slabs the moving bodies are cut into for the solver's passes (slabs()): fixed, whatever the
// thread count; enough for a few a thread on machines of a few cores.
constexpr std::size_t kBlocks = 8;
// The groups of manifolds slabs() makes: each slab's, each boundary's between two neighbouring
// slabs (kBlocks - 1), and those across slabs further apart.
constexpr std::size_t kGroups = 2 * kBlocks;
// The most passes over the slabs handed to the threads at once (each_in_slabs).
constexpr int kMostChained = 4;

// Whether a length whose square is size2 is certainly no more than limit >= 0, without its square
// root: true only where sqrt(size2) <= limit however both round (a margin of 1e-12 beside the
// rounding of limit^2, which is relative to it above 1e-150), so that the square root is taken
// only near or past the limit, and the answer is the one the square root gives. A sticking
// contact's friction is always within its limit, and the square root is on the passes'
// longest chain of dependent operations.
bool within_limit(double size2, double limit) { return limit > 1e-150 && size2 <= limit * limit * (1.0 - 1e-12); }

// The same three numbers to the bit (== takes -0 for 0).
bool same_bits(const Vec3d& a, const Vec3d& b) {
    const double x[3] = {a.x, a.y, a.z}, y[3] = {b.x, b.y, b.z};
    return std::memcmp(x, y, sizeof x) == 0;
}

// True when a manifold holds an impulse of any kind: a point's normal impulse, friction, its turn
// about n or rolling resistance.
bool held_anything(const SolverManifold& m, const PassPoint* P, int n) {
    if (m.friction[0] != 0.0 || m.friction[1] != 0.0 || m.twist != 0.0 || !(m.roll == Vec3d{})) return true;
    for (int i = 0; i < n; ++i) {
        if (P[i].normal_impulse != 0.0) return true;
    }
    return false;
}

Mat3 rotation_of(const Quat& q) { return q.normalized().to_matrix(); }

// How a body's contact anchors have turned since the contacts were found (at q0; now at q): with
// the body, for a point of its surface is a point of the body; not at all for a sphere. A
// sphere's point of contact is not a point of the ball: it is wherever the ball is nearest the
// other side, centre - r n, however the ball turns. Turned with the ball, the anchor at the
// bottom of a ball rolling at w would rise by r (1 - cos(w t)) over the tick (6 mm for a 15 cm
// ball at 2.2 m/s), the solver would read that as a gap opening under it, let the ball fall into
// it, and the push apart would pull it out only slowly: it rolled 13 mm deep, and a small fast
// one went through the ground.
Mat3 anchor_turn(const SolverBody& s, const Quat& q) {
    return s.round ? Mat3::identity() : rotation_of(q) * s.R0_t;
}

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

// A manifold's Jacobians, couplings and masses from its points' anchors and its bodies'
// inverse inertia as they are now (prepare, and again when a body has turned: refresh).
void ContactSolver::setup(Manifold& m) {
    const Body &A = bodies_[m.a], &B = bodies_[m.b];
    const int n = int(m.count);
    Point* points = &points_[m.first];
    PassPoint* pass = &pass_[m.first];
    for (int x = 0; x < n; ++x) {
        pass[x].c_a = cross(points[x].r_a, m.n);
        pass[x].c_b = cross(points[x].r_b, m.n);
    }
    // Friction acts at the points' centre, and turns about n within their mean distance from it
    // (solve()).
    Vec3d centre;
    for (int x = 0; x < n; ++x) centre += points[x].at;
    centre = centre / double(n);
    m.twist_radius = 0.0;
    for (int x = 0; x < n; ++x) m.twist_radius += length(points[x].at - centre) / double(n);
    const Vec3d r_a = A.kind == Body::Kind::Rigid ? centre - A.x : Vec3d{}, r_b = B.kind == Body::Kind::Rigid ? centre - B.x : Vec3d{};
    for (int d = 0; d < 2; ++d) {
        m.ft_a[d] = cross(r_a, m.t[d]);
        m.ft_b[d] = cross(r_b, m.t[d]);
        m.fw_a[d] = A.inv_I * m.ft_a[d];
        m.fw_b[d] = B.inv_I * m.ft_b[d];
        const double k_t = A.inv_mass + B.inv_mass + dot(m.ft_a[d], m.fw_a[d]) + dot(m.ft_b[d], m.fw_b[d]);
        m.tangent_mass[d] = k_t > 0.0 ? 1.0 / k_t : 0.0;
    }
    m.nw_a = A.inv_I * m.n;
    m.nw_b = B.inv_I * m.n;
    const double k_twist = dot(m.n, m.nw_a) + dot(m.n, m.nw_b);
    m.twist_mass = m.twist_radius > 0.0 && k_twist > 0.0 ? 1.0 / k_twist : 0.0;
    if (m.twist_mass == 0.0) m.twist = 0.0;  // one point (or none turning): no turn to hold
    m.roll_mass = m.roll_arm > 0.0 ? (A.inv_I + B.inv_I).inverse() : Mat3{};
    // K_ij = 1/m_a + 1/m_b + (r_ai x n) . J_a^-1 (r_aj x n) + (r_bi x n) . J_b^-1 (r_bj x n).
    Vec3d turn_a[4], turn_b[4];  // J^-1 (r_j x n)
    for (int y = 0; y < n; ++y) {
        turn_a[y] = A.inv_I * pass[y].c_a;
        turn_b[y] = B.inv_I * pass[y].c_b;
    }
    for (int x = 0; x < n; ++x) {
        for (int y = 0; y < n; ++y) m.K[x][y] = A.inv_mass + B.inv_mass + dot(pass[x].c_a, turn_a[y]) + dot(pass[x].c_b, turn_b[y]);
    }
    // The push apart is a spring (contact_hertz, twice that against the static world, which
    // moves for no one), stiffer where the point carries a load: a spring holding an impulse lambda a
    // substep at effective mass m stands compressed by lambda / (m h omega^2), so omega is raised
    // until that is at most stack_depth, up to a quarter of the substep rate (beyond it the
    // substeps cannot follow the spring, and a pyramid shivers).
    const double base = (m.b == 0 ? 2.0 : 1.0) * std::min(settings_.contact_hertz, 0.25 / h_);
    for (int x = 0; x < n; ++x) {
        PassPoint& p = pass[x];
        p.normal_mass = m.K[x][x] > 0.0 ? 1.0 / m.K[x][x] : 0.0;
        const double loaded = std::sqrt(p.normal_impulse * p.normal_mass / (h_ * settings_.stack_depth)) / (2.0 * 3.14159265358979323846);
        p.softness = make_soft(std::clamp(loaded, base, std::max(base, 0.25 / h_)), settings_.damping_ratio, h_);
    }
    double q[4][2];  // the points in the contact plane, from the first (block_solver.h)
    for (int x = 0; x < n; ++x) {
        const Vec3d r = points[x].at - points[0].at;
        q[x][0] = dot(r, m.t[0]);
        q[x][1] = dot(r, m.t[1]);
    }
    prepare_block(n, m.K, q, m.block);
}

// ---------------------------------------------------------------------------------------------
// Prepare: bodies, manifolds, anchors, Jacobians, couplings, warm starts, islands.
// ---------------------------------------------------------------------------------------------
void ContactSolver::prepare(std::vector<RigidContact>& contacts, const std::vector<RigidContact>& previous,
                            const ContactWorld& world, const ContactSettings& settings) {
    settings_ = settings;
    h_ = settings.dt / double(settings.substeps);
    substeps_done_ = 0;
    energy_ = {};
    rigid_index_.assign(world.bodies.size(), 0);
    if (contacts.empty()) {
        bodies_.assign(1, Body{});
        manifolds_.clear();
        points_.clear();
        body_order_.clear();
        return;
    }

    // Solver bodies, numbered in order of first appearance (the contacts' order: the same on
    // every run) as the manifolds are scanned, and built after, on every thread (a body is
    // most of a kilobyte: built one by one, a thousand of them were the longest stretch of the
    // preparation the other thread sat out).
    Buffers& kept = buffers_;
    std::vector<std::vector<std::int32_t>>& particle_index = kept.particle_index;
    particle_index.resize(world.particles.size());
    for (std::vector<std::int32_t>& map : particle_index) map.clear();
    std::vector<std::uint32_t>& body_of = kept.body_of;
    std::vector<std::int32_t>& soft_of = kept.soft_of;
    body_of.assign(1, 0);
    soft_of.assign(1, -1);
    const auto rigid_body = [&](std::int64_t b) -> std::uint32_t {
        if (b < 0) return 0;
        const RigidBody& body = world.bodies[std::size_t(b)];
        if (body.fixed) return 0;
        if (!world.asleep.empty() && world.asleep[std::size_t(b)]) return 0;  // asleep: as still as a fixed body
        std::int32_t& at = rigid_index_[std::size_t(b)];
        if (at == 0) {
            at = std::int32_t(body_of.size());
            body_of.push_back(std::uint32_t(b));
            soft_of.push_back(-1);
        }
        return std::uint32_t(at);
    };
    const auto particle = [&](std::int32_t soft, std::uint32_t i) -> std::uint32_t {
        std::vector<std::int32_t>& map = particle_index[std::size_t(soft)];
        const SolverParticles& p = world.particles[std::size_t(soft)];
        if (p.inv_mass[i] == 0.0f) return 0;  // pinned: it does not move
        if (map.empty()) map.assign(world.particle_step_start_v[std::size_t(soft)]->size(), 0);
        if (map[i] == 0) {
            map[i] = std::int32_t(body_of.size());
            body_of.push_back(i);
            soft_of.push_back(soft);
        }
        return std::uint32_t(map[i]);
    };
    // Body b as numbered (0: the static world).
    const auto build_body = [&](std::size_t b) {
        Body& s = bodies_[b];
        s = Body{};
        if (b == 0) return;
        const std::uint32_t i = body_of[b];
        const std::int32_t soft = soft_of[b];
        if (soft < 0) {
            const RigidBody& body = world.bodies[i];
            s.kind = Body::Kind::Rigid;
            s.index = i;
            s.inv_mass = body.inv_mass;
            const double* y = &world.tick_start[std::size_t(i) * rigid::kStateSize];
            s.x0 = s.x = {y[rigid::X], y[rigid::X + 1], y[rigid::X + 2]};
            s.q0 = s.q_ref = Quat{y[rigid::Q], y[rigid::Q + 1], y[rigid::Q + 2], y[rigid::Q + 3]};
            s.round = body.shape == ShapeKind::Sphere;
        } else {
            const SolverParticles& p = world.particles[std::size_t(soft)];
            s.kind = Body::Kind::Particle;
            s.index = i;
            s.soft = soft;
            s.inv_mass = p.inv_mass[i];
            s.x0 = s.x = {p.x[i], p.y[i], p.z[i]};
        }
    };

    // Each contact's point of the last tick, to start from its impulses (warm starting): the
    // one with the same features; failing that (a face exactly over another's edge is clipped
    // into points whose features flip with rounding), the nearest of the same two bodies
    // within kSameContact that no other took. Sorted by key, in log time.
    // The keys are sorted with the contact's place (sorted_keys), so that equal keys too come in
    // one order on every run.
    sorted_keys(previous, kept.runs, kept.run_parts, kept.run_at, kept.last, world.pool);
    const std::vector<std::pair<Key, std::uint32_t>>& last = kept.last;
    std::vector<char>& taken = kept.taken;
    taken.clear();
    resize_with_room(taken, previous.size());
    const auto lower = [&](const Key& key) {
        return std::lower_bound(last.begin(), last.end(), key, [](const std::pair<Key, std::uint32_t>& k, const Key& want) { return k.first < want; });
    };
    // The same features: looked up in parallel, then taken in the contacts' order.
    std::vector<std::int64_t>& match = kept.match;
    match.clear();
    reserve_with_room(match, contacts.size());
    match.resize(contacts.size(), -1);
    // Each chunk's searches start from where the last one ended: the contacts come much in
    // the order of the last tick's, so the next key is mostly a step or two on.
    // A contact of the last tick goes to the first of this tick's (in their order) that found
    // it: each one's first finder, the least k, is kept as it is found (on every thread, the
    // compilers' atomic built-ins; a plain compare on one), then the others let it go.
    std::vector<std::uint32_t>& first_finder = kept.first_finder;
    first_finder.assign(previous.size(), std::numeric_limits<std::uint32_t>::max());
    const bool threads = world.pool && world.pool->threads() > 1;
    for_chunks(world.pool, contacts.size(), kPointGrain, [&](std::size_t, std::size_t begin, std::size_t end) {
        auto near = last.begin();
        for (std::size_t k = begin; k < end; ++k) {
            const Key key = key_of(contacts[k]);
            near = lower_bound_from(last.begin(), last.end(), near, key,
                                    [](const std::pair<Key, std::uint32_t>& x, const Key& want) { return x.first < want; });
            if (near == last.end() || near->first != key) continue;
            match[k] = near->second;
            std::uint32_t& finder = first_finder[near->second];
            const std::uint32_t mine = std::uint32_t(k);
            if (!threads) {
                finder = std::min(finder, mine);
                continue;
            }
            std::uint32_t now = __atomic_load_n(&finder, __ATOMIC_RELAXED);
            while (mine < now && !__atomic_compare_exchange_n(&finder, &now, mine, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
            }
        }
    });
    for_chunks(world.pool, contacts.size(), kPointGrain, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            if (match[k] < 0) continue;
            if (first_finder[std::size_t(match[k])] == std::uint32_t(k)) {
                taken[std::size_t(match[k])] = 1;
            } else {
                match[k] = -1;
            }
        }
    });
    for (std::size_t k = 0; k < contacts.size(); ++k) {
        const RigidContact& c = contacts[k];
        if (match[k] >= 0 || c.soft >= 0) continue;
        double best = kSameContact * kSameContact;
        for (auto it = lower({c.soft, c.a, c.b, 0u}); it != last.end(); ++it) {
            const RigidContact& p = previous[it->second];
            if (p.soft != c.soft || p.a != c.a || p.b != c.b) break;
            const Vec3d d = p.point - c.point;
            if (!taken[it->second] && dot(d, d) < best) {
                best = dot(d, d);
                match[k] = it->second;
            }
        }
        if (match[k] >= 0) taken[std::size_t(match[k])] = 1;
    }
    const auto warm = [&](std::size_t k) -> const RigidContact* { return match[k] >= 0 ? &previous[std::size_t(match[k])] : nullptr; };

    // The manifolds as found: a pair's points next to each other (RigidContact's order), at
    // most four, and their solver bodies in order of first appearance. Then each is built where
    // the passes take it (slabs()), its points after the last one's: every pass reads them through
    // memory in order (in stack:20 the passes read 23 MB of them 20 times a tick).
    // The scan of the contacts, on every thread: each chunk takes the manifolds that begin in it
    // (a pair's points are split into manifolds from the first of them, and the last manifold may
    // go on into the next chunk, which leaves its points to it). Then their bodies are numbered,
    // in the manifolds' order.
    const auto together = [&](std::size_t j, std::size_t k) {  // points of one pair's manifolds
        return contacts[j].soft < 0 && contacts[k].soft < 0 && contacts[j].a == contacts[k].a && contacts[j].b == contacts[k].b;
    };
    std::vector<std::vector<FoundPoints>>& parts = kept.found_parts;
    if (parts.size() < most_chunks(world.pool)) parts.resize(most_chunks(world.pool));
    const std::size_t chunks = for_chunks(world.pool, contacts.size(), kScanGrain, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        ChunkList own(parts[chunk]);
        std::vector<FoundPoints>& part = *own;
        std::size_t k = begin;
        if (k > 0 && k < end && together(k, k - 1)) {
            std::size_t pair_begins = k - 1;
            while (pair_begins > 0 && together(pair_begins - 1, k)) --pair_begins;
            const std::size_t manifold_begins = pair_begins + (k - pair_begins) / kMaxManifoldPoints * kMaxManifoldPoints;
            if (manifold_begins < k) {
                while (k < end && k < manifold_begins + kMaxManifoldPoints && together(k, manifold_begins)) ++k;
            }
        }
        while (k < end) {
            const RigidContact& first = contacts[k];
            std::size_t stop = k + 1;
            while (stop < contacts.size() && stop < k + kMaxManifoldPoints && together(stop, k)) ++stop;
            part.push_back({std::uint32_t(k), std::uint32_t(stop - k), first.soft, first.b, first.a});
            k = stop;
        }
    });
    std::vector<FoundManifold>& found = kept.found;
    found.clear();
    for (std::size_t chunk = 0; chunk < chunks; ++chunk) {
        for (const FoundPoints& p : parts[chunk]) {
            FoundManifold f;
            f.a = p.soft >= 0 ? particle(p.soft, p.a) : rigid_body(p.a);
            f.b = rigid_body(p.b);
            f.contact = p.contact;
            f.count = p.count;
            found.push_back(f);
        }
    }
    pool_ = world.pool;
    // (Sized without clearing first: each is set whole.)
    resize_with_room(bodies_, body_of.size());
    parallel(bodies_.size(), kBodyGrain, build_body);
    slabs(found);
    // Sized without clearing first: each manifold and point is set whole below (a pile's are
    // tens of megabytes, and clearing them first too is work on one thread every tick).
    resize_with_room(manifolds_, found.size());
    resize_with_room(points_, contacts.size());
    resize_with_room(pass_, contacts.size());
    resize_with_room(gap_, contacts.size());
    resize_with_room(found_order_, found.size());
    std::vector<std::uint32_t>& first_point = kept.first_point;
    resize_with_room(first_point, found.size());
    std::uint32_t next = 0;
    for (std::size_t at = 0; at < found.size(); ++at) {
        first_point[at] = next;
        next += found[slab_order_[at]].count;
        found_order_[slab_order_[at]] = std::uint32_t(at);
    }
    // Each rigid body's inertia in world axes, Eq. 32 with q made unit first (between
    // renormalisations |q| drifts under explicit Euler and RK4), so that I and inv_I are each
    // other's inverse: the impulses' L (I dw) is then exactly r x j.
    each_body([&](std::size_t b) {
        Body& s = bodies_[b];
        if (s.kind != Body::Kind::Rigid) return;
        const RigidBody& body = world.bodies[s.index];
        const Mat3 R = rotation_of(s.q0);
        s.inv_I = R * body.J_body_inv * R.transposed();
        s.I = R * body.J_body * R.transposed();
        s.R0_t = R.transposed();
        s.q_now = s.q0;
        s.turn = anchor_turn(s, s.q0);
    });
    // The approach of a manifold's points as the tick began, for the record (the app's Last
    // collision panel).
    const auto velocity = [&](const Body& s, Vec3d& v, Vec3d& w) {
        v = w = {};
        if (s.kind == Body::Kind::Rigid) {
            const double* y = &world.tick_start[s.index * rigid::kStateSize];
            v = Vec3d{y[rigid::P], y[rigid::P + 1], y[rigid::P + 2]} * s.inv_mass;
            w = s.inv_I * Vec3d{y[rigid::L], y[rigid::L + 1], y[rigid::L + 2]};
        } else if (s.kind == Body::Kind::Particle) {
            const SolverParticles& q = world.particles[std::size_t(s.soft)];
            v = {q.vx[s.index], q.vy[s.index], q.vz[s.index]};
        }
    };
    // Each manifold built where the passes take it, then set up, and its approach recorded, while
    // it is at hand (in stack:20, 20,000 manifolds of 40 MB with their points).
    parallel(found.size(), kManifoldGrain, [&](std::size_t at) {
        if (at + kFetchAhead < found.size()) {
            const FoundManifold& ahead = found[slab_order_[at + kFetchAhead]];
            fetch_contacts<false>(&contacts[ahead.contact], ahead.count);
        }
        const FoundManifold& f = found[slab_order_[at]];
        const RigidContact& first = contacts[f.contact];
        Manifold& m = manifolds_[at];
        m = Manifold{};
        m.a = f.a;
        m.b = f.b;
        m.n = first.normal;
        contact_tangents(m.n, m.t[0], m.t[1]);
        // A particle at rest on the surface is held by Eq. 24's mu_s (static_friction is mu_d
        // for one already sliding: particle_contacts.h); a rigid body has one mu.
        m.mu = first.soft >= 0 ? first.static_friction : first.friction;
        m.e = first.restitution;
        m.roll_arm = first.rolling;
        m.first = first_point[at];
        m.count = f.count;
        const Body &A = bodies_[m.a], &B = bodies_[m.b];
        for (std::uint32_t j = 0; j < f.count; ++j) {
            const std::size_t k = f.contact + j;
            const RigidContact& c = contacts[k];
            Point& p = points_[m.first + j];
            PassPoint& q = pass_[m.first + j];
            GapPoint& g = gap_[m.first + j];
            p = Point{};
            q = PassPoint{};
            g = GapPoint{};
            p.contact = std::uint32_t(k);
            p.r_a = g.r_a0 = A.kind == Body::Kind::Rigid ? c.arm_a : Vec3d{};
            p.r_b = g.r_b0 = B.kind == Body::Kind::Rigid ? c.arm_b : Vec3d{};
            p.at = c.point;
            g.s0 = q.s = c.separation;
            if (const RigidContact* before = warm(k)) {
                // Kept as forces (impulses per second): the substep may have changed since.
                q.normal_impulse = before->warm_normal * h_;
                m.friction[0] += before->warm_tangent[0] * h_;
                m.friction[1] += before->warm_tangent[1] * h_;
                m.twist += before->warm_twist * h_;
                m.roll += before->warm_roll * h_;
            }
        }
        setup(m);
        Vec3d v_a, w_a, v_b, w_b;
        velocity(A, v_a, w_a);
        velocity(B, v_b, w_b);
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
            const PassPoint& q = pass_[k];
            points_[k].v_n0 = dot(v_a - v_b, m.n) + dot(w_a, q.c_a) - dot(w_b, q.c_b);
        }
    });

    // Islands: bodies joined by this tick's contacts (the static world joins nothing; a soft
    // body's particles are one body here). Restitution's energy is bounded per island.
    const std::size_t nodes = world.bodies.size() + world.particles.size();
    std::vector<std::uint32_t>& parent = kept.parent;
    resize_with_room(parent, nodes);
    std::iota(parent.begin(), parent.end(), 0u);
    const auto find = [&](std::uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    const auto node = [&](const Body& s) -> std::uint32_t {
        return s.kind == Body::Kind::Rigid ? s.index : std::uint32_t(world.bodies.size() + std::size_t(s.soft));
    };
    // Joined on every thread: a root is only ever hung under a lesser one (compared and swapped
    // while it is still a root), so each node's parent is always an ancestor, never more than
    // itself, and the islands come out the same, whatever joins first. (On one thread, plainly.)
    const bool join_on_threads = world.pool && world.pool->threads() > 1;
    const auto load = [&](std::uint32_t x) { return __atomic_load_n(&parent[x], __ATOMIC_RELAXED); };
    const auto find_shared = [&](std::uint32_t x) {
        for (std::uint32_t up = load(x); up != x; up = load(x)) {
            const std::uint32_t above = load(up);
            if (above != up) __atomic_store_n(&parent[x], above, __ATOMIC_RELAXED);
            x = above;
        }
        return x;
    };
    parallel(manifolds_.size(), kPointGrain, [&](std::size_t i) {
        const Manifold& m = manifolds_[i];
        if (m.a == 0 || m.b == 0) return;
        std::uint32_t x = node(bodies_[m.a]), y = node(bodies_[m.b]);
        if (!join_on_threads) {
            x = find(x);
            y = find(y);
            if (x != y) parent[std::max(x, y)] = std::min(x, y);
            return;
        }
        for (;;) {
            x = find_shared(x);
            y = find_shared(y);
            if (x == y) return;
            if (x > y) std::swap(x, y);
            std::uint32_t root = y;
            if (__atomic_compare_exchange_n(&parent[y], &root, x, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) return;
        }
    });
    std::vector<std::int64_t>& number = kept.number;
    number.clear();
    reserve_with_room(number, nodes);
    number.resize(nodes, -1);
    island_of_.assign(bodies_.size(), 0);
    std::uint32_t islands = 0;
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
        const std::uint32_t root = find(node(bodies_[b]));
        if (number[root] < 0) number[root] = islands++;
        island_of_[b] = std::uint32_t(number[root]);
    }
    parallel(manifolds_.size(), kManifoldGrain, [&](std::size_t i) {
        Manifold& m = manifolds_[i];
        m.island = island_of_[m.a != 0 ? m.a : m.b];
    });
    absorbed_.assign(islands, 0.0);
}

// ---------------------------------------------------------------------------------------------
// Both cores
// ---------------------------------------------------------------------------------------------

template <class F>
void ContactSolver::parallel(std::size_t count, std::size_t grain, const F& f) {
    for_chunks(pool_, count, grain, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) f(i);
    });
}

template <class F>
void ContactSolver::each_body(const F& f) {
    parallel(body_order_.size(), kBodyGrain, [&](std::size_t k) { f(std::size_t(body_order_[k])); });
}

// Gauss-Seidel on every core, in the order a single thread would take: the moving bodies are cut
// into kBlocks slabs along the axis they spread most on (kBlocks is fixed: no machine changes
// it), each holding the same number of bodies. A manifold whose moving bodies are all in one
// slab belongs to it; the slabs' manifolds are solved at once, each slab's in the manifolds'
// own order on one thread (a slab shares no moving body with another: the static world is
// shared by all, and never written to). Then the manifolds across two neighbouring slabs, a
// boundary's on one thread: the boundaries 0|1, 2|3, 4|5, 6|7 (they share no slab), then 1|2,
// 3|4, 5|6. The few across slabs further apart follow, in their order, on one thread.
// Each group waits only for what it shares a slab with, not for a whole phase: a boundary for
// its two slabs, and 1|2 (say) for 0|1 and 2|3 as well. So a body meets its manifolds in one
// order, the same whatever the thread count (the same bits at any), and a thread that is done
// with its part of a phase starts on the next one's instead of waiting for the other thread
// (with seven boundaries on two threads, one waited a third of the second phase).
template <class F>
void ContactSolver::each_in_slabs(int passes, const F& f) {
    if (slab_start_.size() < kGroups + 1) return;
    for (int first = 0; first < passes; first += kMostChained) chain_in_slabs(first, std::min(passes - first, kMostChained), f);
}

template <class F>
void ContactSolver::chain_in_slabs(int first, int passes, const F& f) {
    const auto run_group = [&](int pass, std::size_t c) {
        const std::uint32_t end = slab_start_[c + 1];
        for (std::uint32_t i = slab_start_[c]; i < end; ++i) {
            if (i + kFetchAhead < end) fetch_bodies(manifolds_[i + kFetchAhead]);
            f(manifolds_[i], first + pass);
        }
    };
    // The groups before the last, in the order one thread takes them: the slabs, the boundaries
    // from an even slab, those from an odd one.
    constexpr std::size_t kOrdered = kGroups - 1, kAcross = kGroups - 1;
    static constexpr std::array<std::uint8_t, kOrdered> order = [] {
        std::array<std::uint8_t, kOrdered> o{};
        std::size_t k = 0;
        for (std::size_t c = 0; c < kBlocks; ++c) o[k++] = std::uint8_t(c);
        for (std::size_t c = 0; c + 1 < kBlocks; c += 2) o[k++] = std::uint8_t(kBlocks + c);
        for (std::size_t c = 1; c + 1 < kBlocks; c += 2) o[k++] = std::uint8_t(kBlocks + c);
        return o;
    }();
    const bool threads = pool_ && pool_->threads() > 1 && manifolds_.size() >= kManifoldGrain * kBlocks;
    if (!threads) {
        for (int pass = 0; pass < passes; ++pass) {
            for (const std::uint8_t c : order) run_group(pass, c);
            run_group(pass, kAcross);
        }
        return;
    }
    // Each group of each pass free (0), taken (1) or done (2).
    std::array<std::atomic<std::uint8_t>, kGroups * kMostChained> state;
    for (std::atomic<std::uint8_t>& g : state) g.store(0, std::memory_order_relaxed);
    const auto at = [](int pass, std::size_t c) { return std::size_t(pass) * kGroups + c; };
    const auto done = [&](int pass, std::size_t c) { return state[at(pass, c)].load(std::memory_order_acquire) == 2; };
    const bool no_across = slab_start_[kAcross] == slab_start_[kAcross + 1];
    const auto ready = [&](int pass, std::size_t c) {
        if (c == kAcross) {
            for (const std::uint8_t g : order) {
                if (!done(pass, g)) return false;
            }
            return true;
        }
        if (c < kBlocks) {
            // After every group of the pass before that has a body in this slab: its own, the
            // boundaries on either side, and those across (which may have one anywhere).
            if (pass == 0) return true;
            return done(pass - 1, c) && (c == 0 || done(pass - 1, kBlocks + c - 1)) && (c + 1 == kBlocks || done(pass - 1, kBlocks + c)) &&
                   (no_across || done(pass - 1, kAcross));
        }
        const std::size_t low = c - kBlocks;  // the boundary low|low + 1
        if (!done(pass, low) || !done(pass, low + 1)) return false;
        if (low % 2 == 0) return true;
        return done(pass, c - 1) && (low + 2 >= kBlocks || done(pass, c + 1));
    };
    // Every thread takes the first free group that is ready, pass by pass, until none is free:
    // first among its own (thread t of T: the slabs t kBlocks / T up to (t + 1) kBlocks / T and
    // the boundaries above them, whose bodies it holds in its core's cache from the last pass),
    // then any. One that finds none ready waits for a group another is running (whatever it
    // waits for is taken: the order lists each group after those it waits for).
    const std::size_t threads_n = std::size_t(pool_->threads());
    pool_->run(threads_n, [&](std::size_t) {
        const std::size_t t = std::size_t(ThreadPool::slot()) % threads_n;
        const std::size_t home_lo = kBlocks * t / threads_n, home_hi = kBlocks * (t + 1) / threads_n;
        const auto home = [&](std::size_t c) {
            if (c == kAcross) return false;
            const std::size_t slab = c < kBlocks ? c : c - kBlocks;
            return slab >= home_lo && slab < home_hi;
        };
        const auto try_take = [&](int pass, std::size_t c, int round, bool& free) {
            if (state[at(pass, c)].load(std::memory_order_acquire) != 0) return false;
            if (round == 0 && !home(c)) return false;
            free = true;
            std::uint8_t expected = 0;
            if (!ready(pass, c) || !state[at(pass, c)].compare_exchange_strong(expected, 1, std::memory_order_acq_rel)) return false;
            run_group(pass, c);
            state[at(pass, c)].store(2, std::memory_order_release);
            return true;
        };
        for (;;) {
            bool free = false, took = false;
            for (int round = 0; round < 2 && !took; ++round) {
                for (int pass = 0; pass < passes && !took; ++pass) {
                    for (const std::uint8_t c : order) {
                        if ((took = try_take(pass, c, round, free))) break;
                    }
                    if (!took) took = try_take(pass, kAcross, round, free);
                }
            }
            if (!free) return;
            if (!took) std::this_thread::yield();
        }
    });
}

// Why slabs and not a colouring (a graph colouring, tried first): a colour takes
// manifolds from everywhere in a stack, and solved colour after colour the weight of a pyramid's
// top layers reached the ground a layer a pass instead of in one pass from the bottom up (the
// contacts' order): pyramid:20 took 47 ticks instead of 30 to fall asleep, and each tick 40%
// longer on one thread (the bodies visited out of memory order).
void ContactSolver::slabs(std::span<const FoundManifold> found) {
    // The axis the moving bodies spread most on, and each one's slab along it.
    const std::size_t n = bodies_.size();
    Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (std::size_t b = 1; b < n; ++b) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], bodies_[b].x0[k]);
            hi[k] = std::max(hi[k], bodies_[b].x0[k]);
        }
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k) {
        if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
    }
    // A body's slab is its rank r in (place, body) order over kBlocks: slab c holds ranks from
    // ceil(c N / kBlocks) on. Only where those edges fall is needed, not the whole order: each
    // found by selection (halves first, then quarters, eighths), each part then holding the
    // bodies of its ranks. (Place and body side by side: compared through the bodies, each a
    // few hundred bytes from the next, a sort of them waited on memory.)
    std::vector<std::pair<double, std::uint32_t>>& by_place = buffers_.by_place;
    const std::size_t moving = n > 0 ? n - 1 : 0;
    resize_with_room(by_place, moving);
    for (std::size_t b = 1; b < n; ++b) by_place[b - 1] = {bodies_[b].x0[axis], std::uint32_t(b)};
    const auto edge = [&](std::size_t c) { return std::ptrdiff_t((c * moving + kBlocks - 1) / kBlocks); };
    const auto cut = [&](const auto& self, std::size_t first, std::size_t last) -> void {
        if (last - first < 2) return;
        const std::size_t middle = (first + last) / 2;
        std::nth_element(by_place.begin() + edge(first), by_place.begin() + edge(middle), by_place.begin() + edge(last));
        self(self, first, middle);
        self(self, middle, last);
    };
    cut(cut, 0, kBlocks);
    std::vector<std::uint32_t>& slab = buffers_.slab;
    slab.clear();
    reserve_with_room(slab, n);
    slab.resize(n, 0);
    for (std::size_t c = 0; c < kBlocks; ++c) {
        for (std::ptrdiff_t r = edge(c); r < edge(c + 1); ++r) slab[by_place[std::size_t(r)].second] = std::uint32_t(c);
    }
    // The bodies slab after slab (each_body), each slab's in their order.
    resize_with_room(body_order_, moving);
    for (std::size_t c = 0; c < kBlocks; ++c) {
        for (std::ptrdiff_t r = edge(c); r < edge(c + 1); ++r) body_order_[std::size_t(r)] = by_place[std::size_t(r)].second;
    }
    // Each manifold to its slab (c), its boundary (kBlocks + the lower slab) or across further
    // (the last group); then laid out group after group, each in order.
    std::vector<std::uint32_t> &group = buffers_.group, &count = buffers_.count;
    resize_with_room(group, found.size());
    count.assign(kGroups + 1, 0);
    for (std::size_t i = 0; i < found.size(); ++i) {
        const FoundManifold& m = found[i];
        const std::uint32_t a = m.a != 0 ? slab[m.a] : slab[m.b], b = m.b != 0 ? slab[m.b] : a;
        const std::uint32_t low = std::min(a, b), high = std::max(a, b);
        group[i] = low == high ? low : high == low + 1 ? std::uint32_t(kBlocks) + low : std::uint32_t(kGroups - 1);
        ++count[group[i] + 1];
    }
    slab_start_.assign(kGroups + 1, 0);
    for (std::size_t c = 0; c < kGroups; ++c) slab_start_[c + 1] = slab_start_[c] + count[c + 1];
    std::vector<std::uint32_t>& at = buffers_.at;
    at.assign(slab_start_.begin(), slab_start_.end() - 1);
    resize_with_room(slab_order_, found.size());
    for (std::size_t i = 0; i < found.size(); ++i) slab_order_[at[group[i]]++] = std::uint32_t(i);
}

// ---------------------------------------------------------------------------------------------
// Each substep
// ---------------------------------------------------------------------------------------------

// The velocities the integrator left, where the substep began, and how far each body has come.
// The impulses of the solve act as the substep begins (the positions then move from there with
// the new velocities): each rigid body's angular velocity is J_world^-1 L with J_world where it
// was then (refresh) and L after the free step's torques.
void ContactSolver::load(const ContactWorld& world) {
    pool_ = world.pool;
    // Each body's inertia found again where it needs it (refresh), in the same sweep.
    std::atomic<bool> any_refreshed{false};
    each_body([&](std::size_t b) {
        Body& s = bodies_[b];
        if (s.kind == Body::Kind::Rigid) {
            const double* y = &world.state[s.index * rigid::kStateSize];
            const double* y0 = &world.step_start[s.index * rigid::kStateSize];
            const Quat q{y[rigid::Q], y[rigid::Q + 1], y[rigid::Q + 2], y[rigid::Q + 3]};
            const Quat q_start{y0[rigid::Q], y0[rigid::Q + 1], y0[rigid::Q + 2], y0[rigid::Q + 3]};
            s.L_free = Vec3d{y[rigid::L], y[rigid::L + 1], y[rigid::L + 2]};
            s.v_free = Vec3d{y[rigid::P], y[rigid::P + 1], y[rigid::P + 2]} * s.inv_mass;
            s.w_free = s.inv_I * s.L_free;
            s.v_start = Vec3d{y0[rigid::P], y0[rigid::P + 1], y0[rigid::P + 2]} * s.inv_mass;
            s.L_start = Vec3d{y0[rigid::L], y0[rigid::L + 1], y0[rigid::L + 2]};
            s.w_start = s.inv_I * s.L_start;
            // Where the substep began, and where the free step took it: the positions move on from
            // the integrator's by the contacts' share. (Where the last substep's positions left
            // the body, its turn is the one they found.)
            const Vec3d x_start{y0[rigid::X], y0[rigid::X + 1], y0[rigid::X + 2]};
            const bool turned = !(q_start == s.q_now);
            s.same_start = !turned && same_bits(x_start, s.x);
            if (turned) s.turn = anchor_turn(s, q_start);
            s.x = x_start;
            s.q_now = q_start;
            s.dp = s.x - s.x0;
            s.dp_free = Vec3d{y[rigid::X], y[rigid::X + 1], y[rigid::X + 2]} - s.x0;
            s.turn_free = anchor_turn(s, q);
        } else {
            const SolverParticles& p = world.particles[std::size_t(s.soft)];
            const Vec3Array& v0 = *world.particle_step_start_v[std::size_t(s.soft)];
            s.v_free = {p.vx[s.index], p.vy[s.index], p.vz[s.index]};
            s.v_start = Vec3d(v0[s.index]);
            const Vec3d x{p.x[s.index], p.y[s.index], p.z[s.index]};
            const Vec3d x_start{p.x0[s.index], p.y0[s.index], p.z0[s.index]};  // where the substep began
            s.same_start = same_bits(x_start, s.x);
            s.x = x_start;
            s.dp = s.x - s.x0;
            s.dp_free = x - s.x0;
            s.chord = (x - s.x) / h_ - s.v_free;
            s.w_free = s.w_start = {};
            s.turn = s.turn_free = Mat3::identity();
        }
        s.v = s.v_free;
        s.w = s.w_free;
        if (refresh(world, s)) any_refreshed.store(true, std::memory_order_relaxed);
    });
    if (any_refreshed.load()) refresh_manifolds();
}

// A rigid body's inverse inertia in world axes, and its contacts' anchors, are those of where
// they were found; once the inertia would make its angular velocity J_world^-1 L wrong by more
// than kStaleSpeed at its surface, both are found again where the body is now (s.x, s.q_now: the
// substep's start for the solve, its end for the relax). A thin body needs that often: a tilt
// delta puts |L| delta / I_min of spin on a rod's long axis, and velocities from a stale inertia
// would be wrong enough to throw it. A body turning about a principal axis (a plank tipping on
// an edge) or resting never does. (How far the anchors turn is bounded by finding the contacts
// again more often: World::contact_intervals.) The body's velocities keep its momenta: w is
// found again from L = L_free + I (w - w_free), and w_free with it.
bool ContactSolver::refresh(const ContactWorld& world, Body& s) {
    s.refreshed = false;
    if (s.kind != Body::Kind::Rigid || s.q_now == s.q_ref) return false;
    const RigidBody& body = world.bodies[s.index];
    const Vec3d L = s.L_free + s.I * (s.w - s.w_free);
    // First a bound, without the new inertia. J^-1's isotropic part (1 / I_max) turns into
    // itself, so the change R J^-1 R^T - R0 J^-1 R0^T is at most 2 |R - R0| (1 / I_min -
    // 1 / I_max), and |R - R0| = 2 sin(theta/2) for the turn theta between them; plus the
    // rounding of the products below. Where even twice that keeps the error under
    // kStaleSpeed, so would the test below: a ball or a cube (isotropic), a body resting or
    // turning slowly, skips two matrix products.
    const Vec3d& moments = body.principal_moments;
    if (moments.x > 0.0) {
        const Quat turn = s.q_now * s.q_ref.conjugate();
        const double sin_half = std::sqrt(turn.x * turn.x + turn.y * turn.y + turn.z * turn.z) / (s.q_now.norm() * s.q_ref.norm());
        const double spread = 1.0 / moments.x - 1.0 / moments.z, rounding = 1e-12 / moments.x;
        if ((8.0 * sin_half * spread + rounding) * length(L) * body.bounding_radius < kStaleSpeed) return false;
    }
    const Mat3 R = rotation_of(s.q_now);
    const Mat3 inv_I = R * body.J_body_inv * R.transposed();
    if (!(length((inv_I - s.inv_I) * L) * body.bounding_radius > kStaleSpeed)) return false;
    s.inv_I = inv_I;
    s.I = R * body.J_body * R.transposed();
    s.q_ref = s.q_now;
    s.w = inv_I * L;
    s.w_free = inv_I * s.L_free;
    s.w_start = inv_I * s.L_start;
    s.refreshed = true;
    return true;
}

void ContactSolver::refresh_manifolds() {
    // Each point of a turned body's manifold: its two anchors where they are (each body's anchor
    // from the start turned with it), and the point between them, where both impulses act (so
    // that they keep the angular momentum about any point exactly).
    parallel(manifolds_.size(), kManifoldGrain, [&](std::size_t i) {
        Manifold& m = manifolds_[i];
        const Body &A = bodies_[m.a], &B = bodies_[m.b];
        if (!A.refreshed && !B.refreshed) return;
        const auto anchor = [&](const Body& s, const Vec3d& r0) {
            if (s.kind != Body::Kind::Rigid) return s.x;
            if (s.round) return s.x + r0;  // anchor_turn
            return s.x + rotation_of(s.q_now) * (rotation_of(s.q0).transposed() * r0);
        };
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
            Point& p = points_[k];
            const GapPoint& g = gap_[k];
            const Vec3d on_a = anchor(A, g.r_a0);
            p.at = B.kind == Body::Kind::Static ? on_a : (on_a + anchor(B, g.r_b0)) * 0.5;
            p.r_a = A.kind == Body::Kind::Rigid ? p.at - A.x : Vec3d{};
            p.r_b = B.kind == Body::Kind::Rigid ? p.at - B.x : Vec3d{};
        }
        setup(m);
    });
}

// Each point's separation where the bodies are: as the tick began, moved on by each body's
// move and turn since (the anchors turn with their bodies). Kept as the substep's start
// (s_start) or, once its positions `moved`, as s_moved.
//
// At the substep's start, in the same sweep: how far each point's gap closes in the free step,
// against what its normal velocity at the step's end says (the solve takes the difference as
// an offset to that velocity). The solver's velocities are the free step's end; a point on a
// body turning fast follows an arc, not that straight line: a corner 1.5 m out at 55 rad/s is
// off by a centripetal 1/2 w^2 r h^2 = 0.3 mm in a substep of 0.37 ms, enough to sink the corner
// a little deeper every substep, and the push out of it would spin the body up. With the free
// step's own displacement the gap closes as far as the motion actually takes it.
//
// One manifold's points at a time, inside the sweep that reads them next (who bounces; the
// relax's first pass): each point is its own, so it is the same as a sweep of its own before,
// and in a pile it saves a pass through memory (in stack:20, 78,000 points of 184 bytes, twice a
// substep). separations() is such a sweep, for when there is no relax to put it in.
void ContactSolver::separate(const Manifold& m, bool moved) {
    const double inv_h = 1.0 / h_;
    const Body &A = bodies_[m.a], &B = bodies_[m.b];
    const double v_lin = moved ? 0.0 : dot(A.v_free - B.v_free, m.n);
    // A point's gap closes by (d_a - d_b) . n, each side's anchor moved by d = dp + (turn - 1) r0;
    // and (turn - 1) r0 . n = r0 . (turn^T - 1) n. So each side's (turn^T - 1) n once a
    // manifold, and a dot product a point (not a matrix product each).
    const auto along = [&](const Body& s, const Mat3& turn) { return s.kind == Body::Kind::Rigid ? turn.transposed() * m.n - m.n : Vec3d{}; };
    // As a substep begins where the last one's positions left both bodies (the same dp and turn
    // to the bit), each gap is the one found then (s_moved), the same numbers worked out the same
    // way: taken as it is. Only the first substep after prepare() has none.
    const bool as_left = !moved && substeps_done_ > 0 && A.same_start && B.same_start;
    struct Move {
        Vec3d u_a, u_b;
        double shift = 0.0;
    };
    const auto move = [&](const Mat3& turn_a, const Mat3& turn_b, const Vec3d& dp_a, const Vec3d& dp_b) {
        return Move{along(A, turn_a), along(B, turn_b), dot(dp_a - dp_b, m.n)};
    };
    const auto gap = [](const GapPoint& g, const Move& d) { return g.s0 + d.shift + dot(g.r_a0, d.u_a) - dot(g.r_b0, d.u_b); };
    const Move now = as_left ? Move{} : move(A.turn, B.turn, A.dp, B.dp);
    const Move free_step = moved ? Move{} : move(A.turn_free, B.turn_free, A.dp_free, B.dp_free);
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
        GapPoint& g = gap_[k];
        PassPoint& q = pass_[k];
        const double s = as_left ? g.s_moved : gap(g, now);
        q.s = s;
        if (moved) {
            g.s_moved = s;
            continue;
        }
        g.s_start = s;
        const double closing = (gap(g, free_step) - s) * inv_h;
        q.offset = closing - (v_lin + dot(A.w_free, q.c_a) - dot(B.w_free, q.c_b));
    }
}

void ContactSolver::separations(bool moved) {
    parallel(manifolds_.size(), kManifoldGrain, [&](std::size_t i) { separate(manifolds_[i], moved); });
}

// The work the contacts did on a body since the integrator left it: the impulse m dv at the
// substep's middle velocity, (v + v_free) / 2, less the weight's work over the move it added,
// h dv (kinetic plus potential energy, exactly), and the turn's change of 1/2 w . J w.
// `shown`: as the energy panel shows it, with half the weight's work: then a body the contacts
// hold still under gravity takes zero (its contact only gives back the half step of fall the
// free step lost, 1/2 m g^2 h^2), where exactly it gives that much. Restitution's allowance
// counts exactly: a bounce also lifts the body h dv, and that is energy too.
double ContactSolver::work(const Body& s, bool shown) const {
    if (s.inv_mass == 0.0) return 0.0;
    const Vec3d dv = s.v - s.v_free;
    double W = dot(dv, (s.v + s.v_free) * 0.5 - settings_.gravity * ((shown ? 0.5 : 1.0) * h_)) / s.inv_mass;
    if (s.kind == Body::Kind::Rigid) W += 0.5 * (dot(s.w, s.I * s.w) - dot(s.w_free, s.I * s.w_free));
    return W;
}

// The impulses' share of each side, Eq. 37 (solve_manifold too). The static world (body 0) is
// in every slab, so it is never written to (1/m = 0 and J^-1 = 0: it would not move anyway):
// no two threads touch the same body.
void ContactSolver::warm_start(Manifold& m) {
    if (!held_anything(m, &pass_[m.first], int(m.count))) return;  // nothing to start from
    Body &A = bodies_[m.a], &B = bodies_[m.b];
    double sum = 0.0;
    Vec3d L_a, L_b;
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
        const PassPoint& p = pass_[k];
        sum += p.normal_impulse;
        L_a += p.c_a * p.normal_impulse;
        L_b += p.c_b * p.normal_impulse;
    }
    const Vec3d j = m.n * sum + m.t[0] * m.friction[0] + m.t[1] * m.friction[1];
    L_a += m.ft_a[0] * m.friction[0] + m.ft_a[1] * m.friction[1] + m.n * m.twist + m.roll;
    L_b += m.ft_b[0] * m.friction[0] + m.ft_b[1] * m.friction[1] + m.n * m.twist + m.roll;
    if (m.a != 0) {
        A.v += j * A.inv_mass;
        A.w += A.inv_I * L_a;
    }
    if (m.b != 0) {
        B.v -= j * B.inv_mass;
        B.w -= B.inv_I * L_b;
    }
}

// One manifold's visit in a pass: its normal impulses together toward each point's target, then
// friction at its centre. `bias`: push overlaps apart (the solve), or not (the relax).
void ContactSolver::solve_manifold(Manifold& m, bool bias) {
    const double inv_h = 1.0 / h_;
    if (!bias && m.bouncing) return;  // it leaves: nothing to relax
    Body &A = bodies_[m.a], &B = bodies_[m.b];
    const int n = int(m.count);
    // Each point's target normal velocity: minus the gap over h where it is still apart
    // (close it in this substep, no more); where it touches or overlaps, what one step of a
    // soft spring pushing it out would leave (never faster than push_speed), and in the
    // relax 0. Touching means closer than kSpeculative: a face resting on another has its
    // corners at gaps of +-1e-17 m, and treating each by the sign of its rounding would
    // hold one corner stiffly and the next softly, and turn the face.
    // The relax leaves a point that is still apart alone: it holds what is touching, and the
    // next substep's solve stops that point at its surface (held here, it would stop short
    // of it, and bounce in the air).
    PassPoint* const P = &pass_[m.first];
    // The points that take part (all of them in the solve), as a set of bits, then listed from
    // a table: without a branch (in the relax, which points touch changes from manifold to
    // manifold, and a branch on it was mispredicted often enough to show in a profile) and
    // without a count carried through each point's store.
    unsigned taking = (1u << n) - 1u;
    if (!bias) {
        taking = 0;
        for (int i = 0; i < n; ++i) taking |= unsigned(P[i].s <= kSpeculative) << i;
    }
    const std::array<int, 4>& index = kPointsOf[taking].index;
    const int count = kPointsOf[taking].count;
    // A point's normal velocity: the bodies' relative motion along n (the same for every point
    // of the manifold), then each side's turn at the point.
    const auto linear_velocity = [&] { return dot(A.v - B.v, m.n); };
    const auto normal_velocity = [&](double v_lin, const PassPoint& p) {
        return v_lin + dot(A.w, p.c_a) - dot(B.w, p.c_b) + (bias ? p.offset : 0.0);
    };
    // A manifold holding no impulse of any kind whose points all stay apart does nothing: no
    // normal impulse to solve for, and friction, twist and roll limited to zero stay zero. In
    // the relax, that is one none of whose points touch (a falling pile's manifolds are mostly
    // such: in bin:1000, 94% of the relax's visits; in stack:20, 17%). In the solve, one whose
    // points are all apart and none closing its gap within the substep, by a margin (then no
    // set of pushing points fits, and the block solve's answer is none: solve_block); in the
    // stacks of touching cubes 17% of the solve's visits, in the bins 27 to 29%.
    if ((bias || count == 0) && !held_anything(m, P, n)) {
        if (!bias) return;
        const double v_lin = linear_velocity();
        bool apart = true;
        for (int i = 0; i < n && apart; ++i) {
            apart = P[i].s > kSpeculative && -P[i].s * inv_h - normal_velocity(v_lin, P[i]) < -kClearlyApart;
        }
        if (apart) return;
    }
    double target[4] = {0.0, 0.0, 0.0, 0.0};  // the relax's: 0
    if (bias) {
        const double v_lin = linear_velocity();
        for (int k = 0; k < count; ++k) {
            const PassPoint& p = P[index[k]];
            // The solve moves the positions: its normal velocity is the one that closes the gap
            // (separations); the relax is of velocities alone.
            if (p.s > kSpeculative) {
                target[k] = -p.s * inv_h;
            } else {
                const double v_n = normal_velocity(v_lin, p);
                const Softness& soft = p.softness;
                const double push = std::min(-soft.bias_rate * p.s, settings_.push_speed);
                target[k] = (1.0 - soft.mass_scale) * v_n + soft.mass_scale * push - soft.impulse_scale * p.normal_impulse / p.normal_mass;
            }
        }
    }
    // The normal impulses toward those targets, together; then friction. Friction at a
    // point away from the centre of mass turns the body, and so changes the normal
    // velocities again: for a light body (a coin's rim, 5 mm from its centre) by more than
    // the normal impulses just did. Then the two again, until the targets hold (at most
    // kCouplingPasses): the solve's must, before the positions move. The relax makes one
    // pass a visit: it is itself passes over every manifold (relax_passes), and the next takes
    // up what friction undid (passes again within the visit cost a pyramid of touching cubes
    // a tenth of its instructions; without them its 20 layers stand 0.2 mm deeper).
    // Where every point takes part, K is the manifold's own; otherwise the rows and columns
    // of those that do.
    double K_part[4][4];
    if (count < n) {
        for (int k = 0; k < count; ++k)
            for (int j = 0; j < count; ++j) K_part[k][j] = m.K[index[k]][index[j]];
    }
    const double (&K)[4][4] = count < n ? K_part : m.K;
    const int coupling_passes = bias ? kCouplingPasses : 1;
    for (int pass = 0; pass < coupling_passes; ++pass) {
        double b[4], x[4], lambda[4];
        for (int i = 0; i < n; ++i) lambda[i] = P[i].normal_impulse;
        const double v_lin = linear_velocity();
        for (int k = 0; k < count; ++k) {
            b[k] = target[k] - normal_velocity(v_lin, P[index[k]]);
            for (int j = 0; j < count; ++j) b[k] += K[k][j] * lambda[index[j]];
        }
        if (count > 0) {
            solve_block(m.block, count, K, b, x, count == n);
            for (int k = 0; k < count; ++k) lambda[index[k]] = x[k];
        }
        double sum = 0.0, normal = 0.0;
        Vec3d L_a, L_b;
        for (int i = 0; i < n; ++i) {
            PassPoint& p = P[i];
            const double applied = lambda[i] - p.normal_impulse;
            p.normal_impulse = lambda[i];
            sum += applied;
            L_a += p.c_a * applied;
            L_b += p.c_b * applied;
            normal += lambda[i];
        }
        // Eq. 37 for the manifold's impulses at once: P by sum lambda n, L by sum r x lambda n.
        if (m.a != 0) {
            A.v += m.n * (sum * A.inv_mass);
            A.w += A.inv_I * L_a;
        }
        if (m.b != 0) {
            B.v -= m.n * (sum * B.inv_mass);
            B.w -= B.inv_I * L_b;
        }
        // Coulomb friction in impulse form, at the manifold's centre (all its points
        // together, so that a face slides, sticks and lands alike at every corner): the
        // tangential velocity there brought to zero while |lambda_t| <= mu lambda_n allows,
        // lambda_n the manifold's (normal); and its turn about n, within mu lambda_n times the
        // points' mean distance from the centre. For a particle (one point) that is Eq. 24's
        // min(mu_s |F_n|, |F_t|) when it was at rest and Eq. 25's mu_d |F_n| when sliding; one
        // mu between rigid bodies.
        // Rolling resistance (not in the addendum: the rolling resistance coefficient,
        // F = C_rr |F_n|, as a torque C_rr r |F_n| on a body rolling on radius r): the two
        // sides' relative turn, rolling or spinning about n, brought to zero by an angular
        // impulse of at most roll_arm times the normal impulse. A ball left rolling on a
        // floor stops, as a real one does, instead of rolling (or spinning in place) forever.
        if (m.roll_arm > 0.0) {
            Vec3d turn = m.roll - m.roll_mass * (A.w - B.w);
            const double size = length(turn), roll_limit = m.roll_arm * normal;
            if (size > roll_limit) turn = size > 0.0 ? turn * (roll_limit / size) : Vec3d{};
            const Vec3d d = turn - m.roll;
            m.roll = turn;
            if (m.a != 0) {
                A.w += A.inv_I * d;
            }
            if (m.b != 0) {
                B.w -= B.inv_I * d;
            }
        }
        if (m.mu <= 0.0) break;
        const Vec3d dv = A.v - B.v;
        double t[2];
        for (int d = 0; d < 2; ++d) {
            const double v_t = dot(dv, m.t[d]) + dot(A.w, m.ft_a[d]) - dot(B.w, m.ft_b[d]);
            t[d] = m.friction[d] - v_t * m.tangent_mass[d];
        }
        const double size2 = t[0] * t[0] + t[1] * t[1], limit = m.mu * normal;
        if (!within_limit(size2, limit) && std::sqrt(size2) > limit) {
            const double size = std::sqrt(size2);
            const double scale = size > 0.0 ? limit / size : 0.0;
            t[0] *= scale;
            t[1] *= scale;
        }
        const double d0 = t[0] - m.friction[0], d1 = t[1] - m.friction[1];
        m.friction[0] = t[0];
        m.friction[1] = t[1];
        const Vec3d j = m.t[0] * d0 + m.t[1] * d1;
        if (m.a != 0) {
            A.v += j * A.inv_mass;
            A.w += m.fw_a[0] * d0 + m.fw_a[1] * d1;
        }
        if (m.b != 0) {
            B.v -= j * B.inv_mass;
            B.w -= m.fw_b[0] * d0 + m.fw_b[1] * d1;
        }
        if (m.twist_mass > 0.0) {
            const double twist_limit = limit * m.twist_radius;
            const double turn = std::clamp(m.twist - dot(A.w - B.w, m.n) * m.twist_mass, -twist_limit, twist_limit);
            const double d = turn - m.twist;
            m.twist = turn;
            if (m.a != 0) {
                A.w += m.nw_a * d;
            }
            if (m.b != 0) {
                B.w -= m.nw_b * d;
            }
        }
        if (pass + 1 == coupling_passes) break;
        // Did friction undo the targets? By what it would take to restore them, against the
        // impulses in play.
        double undone = 0.0;
        const double v_lin_after = linear_velocity();
        for (int k = 0; k < count; ++k) {
            const PassPoint& p = P[index[k]];
            const double short_of = target[k] - normal_velocity(v_lin_after, p);
            if (short_of > 0.0 || p.normal_impulse > 0.0) undone = std::max(undone, std::abs(short_of) * p.normal_mass);
        }
        if (undone <= 1e-3 * normal + 1e-12) break;
    }
}

void ContactSolver::substep(const ContactWorld& world) {
    if (manifolds_.empty()) return;
    const double h = h_, inv_h = 1.0 / h;
    load(world);

    // Which points bounce before the positions move: those touching as the substep begins and
    // coming in faster than a resting contact does. The bounce leaves at -e times that speed,
    // plus what the substep's forces add to it (as the free step would have).
    // Then the warm start: the impulses that held the contacts in the last substep, again. Both in
    // one sweep, a manifold at a time: the first reads the velocities the integrator left
    // (v_free, v_start) and writes the manifold's own points, the second changes only v and w, so
    // it is the same as two sweeps one after the other, with one pass through the manifolds less.
    // And in the sweep after, the solve (each manifold once every manifold it shares a body with
    // has been warm-started).
    std::atomic<bool> any_bouncing{false};
    each_in_slabs(2, [&](Manifold& m, int pass) {
        if (pass == 1) {
            solve_manifold(m, true);
            return;
        }
        separate(m, false);
        // Only a manifold that was bouncing has points with a bounce to clear.
        if (m.bouncing) {
            for (std::uint32_t k = m.first; k < m.first + m.count; ++k) points_[k].bounce = points_[k].bounce_impulse = 0.0;
        }
        m.bouncing = false;
        if (m.e > 0.0) {  // else it never bounces: its bounces stay 0
            const Body &A = bodies_[m.a], &B = bodies_[m.b];
            for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
                const PassPoint& q = pass_[k];
                if (q.s > settings_.touching) continue;
                const double vn_start = dot(A.v_start - B.v_start, m.n) + dot(A.w_start, q.c_a) - dot(B.w_start, q.c_b);
                if (-vn_start <= settings_.bounce_speed) continue;
                const double vn_free = dot(A.v_free - B.v_free, m.n) + dot(A.w_free, q.c_a) - dot(B.w_free, q.c_b);
                Point& p = points_[k];
                p.bounce = -vn_start;
                p.bounce_target = -m.e * vn_start + (vn_free - vn_start);
                m.bouncing = true;
                any_bouncing.store(true, std::memory_order_relaxed);
            }
        }
        warm_start(m);
    });
    const bool bouncing = any_bouncing.load();
    if (bouncing) restitute(false);

    // The positions: the free step's, moved on by h times what the contacts changed. The turn:
    // under symplectic Euler and Verlet the free turn again from where the substep began, with
    // the angular momentum the contacts left (free_turn keeps its energy); under the others,
    // turned on by h times the change. Each body's inertia found again where it needs it
    // (refresh), in the same sweep.
    std::atomic<bool> any_refreshed{false};
    each_body([&](std::size_t b) {
        Body& s = bodies_[b];
        const Vec3d dx = (s.v - s.v_free) * h;
        if (s.kind == Body::Kind::Rigid) {
            double* y = &world.state[s.index * rigid::kStateSize];
            for (int k = 0; k < 3; ++k) y[rigid::X + k] += dx[k];
            const RigidBody& body = world.bodies[s.index];
            Quat q;
            if (settings_.exact_turn) {
                const double* y0 = &world.step_start[s.index * rigid::kStateSize];
                const Vec3d L = Vec3d{y[rigid::L], y[rigid::L + 1], y[rigid::L + 2]} + s.I * (s.w - s.w_free);
                q = free_turn(body, Quat{y0[rigid::Q], y0[rigid::Q + 1], y0[rigid::Q + 2], y0[rigid::Q + 3]}, L, h);
            } else {
                q = turned(Quat{y[rigid::Q], y[rigid::Q + 1], y[rigid::Q + 2], y[rigid::Q + 3]}, (s.w - s.w_free) * h);
            }
            y[rigid::Q] = q.w;
            y[rigid::Q + 1] = q.x;
            y[rigid::Q + 2] = q.y;
            y[rigid::Q + 3] = q.z;
            s.x = Vec3d{y[rigid::X], y[rigid::X + 1], y[rigid::X + 2]};
            s.q_now = q;
            s.dp = s.x - s.x0;
            s.turn = anchor_turn(s, q);
        } else {
            SolverParticles& p = world.particles[std::size_t(s.soft)];
            p.x[s.index] = float(double(p.x[s.index]) + dx.x);
            p.y[s.index] = float(double(p.y[s.index]) + dx.y);
            p.z[s.index] = float(double(p.z[s.index]) + dx.z);
            s.x = Vec3d{p.x[s.index], p.y[s.index], p.z[s.index]};
            s.dp = s.x - s.x0;
        }
        if (refresh(world, s)) any_refreshed.store(true, std::memory_order_relaxed);
    });
    if (any_refreshed.load()) refresh_manifolds();
    // The relax; its first pass works out each manifold's separations where the positions left
    // its points just before, and its last adds each manifold's impulses to the tick's just
    // after, while its points are at hand (separate(), totals()).
    // Fewer passes before the interval's last substep: each next substep begins with a solve of
    // every manifold, which takes up what these left; the last leaves the bodies as the tick
    // ends, and relaxes fully.
    const bool last = ++substeps_done_ >= settings_.substeps;
    const int relax_passes = last ? settings_.relax_passes : std::min(settings_.relax_passes, settings_.early_relax_passes);
    each_in_slabs(relax_passes, [&](Manifold& m, int pass) {
        if (pass == 0) separate(m, true);
        solve_manifold(m, false);
        if (pass + 1 == relax_passes) add_to_totals(m);
    });
    if (relax_passes == 0) {
        separations(true);
        totals();
    }
    // Under RK4 and explicit Euler, a particle its contact pushed leaves with the velocity it
    // moved with along the normal (its chord), not with what its integrator's end velocity still
    // holds beyond that: a step of its springs pressing it into the surface (v_end - chord is
    // a h / 2 under RK4), which the surface cancels while it holds the particle: an impulse,
    // equal and opposite on the other side. Kept, a particle that reached the surface in this
    // substep (a speculative point, left 0.07 mm off it and so not relaxed) went on into it at
    // 12 m/s with nothing moving it so, and the next substep took that for an impact and bounced
    // it back out at e times it (a bounce's velocity carries the same step): a soft ball landing
    // on a pyramid of boxes gained 2.7% of the energy in play under RK4, 5.9% with softer
    // dampers. (Under Verlet and symplectic Euler the two are one.)
    if (settings_.particle_chord) {
        for (const std::uint32_t at : found_order_) {
            const Manifold& m = manifolds_[at];
            Body &A = bodies_[m.a], &B = bodies_[m.b];
            if (A.kind != Body::Kind::Particle) continue;
            const Point& p = points_[m.first];
            const PassPoint& q = pass_[m.first];
            const double lag = dot(A.chord, m.n);
            const bool bounced = p.bounce > 0.0, held = gap_[m.first].s_moved > kSpeculative && q.normal_impulse > 0.0 && lag > 0.0;
            if (!bounced && !held) continue;
            const double j = lag / A.inv_mass;  // Eq. 37 on both sides
            A.v += m.n * lag;
            if (m.b != 0) {
                B.v -= m.n * (j * B.inv_mass);
                B.w -= B.inv_I * (q.c_b * j);
            }
        }
    }

    // The energy of this substep's contacts, island by island: what restitution may give back.
    // Each body's on the threads, the sums in the bodies' order.
    body_work_.resize(bodies_.size());
    each_body([&](std::size_t b) {
        body_work_[b] = {work(bodies_[b], false), work(bodies_[b], true)};
    });
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
        absorbed_[island_of_[b]] -= body_work_[b].first;
        energy_.total += body_work_[b].second;
    }

    // A point still apart as the substep began and touching once the positions moved met its
    // surface in this substep: it bounces from there, at -e times the speed it met it with under
    // the substep's acceleration, sqrt(v_n^2 + 2 a s), once the tick is over (finish): so the
    // tick ends with the bodies touching, and a ball seen tick by tick (or drawn between ticks)
    // turns at the surface, not above it. It rests there for the rest of the tick, held.
    // In the same sweep, a manifold that bounced forgets its impulses (forget_bounced()); only
    // one that can bounce ever has.
    parallel(manifolds_.size(), kManifoldGrain, [&](std::size_t i) {
        Manifold& m = manifolds_[i];
        if (m.e <= 0.0) return;
        forget_if_bounced(m);
        const Body &A = bodies_[m.a], &B = bodies_[m.b];
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
            const GapPoint& g = gap_[k];
            if (g.s_start <= settings_.touching || g.s_moved > settings_.touching) continue;
            const PassPoint& q = pass_[k];
            const double vn_start = dot(A.v_start - B.v_start, m.n) + dot(A.w_start, q.c_a) - dot(B.w_start, q.c_b);
            // A particle's free velocity as it moved (its chord), not its integrator's end
            // velocity: under RK4 that holds a step of its springs pressing it on, and the speed
            // it met the surface with came out too high, and its bounce.
            const double chord = settings_.particle_chord && A.kind == Body::Kind::Particle ? dot(A.chord, m.n) : 0.0;
            const double vn_free = dot(A.v_free - B.v_free, m.n) + dot(A.w_free, q.c_a) - dot(B.w_free, q.c_b) + chord;
            const double a_n = (vn_free - vn_start) * inv_h;  // toward the surface: < 0
            const double speed2 = vn_start * vn_start - 2.0 * std::min(a_n, 0.0) * g.s_start;
            const bool closing = vn_start < 0.0 || a_n < 0.0;
            if (closing && speed2 > settings_.bounce_speed * settings_.bounce_speed) {
                Point& p = points_[k];
                p.pending = std::max(p.pending, std::sqrt(speed2));
            }
        }
    });
    store(world);
}

// What the substep's impulses added to the tick's: each one as it ended (the warm start's and
// every pass's changes, summed).
void ContactSolver::add_to_totals(Manifold& m) {
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) pass_[k].total_normal += pass_[k].normal_impulse;
    m.total_friction[0] += m.friction[0];
    m.total_friction[1] += m.friction[1];
}

void ContactSolver::totals() {
    parallel(manifolds_.size(), kManifoldGrain, [&](std::size_t i) { add_to_totals(manifolds_[i]); });
}

// A manifold that bounced is coming apart: it starts the next substep (or tick) from no impulse.
// Warm starting it from the impulse that stopped it would throw it again, and its friction,
// limited by that impulse, would spin it up.
void ContactSolver::forget_if_bounced(Manifold& m) {
    if (!m.bouncing) return;
    for (std::uint32_t k = m.first; k < m.first + m.count; ++k) pass_[k].normal_impulse = 0.0;
    m.friction[0] = m.friction[1] = m.twist = 0.0;
    m.roll = Vec3d{};
}

void ContactSolver::forget_bounced() {
    parallel(manifolds_.size(), kManifoldGrain, [&](std::size_t i) { forget_if_bounced(manifolds_[i]); });
}

// Restitution: each manifold's bouncing points toward their bounce_target together
// (solve_block), the round of manifolds a few times for those that share a body; then no more
// energy than the island's contacts took this tick.
void ContactSolver::restitute(bool after_positions) {
    // The bouncing manifolds, in the order the rounds take them (as found), and their islands.
    std::vector<std::uint32_t>& bouncing = buffers_.bouncing;
    bouncing.clear();
    for (const std::uint32_t at : found_order_) {
        if (manifolds_[at].bouncing) bouncing.push_back(at);
    }
    std::vector<std::uint32_t> islands;
    std::vector<char> bounces(absorbed_.size(), 0);  // per island
    for (const std::uint32_t at : bouncing) {
        const std::uint32_t island = manifolds_[at].island;
        if (!bounces[island]) islands.push_back(island);
        bounces[island] = 1;
    }
    std::sort(islands.begin(), islands.end());
    // The bodies of those islands and their velocities before the bounce.
    std::vector<std::uint32_t> touched;
    for (std::size_t b = 1; b < bodies_.size(); ++b) {
        if (bounces[island_of_[b]]) touched.push_back(std::uint32_t(b));
    }
    std::vector<std::pair<Vec3d, Vec3d>> before(touched.size());
    std::vector<double> W_before(absorbed_.size(), 0.0);
    for (std::size_t k = 0; k < touched.size(); ++k) {
        const Body& s = bodies_[touched[k]];
        before[k] = {s.v, s.w};
        if (!after_positions) W_before[island_of_[touched[k]]] += work(s, false);
    }
    for (int round = 0; round < settings_.restitution_passes; ++round) {
        for (const std::uint32_t at : bouncing) {
            Manifold& m = manifolds_[at];
            Body &A = bodies_[m.a], &B = bodies_[m.b];
            // The bouncing points only: the others stay as the solve left them.
            int index[4], n = 0;
            for (std::uint32_t k = 0; k < m.count; ++k) {
                if (points_[m.first + k].bounce > 0.0) index[n++] = int(k);
            }
            double K[4][4], b[4], lambda[4];
            const double v_lin = dot(A.v - B.v, m.n);
            for (int i = 0; i < n; ++i) {
                const Point& p = points_[m.first + std::uint32_t(index[i])];
                const PassPoint& q = pass_[m.first + std::uint32_t(index[i])];
                const double v_n = v_lin + dot(A.w, q.c_a) - dot(B.w, q.c_b);
                b[i] = p.bounce_target - v_n;
                for (int j = 0; j < n; ++j) {
                    K[i][j] = m.K[index[i]][index[j]];
                    b[i] += K[i][j] * points_[m.first + std::uint32_t(index[j])].bounce_impulse;
                }
            }
            solve_block(m.block, n, K, b, lambda, n == int(m.count));
            for (int i = 0; i < n; ++i) {
                Point& p = points_[m.first + std::uint32_t(index[i])];
                const PassPoint& q = pass_[m.first + std::uint32_t(index[i])];
                const double applied = lambda[i] - p.bounce_impulse;
                p.bounce_impulse = lambda[i];
                A.v += m.n * (applied * A.inv_mass);
                A.w += A.inv_I * (q.c_a * applied);
                B.v -= m.n * (applied * B.inv_mass);
                B.w -= B.inv_I * (q.c_b * applied);
            }
        }
    }
    // What the bounce gave each island, against what its contacts took: scaled down to fit.
    // Before the positions the bounce moves them too (the work at the substep's middle
    // velocity, as work() counts it, exactly for the allowance, and as shown); after them, only
    // the velocities: its work is 1/2 m dv^2.
    // (Island by island, each one's bodies and manifolds in their order: lists of them by island,
    // so that many small islands bouncing at once, a pile falling, cost no more than one.)
    std::vector<std::uint32_t> slot(absorbed_.size(), 0);
    for (std::size_t i = 0; i < islands.size(); ++i) slot[islands[i]] = std::uint32_t(i);
    const auto by_island = [&](std::size_t count, const auto& island_of, std::vector<std::uint32_t>& start, std::vector<std::uint32_t>& order) {
        start.assign(islands.size() + 1, 0);
        for (std::size_t k = 0; k < count; ++k) ++start[slot[island_of(k)] + 1];
        for (std::size_t i = 0; i < islands.size(); ++i) start[i + 1] += start[i];
        order.resize(count);
        std::vector<std::uint32_t> at(start.begin(), start.end() - 1);
        for (std::size_t k = 0; k < count; ++k) order[at[slot[island_of(k)]]++] = std::uint32_t(k);
    };
    std::vector<std::uint32_t> body_start, body_order, manifold_start, manifold_order;
    by_island(touched.size(), [&](std::size_t k) { return island_of_[touched[k]]; }, body_start, body_order);
    by_island(bouncing.size(), [&](std::size_t k) { return manifolds_[bouncing[k]].island; }, manifold_start, manifold_order);
    const Vec3d hg = settings_.gravity * (after_positions ? 0.0 : h_);
    for (std::size_t i = 0; i < islands.size(); ++i) {
        const std::uint32_t island = islands[i];
        double B_exact = 0.0, B_shown = 0.0, C = 0.0;
        for (std::uint32_t j = body_start[i]; j < body_start[i + 1]; ++j) {
            const std::uint32_t k = body_order[j];
            const Body& s = bodies_[touched[k]];
            const double m = 1.0 / s.inv_mass;
            const Vec3d dv = s.v - before[k].first, dw = s.w - before[k].second;
            // W(alpha) = alpha B + alpha^2 C for the bounce scaled by alpha.
            const double turn = dot(before[k].second, s.I * dw);
            B_exact += m * dot(dv, before[k].first - hg) + turn;
            B_shown += m * dot(dv, before[k].first - hg * 0.5) + turn;
            C += 0.5 * (m * dot(dv, dv) + dot(dw, s.I * dw));
        }
        const double allowed = absorbed_[island] - W_before[island];
        double alpha = 1.0;
        if (B_exact + C > allowed) {
            alpha = 0.0;
            if (allowed > 0.0 && C > 0.0) {
                const double disc = B_exact * B_exact + 4.0 * C * allowed;
                alpha = std::clamp((-B_exact + std::sqrt(std::max(disc, 0.0))) / (2.0 * C), 0.0, 1.0);
            }
            for (std::uint32_t j = body_start[i]; j < body_start[i + 1]; ++j) {
                const std::uint32_t k = body_order[j];
                Body& s = bodies_[touched[k]];
                s.v = before[k].first + (s.v - before[k].first) * alpha;
                s.w = before[k].second + (s.w - before[k].second) * alpha;
            }
            for (std::uint32_t j = manifold_start[i]; j < manifold_start[i + 1]; ++j) {
                const Manifold& m = manifolds_[bouncing[manifold_order[j]]];
                for (std::uint32_t k = m.first; k < m.first + m.count; ++k) points_[k].bounce_impulse *= alpha;
            }
        }
        const double shown = alpha * B_shown + alpha * alpha * C;
        energy_.restitution += shown;
        if (after_positions) {
            absorbed_[island] -= alpha * B_exact + alpha * alpha * C;
            energy_.total += shown;
        }
    }
    // Only a bouncing manifold's points have a bounce impulse.
    parallel(bouncing.size(), kManifoldGrain, [&](std::size_t i) {
        const Manifold& m = manifolds_[bouncing[i]];
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k) points_[k].total_bounce += points_[k].bounce_impulse;
    });
}

// The solved velocities back into the bodies: P and L by what the contacts changed (Eq. 37's
// L += r x j, as J_world dw), a particle's v, and Verlet's step with it.
void ContactSolver::fetch_bodies(const Manifold& m) const {
    for (const std::uint32_t b : {m.a, m.b}) {
        const Body& s = bodies_[b];
        __builtin_prefetch(&s.inv_I.m[0][0], 0);
        __builtin_prefetch(&s.inv_I.m[2][2], 0);
        __builtin_prefetch(&s.v, 1);
        __builtin_prefetch(&s.w.z, 1);
    }
}

void ContactSolver::store(const ContactWorld& world) {
    each_body([&](std::size_t b) {
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
    });
}

void ContactSolver::finish(std::vector<RigidContact>& contacts, const ContactWorld& world) {
    if (manifolds_.empty()) return;
    // The bounces due: points that met their surface in this tick, from there.
    std::atomic<bool> any_due{false};
    parallel(manifolds_.size(), kManifoldGrain, [&](std::size_t i) {
        Manifold& m = manifolds_[i];
        m.bouncing = false;
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
            Point& p = points_[k];
            p.bounce = 0.0;
            p.bounce_impulse = 0.0;
            if (p.pending > 0.0 && m.e > 0.0) {
                p.bounce = p.pending;
                p.bounce_target = m.e * p.pending;
                m.bouncing = true;
                any_due.store(true, std::memory_order_relaxed);
            }
            p.pending = 0.0;
        }
    });
    const bool due = any_due.load();
    if (due) {
        each_body([&](std::size_t b) {
            Body& s = bodies_[b];
            if (s.kind == Body::Kind::Rigid) {
                const double* y = &world.state[s.index * rigid::kStateSize];
                s.L_free = Vec3d{y[rigid::L], y[rigid::L + 1], y[rigid::L + 2]};
                s.v_free = Vec3d{y[rigid::P], y[rigid::P + 1], y[rigid::P + 2]} * s.inv_mass;
                s.w_free = s.inv_I * s.L_free;
            } else {
                const SolverParticles& p = world.particles[std::size_t(s.soft)];
                s.v_free = {p.vx[s.index], p.vy[s.index], p.vz[s.index]};
                s.w_free = {};
            }
            s.v = s.v_free;
            s.w = s.w_free;
        });
        restitute(true);
        forget_bounced();
        store(world);
    }
    // The record: what each point took over the tick, and what the next tick starts from.
    parallel(manifolds_.size(), kManifoldGrain, [&](std::size_t i) {
        if (i + kFetchAhead < manifolds_.size()) {
            const Manifold& ahead = manifolds_[i + kFetchAhead];
            fetch_contacts<true>(&contacts[points_[ahead.first].contact], ahead.count);
        }
        const Manifold& m = manifolds_[i];
        for (std::uint32_t k = m.first; k < m.first + m.count; ++k) {
            const Point& p = points_[k];
            const PassPoint& q = pass_[k];
            RigidContact& c = contacts[p.contact];
            c.approach_speed = -p.v_n0;
            c.normal_impulse = q.total_normal + p.total_bounce;
            c.bounce_impulse = p.total_bounce;
            // The manifold's friction shared by the points: as their normal impulses over the
            // tick (evenly when none), and its last substep's the same way for warm starting.
            double total = 0.0, last = 0.0;
            for (std::uint32_t j = m.first; j < m.first + m.count; ++j) {
                total += pass_[j].total_normal + points_[j].total_bounce;
                last += pass_[j].normal_impulse;
            }
            const double share = total > 0.0 ? (q.total_normal + p.total_bounce) / total : 1.0 / double(m.count);
            const double share_last = last > 0.0 ? q.normal_impulse / last : 1.0 / double(m.count);
            c.tangent_impulse[0] = m.total_friction[0] * share;
            c.tangent_impulse[1] = m.total_friction[1] * share;
            c.warm_normal = q.normal_impulse / h_;
            c.warm_tangent[0] = m.friction[0] * share_last / h_;
            c.warm_tangent[1] = m.friction[1] * share_last / h_;
            c.warm_twist = m.twist * share_last / h_;
            c.warm_roll = m.roll * (share_last / h_);
            c.depth = -q.s;
        }
    });
}

}  // namespace softbody
