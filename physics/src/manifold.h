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
// After the first, points go in tiers, whatever the area: those overlapping by more than
// kManifoldDeep before the rest that touch (within kManifoldTouching of it, or overlapping less),
// and those before the ones still apart (speculative points a few millimetres off). A cylinder
// lying on its side has its two bottom corners deepest, and the corners of the sides next to
// them, a few millimetres up, span more area with the first; kept instead of the second bottom
// corner, they let that end sink unheld (a cylinder in a pile rocked end to end 10 mm into the
// ground); kept instead of a facet's touching corners while it rested, the facet tipped onto
// them, was pushed back out and tipped again every sixth tick, for ever (a cylinder alone on
// the floor never slept). The deep tier starts well past the 0.5 mm a loaded face rests at
// (ContactSettings::stack_depth) and the 2 mm a body at rest may stand (sleep.h): at 0.5 mm a box
// resting on another had its corners on either side of the line, kept two of them 8 mm apart and
// not the far corner, and tipped every twelfth tick. Within a tier, area alone.
inline constexpr double kManifoldDeep = 3e-3;      // m
inline constexpr double kManifoldTouching = 5e-4;  // m

template <class Contact>
void reduce_manifold(std::vector<Contact>& points, const Vec3d& n, double depth_tie = 0.0) {
    if (points.size() <= 4) return;
    const auto area = [&](const Vec3d& a, const Vec3d& b, const Vec3d& c) { return dot(cross(b - a, c - a), n); };
    std::vector<Contact> kept;
    // The earliest point whose score is within `tie` of the best.
    const auto take = [&](auto score, double tie) {
        const bool first = kept.empty();
        const auto tier = [&](const Contact& c) {
            if (first) return 0;
            return c.depth > kManifoldDeep ? 2 : c.depth >= -kManifoldTouching ? 1 : 0;
        };
        int top = 0;
        for (const Contact& c : points) top = std::max(top, tier(c));
        const auto candidate = [&](const Contact& c) { return tier(c) == top; };
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
