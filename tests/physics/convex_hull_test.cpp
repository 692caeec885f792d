// Convex hulls: the shape of the answer (vertices that are input points, merged polygon faces
// turning counter-clockwise about outward unit normals, every point under every plane, unique
// edges, Euler's V - E + F = 2), the vertex budget, refusals of sets that span no volume,
// determinism, silence, and mass properties of a hull against Table 1.
//
// Tolerances: points and planes are in double, so a point on a plane is found on it to a few
// ulps of the coordinates (1e-12 of the size is far above that). Where the hull merges facets
// closer to coplanar than its tolerance t (1e-6 of the larger of the size and the largest
// coordinate, see convex_hull.h), merges add up: a merged face's corners, and the points, can
// be off its plane by a few t (2.7 t at most in trials with spheres and slabs), so such hulls
// are checked to 5 t.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "physics/convex_hull.h"
#include "physics/mass_properties.h"
#include "physics/quat.h"
#include "physics/shape_meshes.h"
#include "test_support.h"

namespace softbody::test {
namespace {

std::vector<Vec3d> cube8(double side = 1.0, const Vec3d& at = {}) {
    std::vector<Vec3d> out;
    for (int i = 0; i < 8; ++i) {
        out.push_back(at + Vec3d{i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5} * side);
    }
    return out;
}

// n points uniform in the box of `size` about `at` (strictly inside by `margin` of each side).
std::vector<Vec3d> in_box(std::size_t n, std::uint32_t seed, const Vec3d& size, const Vec3d& at = {},
                          double margin = 0.01) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-0.5 + margin, 0.5 - margin);
    std::vector<Vec3d> out;
    for (std::size_t i = 0; i < n; ++i) out.push_back(at + Vec3d{unit(rng) * size.x, unit(rng) * size.y, unit(rng) * size.z});
    return out;
}

// n points on the unit sphere, spread uniformly.
std::vector<Vec3d> on_sphere(std::size_t n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::vector<Vec3d> out;
    while (out.size() < n) {
        const Vec3d p{unit(rng), unit(rng), unit(rng)};
        const double l = length(p);
        if (l > 0.1 && l <= 1.0) out.push_back(p / l);
    }
    return out;
}

template <class T>
void append(std::vector<T>& to, const std::vector<T>& more) {
    to.insert(to.end(), more.begin(), more.end());
}

double size_of(std::span<const Vec3d> points) {
    Vec3d lo = points[0], hi = points[0];
    for (const Vec3d& p : points) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
        }
    }
    return length(hi - lo);
}

