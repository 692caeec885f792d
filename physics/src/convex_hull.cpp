// Convex hulls through Qhull's reentrant C library, wrapped so that it never prints, never ends
// the process, and always gives the same hull in the same order for the same points.
//
// Qhull is run on the points moved to their bounding-box centre and divided by its diagonal, so
// its own tolerances (relative to the largest coordinate it sees) are the same for a part in
// millimetres far from the origin as for a unit cube at it; the hull's vertices are then the
// caller's own points, looked up by index, and the face planes are recomputed from them.
//
// Options: 'Qs' searches all points for the initial simplex (sturdier on thin sets, for one
// more pass over the points). The run that makes the faces adds 'C-<tolerance>': facets are
// merged while the hull is built when one's centrum lies within the tolerance of its
// neighbour's plane. Qhull's default ('C-0') merges only within double rounding, which leaves a
// box whose corners were stored in float, and so sit off their planes by 1e-8 of their distance
// from the origin, split into needle triangles. The tolerance here is 1e-6 of the larger of the
// points' size and their distance from the origin: 16 times float's rounding of a coordinate,
// so those faces join, and a micrometre on a metre, so no face a collision step should see
// vanishes. Runs that only look for the vertices keep Qhull's default.
#include "physics/convex_hull.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/error.h"

extern "C" {
#include <libqhull_r/libqhull_r.h>
}

namespace softbody {

namespace {

// Facets closer to coplanar than this, relative to the larger of the points' size and their
// distance from the origin, are merged into one face.
constexpr double kMergeTolerance = 1e-6;
// Points within this many merge tolerances of one plane span no volume. Qhull's merging needs
// the body well above its merge tolerance: random slabs and needles 10 tolerances thick already
// lost faces in trials, 100 were sound.
constexpr double kFlatFactor = 100.0;
constexpr const char* kVertexOptions = "qhull Qs";

const std::string kWho = "convex hull: ";

std::string three_digits(double x) {
    std::ostringstream out;
    out.precision(3);
    out << x;
    return out.str();
}

// --- Qhull, quietly ---------------------------------------------------------------------------

// Qhull's messages go to a buffer in memory (never to stdout or stderr); on an error its first
// line becomes the exception's text.
class MessageBuffer {
public:
    MessageBuffer() : file_(::open_memstream(&text_, &size_)) {
        if (!file_) throw std::runtime_error(kWho + "cannot open a buffer for the hull library's messages");
    }
    ~MessageBuffer() {
        if (file_) std::fclose(file_);
        std::free(text_);
    }
    MessageBuffer(const MessageBuffer&) = delete;
    MessageBuffer& operator=(const MessageBuffer&) = delete;

    FILE* file() const { return file_; }
    // The first line that reports an error, or the first line.
    std::string error_line() {
        std::fflush(file_);
        const std::string all = text_ ? std::string(text_, size_) : std::string();
        std::size_t start = all.find("error");
        start = start == std::string::npos ? 0 : all.rfind('\n', start);
        start = start == std::string::npos ? 0 : start + 1;
        std::string line = all.substr(start, all.find('\n', start) - start);
        if (line.size() > 200) line = line.substr(0, 200) + "...";
        return line.empty() ? "no message" : line;
    }

private:
    char* text_ = nullptr;
    std::size_t size_ = 0;
    FILE* file_ = nullptr;
};

// One Qhull computation over `coordinates` (x, y, z per point), freed when it goes.
class Qhull {
public:
    Qhull(std::vector<double>& coordinates, const char* options) : qh_(std::make_unique<qhT>()) {
        qhT* qh = qh_.get();
        std::string command = options;  // Qhull wants it writable
        qh_zero(qh, messages_.file());
        // Errors come back here as an exit code (Qhull longjmps to its own setjmp inside
        // qh_new_qhull); no output file, so nothing is printed.
        code_ = qh_new_qhull(qh, 3, static_cast<int>(coordinates.size() / 3), coordinates.data(), False, command.data(),
                             nullptr, messages_.file());
        base_ = coordinates.data();
        count_ = coordinates.size() / 3;
    }
    ~Qhull() {
        qhT* qh = qh_.get();
        qh_freeqhull(qh, !qh_ALL);
        int still_long = 0, still_total = 0;
        qh_memfreeshort(qh, &still_long, &still_total);
    }
    Qhull(const Qhull&) = delete;
    Qhull& operator=(const Qhull&) = delete;

