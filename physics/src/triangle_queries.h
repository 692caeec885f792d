// Internal to the physics library: geometry of triangles and of surfaces made of them, and the
// points a convex hull puts against them. Pure geometry, beside the other collision queries
// (collide_internal.h, shape_queries.cpp): the point of a triangle nearest a point, a closed
// surface's neighbours and volume, which way is out of it at a point, whether a point is inside
// it. No contact model here: what a soft body does about a point near or inside another's
// surface (the contact distance, the impulses of Eq. 38) is soft_contacts.h's business.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "physics/arrays.h"
#include "physics/convex_hull.h"
#include "physics/vec3.h"

namespace softbody {

// The point of triangle (a, b, c) nearest p, as barycentric weights (each >= 0, sum 1): by the
// region p falls in (a corner, an edge, or the face), each tested with dot products only.
// Inline: the contact search asks it for every particle and triangle in reach, every substep.
inline std::array<float, 3> nearest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return {1.0f, 0.0f, 0.0f};
    const Vec3 bp = p - b;
    const float d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return {0.0f, 1.0f, 0.0f};
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
        const float t = d1 / (d1 - d3);
        return {1.0f - t, t, 0.0f};
    }
    const Vec3 cp = p - c;
    const float d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return {0.0f, 0.0f, 1.0f};
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
        const float t = d2 / (d2 - d6);
        return {1.0f - t, 0.0f, t};
    }
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
        const float t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0.0f, 1.0f - t, t};
    }
    const float sum = va + vb + vc;
    if (!(sum > 0.0f)) return {1.0f / 3.0f, 1.0f / 3.0f, 1.0f / 3.0f};  // a degenerate triangle: its centre
    const float v = vb / sum, w = vc / sum;
    return {1.0f - v - w, v, w};
}

// The distance from p to the nearest point of triangle (a, b, c).
inline float distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const auto w = nearest_on_triangle(p, a, b, c);
    return length(p - (a * w[0] + b * w[1] + c * w[2]));
}

// A surface of triangles on numbered points, with what the queries below need of its shape.
// A closed surface (every edge between exactly two triangles, wound the same way) has an
// inside. `orient` says which way its winding faces: +1 out, -1 in, 0 for no inside worth the
// name (its owner decides when, from its volume: soft_contacts.cpp).
struct TriangleSurface {
    std::vector<std::uint32_t> triangles;  // three points each
    bool closed = false;
    double rest_volume = 0.0;   // six times it, signed by the winding
    float orient = 1.0f;
    std::vector<std::uint32_t> across;     // per triangle and edge (k to k + 1): the triangle on its other side
    std::vector<std::uint32_t> fan_begin;  // per point: its triangles are fan[fan_begin[i]] up to fan_begin[i + 1]
    std::vector<std::uint32_t> fan;
    // Per triangle: which way it faced from the surface's centre at rest (+1 away, -1 toward),
    // and whether it faces the other way now (mark_turned; empty until then).
    std::vector<std::int8_t> rest_facing;
    std::vector<std::uint8_t> turned;
    bool any_turned = false;
};

// Six times the volume the triangles enclose at points x, sum x0 . (x1 x x2): positive when
// a closed surface's winding faces out.
double six_volume(const std::vector<std::uint32_t>& triangles, const Vec3Array& x);

// Whether s.triangles (on `points` points) make a closed surface, which way its winding faces
// at `rest`, and its neighbours: each triangle's across each of its edges, each point's fan of
// triangles. Sets closed, rest_volume, orient, across, fan_begin and fan.
void close_surface(TriangleSurface& s, const Vec3Array& rest, std::size_t points);

// Which triangles of a closed surface face the other way from its centre (the mean of its
// corners) than they did at rest: turned over through their neighbours, as a face of a body
// squeezed hard can be. Their outward direction says nothing about which side is in (inside()).
void mark_turned(TriangleSurface& s, const Vec3Array& x);

// A closed surface's outward direction at the point of triangle `tri` with weights w (not of
// unit length): the face's normal on the face, the two faces' beside an edge, and the faces'
// around a corner weighted by their angles there. Its sign against the way from that nearest
// point to a point says whether the point is inside.
Vec3 outward(const TriangleSurface& s, const Vec3Array& x, std::uint32_t tri, const std::array<float, 3>& w);

// The solid angle the triangles span seen from p (4 pi times the winding number about p, for
// a closed surface wound outward: 4 pi inside, 0 outside, whatever its folds).
double solid_angle(const std::vector<std::uint32_t>& triangles, const Vec3Array& x, const Vec3& p);

// Whether point p, `away` from its nearest point (triangle tri, weights w) of closed surface
// s, is inside it: by outward() where that is clear and no triangle there is turned over
// (mark_turned), else by the winding number.
bool inside(const TriangleSurface& s, const Vec3Array& x, std::uint32_t tri, const std::array<float, 3>& w, const Vec3& p,
            const Vec3& away);

// A hull's points that meet triangles: its vertices, then points along its edges every
// kHullEdgeSpacing at most (a box's edge under a soft face that overhangs it holds the face
// where no vertex is). Point k < vertices is vertex k; past them, edge samples in the hull's
// order.
inline constexpr double kHullEdgeSpacing = 0.1;  // m
inline constexpr std::uint32_t kMostHullEdgeSamples = 32;
std::uint32_t hull_feature_count(const ConvexHull& hull);
Vec3d hull_feature(const ConvexHull& hull, std::uint32_t feature);

}  // namespace softbody
