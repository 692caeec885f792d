#include "rigid_contacts.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "collide_internal.h"
#include "ground_contact.h"
#include "kept_memory.h"
#include "nearly_sorted.h"

namespace softbody {

namespace {

// The first few lines of a list (a hint: the same bits).
template <class T>
void fetch_lines(const std::vector<T>& list) {
    const char* at = reinterpret_cast<const char*>(list.data());
    const std::size_t bytes = std::min<std::size_t>(list.size() * sizeof(T), 256);
    for (std::size_t byte = 0; byte < bytes; byte += 64) __builtin_prefetch(at + byte, 0);
}
// The least work worth another thread: bodies (a box each), pairs (a narrow-phase test each).
constexpr std::size_t kBoxGrain = 128;
constexpr std::size_t kPairGrain = 32;
// Up to this many bodies woken at once, their pairs are found by testing each one's box against
// every other, cheaper than sorting thousands of boxes again; more, by the sweep. (In bin:3000's
// first 10 s, 480 wakes woke 11 bodies each on average, 91 at most.)
constexpr std::size_t kFewWoken = 32;
}  // namespace

namespace {

// m and rad (as the largest change of an element of b's rotation in a's axes): how far two
// hulls may move relative to each other before their points are found again. A tenth of a
// millimetre: a fifth of the loaded slop (ContactSettings::stack_depth), of which the carried
// points' depths are exact and only where along the faces they sit is not.
constexpr double kReuseMove = 1e-4;
constexpr double kReuseTurn = 1e-3;

// collide() for two hulls, or their last points carried along when they have not moved
// relative to each other; either way the answer is noted for the next find. The pair's entry in
// the cache is looked for from `near`, where the last pair's was (the pairs come in the cache's
// order, mostly), and `near` is left at it.
void collide_hulls_again(const RigidContactScratch& scratch, const CollisionShape& A, std::uint32_t ia, const Pose& pa,
                         const CollisionShape& B, std::uint32_t ib, const Pose& pb, double margin, std::vector<ContactPoint>& points,
                         std::vector<CachedPair>& new_pairs, std::vector<CachedPoint>& new_points,
                         std::vector<CachedPair>::const_iterator& near) {
    const Transform Ta = world_transform(pa), Tb = world_transform(pb);
    const Transform rel = relative_transform(Ta, Tb);
    const std::uint64_t key = (std::uint64_t(ia) << 32) | ib;
    near = lower_bound_from(scratch.cache.pairs.cbegin(), scratch.cache.pairs.cend(), near, key,
                            [](const CachedPair& c, std::uint64_t k) { return c.key < k; });
    const auto last = near;
    const auto still = [&](const CachedPair& c) {
        if (c.stamp_a != A.stamp || c.stamp_b != B.stamp || margin > c.margin + kReuseMove) return false;
        if (length(rel.x - c.x) > kReuseMove) return false;
        for (int r = 0; r < 3; ++r) {
            for (int k = 0; k < 3; ++k) {
                if (std::abs(rel.R.m[r][k] - c.R.m[r][k]) > kReuseTurn) return false;
            }
        }
        return true;
    };
    CachedPair note;
    if (last != scratch.cache.pairs.end() && last->key == key && still(*last)) {
        note = *last;
        for (std::uint32_t k = last->first; k < last->first + last->count; ++k) {
            const CachedPoint& c = scratch.cache.points[k];
            const Vec3d on_a = Ta.apply(c.on_a), on_b = Tb.apply(c.on_b), n = Tb.R * c.normal_b;
            points.push_back({(on_a + on_b) * 0.5, n, dot(on_b - on_a, n), c.feature});
        }
        note.first = std::uint32_t(new_points.size());
        for (std::uint32_t k = last->first; k < last->first + last->count; ++k) new_points.push_back(scratch.cache.points[k]);
    } else {
        collide(A, pa, B, pb, margin, points);
        note.key = key;
        note.stamp_a = A.stamp;
        note.stamp_b = B.stamp;
        note.R = rel.R;
        note.x = rel.x;
        note.margin = margin;
        note.first = std::uint32_t(new_points.size());
        note.count = std::uint32_t(points.size());
        const Mat3 Ra_t = Ta.R.transposed(), Rb_t = Tb.R.transposed();
        for (const ContactPoint& p : points) {
            // The two surfaces' points: a's depth/2 behind the middle along n, b's ahead.
            const Vec3d on_a = p.point - p.normal * (0.5 * p.depth), on_b = p.point + p.normal * (0.5 * p.depth);
            new_points.push_back({Ra_t * (on_a - Ta.x), Rb_t * (on_b - Tb.x), Rb_t * p.normal, p.feature});
        }
    }
    new_pairs.push_back(note);
}

// Marks each body asleep or fixed in scratch.quiet; true when every body is.
bool mark_quiet(std::span<const RigidBody> bodies, std::span<const std::uint8_t> asleep, RigidContactScratch& scratch) {
    scratch.quiet.resize(bodies.size());
    bool all_quiet = true;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        scratch.quiet[b] = bodies[b].fixed || (!asleep.empty() && asleep[b]) ? 1 : 0;
        all_quiet = all_quiet && scratch.quiet[b];
    }
    return all_quiet;
}

// Body b's speculative margin and its box grown by it, where the tick began (its motion then:
// from `motions` when given, worked out for every awake body, else from `start`).
void box_of(std::span<const RigidBody> bodies, std::span<const CollisionShape> shapes, std::span<const double> start, double h,
            double g, std::span<const std::uint8_t> asleep, std::span<const RigidMotion> motions, std::size_t b,
            RigidContactScratch& scratch) {
    const double* s = &start[b * rigid::kStateSize];
    // Asleep, P and L are exactly 0: the margin of a body at rest, without its motion.
    const bool still = !asleep.empty() && asleep[b];
    if (bodies[b].fixed) {
        scratch.margins[b] = 0.0;
    } else if (still) {
        scratch.margins[b] = speculative_margin(bodies[b], RigidMotion{}, h, g);
    } else {
        scratch.margins[b] = speculative_margin(bodies[b], motions.empty() ? rigid_motion(bodies[b], s) : motions[b], h, g);
    }
    const Pose pose = pose_of(s);
    if (shapes[b].is_sphere()) {
        scratch.boxes[b] = world_aabb(shapes[b], pose, scratch.margins[b]);
        return;
    }
    RigidContactScratch::HullBox& kept = scratch.hull_boxes[b];
    const auto same_bits = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof(x)) == 0; };
    if (!kept.made || kept.stamp != shapes[b].stamp || !same_bits(kept.pose.x, pose.x) || !same_bits(kept.pose.q, pose.q)) {
        kept = {true, shapes[b].stamp, pose, hull_aabb(shapes[b], pose)};
    }
    scratch.boxes[b] = grown(kept.box, scratch.margins[b]);
}