    // Throws for a failed run: InputError for what the points cause, runtime_error otherwise.
    void check(std::size_t point_count) {
        if (code_ == qh_ERRnone) return;
        const std::string line = messages_.error_line();
        const std::string points = std::to_string(point_count) + " points";
        switch (code_) {
            case qh_ERRsingular:
                throw InputError(kWho + "the set of " + points + " spans no volume (" + line + ")");
            case qh_ERRprec:
            case qh_ERRtopology:
            case qh_ERRwide:
                throw InputError(kWho + "no hull can be built from these " + points +
                                 " (nearly flat, or nearly coincident points?): " + line);
            default:
                throw std::runtime_error(kWho + "the hull library failed (code " + std::to_string(code_) + ") on " +
                                         points + ": " + line);
        }
    }

    qhT* get() const { return qh_.get(); }
    // The index into the coordinates given of the point a vertex stands on.
    std::size_t point_index(const vertexT* vertex) const {
        const std::ptrdiff_t at = vertex->point - base_;
        if (at < 0 || at % 3 != 0 || static_cast<std::size_t>(at / 3) >= count_) {
            throw std::runtime_error(kWho + "the hull library returned a vertex that is not an input point");
        }
        return static_cast<std::size_t>(at / 3);
    }

private:
    MessageBuffer messages_;
    std::unique_ptr<qhT> qh_;
    int code_ = 0;
    const double* base_ = nullptr;
    std::size_t count_ = 0;
};

// The options for the face run. The number is written as an integer times a power of ten, with
// no decimal point: Qhull reads it with strtod, which follows the process's locale.
std::string face_options(double merge_tolerance) {
    return "qhull Qs C-" + std::to_string(std::llround(merge_tolerance * 1e12)) + "e-12";
}

std::vector<double> coordinates_of(std::span<const Vec3d> scaled, std::span<const std::uint32_t> subset) {
    std::vector<double> out;
    out.reserve(3 * subset.size());
    for (const std::uint32_t i : subset) {
        out.push_back(scaled[i].x);
        out.push_back(scaled[i].y);
        out.push_back(scaled[i].z);
    }
    return out;
}

// The input indices of the hull's vertices (ascending), from a run on `subset`.
std::vector<std::uint32_t> hull_vertex_indices(std::span<const Vec3d> scaled, std::span<const std::uint32_t> subset) {
    std::vector<double> coordinates = coordinates_of(scaled, subset);
    Qhull hull(coordinates, kVertexOptions);
    hull.check(subset.size());
    qhT* qh = hull.get();
    std::vector<std::uint32_t> out;
    vertexT* vertex = nullptr;
    FORALLvertices out.push_back(subset[hull.point_index(vertex)]);
    std::sort(out.begin(), out.end());
    return out;
}

// --- Spanning and choosing points -------------------------------------------------------------

double distance_squared(const Vec3d& a, const Vec3d& b) { return dot(a - b, a - b); }

// Four of `candidates` far apart: a at one end of the widest axis, b farthest from a, c
// farthest from the line ab, d farthest from the plane abc, with the distances found. The first
// candidate wins a tie, so the choice is deterministic.
struct Spanning {
    std::uint32_t a = 0, b = 0, c = 0, d = 0;
    double from_line = 0.0, from_plane = 0.0;
};

Spanning spanning_simplex(std::span<const Vec3d> q, std::span<const std::uint32_t> candidates) {
    Vec3d lo = q[candidates[0]], hi = lo;
    for (const std::uint32_t i : candidates) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], q[i][k]);
            hi[k] = std::max(hi[k], q[i][k]);
        }
    }
    const Vec3d extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    auto farthest = [&](auto&& score) {
        std::uint32_t best = candidates[0];
        double best_score = -std::numeric_limits<double>::infinity();
        for (const std::uint32_t i : candidates) {
            const double s = score(q[i]);
            if (s > best_score) {
                best_score = s;
                best = i;
            }
        }
        return std::pair{best, best_score};
    };
    Spanning s;
    s.a = farthest([&](const Vec3d& p) { return -p[axis]; }).first;
    s.b = farthest([&](const Vec3d& p) { return distance_squared(p, q[s.a]); }).first;
    const Vec3d ab = normalize(q[s.b] - q[s.a]);
    const auto [c, c_score] = farthest([&](const Vec3d& p) {
        const Vec3d r = p - q[s.a];
        return dot(r, r) - dot(r, ab) * dot(r, ab);
    });
    s.c = c;
    s.from_line = std::sqrt(std::max(c_score, 0.0));
    const Vec3d n = normalize(cross(q[s.b] - q[s.a], q[s.c] - q[s.a]));
    const auto [d, d_score] = farthest([&](const Vec3d& p) { return std::abs(dot(p - q[s.a], n)); });
    s.d = d;
    s.from_plane = d_score;
    return s;
}

