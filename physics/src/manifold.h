// Internal to the physics library: a contact manifold cut down to the points that hold a face
// steady, for the ground's contacts (RigidContact) and the narrow phase's (ContactPoint) alike.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "physics/vec3.h"

namespace softbody {

// Keeps at most four of a manifold's points on a plane of normal n: the deepest, the one
// farthest from it, the one that spans the largest triangle with those two, and the one that
// adds the most area outside that triangle. Four points hold a face steady; more only cost.
// `Contact` has a `point` (Vec3d) and a `depth` (double).
//
// Ties go to the earliest point. With `depth_tie` (m), a point within depth_tie of the deepest
// counts as deepest: a cylinder standing on its cap has 32 rim points at one depth, and the
// slightest tilt would otherwise start the four from a different corner. Zero (the default)
// keeps only exact ties.
//
// After the first, a point overlapping by more than kManifoldOverlap goes before any that does
// not, whatever the area: a cylinder lying on its side has its two bottom corners deepest, and
// the corners of the sides next to them, a few millimetres up, span more area with the first;
// kept instead of the second bottom corner, they let that end sink unheld (a cylinder in a pile
// rocked end to end 10 mm into the ground). Points within kManifoldOverlap of touching (a face
// resting, its corners at rounding's depths) are chosen by area alone.
inline constexpr double kManifoldOverlap = 5e-4;  // m

template <class Contact>
void reduce_manifold(std::vector<Contact>& points, const Vec3d& n, double depth_tie = 0.0) {
    if (points.size() <= 4) return;
    const auto area = [&](const Vec3d& a, const Vec3d& b, const Vec3d& c) { return dot(cross(b - a, c - a), n); };
    std::vector<Contact> kept;
    // The earliest point whose score is within `tie` of the best.
    const auto take = [&](auto score, double tie) {
        const bool first = kept.empty();
        const auto overlapping = [&](const Contact& c) { return !first && c.depth > kManifoldOverlap; };
        bool any_overlapping = false;
        for (const Contact& c : points) any_overlapping = any_overlapping || overlapping(c);
        const auto candidate = [&](const Contact& c) { return !any_overlapping || overlapping(c); };
        double best_score = -1e300;
        for (const Contact& c : points) {
            if (candidate(c)) best_score = std::max(best_score, score(c));
        }
        const double enough = best_score - tie;
        std::size_t best = 0;
        while (best < points.size() && !(candidate(points[best]) && score(points[best]) >= enough)) ++best;
        if (best == points.size()) best = 0;  // scores that are not numbers: the first
        kept.push_back(points[best]);
        points.erase(points.begin() + static_cast<std::ptrdiff_t>(best));
    };
    take([](const Contact& c) { return c.depth; }, depth_tie);
    const Vec3d p0 = kept[0].point;
    take([&](const Contact& c) { return length(c.point - p0); }, 0.0);
    const Vec3d p1 = kept[1].point;
    take([&](const Contact& c) { return std::abs(area(p0, p1, c.point)); }, 0.0);
    Vec3d p2 = kept[2].point;
    Vec3d a = p0, b = p1;
    if (area(a, b, p2) < 0.0) std::swap(a, b);  // a, b, p2 counter-clockwise about n
    take([&](const Contact& c) {
        return std::max({-area(a, b, c.point), -area(b, p2, c.point), -area(p2, a, c.point)});
    }, 0.0);
    points = std::move(kept);
}

}  // namespace softbody
