// The geometry of collisions between rigid bodies, and between a rigid body and a soft body's
// particle: where two shapes touch, along which normal and how deep. What to do about it (the
// impulses of Eq. 37 and 38) is the contact solver's business, and which pairs to ask about is
// the broad phase's (broad_phase.h).
//
// Every shape collides as a convex one: a sphere by its radius, everything else by its convex
// hull (a box's 8 corners, a cylinder's 32-sided prism, a mesh's hull of at most 64 vertices).
// Two hulls are tested by separating axes (the faces of each, and the cross products of the edge
// pairs that make faces of their Minkowski difference); a face contact is clipped to a manifold
// of up to four points, an edge contact is one point (see collide.cpp). Everything is in double.
//
// Pairs closer than a margin but not yet touching give speculative contacts: a negative depth
// (the gap) along the normal of the separating axis, which the solver lets close in one step and
// no further. A margin about the pair's relative motion in a step stops a fast thin body from
// passing through another between two steps.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "physics/convex_hull.h"
#include "physics/mat3.h"
#include "physics/quat.h"
#include "physics/rigid_body.h"
#include "physics/vec3.h"

namespace softbody {

// Where a body is: its centre of mass x and its orientation q (unit; body to world):
// p_world = x + R(q) p_body.
struct Pose {
    Vec3d x;
    Quat q;
};

// A body's pose from its thirteen numbers in the world's flat state (Listing 10's layout).
Pose pose_of(const double* state);

// The pose a fraction t of the way from p0 to p1: x linear, q along the shorter arc (nlerp).
Pose interpolate(const Pose& p0, const Pose& p1, double t);

// A hull's edge with the two faces that meet there: faces[0] runs from vertices[0] to
// vertices[1] as it turns counter-clockwise about its outward normal, faces[1] the other way.
struct HullEdge {
    std::array<std::uint32_t, 2> vertices{};
    std::array<std::uint32_t, 2> faces{};
};

// How far a body may turn between two finds of its contacts, rad (World::contact_intervals).
// Contacts found where a hull was stay those of the right faces, edges and corners until it has
// turned about half the way from one face to its neighbour: half the least angle between the
// normals of two faces that share an edge, but no less than kLeastContactTurn (a hull of many
// faces, a cylinder's 32 sides 0.196 rad apart) and no more than kMostContactTurn (the normal a
// contact keeps within its interval stays within 0.2 rad of the turning face's: a box's faces
// are pi/2 apart). Measured: with the 32-sided cylinder rolling on its side at 2.2 m/s allowed
// 0.2 rad, it went 0.26 mm into the ground under explicit Euler (0.23 with 0.1), past half the
// loaded slop; with boxes allowed 0.2, every pile, stack and random scene keeps its bounds, and
// bin:1000 takes a fifth less time (boxes tumbling as they land need fewer finds).
inline constexpr double kLeastContactTurn = 0.1;
inline constexpr double kMostContactTurn = 0.2;

// A body's collision shape: a sphere (radius, no hull) or a convex hull, in body axes about the
// centre of mass. Built once per body and kept beside it, as its topology: the separating-axis
// test needs each edge's two faces, which ConvexHull does not store and which would cost more to
// find on every test than the test itself.
struct CollisionShape {
    double radius = 0.0;                     // a sphere's, m
    std::shared_ptr<const ConvexHull> hull;  // or a hull (null for a sphere)
    std::vector<HullEdge> edges;             // the hull's edges in its own order, with their faces
    double bounding_radius = 0.0;            // the farthest point from the centre of mass, m
    std::uint64_t stamp = 0;                 // from its geometry's bits: equal stamps, the same shape
    double contact_turn = kLeastContactTurn;  // rad, how far it may turn between two finds (above)