// The hull's merge tolerance for these points (see convex_hull.h), times 5 (see the top).
double merged_eps(std::span<const Vec3d> points) {
    double farthest = 0.0;
    for (const Vec3d& p : points) farthest = std::max({farthest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    return 5.0 * 1e-6 * std::max(size_of(points), farthest);
}

// Rounded to float, as a mesh stores it. Through volatile floats: GCC 12 at -O3 turns
// Vec3d(to_float(v)) into a plain copy of x and y (its SLP vectorizer drops the double -> float
// -> double pair), and the points would keep their unrounded coordinates.
Vec3d stored_in_float(const Vec3d& v) {
    volatile float x = static_cast<float>(v.x), y = static_cast<float>(v.y), z = static_cast<float>(v.z);
    return {x, y, z};
}

// Everything a hull must be, whatever the points: "" when it is, else the first fault found.
// `inside` are points that must lie under every face plane within `eps`.
std::string hull_fault(const ConvexHull& hull, std::span<const Vec3d> points, std::span<const Vec3d> inside, double eps) {
    const std::size_t V = hull.vertices.size(), F = hull.faces.size(), E = hull.edges.size();
    if (V < 4 || F < 4) return "fewer than 4 vertices or faces";
    // Each vertex one of the input points.
    for (std::size_t v = 0; v < V; ++v) {
        if (std::find(points.begin(), points.end(), hull.vertices[v]) == points.end()) {
            return "vertex " + std::to_string(v) + " is not an input point";
        }
    }
    Vec3d middle;
    for (const Vec3d& v : hull.vertices) middle += v / static_cast<double>(V);
    std::map<std::array<std::uint32_t, 2>, int> sides;  // edge -> faces using it
    for (std::size_t f = 0; f < F; ++f) {
        const ConvexHull::Face& face = hull.faces[f];
        const std::string which = "face " + std::to_string(f) + ": ";
        const std::size_t m = face.vertices.size();
        if (m < 3) return which + "fewer than 3 corners";
        if (std::abs(length(face.normal) - 1.0) > 1e-12) return which + "normal not of unit length";
        Vec3d centroid;
        for (const std::uint32_t v : face.vertices) {
            if (v >= V) return which + "corner out of range";
            centroid += hull.vertices[v] / static_cast<double>(m);
            // Its corners on its plane (a merged face: within eps).
            if (std::abs(dot(face.normal, hull.vertices[v]) - face.offset) > eps) return which + "corner off its plane";
        }
        if (!(dot(face.normal, centroid - middle) > 0.0)) return which + "normal points inward";
        for (std::size_t k = 0; k < m; ++k) {
            const Vec3d& a = hull.vertices[face.vertices[k]];
            const Vec3d& b = hull.vertices[face.vertices[(k + 1) % m]];
            const Vec3d& c = hull.vertices[face.vertices[(k + 2) % m]];
            // Counter-clockwise seen from outside: each turn is to the left about the normal.
            if (!(dot(cross(b - a, c - b), face.normal) > 0.0)) return which + "corners not counter-clockwise (convex) from outside";
            const std::uint32_t x = face.vertices[k], y = face.vertices[(k + 1) % m];
            ++sides[{std::min(x, y), std::max(x, y)}];
        }
        for (const Vec3d& p : hull.vertices) {
            if (dot(face.normal, p) > face.offset + eps) return which + "a hull vertex lies above it";
        }
        for (const Vec3d& p : inside) {
            if (dot(face.normal, p) > face.offset + eps) return which + "an input point lies above it";
        }
    }
    // Edges: unique, first < second, exactly the faces' sides, each between two faces.
    for (std::size_t e = 0; e < E; ++e) {
        if (hull.edges[e][0] >= hull.edges[e][1]) return "edge " + std::to_string(e) + " not first < second";
        if (e > 0 && !(hull.edges[e - 1] < hull.edges[e])) return "edges not unique";
        const auto it = sides.find(hull.edges[e]);
        if (it == sides.end()) return "edge " + std::to_string(e) + " is no face's side";
        if (it->second != 2) return "edge " + std::to_string(e) + " has " + std::to_string(it->second) + " faces";
    }
    if (sides.size() != E) return "a face's side is missing from the edges";
    // Euler's formula for a convex polyhedron.
    if (static_cast<long>(V) - static_cast<long>(E) + static_cast<long>(F) != 2) return "V - E + F != 2";
    // Its triangles: a closed, outward mesh.
    const auto triangles = hull.triangles();
    std::size_t expected = 0;
    for (const auto& face : hull.faces) expected += face.vertices.size() - 2;
    if (triangles.size() != expected) return "triangles() is not the faces' fans";
    if (!is_closed_oriented(triangles)) return "triangles() not closed and oriented";
    double volume6 = 0.0;  // facing outward: a positive signed volume, sum of det(a, b, c)
    for (const auto& t : triangles) {
        volume6 += dot(hull.vertices[t[0]] - middle, cross(hull.vertices[t[1]] - middle, hull.vertices[t[2]] - middle));
    }
    if (!(volume6 > 0.0)) return "triangles() face inward";
    return "";
}

// --- The shape of the answer ------------------------------------------------------------------

// A cube's corners plus points inside it, on its faces (their centres) and on its edges (their
// midpoints): the hull is the cube, 8 corners, 6 square faces with axis normals, 12 edges.
// Coordinates are exact in binary, so planes and offsets are exact to rounding: 1e-15.
TEST(ConvexHull, CubeWithInnerPointsIsTheCube) {
    std::vector<Vec3d> points = in_box(50, 1, {1, 1, 1});
    append(points, cube8());
    for (int axis = 0; axis < 3; ++axis) {
        for (const double side : {-0.5, 0.5}) {
            Vec3d centre;
            centre[axis] = side;
            points.push_back(centre);  // a face's centre
            Vec3d edge_middle{side, side, side};
            edge_middle[axis] = 0.0;
            points.push_back(edge_middle);  // an edge's midpoint
        }
    }
    const ConvexHull hull = convex_hull(points);
    EXPECT_EQ(hull_fault(hull, points, points, 1e-12), "");
    ASSERT_EQ(hull.vertices.size(), 8u);
    EXPECT_EQ(hull.faces.size(), 6u);
    EXPECT_EQ(hull.edges.size(), 12u);
    for (const Vec3d& v : hull.vertices) {
        EXPECT_EQ(std::abs(v.x), 0.5);
        EXPECT_EQ(std::abs(v.y), 0.5);
        EXPECT_EQ(std::abs(v.z), 0.5);
    }
    for (const ConvexHull::Face& face : hull.faces) {
        EXPECT_EQ(face.vertices.size(), 4u);
        EXPECT_NEAR(face.offset, 0.5, 1e-15);
        // An axis, outward.
        EXPECT_NEAR(std::abs(face.normal.x) + std::abs(face.normal.y) + std::abs(face.normal.z), 1.0, 1e-15);
    }
    // The vertices keep the input's order: the corners were appended in the order of their bits.
    EXPECT_EQ(hull.vertices, cube8());
    EXPECT_EQ(hull.support({1.0, 1.0, 1.0}), (Vec3d{0.5, 0.5, 0.5}));
    EXPECT_EQ(hull.support({1.0, 0.1, -0.2}), (Vec3d{0.5, 0.5, -0.5}));
}

// Support points against a brute-force search over the vertices.
TEST(ConvexHull, SupportIsTheFarthestVertex) {
    const std::vector<Vec3d> points = on_sphere(500, 3);
    const ConvexHull hull = convex_hull(points);
    for (const Vec3d& d : on_sphere(100, 4)) {
        double best = -INFINITY;
        for (const Vec3d& v : hull.vertices) best = std::max(best, dot(v, d));
        EXPECT_EQ(dot(hull.support(d), d), best);
    }
}

// A cylinder's rim points: the hull is the prism, its two caps one polygon each (coplanar
// facets merged), its sides quadrilaterals: V = 2n, F = n + 2, E = 3n.
TEST(ConvexHull, CoplanarFacetsAreMergedIntoPolygons) {
    const int n = 24;
    const Mesh cylinder = cylinder_mesh(0.5, 2.0, n);
    std::vector<Vec3d> points;
    for (const Vec3& p : cylinder.positions) points.push_back(Vec3d(p));
    const ConvexHull hull = convex_hull(points);
    EXPECT_EQ(hull_fault(hull, points, points, merged_eps(points)), "");
    EXPECT_EQ(hull.vertices.size(), 2u * n);  // the caps' centres lie inside the caps
    EXPECT_EQ(hull.faces.size(), n + 2u);
    EXPECT_EQ(hull.edges.size(), 3u * n);
    std::map<std::size_t, int> corners;
    for (const auto& face : hull.faces) ++corners[face.vertices.size()];
    EXPECT_EQ(corners[static_cast<std::size_t>(n)], 2);
    EXPECT_EQ(corners[4], n);
}

// A box 40 x 25 x 10 mm, its faces sampled on a grid (edges and corners included), turned and
// placed 9 m from the origin, its points stored in float as a mesh file would hold them: off
// their planes by up to 5e-4 mm (half a float ulp at 9000), ten times 1e-6 of the box's size.
// It must still be a box: 8 corners, 6 quadrilaterals, 12 edges, with every point under every
// face within 5 merge tolerances (of 1e-6 of 9000 mm).
TEST(ConvexHull, TurnedFloatBoxInMillimetresKeepsSixFaces) {
    const Vec3d size{40.0, 25.0, 10.0};
    const Vec3d at{9000.0, -4000.0, 2500.0};
    const Mat3 R = Quat::from_axis_angle(normalize(Vec3d{1.0, -2.0, 0.5}), 0.9).to_matrix();
    std::vector<Vec3d> points;
    const int n = 8;
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
            for (int k = 0; k <= n; ++k) {
                if (i % n != 0 && j % n != 0 && k % n != 0) continue;  // the surface only
                const Vec3d local{(double(i) / n - 0.5) * size.x, (double(j) / n - 0.5) * size.y, (double(k) / n - 0.5) * size.z};
                points.push_back(stored_in_float(R * local + at));
            }
        }
    }
    const ConvexHull hull = convex_hull(points);
    EXPECT_EQ(hull_fault(hull, points, points, merged_eps(points)), "");
    EXPECT_EQ(hull.vertices.size(), 8u);
    EXPECT_EQ(hull.faces.size(), 6u);
    EXPECT_EQ(hull.edges.size(), 12u);
    for (const auto& face : hull.faces) EXPECT_EQ(face.vertices.size(), 4u);
}

