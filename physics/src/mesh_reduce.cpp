// Choosing the particles a large mesh simulates with, and binding every vertex to them.
//
// How the particles are chosen, and why:
// - The springs join every pair of particles, so the particles are the body: its shape, its
//   mass (each particle carries the same mass) and its stiffness. They must cover the whole
//   body evenly. A dense cluster somewhere makes that part heavy and stiff, a bare patch leaves
//   it to be dragged along.
// - A surface is reduced with meshoptimizer's vertex-clustering simplifier
//   (meshopt_simplifySloppy): it lays a uniform grid over the mesh, keeps one of the mesh's own
//   vertices per occupied cell (the one whose position best fits the cell's surface) and
//   rebuilds triangles between the kept vertices. So the particles are spread over the surface
//   at an even spacing, are all vertices of the file (no invented points), and come with a
//   triangulation to bind the dropped vertices to.
// - The edge-collapse simplifier (meshopt_simplify) was measured against it. It keeps the
//   outline a little closer (its dropped vertices lie nearer the kept triangles), but it spends
//   its vertices on creases and small details and leaves smooth regions bare. With h the
//   spacing an even spread would have (sqrt(area / kept)), each full vertex's area given to its
//   nearest kept particle, clustering against edge collapse:
//       mesh (vertices -> budget)     farthest vertex from a particle    spread of area per particle
//       scanned bunny (37,706 -> 3,000)      1.17 h / 2.75 h                  CV 0.33 / 0.66
//       armadillo (26,002 -> 4,000)          1.26 h / 1.77 h                  CV 0.33 / 0.52
//       mug (12,272 -> 1,000)                1.12 h / 2.80 h                  CV 0.41 / 1.92
//       man (17,495 -> 4,000)                1.02 h / 2.12 h                  CV 0.46 / 0.95
//   For equal particle masses, the clustered choice is the more even body; it also ran faster
//   (180 ms against 245 ms for the bunny, binding included).
// - Vertices in no triangle (a point cloud, or the stray points of a mesh) get their share of
//   the budget in proportion to their number and are chosen on a uniform grid as well
//   (meshopt_simplifyPoints).
// - The budget is exact: the grid is coarsened until the kept vertices fit.
//
// How a dropped vertex is bound: to the nearest triangle of the kept particles' triangulation
// (for a surface; triangles thinner than kMinQuality are not used), or to its nearest kept
// particles for a point in no triangle (the nearest two, and of the next ten the one that
// makes a well-shaped triangle with them and needs the smallest weights; the point on the line
// through the two when all of them are nearly collinear). The binding is the vertex's projection onto the triangle's
// plane in barycentric weights, plus its signed distance along the triangle's normal: at rest
// it gives the vertex back exactly (up to float rounding), and under any rigid motion of the
// three particles it moves rigidly with them.
#include "physics/mesh_reduce.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include "physics/error.h"
#include "physics/portable_math.h"