// The narrow phase over scratch.pairs (a pair of two quiet bodies skipped, and with `was_quiet`
// given, a pair of which either body was not quiet then: it was tested before). The contacts
// are written into `out` from `at` on in the pairs' order (place_chunks), and where they end
// returned; the hull pairs' answers go to the cache, which they replace (`replace_cache`) or join.
std::size_t test_pairs(std::span<const RigidBody> bodies, std::span<const CollisionShape> shapes, std::span<const double> start,
                       const WorldSettings& world, RigidContactScratch& scratch, std::vector<RigidContact>& out, std::size_t at,
                       std::span<const std::uint8_t> was_quiet, bool replace_cache, ThreadPool* pool) {
    const std::size_t most = pool ? 4 * std::size_t(pool->threads()) : 1;
    if (scratch.found.size() < most) {
        scratch.found.resize(most);
        scratch.found_pairs.resize(most);
        scratch.points.resize(most);
        scratch.new_pairs.resize(most);
        scratch.new_points.resize(most);
    }
    const std::size_t chunks = for_chunks(pool, scratch.pairs.size(), kPairGrain, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        ChunkList taken_found(scratch.found[chunk]);
        ChunkList taken_found_pairs(scratch.found_pairs[chunk]);
        ChunkList taken_points(scratch.points[chunk]);
        ChunkList taken_pairs(scratch.new_pairs[chunk]);
        ChunkList taken_new_points(scratch.new_points[chunk]);
        std::vector<RigidContactScratch::FoundPoint>& found = *taken_found;
        std::vector<RigidContactScratch::FoundPair>& found_pairs = *taken_found_pairs;
        std::vector<ContactPoint>& points = *taken_points;
        std::vector<CachedPair>& new_pairs = *taken_pairs;
        std::vector<CachedPoint>& new_points = *taken_new_points;
        auto near = scratch.cache.pairs.cbegin();
        for (std::size_t k = begin; k < end; ++k) {
            const BodyPair& pair = scratch.pairs[k];
            const RigidBody &A = bodies[pair.a], &B = bodies[pair.b];
            if (A.fixed && B.fixed) continue;
            if (scratch.quiet[pair.a] && scratch.quiet[pair.b]) continue;
            if (!was_quiet.empty() && !(was_quiet[pair.a] && was_quiet[pair.b])) continue;
            // The normal points out of b toward a: a moving body is a, so a fixed one is always b.
            std::uint32_t ia = pair.a, ib = pair.b;
            if (A.fixed) std::swap(ia, ib);
            const double* sa = &start[ia * rigid::kStateSize];
            const double* sb = &start[ib * rigid::kStateSize];
            points.clear();
            const double margin = scratch.margins[ia] + scratch.margins[ib];
            if (shapes[ia].is_sphere() || shapes[ib].is_sphere()) {
                collide(shapes[ia], pose_of(sa), shapes[ib], pose_of(sb), margin, points);
            } else {
                collide_hulls_again(scratch, shapes[ia], ia, pose_of(sa), shapes[ib], ib, pose_of(sb), margin, points, new_pairs,
                                    new_points, near);
            }
            if (points.empty()) continue;
            const Vec3d xa{sa[rigid::X], sa[rigid::X + 1], sa[rigid::X + 2]}, xb{sb[rigid::X], sb[rigid::X + 1], sb[rigid::X + 2]};
            const RigidBody &a = bodies[ia], &b = bodies[ib];
            RigidContactScratch::FoundPair& pair_found = found_pairs.emplace_back();
            pair_found.a = ia;
            pair_found.b = ib;
            pair_found.restitution = std::max(a.restitution.value_or(world.restitution), b.restitution.value_or(world.restitution));
            pair_found.friction = std::sqrt(double(a.friction.value_or(world.dynamic_friction)) * b.friction.value_or(world.dynamic_friction));
            pair_found.rolling = std::max(double(a.rolling_resistance) * a.rolling_radius, double(b.rolling_resistance) * b.rolling_radius);
            pair_found.xa = xa;
            pair_found.xb = xb;
            const std::uint32_t pair_at = std::uint32_t(found_pairs.size() - 1);
            for (const ContactPoint& p : points) found.push_back({p.point, p.normal, p.depth, p.feature, pair_at});
        }
    });
    const std::size_t end = place_made(out, at, scratch.found, chunks, pool, [&](const RigidContactScratch::FoundPoint& p, std::size_t chunk) {
        const RigidContactScratch::FoundPair& pair = scratch.found_pairs[chunk][p.pair];
        RigidContact c;
        c.a = pair.a;
        c.b = std::int32_t(pair.b);
        c.restitution = pair.restitution;
        c.friction = pair.friction;
        c.rolling = pair.rolling;
        c.feature = p.feature;
        c.point = p.point;
        c.normal = p.normal;
        c.separation = -p.depth;
        c.depth = p.depth;
        c.arm_a = p.point - pair.xa;
        c.arm_b = p.point - pair.xb;
        return c;
    });
    // This find's answers, by key, for the next (over the last find's, or after them): each
    // pair's first point moved on by the points of the chunks before its own, and by those
    // already in the cache.
    const std::size_t pairs_at = replace_cache ? 0 : scratch.cache.pairs.size();
    const std::size_t points_at = replace_cache ? 0 : scratch.cache.points.size();
    std::vector<std::size_t> points_before(chunks, points_at);
    for (std::size_t chunk = 1; chunk < chunks; ++chunk) points_before[chunk] = points_before[chunk - 1] + scratch.new_points[chunk - 1].size();
    scratch.cache.pairs.resize(place_chunks(scratch.cache.pairs, pairs_at, scratch.new_pairs, chunks, pool,
                                            [&](CachedPair& pair, std::size_t chunk) { pair.first += std::uint32_t(points_before[chunk]); }));
    scratch.cache.points.resize(place_chunks(scratch.cache.points, points_at, scratch.new_points, chunks, pool));
    // (In the pairs' order already, but for a moving body paired with a fixed one of lower
    // index, and for those a wake joins: a few stretches, merged.)
    sort_nearly_sorted(scratch.cache.pairs, [](const CachedPair& x, const CachedPair& y) { return x.key < y.key; });
    return end;
}

}  // namespace

