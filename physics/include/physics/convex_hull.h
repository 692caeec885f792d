// Convex hulls of point sets (a mesh's vertices, say), for rigid-body collision shapes and their
// mass properties. The hull itself is Qhull's; this adds a vertex budget, merged polygon faces,
// a canonical order, and errors that name the problem.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "physics/vec3.h"

namespace softbody {

// A collision hull's budget of vertices. A contact test walks the hull (support points along a
// direction, clipping against its faces) every tick for every touching pair, so its cost grows
// with the vertex count; 64 well-chosen vertices keep a curved body within a few per cent of its
// size (the 64-vertex hull of a densely sampled sphere is nowhere more than about 6% of the
// radius inside it) while the walk stays short.
inline constexpr std::size_t kMaxHullVertices = 64;

struct ConvexHull {
    std::vector<Vec3d> vertices;  // in the input's order (each one of the input points)
    struct Face {
        Vec3d normal;                         // unit, outward
        double offset = 0.0;                  // plane: dot(normal, x) = offset
        std::vector<std::uint32_t> vertices;  // counter-clockwise seen from outside; coplanar facets merged into one polygon
    };
    std::vector<Face> faces;
    std::vector<std::array<std::uint32_t, 2>> edges;  // unique, first < second

    // The faces as outward triangle fans (from each face's first vertex).
    std::vector<std::array<std::uint32_t, 3>> triangles() const;
    // The vertex farthest along direction (the first such, on a tie).
    Vec3d support(const Vec3d& direction) const;
};

// The convex hull of `points`, with at most `max_vertices` vertices (at least 4). When the full
// hull has more, a well-spread subset of its vertices is hulled instead: from a spanning
// tetrahedron, the vertex farthest outside the hull of those chosen so far is added, again and
// again, until the budget is spent. That hull lies inside the full one, and close to it.
//
// Facets closer to coplanar than a tolerance are merged into one polygon (a box whose corners
// were stored in float, say, keeps six faces), and points on an edge or a face are not
// vertices. The tolerance is 1e-6 of the larger of the points' bounding-box diagonal and their
// largest coordinate. Merges add up, so a merged face's corners, and any point, can lie off its
// plane by a few tolerances (under 3 in tests); otherwise every point lies under every face
// plane, unless the budget left it outside. Deterministic: the same points give the same hull,
// in the same order.
//
// Throws InputError with one line when the points span no volume (fewer than 4, all one point,
// or all within 100 tolerances of one line or one plane), when a coordinate is not finite, or
// when Qhull cannot build a hull from them; std::runtime_error (one line) for an internal failure.
ConvexHull convex_hull(std::span<const Vec3d> points, std::size_t max_vertices = kMaxHullVertices);

}  // namespace softbody
