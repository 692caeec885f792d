// Geometry of triangle surfaces and the points a hull puts against them (triangle_queries.h):
// a closed surface's neighbours and volume, its outward direction at a point, the winding
// number, and a hull's vertices and edge samples. Pure geometry; the soft contacts use it.
#include "triangle_queries.h"

#include <algorithm>
#include <cmath>

namespace softbody {

double six_volume(const std::vector<std::uint32_t>& triangles, const Vec3Array& x) {
    double volume = 0.0;
    for (std::size_t t = 0; t < triangles.size(); t += 3) {
        const Vec3d x0(x[triangles[t]]), x1(x[triangles[t + 1]]), x2(x[triangles[t + 2]]);
        volume += dot(x0, cross(x1, x2));
    }
    return volume;
}

// Closed: every edge is shared by exactly two triangles that run along it in opposite
// directions (wound alike). Found by sorting the edges by their two ends: a closed surface's
// come in pairs, one each way.
namespace {

// Each triangle's facing from the surface's centre (the mean of its corners) at points x: the
// sign of its normal along the way from the centre to its middle.
void facing(const TriangleSurface& s, const Vec3Array& x, std::vector<std::int8_t>& out) {
    Vec3d centre;
    for (const std::uint32_t v : s.triangles) centre += Vec3d(x[v]);
    centre = centre / double(s.triangles.size());
    for (std::size_t t = 0; t < out.size(); ++t) {
        const std::uint32_t* v = &s.triangles[3 * t];
        const Vec3d a(x[v[0]]), b(x[v[1]]), c(x[v[2]]);
        const double side = dot(cross(b - a, c - a), (a + b + c) / 3.0 - centre);
        out[t] = side > 0.0 ? 1 : side < 0.0 ? -1 : 0;
    }
}

}  // namespace

void close_surface(TriangleSurface& s, const Vec3Array& rest, std::size_t points) {
    const std::size_t count = s.triangles.size() / 3;
    s.closed = false;
    s.across.assign(s.triangles.size(), 0);
    s.fan_begin.assign(points + 1, 0);
    s.fan.clear();
    if (count == 0) return;
    struct Edge {
        std::uint32_t lo, hi, at;  // at: 3 tri + k, the edge from corner k to k + 1
        bool forward;              // lo to hi
    };
    std::vector<Edge> edges;
    edges.reserve(s.triangles.size());
    for (std::uint32_t at = 0; at < s.triangles.size(); ++at) {
        const std::uint32_t u = s.triangles[at], v = s.triangles[at - at % 3 + (at % 3 + 1) % 3];
        edges.push_back({std::min(u, v), std::max(u, v), at, u < v});
    }
    std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
        return x.lo < y.lo || (x.lo == y.lo && (x.hi < y.hi || (x.hi == y.hi && x.at < y.at)));
    });
    bool closed = edges.size() % 2 == 0;
    for (std::size_t k = 0; closed && k < edges.size(); k += 2) {
        const Edge &e = edges[k], &f = edges[k + 1];
        closed = e.lo == f.lo && e.hi == f.hi && e.forward != f.forward &&
                 (k + 2 == edges.size() || edges[k + 2].lo != e.lo || edges[k + 2].hi != e.hi);
        if (closed) {
            s.across[e.at] = f.at / 3;
            s.across[f.at] = e.at / 3;
        }
    }
    if (!closed) return;
    s.closed = true;
    // The volume at rest: positive when the winding faces out.
    const double volume = six_volume(s.triangles, rest);
    s.rest_volume = volume;
    s.orient = volume < 0.0 ? -1.0f : 1.0f;
    for (const std::uint32_t v : s.triangles) ++s.fan_begin[v + 1];
    for (std::size_t i = 0; i < points; ++i) s.fan_begin[i + 1] += s.fan_begin[i];
    s.fan.assign(s.triangles.size(), 0);
    std::vector<std::uint32_t> filled(s.fan_begin.begin(), s.fan_begin.end() - 1);
    for (std::uint32_t at = 0; at < s.triangles.size(); ++at) s.fan[filled[s.triangles[at]]++] = at / 3;
    s.rest_facing.resize(count);
    facing(s, rest, s.rest_facing);
    s.turned.assign(count, 0);
    s.any_turned = false;
}

void mark_turned(TriangleSurface& s, const Vec3Array& x) {
    if (!s.closed) return;
    std::vector<std::int8_t> now(s.rest_facing.size());
    facing(s, x, now);
    s.any_turned = false;
    for (std::size_t t = 0; t < now.size(); ++t) {
        s.turned[t] = s.rest_facing[t] != 0 && now[t] != s.rest_facing[t];
        s.any_turned = s.any_turned || s.turned[t];
    }
}

