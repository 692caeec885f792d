// The broad phase: which pairs of bodies are near enough to be worth the narrow phase
// (collide.h). Each body is boxed by its world axis-aligned bounding box, fattened by a margin;
// the boxes are cut into strips across a second axis, and each strip's are sorted along the
// first and swept (sort and sweep), so only boxes near each other on two axes are compared.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "physics/collide.h"
#include "physics/thread_pool.h"
#include "physics/vec3.h"

namespace softbody {

struct Aabb {
    Vec3d lo, hi;
    // Boxes that touch overlap (closed intervals on each axis).
    bool overlaps(const Aabb& o) const {
        return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y && lo.z <= o.hi.z && o.lo.z <= hi.z;
    }
};

// The shape's box at the pose, grown by `margin` on every side: a hull's from its vertices
// under the pose (exact), a sphere's from its radius.
Aabb world_aabb(const CollisionShape& shape, const Pose& pose, double margin);
// A hull's box at the pose, not grown; and a box grown by `margin` on every side (world_aabb
// of a hull is the two, to the bit).
Aabb hull_aabb(const CollisionShape& hull, const Pose& pose);
Aabb grown(const Aabb& box, double margin);

// Two bodies by their indices, a < b.
struct BodyPair {
    std::uint32_t a = 0, b = 0;
    bool operator==(const BodyPair&) const = default;
    auto operator<=>(const BodyPair&) const = default;
};

// The order a sweep left the boxes in along its axis, for the next to start its sort from: a
// pile moves little between two finds, so its boxes come nearly in order, and a sort by
// insertion from there moves each a place or two where a sort from nothing compares n log n
// times. Only a hint: the pairs are the same whatever it holds (or none).
struct SweepOrder {
    int axis = -1;
    std::vector<std::uint32_t> boxes;  // indices, by their start on `axis`
    std::vector<std::uint8_t> named;   // (scratch: which boxes it names)
};

// Every pair of overlapping boxes, written into `out` (cleared first), in increasing order of
// (a, b): the same pairs in the same order on every run and machine, whatever the sort did.
// The sweep runs along the axis on which the boxes' centres spread most (a pile is tall, a row
// is long), so a stack of hundreds sharing one x range is still swept cheaply; the strips are
// across the axis they spread most on after it, each about two boxes wide (on average), so a
// pile spread over a floor is not swept as one long row: a box meets the few of its strips
// that it overlaps on the sweep axis, not every box of the floor's width that does. A huge box
// (a fixed ramp, the floor) is in every strip it reaches, and costs one pass over the boxes
// that start within it in each. A box with a coordinate that is not a number overlaps nothing.
// Cost: O(n log n) for the sort (about O(n) from the last order, when `last` holds it) plus
// O(n k) for the sweep, k the boxes of its strips overlapping one on the sweep axis.
// `quiet` (empty: none): boxes so marked (bodies asleep or fixed) are not paired with one another.
// With a `pool`, the sweep runs on its threads in chunks of boxes (the pairs sorted all the same).
// With `order`, the sort starts from the order it holds, and it is left holding this sweep's.
void overlapping_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out, std::span<const std::uint8_t> quiet = {},
                       ThreadPool* pool = nullptr, SweepOrder* order = nullptr);

// The pairs of overlapping boxes of which at least one is among `some` (indices into boxes),
// written into `out` (cleared first) in increasing order of (a, b), as overlapping_pairs gives
// them: each of `some` against every box, O(|some| n). For a few boxes among many (bodies just
// woken in a pile) instead of sorting them all again. A box that is not finite overlaps nothing.
void overlapping_pairs_of(std::span<const Aabb> boxes, std::span<const std::uint32_t> some, std::vector<BodyPair>& out);

}  // namespace softbody