void fetch_hull_ahead(std::span<const CollisionShape> shapes, std::size_t b, std::size_t end) {
    if (b + 8 < end && shapes[b + 8].hull) __builtin_prefetch(shapes[b + 8].hull.get(), 0);
    if (b + 4 < end && shapes[b + 4].hull) fetch_lines(shapes[b + 4].hull->vertices);
}

std::size_t rigid_body_contacts(std::span<const RigidBody> bodies, std::span<const CollisionShape> shapes,
                                std::span<const double> start, const WorldSettings& world, double h, RigidContactScratch& scratch,
                                std::vector<RigidContact>& out, std::size_t at, std::span<const std::uint8_t> asleep,
                                ThreadPool* pool, std::span<const RigidMotion> motions) {
    const std::size_t n = bodies.size();
    if (n < 2) return at;
    const double g = length(Vec3d(world.gravity));
    // Two bodies each asleep or fixed are not paired at all (they are not tested: sleep.h). When
    // every body is, there is nothing to find: a pile or stack asleep costs no broad phase (in
    // stack:10 asleep, its boxes and sweep were 71% of a tick's instructions).
    if (mark_quiet(bodies, asleep, scratch)) {
        scratch.boxes.clear();  // not measured in this find
        scratch.pairs.clear();
        scratch.cache.pairs.clear();  // as a find that tested no pair leaves it
        scratch.cache.points.clear();
        return at;
    }
    scratch.boxes.resize(n);
    scratch.margins.resize(n);
    scratch.hull_boxes.resize(n);
    for_chunks(pool, n, kBoxGrain, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b) {
            fetch_hull_ahead(shapes, b, end);
            box_of(bodies, shapes, start, h, g, asleep, motions, b, scratch);
        }
    });
    overlapping_pairs(scratch.boxes, scratch.pairs, scratch.quiet, pool, &scratch.sweep_order);
    return test_pairs(bodies, shapes, start, world, scratch, out, at, {}, true, pool);
}

