#include "rigid_contacts.h"

#include <cmath>

#include "ground_contact.h"

namespace softbody {

namespace {
// The least work worth another thread: bodies (a box each), pairs (a narrow-phase test each).
constexpr std::size_t kBodyGrain = 128;
constexpr std::size_t kPairGrain = 32;
}  // namespace

void rigid_body_contacts(std::span<const RigidBody> bodies, std::span<const CollisionShape> shapes,
                         std::span<const double> start, const WorldSettings& world, double h, RigidContactScratch& scratch,
                         std::vector<RigidContact>& out, std::span<const std::uint8_t> asleep, ThreadPool* pool) {
    const std::size_t n = bodies.size();
    if (n < 2) return;
    const double g = length(Vec3d(world.gravity));
    scratch.boxes.resize(n);
    scratch.margins.resize(n);
    for_chunks(pool, n, kBodyGrain, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t b = begin; b < end; ++b) {
            const double* s = &start[b * rigid::kStateSize];
            // Asleep, P and L are exactly 0: the margin of a body at rest, without its motion.
            const bool still = !asleep.empty() && asleep[b];
            scratch.margins[b] = bodies[b].fixed ? 0.0 : speculative_margin(bodies[b], still ? RigidMotion{} : rigid_motion(bodies[b], s), h, g);
            scratch.boxes[b] = world_aabb(shapes[b], pose_of(s), scratch.margins[b]);
        }
    });
    // Two bodies each asleep or fixed are not paired at all (they are not tested: sleep.h).
    scratch.quiet.resize(n);
    for (std::size_t b = 0; b < n; ++b) scratch.quiet[b] = bodies[b].fixed || (!asleep.empty() && asleep[b]) ? 1 : 0;
    overlapping_pairs(scratch.boxes, scratch.pairs, scratch.quiet, pool);
    const std::size_t most = pool ? 4 * std::size_t(pool->threads()) : 1;
    if (scratch.found.size() < most) {
        scratch.found.resize(most);
        scratch.points.resize(most);
    }
    const std::size_t chunks = for_chunks(pool, scratch.pairs.size(), kPairGrain, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        std::vector<RigidContact>& found = scratch.found[chunk];
        std::vector<ContactPoint>& points = scratch.points[chunk];
        found.clear();
        for (std::size_t k = begin; k < end; ++k) {
            const BodyPair& pair = scratch.pairs[k];
            const RigidBody &A = bodies[pair.a], &B = bodies[pair.b];
            if (A.fixed && B.fixed) continue;
            if (!asleep.empty() && (A.fixed || asleep[pair.a]) && (B.fixed || asleep[pair.b])) continue;
            // The normal points out of b toward a: a moving body is a, so a fixed one is always b.
            std::uint32_t ia = pair.a, ib = pair.b;
            if (A.fixed) std::swap(ia, ib);
            const double* sa = &start[ia * rigid::kStateSize];
            const double* sb = &start[ib * rigid::kStateSize];
            points.clear();
            collide(shapes[ia], pose_of(sa), shapes[ib], pose_of(sb), scratch.margins[ia] + scratch.margins[ib], points);
            if (points.empty()) continue;
            const Vec3d xa{sa[rigid::X], sa[rigid::X + 1], sa[rigid::X + 2]}, xb{sb[rigid::X], sb[rigid::X + 1], sb[rigid::X + 2]};
            const RigidBody &a = bodies[ia], &b = bodies[ib];
            RigidContact c;
            c.a = ia;
            c.b = std::int32_t(ib);
            c.restitution = std::max(a.restitution.value_or(world.restitution), b.restitution.value_or(world.restitution));
            c.friction = std::sqrt(double(a.friction.value_or(world.dynamic_friction)) * b.friction.value_or(world.dynamic_friction));
            c.rolling = std::max(double(a.rolling_resistance) * a.rolling_radius, double(b.rolling_resistance) * b.rolling_radius);
            for (const ContactPoint& p : points) {
                c.feature = p.feature;
                c.point = p.point;
                c.normal = p.normal;
                c.separation = -p.depth;
                c.depth = p.depth;
                c.arm_a = p.point - xa;
                c.arm_b = p.point - xb;
                found.push_back(c);
            }
        }
    });
    for (std::size_t chunk = 0; chunk < chunks; ++chunk) out.insert(out.end(), scratch.found[chunk].begin(), scratch.found[chunk].end());
}

}  // namespace softbody