    bool is_sphere() const { return hull == nullptr; }
};

CollisionShape sphere_shape(double radius);
// Throws std::invalid_argument (one line) when the hull is not a closed polyhedron: an edge
// not shared by exactly two faces, in opposite directions.
CollisionShape hull_shape(std::shared_ptr<const ConvexHull> hull);
// A sphere's radius, or the hull the body was made with (box, cylinder, mesh).
CollisionShape collision_shape(const RigidBody& body);

// One point of contact between bodies a and b.
struct ContactPoint {
    Vec3d point;               // world, m: midway between the two surfaces
    Vec3d normal;              // unit, out of b toward a
    double depth = 0.0;        // m along the normal: > 0 overlapping, < 0 a gap (speculative)
    std::uint32_t feature = 0; // which features of a and b made it: the same while the same
                               // features touch, different for different ones within a pair
                               // (for warm starting; see collide.cpp for the packing)
};

// The narrow phase's last answer for each pair of hulls it tested (rigid_contacts.h), kept with
// the world's state (a snapshot holds it): each point as its two surface points, each in its own
// body's axes, and the normal in b's.
struct CachedPoint {
    Vec3d on_a, on_b, normal_b;
    std::uint32_t feature = 0;
};
struct CachedPair {
    std::uint64_t key = 0;  // a << 32 | b (body indices), a the moving body (the normal points out of b)
    std::uint64_t stamp_a = 0, stamp_b = 0;  // the two shapes' stamps
    Mat3 R;                 // b's axes in a's when the answer was found
    Vec3d x;                // b's centre in a's axes then
    double margin = 0.0;
    std::uint32_t first = 0, count = 0;  // its points in PairCache::points
};
struct PairCache {
    std::vector<CachedPair> pairs;  // by key
    std::vector<CachedPoint> points;
};

// Appends the contacts between a at pose pa and b at pose pb: nothing when they are farther
// apart than `margin` (m, >= 0); otherwise one point (sphere-sphere, sphere-hull, edge-edge)
// or a face manifold of up to four. Every point appended shares the one normal.
void collide(const CollisionShape& a, const Pose& pa, const CollisionShape& b, const Pose& pb, double margin,
             std::vector<ContactPoint>& out);

// A lower bound on the distance between a and b (m); when they overlap, minus the depth of
// the shallowest way apart along the axes the test tries (for two hulls, the exact penetration
// depth). Exact for spheres, and for hulls whose closest features are a face and a point or
// two edges; for two corners, the separating-axis test sees less than the gap (two cubes corner
// to corner along their diagonal give 1/sqrt(3) of it).
double separation_bound(const CollisionShape& a, const Pose& pa, const CollisionShape& b, const Pose& pb);

// A point p (a soft body's particle) against a shape: the nearest point of its surface, the
// outward normal there, and the depth (> 0 inside; < 0 outside, minus the distance). Empty when
// p is outside by more than `margin`. Inside a hull, the nearest surface point is on the face
// of least penetration and the normal is that face's: a particle inside goes out along it.
struct SurfacePoint {
    Vec3d point;
    Vec3d normal;
    double depth = 0.0;
};
std::optional<SurfacePoint> point_contact(const CollisionShape& shape, const Pose& pose, const Vec3d& p,
                                          double margin);

// The height of the shape's lowest point at `pose` (m): its support point along -z. A sphere's
// centre less its radius; a hull's lowest vertex as the pose turns and places it (a convex
// hull's lowest point is always one of its vertices). What the world reports as min_z.
double lowest_z(const CollisionShape& shape, const Pose& pose);

// Where the segment p0 -> p1 first enters the shape: p0 + t (p1 - p0) with t in [0, 1], the
// surface's outward normal there. Empty when it misses, and when p0 is already inside (no
// entry: point_contact is the question then). A segment that starts on the surface and goes in
// enters at t = 0.
struct SegmentHit {
    double t = 0.0;
    Vec3d point;
    Vec3d normal;
};
std::optional<SegmentHit> segment_cast(const CollisionShape& shape, const Pose& pose, const Vec3d& p0,
                                       const Vec3d& p1);

// The first time in a step that a and b come within `tolerance` of each other, by conservative
// advancement: each body moves from pose 0 (t = 0) to pose 1 (t = 1), x linearly and q along the
// shorter arc; at each t, separation_bound's distance d is one no point can close faster than
// speed, the bound on how fast any point of one body moves toward the other (relative linear
// motion plus each body's angular rate times its bounding radius), so t may advance by
// (d - tolerance / 2) / speed without the bodies having touched. Stops when d <= tolerance.
//   Touching:  d <= tolerance at t (t = 0 when they start that close, or overlapping).
//   Separate:  they stay farther apart than tolerance up to t = 1 (t is then 1).
//   Stalled:   max_iterations advances did not get there (slow closing on a large rotation
//              bound, or a bound far below the true distance, as corner to corner); t is still
//              safe: they have not touched before it.
// Limits: the rotation bound is for the whole step (its fastest moment), and the distance is
// the separating-axis bound, not the true distance, so steps are short when bodies spin fast or
// meet corner to corner; tunnelling is ruled out only up to the tolerance's loss of t.
struct TimeOfImpact {
    enum class Outcome { Touching, Separate, Stalled };
    Outcome outcome = Outcome::Separate;
    double t = 1.0;
    double separation = 0.0;  // separation_bound at t, m
    int iterations = 0;
};
TimeOfImpact time_of_impact(const CollisionShape& a, const Pose& a0, const Pose& a1, const CollisionShape& b,
                            const Pose& b0, const Pose& b1, double tolerance, int max_iterations = 64);

}  // namespace softbody