void woken_rigid_body_contacts(std::span<const RigidBody> bodies, std::span<const CollisionShape> shapes,
                               std::span<const double> start, const WorldSettings& world, double h, RigidContactScratch& scratch,
                               std::vector<RigidContact>& out, std::span<const std::uint8_t> asleep,
                               std::span<const std::uint8_t> was_asleep, ThreadPool* pool) {
    const std::size_t n = bodies.size();
    if (n < 2) return;
    const double g = length(Vec3d(world.gravity));
    std::vector<std::uint8_t> was_quiet(n);
    std::vector<std::uint32_t> woken;
    for (std::size_t b = 0; b < n; ++b) {
        was_quiet[b] = bodies[b].fixed || was_asleep[b] ? 1 : 0;
        if (was_asleep[b] && !asleep[b]) woken.push_back(std::uint32_t(b));
    }
    if (mark_quiet(bodies, asleep, scratch)) return;
    // A woken body's box is the one it had asleep (its P and L are still 0); the others are as
    // measured in this find, unless it measured none (every body was quiet).
    if (scratch.boxes.size() != n) {
        scratch.boxes.resize(n);
        scratch.margins.resize(n);
        scratch.hull_boxes.resize(n);
        for_chunks(pool, n, kBoxGrain, [&](std::size_t, std::size_t begin, std::size_t end) {
            for (std::size_t b = begin; b < end; ++b) box_of(bodies, shapes, start, h, g, asleep, {}, b, scratch);
        });
    }
    // The same pairs either way; a few woken bodies are tested against every box, more are swept.
    if (woken.size() <= kFewWoken) {
        overlapping_pairs_of(scratch.boxes, woken, scratch.pairs);
    } else {
        overlapping_pairs(scratch.boxes, scratch.pairs, scratch.quiet, pool, &scratch.sweep_order);
    }
    out.resize(test_pairs(bodies, shapes, start, world, scratch, out, out.size(), was_quiet, false, pool));
}

}  // namespace softbody