namespace softbody {

namespace {

using Index = std::uint32_t;

// Triangles of a quality q = 4 sqrt(3) area / (sum of squared edges) below this (1 for an
// equilateral one; a 1:20 sliver is about 0.09) are not bound to: the weights of a point
// beside a sliver grow with its aspect ratio, and so do its errors when the body deforms.
constexpr double kMinQuality = 0.05;

double quality(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
    const double area2 = length(cross(b - a, c - a));  // twice the area
    const double edges = dot(b - a, b - a) + dot(c - b, c - b) + dot(a - c, a - c);
    return edges > 0.0 ? 2.0 * std::sqrt(3.0) * area2 / edges : 0.0;
}

// The closest point of triangle abc to p (by the regions of the triangle's Voronoi diagram).
Vec3d closest_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
    const Vec3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;
    const Vec3d bp = p - b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
    const Vec3d cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double denominator = va + vb + vc;
    return a + ab * (vb / denominator) + ac * (vc / denominator);
}

// q as barycentric weights of its projection onto the plane of abc, plus its signed distance
// along the unit normal normalize(cross(b - a, c - a)). abc must have an area.
SkinBinding bind_to(const Vec3d& q, const std::array<Index, 3>& particles, const Vec3d& a, const Vec3d& b,
                    const Vec3d& c) {
    const Vec3d n = cross(b - a, c - a);
    const double nn = dot(n, n);
    const Vec3d aq = q - a;
    // cross(aq, c - a) . n / |n|^2 is the weight of b, cross(b - a, aq) . n / |n|^2 that of c:
    // the normal part of aq drops out of both.
    const double wb = dot(cross(aq, c - a), n) / nn;
    const double wc = dot(cross(b - a, aq), n) / nn;
    SkinBinding binding;
    binding.particles = particles;
    binding.weights[1] = static_cast<float>(wb);
    binding.weights[2] = static_cast<float>(wc);
    binding.weights[0] = static_cast<float>(1.0 - double(binding.weights[1]) - double(binding.weights[2]));
    binding.offset = static_cast<float>(dot(aq, n) / std::sqrt(nn));
    return binding;
}

// Whether a binding's numbers are finite in float: a point far from a nearly flat triangle gets
// weights beyond float's range (a 1e-44 m bump on a 10 m line, a point 1 mm off it: 1e41).
bool finite(const SkinBinding& binding) {
    return std::isfinite(binding.weights[0]) && std::isfinite(binding.weights[1]) && std::isfinite(binding.weights[2]) &&
           std::isfinite(binding.offset);
}

// The sum of |weights|: how far outside its triangle a binding reaches (1 inside it).
double spread(const SkinBinding& binding) {
    return std::abs(binding.weights[0]) + std::abs(binding.weights[1]) + std::abs(binding.weights[2]);
}

// The largest sum of |weights| a point may get from a triangle thinner than kMinQuality (the
// best shaped of its near particles, when none is well shaped): beyond it the point is put on the
// line through its nearest two instead, as if the particles were collinear.
constexpr double kMaxThinSpread = 1e3;

SkinBinding bind_to_itself(Index particle) {
    SkinBinding binding;
    binding.particles = {particle, particle, particle};
    binding.weights = {1.0f, 0.0f, 0.0f};
    return binding;
}

// --- A uniform grid of cells, for nearest-thing queries ---------------------------------------

struct Cell {
    std::int64_t x, y, z;
};

// Items (points or triangles) filed under every cell their bounding box touches, in a dense
// grid over the mesh's bounding box: cells about `cell` wide, but never more than kMaxSide a
// side, so that the grid stays a few megabytes and a search never walks far through empty
// cells (nearest() below falls back to looking at every item when that would be cheaper).
class Grid {
public:
    static constexpr std::int64_t kMaxSide = 96;

    Grid(const Vec3d& lo, const Vec3d& hi, double cell) : lo_(lo) {
        const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
        cell_ = std::max(cell, extent / double(kMaxSide - 1));
        if (!(cell_ > 0.0) || !std::isfinite(cell_)) cell_ = 1.0;
        side_ = {side(hi.x - lo.x), side(hi.y - lo.y), side(hi.z - lo.z)};
    }
    void add(Index item, const Vec3d& lo, const Vec3d& hi) {
        const Cell a = cell_of(lo), b = cell_of(hi);
        for (std::int64_t x = a.x; x <= b.x; ++x)
            for (std::int64_t y = a.y; y <= b.y; ++y)
                for (std::int64_t z = a.z; z <= b.z; ++z) entries_.push_back({linear({x, y, z}), item});
        ++items_;
    }
    void finish() {  // files the entries by cell
        std::sort(entries_.begin(), entries_.end());
        start_.assign(static_cast<std::size_t>(side_.x * side_.y * side_.z) + 1, 0);
        for (const auto& [cell, item] : entries_) ++start_[cell + 1];
        std::partial_sum(start_.begin(), start_.end(), start_.begin());
    }
    Cell cell_of(const Vec3d& p) const {
        auto clamp = [&](double v, std::int64_t n) {
            return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(v / cell_)), 0, n - 1);
        };
        return {clamp(p.x - lo_.x, side_.x), clamp(p.y - lo_.y, side_.y), clamp(p.z - lo_.z, side_.z)};
    }
    double cell() const { return cell_; }
    std::size_t items() const { return items_; }
    std::size_t entries() const { return entries_.size(); }

    // Calls visit(item) for every item filed in a cell at Chebyshev distance exactly `ring`
    // from `centre` (an item may come more than once); returns the number of cells looked at,
    // 0 when the ring lies wholly outside the grid.
    template <class Visit>
    std::size_t visit_ring(const Cell& centre, std::int64_t ring, Visit&& visit) const {
        std::size_t looked = 0;
        for (std::int64_t dx = -ring; dx <= ring; ++dx) {
            const std::int64_t x = centre.x + dx;
            if (x < 0 || x >= side_.x) continue;
            for (std::int64_t dy = -ring; dy <= ring; ++dy) {
                const std::int64_t y = centre.y + dy;
                if (y < 0 || y >= side_.y) continue;
                const bool side = std::abs(dx) == ring || std::abs(dy) == ring;
                for (std::int64_t dz = -ring; dz <= ring; dz += side || ring == 0 ? 1 : 2 * ring) {
                    const std::int64_t z = centre.z + dz;
                    if (z < 0 || z >= side_.z) continue;
                    ++looked;
                    const std::size_t c = linear({x, y, z});
                    for (std::size_t e = start_[c]; e < start_[c + 1]; ++e) visit(entries_[e].second);
                }
            }
        }
        return looked;
    }