// The planes n . x + offset = 0 (n outward, unit) of the hull of `subset`.
struct Plane {
    Vec3d normal;
    double offset = 0.0;
};

std::vector<Plane> hull_planes(std::span<const Vec3d> scaled, std::span<const std::uint32_t> subset) {
    std::vector<double> coordinates = coordinates_of(scaled, subset);
    Qhull hull(coordinates, kVertexOptions);
    hull.check(subset.size());
    qhT* qh = hull.get();
    std::vector<Plane> out;
    facetT* facet = nullptr;
    FORALLfacets out.push_back({{facet->normal[0], facet->normal[1], facet->normal[2]}, facet->offset});
    return out;
}

// How far p lies outside the hull with these planes (at most 0 inside it).
double outside_by(const Vec3d& p, std::span<const Plane> planes) {
    double most = -std::numeric_limits<double>::infinity();
    for (const Plane& plane : planes) most = std::max(most, dot(plane.normal, p) + plane.offset);
    return most;
}

// At most `budget` of the full hull's vertices (`candidates`, ascending), chosen greedily so
// that their hull stays close to the full one: start from the spanning tetrahedron, then again
// and again add the vertex lying farthest outside the hull of those chosen so far. The largest
// such distance is how far the reduced hull misses the full one (their Hausdorff distance), so
// each step removes the worst error. A vertex's distance only shrinks as the hull grows, so a
// stale distance is an upper bound: candidates wait in a queue by their last distance and only
// the one on top is measured again (a "lazy greedy" search), which keeps it fast.
//
// Support points along a fixed set of directions (the 38 of a subdivided octahedron, then the
// farthest points) were tried first: the reduced hull missed a 3 : 1 : 0.5 ellipsoid by 0.15
// and a sphere by 7.6% of its radius, where this misses them by 0.06 and 5.7%.
std::vector<std::uint32_t> spread_subset(std::span<const Vec3d> q, std::span<const std::uint32_t> candidates,
                                         std::size_t budget, double merge_tolerance) {
    const Spanning s = spanning_simplex(q, candidates);
    std::vector<std::uint32_t> chosen{s.a, s.b, s.c, s.d};
    std::vector<Plane> planes = hull_planes(q, chosen);
    // Largest distance first; on a tie, the smaller index (so the choice is deterministic).
    using Entry = std::pair<double, std::uint32_t>;
    auto below = [](const Entry& x, const Entry& y) { return x.first < y.first || (x.first == y.first && x.second > y.second); };
    std::priority_queue<Entry, std::vector<Entry>, decltype(below)> waiting(below);
    for (const std::uint32_t c : candidates) {
        if (c == s.a || c == s.b || c == s.c || c == s.d) continue;
        waiting.emplace(outside_by(q[c], planes), c);
    }
    while (chosen.size() < budget && !waiting.empty()) {
        const std::uint32_t c = waiting.top().second;
        waiting.pop();
        const double now = outside_by(q[c], planes);
        if (now <= merge_tolerance) continue;  // inside, or as good as on the surface: for good
        if (!waiting.empty() && now < waiting.top().first) {
            waiting.emplace(now, c);  // someone else may be farther out
            continue;
        }
        chosen.push_back(c);
        planes = hull_planes(q, chosen);
    }
    std::sort(chosen.begin(), chosen.end());
    return chosen;
}

// --- Faces ----------------------------------------------------------------------------------

// A number that grows with the angle of (x, y) about the origin, in [0, 4): the same order as
// the angle, from arithmetic alone.
double pseudo_angle(double x, double y) {
    const double r = std::abs(x) + std::abs(y);
    if (r == 0.0) return 0.0;
    const double p = y / r;  // in [-1, 1]
    if (x >= 0.0) return p >= 0.0 ? p : 4.0 + p;
    return 2.0 - p;
}

