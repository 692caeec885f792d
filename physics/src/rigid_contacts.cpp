#include "rigid_contacts.h"

#include <cmath>

#include "ground_contact.h"

namespace softbody {

void rigid_body_contacts(std::span<const RigidBody> bodies, std::span<const CollisionShape> shapes,
                         std::span<const double> start, const Params& world, double h, RigidContactScratch& scratch,
                         std::vector<RigidContact>& out, std::span<const std::uint8_t> asleep) {
    const std::size_t n = bodies.size();
    if (n < 2) return;
    const double g = length(Vec3d(world.gravity));
    scratch.boxes.resize(n);
    scratch.margins.resize(n);
    for (std::size_t b = 0; b < n; ++b) {
        const double* s = &start[b * rigid::kStateSize];
        scratch.margins[b] = bodies[b].fixed ? 0.0 : speculative_margin(bodies[b], rigid_motion(bodies[b], s), h, g);
        scratch.boxes[b] = world_aabb(shapes[b], pose_of(s), scratch.margins[b]);
    }
    scratch.pairs.clear();
    overlapping_pairs(scratch.boxes, scratch.pairs);
    for (const BodyPair& pair : scratch.pairs) {
        const RigidBody &A = bodies[pair.a], &B = bodies[pair.b];
        if (A.fixed && B.fixed) continue;
        if (!asleep.empty() && (A.fixed || asleep[pair.a]) && (B.fixed || asleep[pair.b])) continue;
        // The normal points out of b toward a: a moving body is a, so a fixed one is always b.
        std::uint32_t ia = pair.a, ib = pair.b;
        if (A.fixed) std::swap(ia, ib);
        const double* sa = &start[ia * rigid::kStateSize];
        const double* sb = &start[ib * rigid::kStateSize];
        scratch.points.clear();
        collide(shapes[ia], pose_of(sa), shapes[ib], pose_of(sb), scratch.margins[ia] + scratch.margins[ib], scratch.points);
        if (scratch.points.empty()) continue;
        const RigidMotion ma = rigid_motion(bodies[ia], sa), mb = rigid_motion(bodies[ib], sb);
        const RigidBody &a = bodies[ia], &b = bodies[ib];
        RigidContact c;
        c.a = ia;
        c.b = std::int32_t(ib);
        c.restitution = std::max(a.restitution.value_or(world.restitution), b.restitution.value_or(world.restitution));
        c.friction = std::sqrt(double(a.friction.value_or(world.dynamic_friction)) * b.friction.value_or(world.dynamic_friction));
        for (const ContactPoint& p : scratch.points) {
            c.feature = p.feature;
            c.point = p.point;
            c.normal = p.normal;
            c.separation = -p.depth;
            c.depth = p.depth;
            c.arm_a = p.point - ma.x;
            c.arm_b = p.point - mb.x;
            out.push_back(c);
        }
    }
}

}  // namespace softbody