private:
    std::int64_t side(double extent) const {
        return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(extent / cell_)) + 1, 1, kMaxSide);
    }
    std::size_t linear(const Cell& c) const { return static_cast<std::size_t>((c.x * side_.y + c.y) * side_.z + c.z); }

    Vec3d lo_;
    double cell_ = 1.0;
    Cell side_{1, 1, 1};
    std::vector<std::pair<std::size_t, Index>> entries_;  // (cell, item), sorted
    std::vector<std::size_t> start_;                      // entries of cell c: [start_[c], start_[c + 1])
    std::size_t items_ = 0;
};

// The nearest items to q, by ring search: cells at Chebyshev distance r from q's cell hold
// nothing nearer than (r - 1) cells, so once the worst of the best found is within that, the
// rest cannot do better. When the rings have looked at more cells than the grid has entries (a
// point far from everything), every item is looked at instead, once. `distance_sq(item)` is
// the squared distance; `keep(d, item)` offers one; `enough()` says the best so far may stop
// the search at the distance it returns (squared).
template <class Distance, class Keep, class Enough>
void ring_search(const Grid& grid, const Vec3d& q, Distance&& distance_sq, Keep&& keep, Enough&& enough) {
    const Cell centre = grid.cell_of(q);
    std::size_t looked = 0;
    for (std::int64_t ring = 0;; ++ring) {
        const std::size_t cells = grid.visit_ring(centre, ring, [&](Index item) { keep(distance_sq(item), item); });
        looked += cells;
        const double reach = double(ring) * grid.cell();
        if (cells == 0 || enough(reach * reach)) return;
        if (looked > grid.entries() + 64) {
            for (Index item = 0; item < grid.items(); ++item) keep(distance_sq(item), item);
            return;
        }
    }
}

// --- Choosing --------------------------------------------------------------------------------

// Positions for meshoptimizer: scaled into the unit cube in double first, so that a mesh a
// micrometre or 1e30 across simplifies the same way (its own scaling is in float).
std::vector<float> unit_positions(const std::vector<Vec3>& positions) {
    Vec3d lo(positions[0]), hi(positions[0]);
    for (const Vec3& p : positions) {
        lo = {std::min(lo.x, double(p.x)), std::min(lo.y, double(p.y)), std::min(lo.z, double(p.z))};
        hi = {std::max(hi.x, double(p.x)), std::max(hi.y, double(p.y)), std::max(hi.z, double(p.z))};
    }
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const double scale = extent > 0.0 ? 1.0 / extent : 1.0;
    std::vector<float> out;
    out.reserve(3 * positions.size());
    for (const Vec3& p : positions) {
        out.push_back(static_cast<float>((p.x - lo.x) * scale));
        out.push_back(static_cast<float>((p.y - lo.y) * scale));
        out.push_back(static_cast<float>((p.z - lo.z) * scale));
    }
    return out;
}

std::vector<Index> used_vertices(const std::vector<unsigned>& indices, std::size_t vertex_count) {
    std::vector<char> used(vertex_count, 0);
    for (unsigned i : indices) used[i] = 1;
    std::vector<Index> out;
    for (std::size_t v = 0; v < vertex_count; ++v) {
        if (used[v]) out.push_back(static_cast<Index>(v));
    }
    return out;
}