struct RawFace {
    Vec3d normal;                          // Qhull's, outward (scaled coordinates, same direction)
    std::vector<std::uint32_t> vertices;   // input indices, any order
};

std::vector<RawFace> hull_faces(std::span<const Vec3d> scaled, std::span<const std::uint32_t> subset,
                                double merge_tolerance) {
    std::vector<double> coordinates = coordinates_of(scaled, subset);
    Qhull hull(coordinates, face_options(merge_tolerance).c_str());
    hull.check(subset.size());
    qhT* qh = hull.get();
    std::vector<RawFace> out;
    facetT* facet = nullptr;
    vertexT* vertex = nullptr;
    vertexT** vertexp = nullptr;
    FORALLfacets {
        if (facet->visible) continue;
        RawFace face;
        face.normal = {facet->normal[0], facet->normal[1], facet->normal[2]};
        FOREACHvertex_(facet->vertices) face.vertices.push_back(subset[hull.point_index(vertex)]);
        out.push_back(std::move(face));
    }
    return out;
}

}  // namespace

// --- The hull -------------------------------------------------------------------------------

ConvexHull convex_hull(std::span<const Vec3d> points, std::size_t max_vertices) {
    if (max_vertices < 4) {
        throw InputError(kWho + "max_vertices must be at least 4 (a tetrahedron), got " + std::to_string(max_vertices));
    }
    if (points.size() > static_cast<std::size_t>(std::numeric_limits<int>::max() / 3)) {
        throw InputError(kWho + std::to_string(points.size()) + " points are too many");
    }
    if (points.size() < 4) {
        throw InputError(kWho + "the set of " + std::to_string(points.size()) +
                         " points spans no volume (a solid needs at least 4 points not on one plane)");
    }
    Vec3d lo = points[0], hi = points[0];
    double farthest_out = 0.0;  // the largest |coordinate|
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!is_finite(points[i])) throw InputError(kWho + "point " + std::to_string(i) + " is not a finite point");
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], points[i][k]);
            hi[k] = std::max(hi[k], points[i][k]);
            farthest_out = std::max(farthest_out, std::abs(points[i][k]));
        }
    }
    const Vec3d center = (lo + hi) * 0.5;
    const double diagonal = length(hi - lo);
    const std::string set = "the set of " + std::to_string(points.size()) + " points";
    if (!std::isfinite(diagonal)) throw InputError(kWho + set + " is too large to measure in double precision");
    if (diagonal == 0.0) throw InputError(kWho + set + " spans no volume: they are all one point");
    // From here on, in units of the diagonal about the centre.
    std::vector<Vec3d> q(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) q[i] = (points[i] - center) / diagonal;
    const double merge_tolerance = kMergeTolerance * std::max(1.0, farthest_out / diagonal);
    const double flat_tolerance = kFlatFactor * merge_tolerance;

    std::vector<std::uint32_t> all(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) all[i] = static_cast<std::uint32_t>(i);
    const Spanning span = spanning_simplex(q, all);
    const std::string within = " (within " + three_digits(flat_tolerance * diagonal) + ")";
    if (span.from_line <= flat_tolerance) throw InputError(kWho + set + " spans no volume: they lie on one line" + within);
    if (span.from_plane <= flat_tolerance) throw InputError(kWho + set + " spans no volume: they lie on one plane" + within);

    // Over budget: the full hull's vertices, then a spread subset of them.
    std::vector<std::uint32_t> subset = all;
    if (points.size() > max_vertices) {
        subset = hull_vertex_indices(q, all);
        if (subset.size() > max_vertices) subset = spread_subset(q, subset, max_vertices, merge_tolerance);
    }
    std::vector<RawFace> raw = hull_faces(q, subset, merge_tolerance);

    // A point on an edge between two faces does not come back as a vertex: Qhull never finds
    // it outside the hull by more than its tolerances, or drops it again after merging. (The
    // tests hold it to that: a cube with its edges' midpoints, a float box with points along
    // its edges.)

    // The vertices in input order, renumbered.
    std::vector<std::uint32_t> used;
    for (const RawFace& f : raw) used.insert(used.end(), f.vertices.begin(), f.vertices.end());
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    std::vector<std::uint32_t> index_of(points.size(), 0);
    ConvexHull hull;
    for (std::size_t n = 0; n < used.size(); ++n) {
        index_of[used[n]] = static_cast<std::uint32_t>(n);
        hull.vertices.push_back(points[used[n]]);
    }

    for (const RawFace& f : raw) {
        // Counter-clockwise seen from outside: by angle about the polygon's centroid in a basis
        // (u, v) of its plane with u x v = the outward normal.
        const Vec3d n = normalize(f.normal);
        const Vec3d helper = std::abs(n.x) <= std::abs(n.y) && std::abs(n.x) <= std::abs(n.z) ? Vec3d{1, 0, 0}
                             : std::abs(n.y) <= std::abs(n.z)                                ? Vec3d{0, 1, 0}
                                                                                             : Vec3d{0, 0, 1};
        const Vec3d u = normalize(cross(helper, n));
        const Vec3d v = cross(n, u);
        Vec3d centroid;
        for (const std::uint32_t i : f.vertices) centroid += q[i];
        centroid = centroid / static_cast<double>(f.vertices.size());
        std::vector<std::pair<double, std::uint32_t>> around;
        for (const std::uint32_t i : f.vertices) {
            const Vec3d r = q[i] - centroid;
            around.emplace_back(pseudo_angle(dot(r, u), dot(r, v)), index_of[i]);
        }
        std::sort(around.begin(), around.end());
        ConvexHull::Face face;
        for (const auto& [angle, i] : around) face.vertices.push_back(i);
        // Start at the smallest index, keeping the order.
        std::rotate(face.vertices.begin(), std::min_element(face.vertices.begin(), face.vertices.end()),
                    face.vertices.end());

        // The plane from the caller's own coordinates: Newell's normal of the polygon (the sum of
        // its edges' cross products; exact for a planar polygon, a best fit for a merged one),
        // taken about the centre for precision, and the offset that puts every corner on or
        // under the plane.
        Vec3d newell;
        const std::size_t m = face.vertices.size();
        for (std::size_t k = 0; k < m; ++k) {
            const Vec3d a = hull.vertices[face.vertices[k]] - center;
            const Vec3d b = hull.vertices[face.vertices[(k + 1) % m]] - center;
            newell += cross(a, b);
        }
        face.normal = normalize(newell);
        if (!(dot(face.normal, n) > 0.0)) {
            throw std::runtime_error(kWho + "a face's corners do not turn about its outward normal");
        }
        face.offset = -std::numeric_limits<double>::infinity();
        for (const std::uint32_t i : face.vertices) face.offset = std::max(face.offset, dot(face.normal, hull.vertices[i]));
        hull.faces.push_back(std::move(face));
    }
    std::sort(hull.faces.begin(), hull.faces.end(),
              [](const ConvexHull::Face& a, const ConvexHull::Face& b) { return a.vertices < b.vertices; });

    for (const ConvexHull::Face& face : hull.faces) {
        const std::size_t m = face.vertices.size();
        for (std::size_t k = 0; k < m; ++k) {
            const std::uint32_t a = face.vertices[k], b = face.vertices[(k + 1) % m];
            hull.edges.push_back({std::min(a, b), std::max(a, b)});
        }
    }
    std::sort(hull.edges.begin(), hull.edges.end());
    hull.edges.erase(std::unique(hull.edges.begin(), hull.edges.end()), hull.edges.end());
    return hull;
}

std::vector<std::array<std::uint32_t, 3>> ConvexHull::triangles() const {
    std::vector<std::array<std::uint32_t, 3>> out;
    for (const Face& face : faces) {
        for (std::size_t k = 1; k + 1 < face.vertices.size(); ++k) {
            out.push_back({face.vertices[0], face.vertices[k], face.vertices[k + 1]});
        }
    }
    return out;
}

Vec3d ConvexHull::support(const Vec3d& direction) const {
    if (vertices.empty()) return {};
    std::size_t best = 0;
    double best_dot = dot(vertices[0], direction);
    for (std::size_t i = 1; i < vertices.size(); ++i) {
        const double along = dot(vertices[i], direction);
        if (along > best_dot) {
            best_dot = along;
            best = i;
        }
    }
    return vertices[best];
}

}  // namespace softbody
