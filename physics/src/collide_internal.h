// Internal to the physics library: what the narrow phase (collide.cpp), the point and segment
// queries (shape_queries.cpp) and the time of impact (time_of_impact.cpp) share. The queries
// on triangle surfaces (nearest point, inside or out, a hull's points against them) are
// triangle_queries.h's.
#pragma once

#include <cstdint>
#include <limits>

#include "physics/collide.h"
#include "physics/mat3.h"

namespace softbody {

// A rigid transform: p -> R p + x.
struct Transform {
    Mat3 R;
    Vec3d x;
    Vec3d apply(const Vec3d& p) const { return R * p + x; }
};

// Body to world. The quaternion is normalised first, so R is a rotation even when q has
// drifted between the world's renormalisations (the separating axes need unit normals).
inline Transform world_transform(const Pose& pose) { return {pose.q.normalized().to_matrix(), pose.x}; }

// b's body axes seen in a's: p_a = R_a^T (R_b p_b + x_b - x_a).
inline Transform relative_transform(const Transform& a, const Transform& b) {
    const Mat3 Rt = a.R.transposed();
    return {Rt * b.R, Rt * (b.x - a.x)};
}

// The point of a hull nearest to p (all in the hull's axes), and which feature it lies on.
// Inside (or on) the hull: on the face of least penetration, p moved out along its normal.
// When p lies higher than `beyond` above some face's plane, the hull is farther than that from it
// (the distance is at least the height above any face): only that height comes back, as
// `distance`, and the rest is left unset (a sphere out of reach needs no more).
struct NearestOnHull {
    enum class Feature { Face, Edge, Vertex };
    Vec3d point;
    Vec3d normal;           // outward: the face's inside; (p - point) / distance outside
    double distance = 0.0;  // > 0 outside, <= 0 inside (minus the depth)
    Feature feature = Feature::Face;
    std::uint32_t index[2] = {0, 0};  // the face; the edge's two vertices (smaller first); the vertex
};
NearestOnHull nearest_on_hull(const ConvexHull& hull, const Vec3d& p,
                             double beyond = std::numeric_limits<double>::infinity());

}  // namespace softbody