// --- The vertex budget ------------------------------------------------------------------------

// 2,000 points on a sphere: the full hull has all 2,000 as vertices; the budget keeps 64, and
// their hull stays close: no face more than 7% of the radius inside the sphere (convex_hull.h
// says about 6%; 5.9% here, 5.6% to 6.0% over other seeds), so no input point more than that
// outside the hull.
TEST(ConvexHull, SphereCloudIsReducedToTheBudget) {
    const std::vector<Vec3d> points = on_sphere(2000, 5);
    const ConvexHull hull = convex_hull(points);
    EXPECT_EQ(hull_fault(hull, points, {}, merged_eps(points)), "");
    EXPECT_LE(hull.vertices.size(), kMaxHullVertices);
    EXPECT_GE(hull.vertices.size(), kMaxHullVertices - 4);  // the budget is used
    for (const auto& face : hull.faces) EXPECT_GT(face.offset, 0.93);

    const ConvexHull full = convex_hull(points, points.size());
    EXPECT_EQ(full.vertices.size(), points.size());
    EXPECT_EQ(hull_fault(full, points, points, merged_eps(points)), "");

    // Smaller budgets too, down to a tetrahedron.
    for (const std::size_t budget : {4u, 5u, 8u, 20u}) {
        const ConvexHull small = convex_hull(points, budget);
        EXPECT_EQ(hull_fault(small, points, {}, merged_eps(points)), "") << "budget " << budget;
        EXPECT_LE(small.vertices.size(), budget);
    }
}

