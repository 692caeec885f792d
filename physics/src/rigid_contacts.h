// Internal to the physics library: the contacts between rigid bodies for one tick, found where
// the bodies were when the tick began (broad phase, then narrow phase), as RigidContacts for the
// solver (contact_solver.h).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "physics/broad_phase.h"
#include "physics/collide.h"
#include "physics/contact.h"
#include "physics/defs.h"
#include "physics/rigid_body.h"
#include "physics/thread_pool.h"

namespace softbody {

// Every pair's contacts: each pair's boxes grown by their bodies' speculative margins
// (ground_contact.h), overlapping pairs (two fixed bodies skipped) tested by `collide` within
// the sum of the two margins. Restitution is the larger of the two bodies' (the bouncier one decides),
// friction the geometric mean sqrt(mu_a mu_b); each defaults to the world's. `start`: the flat
// state when the tick began, `h` the tick; `scratch` keeps its allocations from step to step.
// Bodies marked in `asleep` (empty: none) are in the broad phase, but a pair of two that are
// each asleep or fixed is not tested (sleep.h). The pairs are tested on `pool`'s threads, in
// chunks joined in the pairs' order: the same list at any thread count.
//
// Two hulls whose relative pose is within kReuseMove and kReuseTurn of where their points were
// last found, with the same shapes and no wider margin, are not tested again: their last points
// are carried along with the two bodies (each point's depth measured again along the normal
// that turned with b). A resting stack's bodies move micrometres a tick relative to each other;
// the separating-axis test of every pair, every tick, was a fifth of its time. Whether a pair
// is tested depends on that pair alone: the same at any thread count.
struct RigidContactScratch {
    std::vector<Aabb> boxes;
    // Each hull's box before its margin, with what it was made from (the shape's stamp and the
    // pose): made again from the same bits it would be the same box, so it is kept (a sleeping
    // body's, find after find; the margin, which changes with the part of the tick left, is
    // added after).
    struct HullBox {
        bool made = false;
        std::uint64_t stamp = 0;
        Pose pose;
        Aabb box;
    };
    std::vector<HullBox> hull_boxes;
    std::vector<double> margins;
    std::vector<BodyPair> pairs;
    std::vector<std::uint8_t> quiet;               // asleep or fixed: not paired with one another
    SweepOrder sweep_order;                        // the broad phase's last order (only a hint)
    std::vector<std::vector<ContactPoint>> points;  // per chunk of work (for_chunks)
    // The narrow phase's answers, per chunk, joined in order: each point with the pair it is of
    // (in the chunk's found_pairs), made into a RigidContact where it is placed.
    struct FoundPoint {
        Vec3d point, normal;
        double depth = 0.0;
        std::uint32_t feature = 0, pair = 0;
    };
    struct FoundPair {
        std::uint32_t a = 0, b = 0;  // as RigidContact's
        double restitution = 0.0, friction = 0.0, rolling = 0.0;
        Vec3d xa, xb;  // the two centres
    };
    std::vector<std::vector<FoundPoint>> found;
    std::vector<std::vector<FoundPair>> found_pairs;
    std::vector<std::vector<RigidContact>> ground;  // the same for the ground's (World::generate_contacts)
    std::vector<RigidContact> merged;               // a find's list with the woken bodies' (World::add_woken_contacts)
    PairCache cache;  // the pairs of hulls tested in the last find (world state: in a snapshot)
    std::vector<std::vector<CachedPair>> new_pairs;          // per chunk, joined in order
    std::vector<std::vector<CachedPoint>> new_points;        // per chunk
};
// Each body's hull is its own (a pile's boxes differ in size), out of the cache in a large pile,
// and reached through two pointers: a loop over the bodies in order that reads their hulls'
// vertices asks, at body b, for the hull of the body 8 ahead and for the first vertices of the
// one 4 ahead (whose hull it asked for 4 bodies before). A hint only: the same bits.
void fetch_hull_ahead(std::span<const CollisionShape> shapes, std::size_t b, std::size_t end);

// They are written into `out` from `at` on, over what it holds there (a list kept from tick to
// tick), growing it where it is short (place_chunks): the caller cuts it to the returned end.
std::size_t rigid_body_contacts(std::span<const RigidBody> bodies, std::span<const CollisionShape> shapes,
                                std::span<const double> start, const WorldSettings& world, double h, RigidContactScratch& scratch,
                                std::vector<RigidContact>& out, std::size_t at, std::span<const std::uint8_t> asleep = {},
                                ThreadPool* pool = nullptr, std::span<const RigidMotion> motions = {});

// After rigid_body_contacts in the same find, when bodies that were asleep (`was_asleep`) have
// woken (`asleep` now): appends the contacts of the pairs that find did not test, those of two
// bodies each asleep or fixed then and not both now, in the pairs' order; their hulls' answers
// join the cache. The pairs it tested keep their contacts: nothing of them has changed.
void woken_rigid_body_contacts(std::span<const RigidBody> bodies, std::span<const CollisionShape> shapes,
                               std::span<const double> start, const WorldSettings& world, double h, RigidContactScratch& scratch,
                               std::vector<RigidContact>& out, std::span<const std::uint8_t> asleep,
                               std::span<const std::uint8_t> was_asleep, ThreadPool* pool = nullptr);

}  // namespace softbody
