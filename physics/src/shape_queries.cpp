// A point or a segment against one shape (collide.h): for soft bodies' particles, and the nearest
// point of a hull, which the narrow phase's sphere tests share.
#include <algorithm>
#include <cmath>
#include <limits>

#include "collide_internal.h"
#include "physics/collide.h"

namespace softbody {

// Outside the hull, the nearest point lies on a face whose plane p is above: on the face itself
// when p's projection falls inside its polygon, else on the side (or corner) of the polygon
// nearest to p. Every face p is above is tried and the nearest point kept: a few dozen small
// polygons at most, for a 64-vertex hull. Inside, the nearest surface point is p's projection
// onto the nearest face plane, which lies on that face: for any other face j, moving p by the
// least depth t along n_i raises n_j . p by at most t, which is not more than its own depth.
NearestOnHull nearest_on_hull(const ConvexHull& hull, const Vec3d& p, double beyond) {
    NearestOnHull out;
    double highest = -std::numeric_limits<double>::infinity();
    std::size_t top = 0;
    for (std::size_t f = 0; f < hull.faces.size(); ++f) {
        const double above = dot(hull.faces[f].normal, p) - hull.faces[f].offset;
        if (above > highest) {
            highest = above;
            top = f;
        }
    }
    if (highest > beyond) {
        out.distance = highest;
        return out;
    }
    if (highest <= 0.0) {
        const Vec3d n = hull.faces[top].normal;
        out.point = p - n * highest;
        out.normal = n;
        out.distance = highest;
        out.feature = NearestOnHull::Feature::Face;
        out.index[0] = std::uint32_t(top);
        return out;
    }
    double best = std::numeric_limits<double>::infinity();  // squared distance
    for (std::size_t f = 0; f < hull.faces.size(); ++f) {
        const ConvexHull::Face& face = hull.faces[f];
        const double above = dot(face.normal, p) - face.offset;
        if (!(above > 0.0)) continue;
        const std::vector<std::uint32_t>& loop = face.vertices;
        bool over_face = true;
        for (std::size_t k = 0; k < loop.size(); ++k) {
            const std::uint32_t i = loop[k], j = loop[(k + 1) % loop.size()];
            const Vec3d v0 = hull.vertices[i], e = hull.vertices[j] - v0;
            if (dot(cross(e, face.normal), p - v0) <= 0.0) continue;  // inside this side
            over_face = false;
            const double t = std::clamp(dot(p - v0, e) / dot(e, e), 0.0, 1.0);
            const Vec3d q = v0 + e * t;
            const double d2 = dot(p - q, p - q);
            if (d2 < best) {
                best = d2;
                out.point = q;
                if (t <= 0.0 || t >= 1.0) {
                    out.feature = NearestOnHull::Feature::Vertex;
                    out.index[0] = t <= 0.0 ? i : j;
                    out.index[1] = 0;
                } else {
                    out.feature = NearestOnHull::Feature::Edge;
                    out.index[0] = std::min(i, j);
                    out.index[1] = std::max(i, j);
                }
            }
        }
        if (over_face && above * above < best) {
            best = above * above;
            out.point = p - face.normal * above;
            out.feature = NearestOnHull::Feature::Face;
            out.index[0] = std::uint32_t(f);
            out.index[1] = 0;
        }
    }
    out.distance = std::sqrt(best);
    out.normal = (p - out.point) / out.distance;  // distance >= highest > 0
    return out;
}

double lowest_z(const CollisionShape& shape, const Pose& pose) {
    if (shape.is_sphere()) return pose.x.z - shape.radius;
    // Only the height of each turned vertex is needed: the bottom row of R times v.
    const Mat3 R = pose.q.to_matrix();
    double lowest = std::numeric_limits<double>::infinity();
    for (const Vec3d& v : shape.hull->vertices) lowest = std::min(lowest, (R * v).z);
    return pose.x.z + lowest;
}

std::optional<SurfacePoint> point_contact(const CollisionShape& shape, const Pose& pose, const Vec3d& p,
                                          double margin) {
    if (shape.is_sphere()) {
        const Vec3d d = p - pose.x;
        const double distance = length(d);
        if (distance - shape.radius > margin) return std::nullopt;
        const Vec3d n = distance > 0.0 ? d / distance : Vec3d{0.0, 0.0, 1.0};  // at the centre: any way out
        return SurfacePoint{pose.x + n * shape.radius, n, shape.radius - distance};
    }
    const Transform T = world_transform(pose);
    const NearestOnHull q = nearest_on_hull(*shape.hull, T.R.transposed() * (p - T.x));
    if (q.distance > margin) return std::nullopt;
    return SurfacePoint{T.apply(q.point), T.R * q.normal, -q.distance};
}

// A hull: the segment is clipped by every face's half-space (p0 + t d is inside face f while
// n . (p0 + t d) <= offset). It enters at the largest t where it crosses into a half-space, and
// leaves at the smallest t where it crosses out of one; it hits when it enters before it leaves,
// within [0, 1]. A sphere: the smaller root of |p0 + t d - c| = r.
std::optional<SegmentHit> segment_cast(const CollisionShape& shape, const Pose& pose, const Vec3d& p0,
                                       const Vec3d& p1) {
    if (shape.is_sphere()) {
        const Vec3d d = p1 - p0, m = p0 - pose.x;
        const double c = dot(m, m) - shape.radius * shape.radius;
        if (c < 0.0) return std::nullopt;  // starts inside
        const double b = dot(m, d);        // half the linear coefficient
        const double a = dot(d, d);
        if (b >= 0.0 || a == 0.0) return std::nullopt;  // moving away, or not moving
        const double disc = b * b - a * c;
        if (disc < 0.0) return std::nullopt;
        const double t = c / (-b + std::sqrt(disc));  // (-b - sqrt(disc)) / a, without cancellation
        if (t > 1.0) return std::nullopt;
        const Vec3d at = p0 + d * t;
        return SegmentHit{t, at, normalize(at - pose.x)};
    }
    const Transform T = world_transform(pose);
    const Mat3 Rt = T.R.transposed();
    const Vec3d a = Rt * (p0 - T.x), d = Rt * (p1 - p0);
    double enter = -std::numeric_limits<double>::infinity(), leave = std::numeric_limits<double>::infinity();
    std::size_t entry_face = 0;
    for (std::size_t f = 0; f < shape.hull->faces.size(); ++f) {
        const ConvexHull::Face& face = shape.hull->faces[f];
        const double gap = face.offset - dot(face.normal, a);  // > 0: p0 inside this face's half-space
        const double rate = dot(face.normal, d);
        if (rate == 0.0) {
            if (gap < 0.0) return std::nullopt;  // parallel, outside
            continue;
        }
        const double t = gap / rate;
        if (rate < 0.0) {
            if (t > enter) {
                enter = t;
                entry_face = f;
            }
        } else {
            leave = std::min(leave, t);
        }
        if (enter > leave) return std::nullopt;
    }
    if (!(enter >= 0.0) || enter > 1.0 || enter > leave) return std::nullopt;  // starts inside, or misses
    return SegmentHit{enter, p0 + (p1 - p0) * enter, T.R * shape.hull->faces[entry_face].normal};
}

}  // namespace softbody