// Points filling a ball and a 30,000-point sphere: within budget and sound. The second is the
// size of a large mesh; its time is recorded (--gtest_output=xml), not judged here.
TEST(ConvexHull, LargeCloudsStayWithinBudget) {
    std::vector<Vec3d> ball;
    std::mt19937 rng(6);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const Vec3d& p : on_sphere(3000, 6)) ball.push_back(p * std::cbrt(unit(rng)));  // uniform in the ball
    const ConvexHull a = convex_hull(ball);
    EXPECT_EQ(hull_fault(a, ball, {}, merged_eps(ball)), "");
    EXPECT_LE(a.vertices.size(), kMaxHullVertices);

    const std::vector<Vec3d> big = on_sphere(30000, 7);
    const ConvexHull b = convex_hull(big);  // its time: mesh_benchmarks' BM_ConvexHull/30000
    EXPECT_EQ(hull_fault(b, big, {}, merged_eps(big)), "");
    EXPECT_LE(b.vertices.size(), kMaxHullVertices);
}

// --- Refusals ---------------------------------------------------------------------------------

TEST(ConvexHull, SetsThatSpanNoVolumeAreRefused) {
    // On a tilted plane.
    const Mat3 R = Quat::from_axis_angle(normalize(Vec3d{1.0, 1.0, 0.0}), 0.6).to_matrix();
    std::vector<Vec3d> plane;
    for (const Vec3d& p : in_box(100, 8, {2.0, 3.0, 0.0})) plane.push_back(R * p + Vec3d{5.0, 0.0, 1.0});
    EXPECT_REFUSED_NAMING(convex_hull(plane), "convex hull", "100 points", "spans no volume", "one plane");
    // On a line.
    std::vector<Vec3d> line;
    for (int i = 0; i < 10; ++i) line.push_back(Vec3d{1.0, 2.0, 3.0} * (0.37 * i) + Vec3d{0.0, 1.0, 0.0});
    EXPECT_REFUSED_NAMING(convex_hull(line), "convex hull", "10 points", "spans no volume", "one line");
    // One point, five times.
    const std::vector<Vec3d> one(5, Vec3d{1.0, -2.0, 3.0});
    EXPECT_REFUSED_NAMING(convex_hull(one), "convex hull", "5 points", "spans no volume", "one point");
    // Too few.
    const std::vector<Vec3d> three{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    EXPECT_REFUSED_NAMING(convex_hull(three), "convex hull", "3 points", "spans no volume");
    EXPECT_REFUSED_NAMING(convex_hull({}), "convex hull", "0 points", "spans no volume");
    // A slab 1e-5 of its size thick (below 100 merge tolerances) is flat; 1e-3 is a body.
    std::vector<Vec3d> thin = in_box(200, 9, {1.0, 1.0, 1e-5}, {}, 0.0);
    EXPECT_REFUSED_NAMING(convex_hull(thin), "convex hull", "spans no volume", "one plane");
    std::vector<Vec3d> slab = in_box(200, 9, {1.0, 1.0, 1e-3}, {}, 0.0);
    const ConvexHull hull = convex_hull(slab);
    EXPECT_EQ(hull_fault(hull, slab, slab, merged_eps(slab)), "");
}

TEST(ConvexHull, BadPointsAndBudgetsAreRefused) {
    std::vector<Vec3d> points = cube8();
    points[3].z = std::nan("");
    EXPECT_REFUSED_NAMING(convex_hull(points), "convex hull", "point 3", "not a finite");
    points[3].z = INFINITY;
    EXPECT_REFUSED_NAMING(convex_hull(points), "convex hull", "point 3", "not a finite");
    EXPECT_REFUSED_NAMING(convex_hull(cube8(), 3), "convex hull", "max_vertices", "3");
    const std::vector<Vec3d> huge{{-1e308, 0, 0}, {1e308, 0, 0}, {0, 1e308, 0}, {0, 0, 1e308}};
    EXPECT_REFUSED_NAMING(convex_hull(huge), "convex hull", "too large");
}

// --- Determinism and silence ------------------------------------------------------------------

bool same(const ConvexHull& a, const ConvexHull& b) {
    if (a.vertices != b.vertices || a.edges != b.edges || a.faces.size() != b.faces.size()) return false;
    for (std::size_t f = 0; f < a.faces.size(); ++f) {
        if (a.faces[f].vertices != b.faces[f].vertices || !(a.faces[f].normal == b.faces[f].normal) ||
            a.faces[f].offset != b.faces[f].offset) {
            return false;
        }
    }
    return true;
}

// The same points give the same hull, bit for bit, also on another thread at the same time;
// the same points in another order give the same vertices (as positions) and as many faces, so
// the result does not hang on the listing.
TEST(ConvexHull, SamePointsSameHull) {
    std::vector<Vec3d> cloud = on_sphere(3000, 10);
    append(cloud, in_box(500, 11, {1, 1, 1}));
    const ConvexHull first = convex_hull(cloud);
    const ConvexHull second = convex_hull(cloud);
    EXPECT_TRUE(same(first, second));
    // Two at once, on two threads: each call keeps Qhull's state to itself.
    ConvexHull elsewhere;
    std::thread other([&] { elsewhere = convex_hull(cloud); });
    const ConvexHull here = convex_hull(cloud);
    other.join();
    EXPECT_TRUE(same(first, elsewhere));
    EXPECT_TRUE(same(first, here));

    std::vector<Vec3d> shuffled = cloud;
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(12));
    const ConvexHull third = convex_hull(shuffled);
    auto sorted = [](std::vector<Vec3d> v) {
        std::sort(v.begin(), v.end(), [](const Vec3d& a, const Vec3d& b) {
            return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
        });
        return v;
    };
    EXPECT_EQ(sorted(first.vertices), sorted(third.vertices));
    EXPECT_EQ(first.faces.size(), third.faces.size());
}