// The surface's particles: the vertices of the clustered surface, with a target of triangles
// lowered until they fit the budget. Returns the kept triangles (full indices) in `kept_triangles`.
std::vector<Index> choose_on_surface(const std::vector<unsigned>& triangles, const std::vector<float>& xyz,
                                     std::size_t budget, std::vector<unsigned>& kept_triangles) {
    const std::size_t vertex_count = xyz.size() / 3;
    std::vector<unsigned> out(triangles.size());
    // A closed surface has about twice as many triangles as vertices: aim there, then lower
    // the target in proportion while too many vertices survive.
    std::size_t target = std::min(triangles.size(), 6 * budget);
    for (int attempt = 0; attempt < 32 && target >= 3; ++attempt) {
        const std::size_t count = meshopt_simplifySloppy(out.data(), triangles.data(), triangles.size(), xyz.data(),
                                                         vertex_count, 3 * sizeof(float), target,
                                                         std::numeric_limits<float>::max(), nullptr);
        kept_triangles.assign(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(count));
        std::vector<Index> kept = used_vertices(kept_triangles, vertex_count);
        if (kept.size() <= budget) return kept;
        target = std::min(target - 3, static_cast<std::size_t>(double(target) * double(budget) / double(kept.size()) * 0.97));
        target -= target % 3;
    }
    kept_triangles.clear();
    return {};
}

// Points in no triangle: a uniform grid's worth of them.
std::vector<Index> choose_points(const std::vector<Index>& candidates, const std::vector<Vec3>& positions,
                                 std::size_t budget) {
    if (candidates.size() <= budget) return candidates;
    if (budget == 0) return {};
    std::vector<Vec3> subset;
    subset.reserve(candidates.size());
    for (Index i : candidates) subset.push_back(positions[i]);
    const std::vector<float> xyz = unit_positions(subset);
    std::vector<unsigned> chosen(budget);
    const std::size_t count =
        meshopt_simplifyPoints(chosen.data(), xyz.data(), subset.size(), 3 * sizeof(float), budget);
    std::vector<Index> out;
    for (std::size_t k = 0; k < count; ++k) out.push_back(candidates[chosen[k]]);
    std::sort(out.begin(), out.end());
    return out;
}

// --- Binding ---------------------------------------------------------------------------------

// The nearest of the kept particles to a point: up to `k` of them, nearest first (ties by index).
class NearestParticles {
public:
    NearestParticles(const std::vector<Vec3d>& points, double cell, const Vec3d& lo, const Vec3d& hi)
        : points_(points), grid_(lo, hi, cell) {
        for (Index i = 0; i < points.size(); ++i) grid_.add(i, points[i], points[i]);
        grid_.finish();
    }

    std::vector<std::pair<double, Index>> nearest(const Vec3d& q, std::size_t k) const {
        std::vector<std::pair<double, Index>> best;
        ring_search(
            grid_, q, [&](Index i) { return dot(points_[i] - q, points_[i] - q); },
            [&](double d, Index i) {
                const std::pair<double, Index> candidate{d, i};
                if (best.size() == k && !(candidate < best.back())) return;
                const auto at = std::lower_bound(best.begin(), best.end(), candidate);
                if (at != best.end() && *at == candidate) return;  // seen from another cell
                best.insert(at, candidate);
                if (best.size() > k) best.pop_back();
            },
            [&](double reach_sq) { return best.size() == k && best.back().first <= reach_sq; });
        return best;
    }

private:
    const std::vector<Vec3d>& points_;
    Grid grid_;
};

// The nearest triangle to a point (ties by index). corners: 3 per triangle.
class NearestTriangle {
public:
    NearestTriangle(const std::vector<Vec3d>& corners, double cell, const Vec3d& lo, const Vec3d& hi)
        : corners_(corners), grid_(lo, hi, cell) {
        for (Index t = 0; 3 * t < corners.size(); ++t) {
            const Vec3d &a = corners[3 * t], &b = corners[3 * t + 1], &c = corners[3 * t + 2];
            grid_.add(t, {std::min({a.x, b.x, c.x}), std::min({a.y, b.y, c.y}), std::min({a.z, b.z, c.z})},
                      {std::max({a.x, b.x, c.x}), std::max({a.y, b.y, c.y}), std::max({a.z, b.z, c.z})});
        }
        grid_.finish();
    }