Vec3 outward(const TriangleSurface& s, const Vec3Array& x, std::uint32_t tri, const std::array<float, 3>& w) {
    const auto normal = [&](std::uint32_t t) {
        const std::uint32_t* v = &s.triangles[3 * t];
        const Vec3 n = cross(x[v[1]] - x[v[0]], x[v[2]] - x[v[0]]);
        const float l = length(n);
        return l > 0.0f ? n / l : Vec3{};
    };
    const int zeros = (w[0] == 0.0f) + (w[1] == 0.0f) + (w[2] == 0.0f);
    Vec3 n;
    if (zeros == 0) {
        n = normal(tri);
    } else if (zeros == 1) {
        // On the edge opposite the corner of weight 0: the edge from corner k + 1 to k + 2.
        const std::uint32_t k = w[0] == 0.0f ? 0 : w[1] == 0.0f ? 1 : 2;
        n = normal(tri) + normal(s.across[3 * tri + (k + 1) % 3]);
    } else {
        // At a corner: every triangle around it, by its angle there (a corner's normal that
        // says inside from outside whatever the fan's triangles are like).
        const std::uint32_t corner = s.triangles[3 * tri + (w[0] != 0.0f ? 0 : w[1] != 0.0f ? 1 : 2)];
        for (std::uint32_t f = s.fan_begin[corner]; f < s.fan_begin[corner + 1]; ++f) {
            const std::uint32_t t = s.fan[f];
            const std::uint32_t* v = &s.triangles[3 * t];
            const std::uint32_t k = v[0] == corner ? 0 : v[1] == corner ? 1 : 2;
            const Vec3 e1 = x[v[(k + 1) % 3]] - x[corner], e2 = x[v[(k + 2) % 3]] - x[corner];
            const float l1 = length(e1), l2 = length(e2);
            if (!(l1 > 0.0f && l2 > 0.0f)) continue;
            const float angle = std::acos(std::clamp(dot(e1, e2) / (l1 * l2), -1.0f, 1.0f));
            n += normal(t) * angle;
        }
    }
    return n * s.orient;
}

double solid_angle(const std::vector<std::uint32_t>& triangles, const Vec3Array& x, const Vec3& p) {
    double solid = 0.0;
    for (std::size_t t = 0; t < triangles.size(); t += 3) {
        const Vec3 a = x[triangles[t]] - p, b = x[triangles[t + 1]] - p, c = x[triangles[t + 2]] - p;
        const float la = length(a), lb = length(b), lc = length(c);
        // Its solid angle, 2 atan2(a . (b x c), |a||b||c| + (a . b)|c| + (b . c)|a| + (c . a)|b|).
        solid += 2.0 * std::atan2(double(dot(a, cross(b, c))),
                                  double(la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb));
    }
    return solid;
}

bool inside(const TriangleSurface& s, const Vec3Array& x, std::uint32_t tri, const std::array<float, 3>& w, const Vec3& p,
            const Vec3& away) {
    // At the nearest point of a closed surface, the way to a point outside is within the
    // surface's outward cone there: over a face along its normal, beside an edge between its
    // two faces' normals, at a corner among its faces'. So the sign of away . outward says
    // which side it is on, where the cone is clear: not a crease folded nearly flat back on
    // itself (two faces' normals nearly opposite, their sum short), nor a way almost across
    // the outward direction. There, and only there, the winding number says: the solid angle
    // the whole surface spans seen from p over 4 pi, 1 inside and 0 outside, whatever its
    // folds.
    const int zeros = (w[0] == 0.0f) + (w[1] == 0.0f) + (w[2] == 0.0f);
    // Beside a triangle turned over (a face pushed through its neighbours), the outward
    // direction may point in: only the winding number says. A point in a pocket the turned
    // faces wrap (winding -1) is inside too: it is out of the body only by going through them.
    if (s.any_turned) {
        bool turned = s.turned[tri] != 0;
        if (zeros == 1) {
            const std::uint32_t k = w[0] == 0.0f ? 0 : w[1] == 0.0f ? 1 : 2;
            turned = turned || s.turned[s.across[3 * tri + (k + 1) % 3]] != 0;
        } else if (zeros > 1) {
            const std::uint32_t corner = s.triangles[3 * tri + (w[0] != 0.0f ? 0 : w[1] != 0.0f ? 1 : 2)];
            for (std::uint32_t f = s.fan_begin[corner]; f < s.fan_begin[corner + 1] && !turned; ++f) turned = s.turned[s.fan[f]] != 0;
        }
        if (turned) return std::abs(solid_angle(s.triangles, x, p)) > 2.0 * 3.14159265358979323846;
    }
    const Vec3 out = outward(s, x, tri, w);
    const float size = length(out), dist = length(away);
    const float clear = zeros == 0 ? 0.5f : zeros == 1 ? 1.0f : 1.5f;  // of a flat sheet's 1, 2 and 2 pi
    const float along = dot(away, out);
    if (size >= clear && std::abs(along) >= 0.2f * size * dist) return along < 0.0f;
    return solid_angle(s.triangles, x, p) * double(s.orient) > 2.0 * 3.14159265358979323846;
}

namespace {

std::uint32_t edge_samples(const ConvexHull& hull, const std::array<std::uint32_t, 2>& edge) {
    const double l = length(hull.vertices[edge[1]] - hull.vertices[edge[0]]);
    return std::min(kMostHullEdgeSamples, std::uint32_t(std::ceil(l / kHullEdgeSpacing)) - 1);
}

}  // namespace

std::uint32_t hull_feature_count(const ConvexHull& hull) {
    std::uint32_t count = std::uint32_t(hull.vertices.size());
    for (const auto& e : hull.edges) count += edge_samples(hull, e);
    return count;
}

Vec3d hull_feature(const ConvexHull& hull, std::uint32_t feature) {
    if (feature < hull.vertices.size()) return hull.vertices[feature];
    feature -= std::uint32_t(hull.vertices.size());
    for (const auto& e : hull.edges) {
        const std::uint32_t n = edge_samples(hull, e);
        if (feature < n) {
            const double t = double(feature + 1) / double(n + 1);
            return hull.vertices[e[0]] * (1.0 - t) + hull.vertices[e[1]] * t;
        }
        feature -= n;
    }
    return {};
}

}  // namespace softbody