// Qhull writes its warnings and errors to a file it is given; here they must go nowhere near
// the process's standard output or error. In a child whose stdout and stderr are a file: sets
// Qhull warns about (thin, nearly flat) and refusals; the file must stay empty.
TEST(ConvexHull, PrintsNothing) {
    TempDir dir;
    const std::string log = dir.file("output.txt");
    const int code = in_child([&] {
        const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        if (fd < 0 || ::dup2(fd, 1) < 0 || ::dup2(fd, 2) < 0) return 2;
        int refused = 0;
        for (const double thickness : {1e-3, 2e-4, 1e-5, 0.0}) {
            try {
                convex_hull(in_box(300, 13, {1.0, 1.0, thickness}, {}, 0.0));
                convex_hull(in_box(300, 13, {1.0, 1.0, thickness}, {}, 0.0), 300);
            } catch (const InputError&) {
                ++refused;
            }
        }
        try {
            convex_hull(std::vector<Vec3d>(3));
        } catch (const InputError&) {
            ++refused;
        }
        std::fflush(nullptr);
        return refused >= 2 ? 0 : 3;  // at least the flat slab and the three points
    });
    EXPECT_EQ(code, 0);
    EXPECT_EQ(read_text(log), "");
}

// --- Mass properties of a hull ----------------------------------------------------------------