    Index nearest(const Vec3d& q) const {
        std::pair<double, Index> best{std::numeric_limits<double>::infinity(), 0};
        ring_search(
            grid_, q,
            [&](Index t) {
                const Vec3d d = closest_on_triangle(q, corners_[3 * t], corners_[3 * t + 1], corners_[3 * t + 2]) - q;
                return dot(d, d);
            },
            [&](double d, Index t) { best = std::min(best, {d, t}); },
            [&](double reach_sq) { return best.first <= reach_sq; });
        return best.second;
    }

private:
    const std::vector<Vec3d>& corners_;
    Grid grid_;
};

}  // namespace

ReducedMesh reduce_mesh(const Mesh& full, std::size_t max_particles) {
    const std::size_t n = full.particle_count();
    ReducedMesh reduced;
    reduced.full_to_reduced.assign(n, kNotSimulated);

    // Triangles on particles (welding left three distinct particles in each).
    std::vector<unsigned> triangles;
    triangles.reserve(full.triangles.size());
    for (std::uint32_t r : full.triangles) triangles.push_back(full.render_vertices[r].particle);

    if (n <= max_particles) {  // nothing to reduce: every particle as it is
        reduced.positions = full.positions;
        reduced.reduced_to_full.resize(n);
        std::iota(reduced.reduced_to_full.begin(), reduced.reduced_to_full.end(), Index{0});
        reduced.full_to_reduced = reduced.reduced_to_full;
        for (Index i = 0; i < n; ++i) reduced.bindings.push_back(bind_to_itself(i));
        reduced.triangles.assign(triangles.begin(), triangles.end());
        return reduced;
    }
    if (max_particles < kMinReducedParticles) {
        throw InputError(full.source + ": a particle budget of " + std::to_string(max_particles) + " is below " +
                         std::to_string(kMinReducedParticles) + ", too few to keep a body's shape");
    }

    // --- Choose: the surface's share of the budget, and the stray points' ------------------
    std::vector<char> on_surface(n, 0);
    for (unsigned p : triangles) on_surface[p] = 1;
    std::vector<Index> stray;
    for (Index i = 0; i < n; ++i) {
        if (!on_surface[i]) stray.push_back(i);
    }
    const std::size_t surface_count = n - stray.size();
    std::size_t stray_budget = surface_count == 0 ? max_particles : max_particles * stray.size() / n;
    std::vector<unsigned> kept_triangles;
    std::vector<Index> kept;
    if (surface_count > 0) {
        kept = choose_on_surface(triangles, unit_positions(full.positions), max_particles - stray_budget, kept_triangles);
        if (kept.empty()) {  // the surface would not shrink enough: treat it all as points
            stray.resize(n);
            std::iota(stray.begin(), stray.end(), Index{0});
            stray_budget = max_particles;
        }
    }
    const std::vector<Index> kept_points = choose_points(stray, full.positions, stray_budget);
    kept.insert(kept.end(), kept_points.begin(), kept_points.end());
    std::sort(kept.begin(), kept.end());
    kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
    // Too few to hold a shape (a tiny budget clustered away): add the particles farthest from
    // those kept, one at a time (the first when none is).
    while (kept.size() < kMinReducedParticles) {
        std::pair<double, Index> farthest{-1.0, 0};
        for (Index i = 0; i < n; ++i) {
            double d = std::numeric_limits<double>::infinity();
            for (Index k : kept) d = std::min(d, length(Vec3d(full.positions[i]) - Vec3d(full.positions[k])));
            if (d > farthest.first) farthest = {d, i};
        }
        if (farthest.first == 0.0) break;  // welding leaves no two particles at one place, so never
        kept.insert(std::upper_bound(kept.begin(), kept.end(), farthest.second), farthest.second);
    }

    for (Index i : kept) {
        reduced.full_to_reduced[i] = static_cast<Index>(reduced.positions.size());
        reduced.reduced_to_full.push_back(i);
        reduced.positions.push_back(full.positions[i]);
    }
    for (unsigned p : kept_triangles) reduced.triangles.push_back(reduced.full_to_reduced[p]);

    // --- Bind ------------------------------------------------------------------------------
    std::vector<Vec3d> at(n);
    Vec3d lo(full.positions[0]), hi = lo;
    for (Index i = 0; i < n; ++i) {
        at[i] = Vec3d(full.positions[i]);
        lo = {std::min(lo.x, at[i].x), std::min(lo.y, at[i].y), std::min(lo.z, at[i].z)};
        hi = {std::max(hi.x, at[i].x), std::max(hi.y, at[i].y), std::max(hi.z, at[i].z)};
    }
    const double diagonal = length(hi - lo);

    // Triangles to bind to: the clustered surface's, except the thinnest.
    std::vector<Vec3d> corners;
    std::vector<std::array<Index, 3>> corner_particles;  // reduced indices
    double edge_sum = 0.0;
    for (std::size_t t = 0; t + 2 < reduced.triangles.size(); t += 3) {
        const std::array<Index, 3> p = {reduced.triangles[t], reduced.triangles[t + 1], reduced.triangles[t + 2]};
        const Vec3d &a = at[reduced.reduced_to_full[p[0]]], &b = at[reduced.reduced_to_full[p[1]]],
                    &c = at[reduced.reduced_to_full[p[2]]];
        if (!(quality(a, b, c) >= kMinQuality)) continue;
        corners.insert(corners.end(), {a, b, c});
        corner_particles.push_back(p);
        edge_sum += length(b - a) + length(c - b) + length(a - c);
    }
    std::vector<Vec3d> kept_at;
    for (Index i : kept) kept_at.push_back(at[i]);
    // Cells about one particle spacing wide: a surface's mean edge, else the spacing of the
    // kept particles spread through the bounding box.
    const double spacing_cloud = diagonal > 0.0 ? diagonal / portable::cbrt(double(kept.size())) : 1.0;
    const double spacing_surface = corner_particles.empty() ? spacing_cloud : edge_sum / (3.0 * double(corner_particles.size()));
    const NearestTriangle nearest_triangle(corners, spacing_surface, lo, hi);
    const NearestParticles nearest_particles(kept_at, spacing_cloud, lo, hi);

    reduced.bindings.resize(n);
    for (Index i = 0; i < n; ++i) {
        if (reduced.full_to_reduced[i] != kNotSimulated) {
            reduced.bindings[i] = bind_to_itself(reduced.full_to_reduced[i]);
            continue;
        }
        const Vec3d& q = at[i];
        if (on_surface[i] && !corner_particles.empty()) {
            const Index t = nearest_triangle.nearest(q);
            reduced.bindings[i] = bind_to(q, corner_particles[t], corners[3 * t], corners[3 * t + 1], corners[3 * t + 2]);
            if (finite(reduced.bindings[i])) continue;  // else bound as a point, below
        }
        // A point: its nearest two kept particles, and the third that makes the best-shaped
        // triangle with them (the one whose weights for q stay smallest among the well-shaped).
        const auto near = nearest_particles.nearest(q, 12);
        const Index a = near[0].second, b = near.size() > 1 ? near[1].second : a;
        std::pair<double, Index> best{std::numeric_limits<double>::infinity(), kNotSimulated};
        SkinBinding chosen;  // best's binding
        double best_quality = 0.0;
        Index best_any = kNotSimulated;
        for (std::size_t k = 2; k < near.size(); ++k) {
            const Index c = near[k].second;
            const double shape = quality(kept_at[a], kept_at[b], kept_at[c]);
            if (shape > best_quality) best_quality = shape, best_any = c;
            if (shape < kMinQuality) continue;
            const SkinBinding trial = bind_to(q, {a, b, c}, kept_at[a], kept_at[b], kept_at[c]);
            if (const std::pair<double, Index> candidate{spread(trial), c}; candidate < best) best = candidate, chosen = trial;
        }
        bool bound = best.second != kNotSimulated;
        if (!bound && best_any != kNotSimulated) {  // only thin triangles: the best shaped, if usable
            chosen = bind_to(q, {a, b, best_any}, kept_at[a], kept_at[b], kept_at[best_any]);
            bound = finite(chosen) && spread(chosen) <= kMaxThinSpread;
        }
        if (bound) {
            reduced.bindings[i] = chosen;
        } else if (a != b) {  // every near particle on one line: the point on it
            const Vec3d ab = kept_at[b] - kept_at[a];
            const double t = dot(q - kept_at[a], ab) / dot(ab, ab);
            SkinBinding binding;
            binding.particles = {a, b, b};
            binding.weights = {static_cast<float>(1.0 - t), static_cast<float>(t), 0.0f};
            reduced.bindings[i] = binding;
        } else {
            reduced.bindings[i] = bind_to_itself(a);
        }
    }
    return reduced;
}

}  // namespace softbody