// A box-shaped cloud (corners, points inside and on the faces) off the origin: its hull is the
// box, and its mass properties are Table 1's about the box's centre. Coordinates are doubles
// near 1, so only rounding remains: 1e-13.
TEST(ConvexHull, HullOfABoxCloudHasTable1MassProperties) {
    const Vec3d size{1.5, 0.5, 2.0};
    const Vec3d at{2.0, -1.0, 3.0};
    std::vector<Vec3d> points = in_box(300, 14, size, at);
    append(points, cube8(1.0, {}));
    for (Vec3d& p : std::span(points).last(8)) p = at + Vec3d{p.x * size.x, p.y * size.y, p.z * size.z};
    std::mt19937 rng(15);
    std::uniform_real_distribution<double> unit(-0.5, 0.5);
    for (int i = 0; i < 60; ++i) {  // on the faces
        Vec3d p{unit(rng), unit(rng), unit(rng)};
        p[i % 3] = i % 2 ? 0.5 : -0.5;
        points.push_back(at + Vec3d{p.x * size.x, p.y * size.y, p.z * size.z});
    }
    const ConvexHull hull = convex_hull(points);
    ASSERT_EQ(hull_fault(hull, points, points, 1e-12), "");
    EXPECT_EQ(hull.vertices.size(), 8u);
    const MassProperties m = mesh_mass_properties(hull.vertices, hull.triangles());
    const MassProperties box = box_mass_properties(size);
    EXPECT_NEAR(m.volume, box.volume, 1e-13 * box.volume);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(m.center[k], at[k], 1e-13 * 4.0);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(m.inertia.m[i][j], box.inertia.m[i][j], 1e-13 * box.inertia.m[2][2]);
    }
}

// --- A hull as a mesh -------------------------------------------------------------------------

TEST(ConvexHull, HullMeshIsFlatShadedAndClosed) {
    const ConvexHull cube = convex_hull(cube8(2.0));
    const Mesh mesh = hull_mesh(cube);
    EXPECT_EQ(mesh.source, "convex hull (8 vertices, 6 faces)");
    EXPECT_EQ(mesh.particle_count(), 8u);
    EXPECT_EQ(mesh.triangle_count(), 12u);
    // A normal slot per face at each of its corners (slots belong to particles): three at
    // each corner of the cube, every edge hard.
    EXPECT_EQ(mesh.normal_slot_count, 24u);

    // A 64-vertex hull of a sphere, whose faces meet at under 1 to 30 degrees (smooth by
    // build_mesh's 40-degree rule for a mesh without normals). Each corner's normal slot may
    // only join faces whose normals agree within build_mesh's 1 degree for file normals:
    // otherwise an edge would be drawn smooth.
    const ConvexHull round = convex_hull(on_sphere(2000, 16));
    const Mesh round_mesh = hull_mesh(round);
    std::vector<std::size_t> face_of_triangle;  // the faces' fans, in order
    for (std::size_t f = 0; f < round.faces.size(); ++f) {
        for (std::size_t k = 2; k < round.faces[f].vertices.size(); ++k) face_of_triangle.push_back(f);
    }
    ASSERT_EQ(face_of_triangle.size(), round_mesh.triangle_count());
    std::map<std::uint32_t, std::vector<std::size_t>> faces_of_slot;
    for (std::size_t t = 0; t < round_mesh.triangle_count(); ++t) {
        for (int c = 0; c < 3; ++c) {
            faces_of_slot[round_mesh.render_vertices[round_mesh.triangles[3 * t + c]].normal_slot].push_back(face_of_triangle[t]);
        }
    }
    for (const auto& [slot, faces] : faces_of_slot) {
        for (const std::size_t a : faces) {
            for (const std::size_t b : faces) {
                EXPECT_GE(dot(round.faces[a].normal, round.faces[b].normal), std::cos(1.1 * kPi / 180.0)) << "slot " << slot;
            }
        }
    }
    std::vector<Vec3d> corners;
    for (const Vec3& p : round_mesh.positions) corners.push_back(Vec3d(p));
    const std::vector<std::array<std::uint32_t, 3>> triangles = particle_triangles(round_mesh);
    EXPECT_TRUE(is_closed_oriented(triangles));
    const MassProperties a = mesh_mass_properties(corners, triangles);
    const MassProperties b = mesh_mass_properties(round.vertices, round.triangles());
    EXPECT_NEAR(a.volume, b.volume, 1e-6 * b.volume);
    EXPECT_REFUSED_NAMING(hull_mesh(ConvexHull{}), "hull mesh", "empty");
}

}  // namespace
}  // namespace softbody::test
