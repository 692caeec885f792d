// Collision geometry (collide.h, broad_phase.h) against closed forms: box on box, a box on its
// edge, crossed edges, spheres on faces, edges and corners, cylinders lying and standing, an
// icosahedron's hull, speculative contacts, feature ids, symmetry and rotation, particles
// against shapes, the broad phase against brute force, and the time of impact.
//
// Tolerances. Unless a test says otherwise, positions and depths are checked to kExact = 1e-12 m
// on bodies of about a metre: every number is a few dozen double operations on O(1) values
// (a rotation, a plane offset, a clip), each rounding by 1e-16 of 1, so the answers are right to
// about 1e-15; 1e-12 leaves a thousandfold room and is still a million times smaller than any
// depth or offset the tests use (1e-3 m and up), so a wrong point or depth cannot pass. Unit
// normals are checked to kExact too.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <memory>
#include <numeric>
#include <random>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "physics/broad_phase.h"
#include "physics/collide.h"
#include "physics/convex_hull.h"
#include "physics/rigid_body.h"
#include "test_shapes.h"
#include "test_support.h"

namespace softbody::test {
namespace {

constexpr double kExact = 1e-12;
const double kSqrt2 = std::sqrt(2.0), kSqrt3 = std::sqrt(3.0);
const Vec3d kUp{0.0, 0.0, 1.0};

// --- Shapes and poses ------------------------------------------------------------------------------

Pose at(const Vec3d& x, const Quat& q = {}) { return {x, q}; }

std::vector<ContactPoint> contacts(const CollisionShape& a, const Pose& pa, const CollisionShape& b, const Pose& pb,
                                   double margin = 0.0) {
    std::vector<ContactPoint> out;
    collide(a, pa, b, pb, margin, out);
    return out;
}

// The turn that takes unit vector `from` to unit vector `to`.
Quat turn_onto(const Vec3d& from, const Vec3d& to) {
    const Vec3d axis = cross(from, to);
    const double s = length(axis), c = dot(from, to);
    if (s < 1e-15) return c > 0.0 ? Quat{} : Quat::from_axis_angle(std::abs(from.x) < 0.9 ? normalize(cross(from, {1, 0, 0})) : normalize(cross(from, {0, 1, 0})), kPi);
    return Quat::from_axis_angle(axis / s, std::atan2(s, c));
}

Quat random_quat(std::mt19937& rng) {
    std::normal_distribution<double> g(0.0, 1.0);
    return Quat{g(rng), g(rng), g(rng), g(rng)}.normalized();
}

Vec3d random_vec(std::mt19937& rng, double scale) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    return Vec3d{u(rng), u(rng), u(rng)} * scale;
}

// Expects a contact at `point` (the one nearest to it), and returns its index.
std::size_t expect_point(const std::vector<ContactPoint>& cs, const Vec3d& point, double tolerance = kExact) {
    std::size_t nearest = 0;
    for (std::size_t i = 1; i < cs.size(); ++i) {
        if (length(cs[i].point - point) < length(cs[nearest].point - point)) nearest = i;
    }
    EXPECT_FALSE(cs.empty());
    if (cs.empty()) return 0;
    EXPECT_NEAR(length(cs[nearest].point - point), 0.0, tolerance)
        << "no contact at (" << point.x << ", " << point.y << ", " << point.z << ")";
    return nearest;
}

void expect_all(const std::vector<ContactPoint>& cs, const Vec3d& normal, double depth) {
    for (const ContactPoint& c : cs) {
        EXPECT_NEAR(length(c.normal - normal), 0.0, kExact);
        EXPECT_NEAR(c.depth, depth, kExact);
    }
}

// --- Two boxes -------------------------------------------------------------------------------------

// A unit cube on a 4 x 4 x 1 slab, turned 30 degrees about the vertical and sunk by delta: the
// overlap is the cube's whole footprint, so the manifold is its four bottom corners, each delta
// deep, midway between the surfaces (z = 0.5 - delta / 2), the normal straight up.
TEST(CollideBoxes, FaceOnFaceGivesFourCornersAtExactDepth) {
    const double delta = 0.01;
    const CollisionShape cube = box({1, 1, 1}), slab = box({4, 4, 1});
    const Pose top = at({0.3, -0.2, 1.0 - delta}, turn(kUp, 30.0));
    const auto cs = contacts(cube, top, slab, at({}));
    ASSERT_EQ(cs.size(), 4u);
    expect_all(cs, kUp, delta);
    const Mat3 R = top.q.to_matrix();
    for (const double sx : {-0.5, 0.5}) {
        for (const double sy : {-0.5, 0.5}) {
            const Vec3d corner = top.x + R * Vec3d{sx, sy, -0.5};
            expect_point(cs, {corner.x, corner.y, 0.5 - 0.5 * delta});
        }
    }
    for (const ContactPoint& c : cs) {
        // Inside the overlap rectangle: the cube's footprint (in its axes) and the slab's top.
        const Vec3d local = R.transposed() * (c.point - top.x);
        EXPECT_LE(std::abs(local.x), 0.5 + kExact);
        EXPECT_LE(std::abs(local.y), 0.5 + kExact);
        EXPECT_LE(std::abs(c.point.x), 2.0);
        EXPECT_LE(std::abs(c.point.y), 2.0);
    }
}

// Half over the slab's edge: the overlap is x in [1.3, 2], y in [-0.5, 0.5], and the manifold
// is exactly its corners, whichever face is the reference.
TEST(CollideBoxes, OverhangGivesTheOverlapRectangle) {
    const double delta = 0.004;
    const CollisionShape cube = box({1, 1, 1}), slab = box({4, 4, 1});
    for (const bool swapped : {false, true}) {
        const Pose pc = at({1.8, 0.0, 1.0 - delta}), ps = at({});
        const auto cs = swapped ? contacts(slab, ps, cube, pc) : contacts(cube, pc, slab, ps);
        ASSERT_EQ(cs.size(), 4u);
        expect_all(cs, swapped ? -kUp : kUp, delta);
        for (const double x : {1.3, 2.0}) {
            for (const double y : {-0.5, 0.5}) expect_point(cs, {x, y, 0.5 - 0.5 * delta});
        }
    }
}

// A cube turned 30 degrees about x stands on its lowest edge: corners (+-0.5, -0.5, -0.5) turn
// to y' = -(cos 30 - sin 30) / 2, z' = -(sin 30 + cos 30) / 2. Two points, the edge's ends.
TEST(CollideBoxes, TiltedBoxOnItsEdgeGivesTheEdgesEnds) {
    const double delta = 0.002;
    const double c30 = std::cos(kPi / 6), s30 = std::sin(kPi / 6);
    const double y_edge = -(c30 - s30) / 2, z_edge = -(s30 + c30) / 2;
    const CollisionShape cube = box({1, 1, 1}), slab = box({4, 4, 1});
    const Pose top = at({0.1, 0.2, 0.5 - z_edge - delta}, turn({1, 0, 0}, 30.0));
    const auto cs = contacts(cube, top, slab, at({}));
    ASSERT_EQ(cs.size(), 2u);
    expect_all(cs, kUp, delta);
    expect_point(cs, {0.1 - 0.5, 0.2 + y_edge, 0.5 - 0.5 * delta});
    expect_point(cs, {0.1 + 0.5, 0.2 + y_edge, 0.5 - 0.5 * delta});
}

// A plank lying across the top edge of a cube turned 45 degrees about x (its top edge along x
// at z = sqrt(2)/2): two points where that edge meets the plank's underside, at x = +-0.5.
TEST(CollideBoxes, PlankAcrossABoxEdge) {
    const double delta = 0.003;
    const CollisionShape plank = box({2, 0.4, 0.2}), cube = box({1, 1, 1});
    const auto cs = contacts(plank, at({0, 0, kSqrt2 / 2 + 0.1 - delta}), cube, at({}, turn({1, 0, 0}, 45.0)));
    ASSERT_EQ(cs.size(), 2u);
    expect_all(cs, kUp, delta);
    expect_point(cs, {-0.5, 0, kSqrt2 / 2 - 0.5 * delta});
    expect_point(cs, {0.5, 0, kSqrt2 / 2 - 0.5 * delta});
}

// Crossed edges: a cube turned 45 degrees about x (bottom edge along x, y = 0.1) over one turned
// 45 degrees about y (top edge along y, x = 0.2). One point, midway between the edges' closest
// points (0.2, 0.1, sqrt(2)/2 - delta) and (0.2, 0.1, sqrt(2)/2); depth delta.
TEST(CollideBoxes, CrossedEdgesGiveOnePointAtTheClosestPointsDepth) {
    const double delta = 0.005;
    const CollisionShape cube = box({1, 1, 1});
    const auto cs = contacts(cube, at({0, 0.1, kSqrt2 - delta}, turn({1, 0, 0}, 45.0)), cube,
                             at({0.2, 0, 0}, turn({0, 1, 0}, 45.0)));
    ASSERT_EQ(cs.size(), 1u);
    expect_all(cs, kUp, delta);
    expect_point(cs, {0.2, 0.1, kSqrt2 / 2 - 0.5 * delta});
}

// Apart, the nearest points of two crossed edges' lines can lie beyond an edge's end: the
// lower cube's top edge at x = 0.52 passes beyond the upper one's bottom edge, which ends at
// x = 0.5. The separating axis is still the edges' (up, gap 0.2); the point is midway between
// the edges' nearest points, the upper edge's end (0.5, 0.1) and (0.52, 0.1) on the lower.
TEST(CollideBoxes, SpeculativeEdgesNearestPointsStayOnTheEdges) {
    const CollisionShape cube = box({1, 1, 1});
    const auto cs = contacts(cube, at({0, 0.1, kSqrt2 + 0.2}, turn({1, 0, 0}, 45.0)), cube,
                             at({0.52, 0, 0}, turn({0, 1, 0}, 45.0)), 0.5);
    ASSERT_EQ(cs.size(), 1u);
    expect_all(cs, kUp, -0.2);
    expect_point(cs, {0.51, 0.1, kSqrt2 / 2 + 0.1});
    // Beyond either end, and the other way round (the clamped edge is then b's).
    for (const double x : {-0.52, 0.52}) {
        const Pose upper = at({0, 0.1, kSqrt2 + 0.2}, turn({1, 0, 0}, 45.0)), lower = at({x, 0, 0}, turn({0, 1, 0}, 45.0));
        const Vec3d midway{x > 0 ? 0.51 : -0.51, 0.1, kSqrt2 / 2 + 0.1};
        const auto ab = contacts(cube, upper, cube, lower, 0.5), ba = contacts(cube, lower, cube, upper, 0.5);
        ASSERT_EQ(ab.size(), 1u);
        ASSERT_EQ(ba.size(), 1u);
        expect_all(ab, kUp, -0.2);
        expect_all(ba, -kUp, -0.2);
        expect_point(ab, midway);
        expect_point(ba, midway);
    }
}

// Corner over corner: the same cubes placed so that the lower one's top corner lies exactly on
// a side plane of the upper one's face. Clipping yields that corner and the two cuts beside it,
// all one point but for rounding: one contact, not three.
TEST(CollideBoxes, PointsThatCoincideAreOne) {
    const CollisionShape cube = box({1, 1, 1});
    const auto cs = contacts(cube, at({0, 0.1, kSqrt2 + 0.05}, turn({1, 0, 0}, 45.0)), cube,
                             at({0.55, 0, 0}, turn({0, 1, 0}, 45.0)), 0.5);
    ASSERT_EQ(cs.size(), 1u);
    EXPECT_NEAR(cs[0].depth, -0.05 * kSqrt2, kExact);  // the gap along the face's normal (-1, 0, 1)/sqrt(2)
    EXPECT_NEAR(length(cs[0].normal - Vec3d{-1, 0, 1} / kSqrt2), 0.0, kExact);
}

// --- Spheres ----------------------------------------------------------------------------------------

// A ball of radius r = 0.25 sunk by delta into each of a unit cube's 26 features (6 faces, 12
// edges, 8 corners; the direction d in {-1, 0, 1}^3 names one, with a point on it at 0.5 d where
// d is not 0 and off-centre (0.1, -0.2, 0.15) where it is): the normal is d / |d|, the depth
// r - distance. Every feature gets its own id.
TEST(CollideSpheres, OnEachFaceEdgeAndCornerOfABox) {
    const double r = 0.25, delta = 0.01;
    const CollisionShape cube = box({1, 1, 1}), b = ball(r);
    const Vec3d off{0.1, -0.2, 0.15};
    std::vector<std::uint32_t> features;
    for (int i = 0; i < 27; ++i) {
        const Vec3d d{double(i % 3 - 1), double(i / 3 % 3 - 1), double(i / 9 - 1)};
        if (d == Vec3d{}) continue;
        Vec3d feature;
        for (int k = 0; k < 3; ++k) feature[k] = d[k] != 0.0 ? 0.5 * d[k] : off[k];
        const Vec3d n = normalize(d);
        const Vec3d centre = feature + n * (r - delta);
        const auto cs = contacts(b, at(centre), cube, at({}));
        ASSERT_EQ(cs.size(), 1u);
        expect_all(cs, n, delta);
        expect_point(cs, feature + n * (-0.5 * delta));
        features.push_back(cs[0].feature);
        // And the other way round: the normal flips, nothing else changes.
        const auto sc = contacts(cube, at({}), b, at(centre));
        ASSERT_EQ(sc.size(), 1u);
        expect_all(sc, -n, delta);
        expect_point(sc, feature + n * (-0.5 * delta));
    }
    std::sort(features.begin(), features.end());
    EXPECT_EQ(std::adjacent_find(features.begin(), features.end()), features.end());
}

// A ball of radius 0.3 whose centre is inside a 2 m cube, 0.3 below its top face (the nearest):
// out through the top, depth r + 0.3, the point midway between the top face (z = 1) and the
// ball's far side (z = 0.4).
TEST(CollideSpheres, CentreInsideABoxGoesOutThroughTheNearestFace) {
    const CollisionShape cube = box({2, 2, 2}), b = ball(0.3);
    const auto cs = contacts(b, at({0.2, 0.1, 0.7}), cube, at({}));
    ASSERT_EQ(cs.size(), 1u);
    expect_all(cs, kUp, 0.6);
    expect_point(cs, {0.2, 0.1, 0.7});
}

TEST(CollideSpheres, SphereOnSphere) {
    const double ra = 0.3, rb = 0.5, distance = 0.7;  // depth 0.1
    const Vec3d n = Vec3d{1, 2, 2} / 3.0, cb{0.1, -0.4, 2.0};
    const auto cs = contacts(ball(ra), at(cb + n * distance), ball(rb), at(cb));
    ASSERT_EQ(cs.size(), 1u);
    expect_all(cs, n, 0.1);
    expect_point(cs, cb + n * (rb - 0.05));
}

// --- Cylinders and a mesh hull ------------------------------------------------------------------------

// A cylinder (r 0.5, length 2) lying along x: its prism has a corner line at angle 0, which
// the turn about y puts at the bottom, so it touches along a line: two points, its ends.
TEST(CollideHulls, CylinderLyingOnABoxTouchesAlongALine) {
    const double r = 0.5, delta = 0.001;
    const auto cs = contacts(cylinder(r, 2.0), at({0.3, 0.4, 0.5 + r - delta}, turn({0, 1, 0}, 90.0)), box({4, 4, 1}),
                             at({}));
    ASSERT_EQ(cs.size(), 2u);
    expect_all(cs, kUp, delta);
    expect_point(cs, {0.3 - 1.0, 0.4, 0.5 - 0.5 * delta});
    expect_point(cs, {0.3 + 1.0, 0.4, 0.5 - 0.5 * delta});
}

// Standing on its cap on a wider slab: the 32 rim corners are all delta deep; the manifold
// keeps four of them, on the rim (distance r from the axis) and spread as the inscribed square
// (area 2 r^2), the most four points of a 32-gon can span.
TEST(CollideHulls, CylinderStandingGivesFourRimPoints) {
    const double r = 0.5, h = 1.0, delta = 0.002;
    const Vec3d axis{0.2, -0.1, 0.0};
    for (const bool swapped : {false, true}) {
        const Pose pc = at(axis + Vec3d{0, 0, 0.5 + 0.5 * h - delta}), ps = at({});
        const auto cs = swapped ? contacts(box({4, 4, 1}), ps, cylinder(r, h), pc) : contacts(cylinder(r, h), pc, box({4, 4, 1}), ps);
        ASSERT_EQ(cs.size(), 4u);
        expect_all(cs, swapped ? -kUp : kUp, delta);
        for (const ContactPoint& c : cs) {
            EXPECT_NEAR(std::hypot(c.point.x - axis.x, c.point.y - axis.y), r, kExact);
            EXPECT_NEAR(c.point.z, 0.5 - 0.5 * delta, kExact);
        }
        // The area of the quadrilateral (its points sorted by angle about the axis).
        std::vector<Vec3d> p;
        for (const ContactPoint& c : cs) p.push_back(c.point - axis);
        std::sort(p.begin(), p.end(), [](const Vec3d& u, const Vec3d& v) { return std::atan2(u.y, u.x) < std::atan2(v.y, v.x); });
        double area = 0.0;
        for (std::size_t i = 0; i < 4; ++i) area += 0.5 * (p[i].x * p[(i + 1) % 4].y - p[(i + 1) % 4].x * p[i].y);
        EXPECT_NEAR(area, 2.0 * r * r, 1e-9);
    }
}

// Hanging over the slab's edge (x > 2 is off it), the manifold stays on the part of the cap
// over the slab, every point within both the cap's disc and the slab's top, and spans it: its
// four points enclose more than half of that part's area (r^2 (pi - acos(0.4)) + 0.2 sqrt(r^2
// - 0.04) = 0.587 m^2 for the disc; a quadrilateral can cover at most 2 / pi of a whole disc,
// so half is a fair share, and four points bunched on one side would fall far below it).
TEST(CollideHulls, CylinderOverAnEdgeKeepsToTheOverlap) {
    const double r = 0.5, delta = 0.002;
    const Vec3d axis{1.8, 0.0, 1.0 - delta};
    const auto cs = contacts(cylinder(r, 1.0), at(axis), box({4, 4, 1}), at({}));
    ASSERT_EQ(cs.size(), 4u);
    expect_all(cs, kUp, delta);
    Vec3d centre;
    for (const ContactPoint& c : cs) {
        EXPECT_LE(std::hypot(c.point.x - axis.x, c.point.y - axis.y), r + kExact);
        EXPECT_LE(c.point.x, 2.0 + kExact);
        centre += c.point * 0.25;
    }
    std::vector<Vec3d> p;
    for (const ContactPoint& c : cs) p.push_back(c.point - centre);
    std::sort(p.begin(), p.end(), [](const Vec3d& u, const Vec3d& v) { return std::atan2(u.y, u.x) < std::atan2(v.y, v.x); });
    double area = 0.0;
    for (std::size_t i = 0; i < 4; ++i) area += 0.5 * (p[i].x * p[(i + 1) % 4].y - p[(i + 1) % 4].x * p[i].y);
    const double overlap = r * r * (kPi - std::acos(0.2 / r)) + 0.2 * std::sqrt(r * r - 0.04);
    EXPECT_GT(area, 0.5 * overlap);
}

// The regular icosahedron (0, +-1, +-phi) and its cyclic permutations, scaled by 0.1, as a
// mesh body: a file on disk, loaded, hulled and centred as the world does it.
struct Icosahedron {
    RigidBody body;
    CollisionShape shape;
};

Icosahedron icosahedron(const TempDir& dir) {
    const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Vec3d> v;
    for (const double a : {-1.0, 1.0}) {
        for (const double b : {-phi, phi}) {
            v.push_back({0, a, b});
            v.push_back({a, b, 0});
            v.push_back({b, 0, a});
        }
    }
    std::string obj;
    for (const Vec3d& p : v) obj += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    for (const auto& t : convex_hull(v).triangles()) {
        obj += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
    }
    RigidBodyDef def;
    def.name = "die";
    def.shape = ShapeKind::Mesh;
    def.mesh = dir.write("icosahedron.obj", obj);
    def.scale = 0.1;
    Icosahedron out{make_rigid_body(def), {}};
    out.shape = collision_shape(out.body);
    return out;
}

TEST(CollideHulls, IcosahedronOnABox) {
    const TempDir dir;
    const Icosahedron die = icosahedron(dir);
    const ConvexHull& hull = *die.shape.hull;
    ASSERT_EQ(hull.vertices.size(), 12u);
    ASSERT_EQ(hull.faces.size(), 20u);
    // Its inradius is phi^2 / sqrt(3) times the scale (edge 2 before scaling); the file holds
    // six digits, so the hull matches it to about 1e-6 of its size.
    const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
    EXPECT_NEAR(hull.faces[0].offset, 0.1 * phi * phi / kSqrt3, 1e-6);
    const double delta = 0.001;
    const CollisionShape slab = box({4, 4, 1});
    // On a face: the face's three corners, delta deep.
    const ConvexHull::Face& face = hull.faces[7];
    const Quat q = turn_onto(face.normal, -kUp);
    const Pose pose = at({0.2, 0.3, 0.5 + face.offset - delta}, q);
    const auto cs = contacts(die.shape, pose, slab, at({}));
    ASSERT_EQ(cs.size(), 3u);
    expect_all(cs, kUp, delta);
    for (const std::uint32_t i : face.vertices) {
        const Vec3d corner = pose.x + q.to_matrix() * hull.vertices[i];
        EXPECT_NEAR(corner.z, 0.5 - delta, kExact);
        expect_point(cs, corner + kUp * (0.5 * delta));
    }
    // On a corner: one point at it.
    const Vec3d v = hull.vertices[3];
    const Quat qv = turn_onto(normalize(v), -kUp);
    const Pose pv = at({0.2, 0.3, 0.5 + length(v) - delta}, qv);
    const auto cv = contacts(die.shape, pv, slab, at({}));
    ASSERT_EQ(cv.size(), 1u);
    expect_all(cv, kUp, delta);
    expect_point(cv, {0.2, 0.3, 0.5 - 0.5 * delta});
}

// --- Speculative contacts and the margin ---------------------------------------------------------------

// Each pair apart by a known gap g: with a margin above g, contacts of depth -g along the
// separating axis; with a margin a nanometre short of g, none.
struct GapCase {
    std::string name;
    CollisionShape a, b;
    Pose pa, pb;
    double gap;
    std::size_t points;
    Vec3d normal;
};

std::vector<GapCase> gap_cases() {
    const double g = 0.01;
    const CollisionShape cube = box({1, 1, 1});
    return {
        {"face on face", cube, box({4, 4, 1}), at({0.3, 0.1, 1.0 + g}, turn(kUp, 20.0)), at({}), g, 4, kUp},
        {"crossed edges", cube, cube, at({0, 0.1, kSqrt2 + g}, turn({1, 0, 0}, 45.0)), at({0.2, 0, 0}, turn({0, 1, 0}, 45.0)), g, 1, kUp},
        {"ball over a corner", ball(0.25), cube, at(Vec3d{0.5, 0.5, 0.5} + Vec3d{1, 1, 1} / kSqrt3 * (0.25 + g)), at({}), g, 1,
         Vec3d{1, 1, 1} / kSqrt3},
        {"two balls", ball(0.3), ball(0.2), at({0, 0, 0.5 + g}), at({}), g, 1, kUp},
        // A 5 cm ball 0.3 m above a 2 cm plank, falling at 20 m/s: 0.4 m in a 0.02 s step. The gap,
        // 0.3 - 0.025 - 0.01, is what the solver lets it close in one step.
        {"fast ball over a plank", ball(0.025), box({1, 1, 0.02}), at({0, 0, 0.3}), at({}), 0.265, 1, kUp},
    };
}

TEST(CollideMargin, SpeculativeContactsCarryTheGap) {
    for (const GapCase& k : gap_cases()) {
        const auto cs = contacts(k.a, k.pa, k.b, k.pb, k.gap + 0.4);
        ASSERT_EQ(cs.size(), k.points) << k.name;
        expect_all(cs, k.normal, -k.gap);
    }
}

TEST(CollideMargin, NothingBeyondTheMargin) {
    for (const GapCase& k : gap_cases()) {
        EXPECT_TRUE(contacts(k.a, k.pa, k.b, k.pb, k.gap - 1e-9).empty()) << k.name;
        EXPECT_FALSE(contacts(k.a, k.pa, k.b, k.pb, k.gap + 1e-9).empty()) << k.name;
    }
}

// Two cubes corner to corner along their diagonal, s apart on each axis: the true gap is
// s sqrt(3), but the separating axes see s (a face's). Within a margin of s, one speculative
// point from the nearest corner, its gap along that face's normal: conservative, it lets the
// pair close by s this step and no more.
TEST(CollideMargin, CornerToCornerGivesTheAxisGap) {
    const double s = 0.02;
    const CollisionShape cube = box({1, 1, 1});
    const auto cs = contacts(cube, at({}), cube, at({1 + s, 1 + s, 1 + s}), 0.05);
    ASSERT_EQ(cs.size(), 1u);
    EXPECT_NEAR(cs[0].depth, -s, kExact);
    EXPECT_NEAR(std::min({cs[0].normal.x, cs[0].normal.y, cs[0].normal.z}), -1.0, kExact);  // -x, -y or -z
    EXPECT_NEAR(separation_bound(cube, at({}), cube, at({1 + s, 1 + s, 1 + s})), s, kExact);
}

// --- Feature ids, symmetry, rotation --------------------------------------------------------------------

struct Scenario {
    std::string name;
    CollisionShape a, b;
    Pose pa, pb;
    double margin = 0.0;
    bool same_points_swapped = true;  // the same manifold whichever body is a
};

std::vector<Scenario> scenarios() {
    const CollisionShape cube = box({1, 1, 1}), slab = box({4, 4, 1});
    const double c30 = std::cos(kPi / 6), s30 = std::sin(kPi / 6);
    return {
        {"face on face", cube, slab, at({0.3, -0.2, 0.99}, turn(kUp, 30.0)), at({}), 0.0, true},
        {"overhang", cube, slab, at({1.8, 0.0, 0.996}), at({}), 0.0, true},
        {"tilted on an edge", cube, slab, at({0.1, 0.2, 0.5 + (s30 + c30) / 2 - 0.002}, turn({1, 0, 0}, 30.0)), at({}), 0.0, true},
        {"crossed edges", cube, cube, at({0, 0.1, kSqrt2 - 0.005}, turn({1, 0, 0}, 45.0)), at({0.2, 0, 0}, turn({0, 1, 0}, 45.0)), 0.0, true},
        {"ball on an edge", ball(0.25), cube, at(Vec3d{0.1, 0.5, 0.5} + Vec3d{0, 1, 1} / kSqrt2 * 0.24), at({}), 0.0, true},
        {"cylinder lying", cylinder(0.5, 2.0), slab, at({0.3, 0.4, 0.999}, turn({0, 1, 0}, 90.0)), at({}), 0.0, true},
        // Standing, the reference face is the cap one way and the slab the other; the four rim
        // points kept then start from different corners.
        {"cylinder standing", cylinder(0.5, 1.0), slab, at({0.2, -0.1, 0.998}), at({}), 0.0, false},
        {"face on face, speculative", cube, slab, at({0.3, -0.2, 1.01}, turn(kUp, 30.0)), at({}), 0.02, true},
    };
}

std::vector<std::uint32_t> features_of(const std::vector<ContactPoint>& cs) {
    std::vector<std::uint32_t> f;
    for (const ContactPoint& c : cs) f.push_back(c.feature);
    std::sort(f.begin(), f.end());
    return f;
}

// A nudge of a micrometre and a microradian (a resting body's jitter is far larger) leaves every
// id as it was; within a manifold, no two points share an id.
TEST(CollideFeatures, StableUnderATinyPoseChangeAndDistinct) {
    std::mt19937 rng(7);
    for (const Scenario& s : scenarios()) {
        const auto cs = contacts(s.a, s.pa, s.b, s.pb, s.margin);
        ASSERT_FALSE(cs.empty()) << s.name;
        const std::vector<std::uint32_t> f = features_of(cs);
        EXPECT_EQ(std::adjacent_find(f.begin(), f.end()), f.end()) << s.name << ": two points share an id";
        for (int trial = 0; trial < 20; ++trial) {
            Pose nudged = s.pa;
            nudged.x += random_vec(rng, 1e-6);
            nudged.q = Quat::from_axis_angle(normalize(random_vec(rng, 1.0)), 1e-6) * nudged.q;
            EXPECT_EQ(features_of(contacts(s.a, nudged, s.b, s.pb, s.margin)), f) << s.name << ", trial " << trial;
        }
    }
}

// The same places touched by different features get different ids: the cube turned a quarter
// turn about the vertical puts other corners on the same four points.
TEST(CollideFeatures, DifferentFeaturesDifferentIds) {
    const CollisionShape cube = box({1, 1, 1}), slab = box({4, 4, 1});
    const auto first = contacts(cube, at({0, 0, 0.99}, turn(kUp, 30.0)), slab, at({}));
    const auto turned = contacts(cube, at({0, 0, 0.99}, turn(kUp, 120.0)), slab, at({}));
    ASSERT_EQ(first.size(), 4u);
    ASSERT_EQ(turned.size(), 4u);
    for (const ContactPoint& c : first) {
        const std::size_t i = expect_point(turned, c.point);
        EXPECT_NE(turned[i].feature, c.feature);
    }
    // And a face contact, an edge contact and a sphere's never share ids with one another here.
    const auto edge = contacts(cube, at({0, 0.1, kSqrt2 - 0.005}, turn({1, 0, 0}, 45.0)), cube, at({0.2, 0, 0}, turn({0, 1, 0}, 45.0)));
    const auto sphere = contacts(ball(0.25), at({0, 0, 0.74}), cube, at({}));
    ASSERT_EQ(edge.size(), 1u);
    ASSERT_EQ(sphere.size(), 1u);
    for (const ContactPoint& c : first) {
        EXPECT_NE(c.feature, edge[0].feature);
        EXPECT_NE(c.feature, sphere[0].feature);
    }
}

// Swapping a and b flips the normal; the depths stay, and so do the points where the manifold
// does not depend on which face is the reference.
TEST(CollideSymmetry, SwappingFlipsTheNormal) {
    for (const Scenario& s : scenarios()) {
        const auto ab = contacts(s.a, s.pa, s.b, s.pb, s.margin);
        const auto ba = contacts(s.b, s.pb, s.a, s.pa, s.margin);
        ASSERT_EQ(ab.size(), ba.size()) << s.name;
        std::vector<double> da, db;
        for (std::size_t i = 0; i < ab.size(); ++i) {
            EXPECT_NEAR(length(ab[i].normal + ba[0].normal), 0.0, kExact) << s.name;
            da.push_back(ab[i].depth);
            db.push_back(ba[i].depth);
            if (s.same_points_swapped) expect_point(ba, ab[i].point);
        }
        std::sort(da.begin(), da.end());
        std::sort(db.begin(), db.end());
        for (std::size_t i = 0; i < da.size(); ++i) EXPECT_NEAR(da[i], db[i], kExact) << s.name;
    }
}

// Moving and turning both bodies together by a random rigid motion moves and turns the answer:
// points and normals with it, depths and ids unchanged. The tolerance is relative to the
// 10 m the scene moves: 1e-12 of it.
TEST(CollideSymmetry, ResultsTurnWithTheBodies) {
    std::mt19937 rng(11);
    for (const Scenario& s : scenarios()) {
        auto base = contacts(s.a, s.pa, s.b, s.pb, s.margin);
        std::sort(base.begin(), base.end(), [](const ContactPoint& u, const ContactPoint& v) { return u.feature < v.feature; });
        for (int trial = 0; trial < 20; ++trial) {
            const Quat Q = random_quat(rng);
            const Vec3d shift = random_vec(rng, 10.0);
            const Mat3 R = Q.to_matrix();
            const auto move = [&](const Pose& p) { return Pose{R * p.x + shift, Q * p.q}; };
            auto moved = contacts(s.a, move(s.pa), s.b, move(s.pb), s.margin);
            std::sort(moved.begin(), moved.end(), [](const ContactPoint& u, const ContactPoint& v) { return u.feature < v.feature; });
            ASSERT_EQ(moved.size(), base.size()) << s.name;
            for (std::size_t i = 0; i < base.size(); ++i) {
                EXPECT_EQ(moved[i].feature, base[i].feature) << s.name;
                EXPECT_NEAR(length(moved[i].point - (R * base[i].point + shift)), 0.0, 1e-11) << s.name;
                EXPECT_NEAR(length(moved[i].normal - R * base[i].normal), 0.0, kExact) << s.name;
                EXPECT_NEAR(moved[i].depth, base[i].depth, 1e-11) << s.name;
            }
        }
    }
}

// --- The separating axes themselves ----------------------------------------------------------------------

// Random hulls at random poses against a brute-force test of every face normal and every edge
// pair's cross product. Overlapping, the Minkowski-face pruning must find the same largest
// separation (the penetration depth is attained on a face of the Minkowski difference);
// apart, it may find less (a lower bound), but still above zero.
TEST(CollideAxes, PrunedEdgeTestAgreesWithBruteForce) {
    std::mt19937 rng(3);
    const auto hull_of = [&](std::uint32_t seed) {
        std::vector<Vec3d> p;
        for (const Vec3& v : random_cloud(24, seed, 0.5f)) p.push_back(Vec3d(v));
        return hull_shape(std::make_shared<const ConvexHull>(convex_hull(p)));
    };
    const auto brute = [](const CollisionShape& a, const Pose& pa, const CollisionShape& b, const Pose& pb) {
        const Mat3 Ra = pa.q.to_matrix(), Rb = pb.q.to_matrix();
        std::vector<Vec3d> va, vb, axes;
        for (const Vec3d& v : a.hull->vertices) va.push_back(pa.x + Ra * v);
        for (const Vec3d& v : b.hull->vertices) vb.push_back(pb.x + Rb * v);
        for (const auto& f : a.hull->faces) axes.push_back(Ra * f.normal);
        for (const auto& f : b.hull->faces) axes.push_back(Rb * f.normal);
        for (const auto& ea : a.hull->edges) {
            for (const auto& eb : b.hull->edges) {
                const Vec3d u = cross(va[ea[1]] - va[ea[0]], vb[eb[1]] - vb[eb[0]]);
                if (length(u) > 1e-9) axes.push_back(normalize(u));
            }
        }
        double best = -1e300;
        for (const Vec3d& u : axes) {
            double lo_a = 1e300, hi_a = -1e300, lo_b = 1e300, hi_b = -1e300;
            for (const Vec3d& v : va) lo_a = std::min(lo_a, dot(u, v)), hi_a = std::max(hi_a, dot(u, v));
            for (const Vec3d& v : vb) lo_b = std::min(lo_b, dot(u, v)), hi_b = std::max(hi_b, dot(u, v));
            best = std::max(best, std::max(lo_b - hi_a, lo_a - hi_b));
        }
        return best;
    };
    int overlapping = 0, apart = 0;
    for (std::uint32_t trial = 0; trial < 60; ++trial) {
        const CollisionShape a = hull_of(100 + trial), b = hull_of(200 + trial);
        Pose pa, pb;
        pa.x = random_vec(rng, 0.1);
        pa.q = random_quat(rng);
        pb.x = random_vec(rng, 0.6);
        pb.q = random_quat(rng);
        const double pruned = separation_bound(a, pa, b, pb), full = brute(a, pa, b, pb);
        if (full < 0.0) {
            ++overlapping;
            EXPECT_NEAR(pruned, full, kExact) << "trial " << trial;
        } else {
            ++apart;
            EXPECT_LE(pruned, full + kExact) << "trial " << trial;
            EXPECT_GT(pruned, 0.0) << "trial " << trial;
        }
    }
    EXPECT_GT(overlapping, 15);  // both kinds were tried
    EXPECT_GT(apart, 5);
}

TEST(CollideAxes, SeparationBoundClosedForms) {
    const CollisionShape cube = box({1, 1, 1});
    EXPECT_NEAR(separation_bound(cube, at({0, 0, 1.03}), cube, at({})), 0.03, kExact);
    EXPECT_NEAR(separation_bound(cube, at({0.2, 0, 0.96}), cube, at({})), -0.04, kExact);
    EXPECT_NEAR(separation_bound(ball(0.5), at({3, 4, 0}), ball(1.0), at({})), 3.5, kExact);
    // A ball off a corner: exact, the distance to the corner less the radius.
    EXPECT_NEAR(separation_bound(ball(0.1), at({1, 1, 1}), cube, at({})), kSqrt3 / 2 - 0.1, kExact);
}

// Each edge of a box's hull knows its two faces: the one whose loop runs v0 -> v1 and the one
// running back, both at right angles to the edge.
TEST(CollisionShapes, HullEdgesKnowTheirFaces) {
    const CollisionShape cube = box({1, 2, 3});
    ASSERT_EQ(cube.edges.size(), 12u);
    EXPECT_NEAR(cube.bounding_radius, std::sqrt(0.25 + 1 + 2.25), kExact);
    for (const HullEdge& e : cube.edges) {
        for (int side = 0; side < 2; ++side) {
            const auto& loop = cube.hull->faces[e.faces[side]].vertices;
            const std::uint32_t from = e.vertices[side], to = e.vertices[1 - side];
            bool found = false;
            for (std::size_t k = 0; k < loop.size(); ++k) found |= loop[k] == from && loop[(k + 1) % loop.size()] == to;
            EXPECT_TRUE(found);
            const Vec3d d = cube.hull->vertices[e.vertices[1]] - cube.hull->vertices[e.vertices[0]];
            EXPECT_NEAR(dot(d, cube.hull->faces[e.faces[side]].normal), 0.0, kExact);
        }
    }
    ConvexHull broken = *cube.hull;
    broken.faces.pop_back();
    EXPECT_THROW(hull_shape(std::make_shared<const ConvexHull>(broken)), std::invalid_argument);
    EXPECT_TRUE(ball(0.3).is_sphere());
    EXPECT_EQ(ball(0.3).bounding_radius, 0.3);
}

// How far a hull may turn between two finds of its contacts: half the least angle between two
// neighbouring faces' normals, within [kLeastContactTurn, kMostContactTurn]. A prism of N sides
// has its sides 2 pi / N apart (and each at pi/2 to the caps): pi / N, so 8 and 12 sides are held
// to the most, 16 and 24 sides get their own, 32 sides (a cylinder's) the least. A box's
// faces are pi/2 apart, an icosahedron's 0.73 rad: both the most. A ball is never asked.
TEST(CollisionShapes, ContactTurnIsHalfTheAngleBetweenNeighbouringFaces) {
    const auto prism = [](int sides) {
        std::vector<Vec3d> p;
        for (int k = 0; k < sides; ++k) {
            const double a = 2.0 * kPi * k / sides;
            for (const double z : {-0.1, 0.1}) p.push_back({0.1 * std::cos(a), 0.1 * std::sin(a), z});
        }
        return hull_shape(std::make_shared<const ConvexHull>(convex_hull(p)));
    };
    for (const int sides : {8, 12, 16, 24, 32}) {
        const CollisionShape shape = prism(sides);
        ASSERT_EQ(shape.hull->faces.size(), std::size_t(sides + 2));
        EXPECT_NEAR(shape.contact_turn, std::clamp(kPi / sides, kLeastContactTurn, kMostContactTurn), 1e-12) << sides << " sides";
    }
    EXPECT_EQ(box({1, 2, 3}).contact_turn, kMostContactTurn);
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;  // the golden ratio: an icosahedron's corners
    std::vector<Vec3d> ico;
    for (const double a : {-1.0, 1.0}) {
        for (const double b : {-t, t}) ico.insert(ico.end(), {Vec3d{0, a, b}, Vec3d{a, b, 0}, Vec3d{b, 0, a}});
    }
    const CollisionShape icosahedron = hull_shape(std::make_shared<const ConvexHull>(convex_hull(ico)));
    ASSERT_EQ(icosahedron.hull->faces.size(), 20u);
    EXPECT_EQ(icosahedron.contact_turn, kMostContactTurn);
}

// --- Particles: a point and a segment against a shape ---------------------------------------------------

// A box 1 x 2 x 3, turned and moved. Body coordinates make the answers closed forms.
TEST(PointContact, InsideABoxGoesOutThroughTheNearestFace) {
    const CollisionShape b = box({1, 2, 3});
    const Pose pose = at({1, -2, 0.5}, turn({1, 2, 3}, 40.0));
    const Mat3 R = pose.q.to_matrix();
    const auto world = [&](const Vec3d& p) { return pose.x + R * p; };
    // 0.2 under the +y face (+x face 0.4, +z face 1.3): depth 0.2, out along +y.
    const auto inside = point_contact(b, pose, world({0.1, 0.8, 0.2}), 0.0);
    ASSERT_TRUE(inside.has_value());
    EXPECT_NEAR(inside->depth, 0.2, kExact);
    EXPECT_NEAR(length(inside->normal - R * Vec3d{0, 1, 0}), 0.0, kExact);
    EXPECT_NEAR(length(inside->point - world({0.1, 1.0, 0.2})), 0.0, kExact);
    // 0.05 outside the edge x = 0.5, y = 1 (offset 0.03, 0.04): within a margin of 0.06, depth
    // -0.05, normal (0.6, 0.8, 0); beyond a margin of 0.04, nothing.
    const Vec3d near_edge = world({0.53, 1.04, -0.7});
    const auto outside = point_contact(b, pose, near_edge, 0.06);
    ASSERT_TRUE(outside.has_value());
    EXPECT_NEAR(outside->depth, -0.05, kExact);
    EXPECT_NEAR(length(outside->normal - R * Vec3d{0.6, 0.8, 0}), 0.0, kExact);
    EXPECT_NEAR(length(outside->point - world({0.5, 1.0, -0.7})), 0.0, kExact);
    EXPECT_FALSE(point_contact(b, pose, near_edge, 0.04).has_value());
    // A ball: radially.
    const auto in_ball = point_contact(ball(0.5), at({1, 1, 1}), {1.3, 1, 1}, 0.0);
    ASSERT_TRUE(in_ball.has_value());
    EXPECT_NEAR(in_ball->depth, 0.2, kExact);
    EXPECT_NEAR(length(in_ball->point - Vec3d{1.5, 1, 1}), 0.0, kExact);
    EXPECT_NEAR(length(in_ball->normal - Vec3d{1, 0, 0}), 0.0, kExact);
}

// A particle at 20 m/s crosses a 2 cm plank within one 0.02 s step (0.4 m): the segment from
// z = 0.2 to z = -0.2 enters the top face (z = 0.01) at t = 0.19 / 0.4.
TEST(SegmentCast, ThroughAThinPlank) {
    const CollisionShape plank = box({1, 1, 0.02});
    std::mt19937 rng(5);
    for (int trial = 0; trial < 10; ++trial) {
        // The whole scene turned and moved at random (identity first).
        const Quat Q = trial == 0 ? Quat{} : random_quat(rng);
        const Vec3d shift = trial == 0 ? Vec3d{} : random_vec(rng, 3.0);
        const Mat3 R = Q.to_matrix();
        const auto w = [&](const Vec3d& p) { return R * p + shift; };
        const Pose pose{shift, Q};
        const auto hit = segment_cast(plank, pose, w({0.1, 0.1, 0.2}), w({0.1, 0.1, -0.2}));
        ASSERT_TRUE(hit.has_value());
        EXPECT_NEAR(hit->t, 0.475, kExact);
        EXPECT_NEAR(length(hit->point - w({0.1, 0.1, 0.01})), 0.0, 1e-11);
        EXPECT_NEAR(length(hit->normal - R * kUp), 0.0, kExact);
        // From below: the bottom face, normal down.
        const auto up = segment_cast(plank, pose, w({0.1, 0.1, -0.2}), w({0.1, 0.1, 0.2}));
        ASSERT_TRUE(up.has_value());
        EXPECT_NEAR(up->t, 0.475, kExact);
        EXPECT_NEAR(length(up->normal + R * kUp), 0.0, kExact);
        // Beside it, short of it, or from inside: no entry.
        EXPECT_FALSE(segment_cast(plank, pose, w({0.6, 0, 0.2}), w({0.6, 0, -0.2})).has_value());
        EXPECT_FALSE(segment_cast(plank, pose, w({0.1, 0.1, 0.2}), w({0.1, 0.1, 0.02})).has_value());
        EXPECT_FALSE(segment_cast(plank, pose, w({0.1, 0.1, 0.0}), w({0.1, 0.1, -0.2})).has_value());
    }
    // On the surface and going in: enters at t = 0.
    const auto start = segment_cast(plank, at({}), {0, 0, 0.01}, {0, 0, -0.3});
    ASSERT_TRUE(start.has_value());
    EXPECT_EQ(start->t, 0.0);
    // A ball of radius 0.5: the line x = 0.3 meets it at z = 0.4, t = (2 - 0.4) / 4.
    const auto b = segment_cast(ball(0.5), at({}), {0.3, 0, 2}, {0.3, 0, -2});
    ASSERT_TRUE(b.has_value());
    EXPECT_NEAR(b->t, 0.4, kExact);
    EXPECT_NEAR(length(b->normal - Vec3d{0.6, 0, 0.8}), 0.0, kExact);
    EXPECT_FALSE(segment_cast(ball(0.5), at({}), {0.6, 0, 2}, {0.6, 0, -2}).has_value());
    EXPECT_FALSE(segment_cast(ball(0.5), at({}), {0.1, 0, 0}, {0.1, 0, -2}).has_value());
}

// --- Time of impact ------------------------------------------------------------------------------------

// The 5 cm ball at 20 m/s over the 2 cm plank: from z = 0.3 to z = -0.1 in the step, it meets
// the plank's top (gap 0.265) at t* = 0.265 / 0.4. Conservative advancement never passes t*
// and stops within the tolerance's share of the step before it: t in [t* - tol / 0.4, t*].
TEST(TimeOfImpact, FastBallMeetsAThinPlank) {
    const double tol = 1e-4;
    const CollisionShape b = ball(0.025), plank = box({1, 1, 0.02});
    const TimeOfImpact toi = time_of_impact(b, at({0, 0, 0.3}), at({0, 0, -0.1}), plank, at({}), at({}), tol);
    EXPECT_EQ(toi.outcome, TimeOfImpact::Outcome::Touching);
    const double t_star = 0.265 / 0.4;
    EXPECT_LE(toi.t, t_star);
    EXPECT_GE(toi.t, t_star - tol / 0.4);
    EXPECT_LE(toi.separation, tol);
    EXPECT_GE(toi.separation, 0.0);
    EXPECT_LE(toi.iterations, 3);  // straight at a face, the bound is the distance: one advance
    // Passing beside the plank, or moving away: apart for the whole step.
    EXPECT_EQ(time_of_impact(b, at({0.6, 0, 0.3}), at({0.6, 0, -0.1}), plank, at({}), at({}), tol).outcome,
              TimeOfImpact::Outcome::Separate);
    EXPECT_EQ(time_of_impact(b, at({0, 0, 0.3}), at({0, 0, 0.7}), plank, at({}), at({}), tol).outcome,
              TimeOfImpact::Outcome::Separate);
    // Starting in touch: t = 0.
    const TimeOfImpact now = time_of_impact(b, at({0, 0, 0.03}), at({0, 0, 0.5}), plank, at({}), at({}), tol);
    EXPECT_EQ(now.outcome, TimeOfImpact::Outcome::Touching);
    EXPECT_EQ(now.t, 0.0);
}

// A rod 2 m long turning a quarter turn about the vertical in one step sweeps over a small box
// at (0.1, 0.8, 0): the time found must be one at which they have not yet met (checked on a
// fine scan before it), and not much before they do (they overlap within 0.02 of it).
TEST(TimeOfImpact, SpinningRodIsCaughtBeforeItPassesThrough) {
    const double tol = 1e-3;
    const CollisionShape rod = box({2, 0.05, 0.05}), small = box({0.1, 0.1, 0.1});
    const Pose r0 = at({}), r1 = at({}, turn(kUp, 90.0)), s = at({0.1, 0.8, 0});
    const TimeOfImpact toi = time_of_impact(rod, r0, r1, small, s, s, tol);
    ASSERT_EQ(toi.outcome, TimeOfImpact::Outcome::Touching);
    for (int k = 0; k <= 1000; ++k) {
        const double t = toi.t * k / 1000.0;
        ASSERT_GT(separation_bound(rod, interpolate(r0, r1, t), small, s), 0.0) << "t = " << t;
    }
    EXPECT_LT(separation_bound(rod, interpolate(r0, r1, toi.t + 0.02), small, s), 0.0);
    // Capped at one advance, it stalls at a time that is still safe.
    const TimeOfImpact stalled = time_of_impact(rod, r0, r1, small, s, s, tol, 1);
    EXPECT_EQ(stalled.outcome, TimeOfImpact::Outcome::Stalled);
    EXPECT_LE(stalled.t, toi.t);
}

// Half a turn in one step: nlerp turns fastest at mid-step (4 rad per step there, against pi on
// average; see time_of_impact.cpp), and the rod meets the box near then, at about 85 degrees.
// A bound on the turning rate taken as the average would let the advance overshoot.
TEST(TimeOfImpact, HalfTurnIsCaughtAtItsFastest) {
    const double tol = 1e-3;
    const CollisionShape rod = box({2, 0.05, 0.05}), small = box({0.1, 0.1, 0.1});
    const Pose r0 = at({}), r1 = at({}, turn(kUp, 180.0)), s = at({0, 0.9, 0});
    const TimeOfImpact toi = time_of_impact(rod, r0, r1, small, s, s, tol);
    ASSERT_EQ(toi.outcome, TimeOfImpact::Outcome::Touching);
    EXPECT_GT(toi.separation, 0.0);
    EXPECT_NEAR(toi.t, 0.47, 0.03);
    for (int k = 0; k <= 2000; ++k) {
        const double t = toi.t * k / 2000.0;
        ASSERT_GT(separation_bound(rod, interpolate(r0, r1, t), small, s), 0.0) << "t = " << t;
    }
}

// interpolate: x linear, q along the shorter arc: -q is the same turn as q, so from the identity
// to -(a quarter turn) is a quarter turn, and half way is an eighth, not three eighths the
// other way.
TEST(TimeOfImpact, InterpolateTakesTheShorterArc) {
    const Pose p = interpolate(at({0, 0, 0}), at({2, 4, 6}, turn(kUp, 90.0) * -1.0), 0.5);
    EXPECT_NEAR(length(p.x - Vec3d{1, 2, 3}), 0.0, kExact);
    EXPECT_NEAR(std::abs(dot(p.q, turn(kUp, 45.0))), 1.0, kExact);  // nlerp's midpoint is the slerp's
}

// --- The broad phase --------------------------------------------------------------------------------------

std::vector<BodyPair> brute_pairs(const std::vector<Aabb>& boxes) {
    std::vector<BodyPair> out;
    for (std::uint32_t i = 0; i < boxes.size(); ++i) {
        for (std::uint32_t j = i + 1; j < boxes.size(); ++j) {
            if (boxes[i].overlaps(boxes[j])) out.push_back({i, j});
        }
    }
    return out;
}

// 300 boxes of random sizes and turns in a 6 m cube, and one fixed ramp 40 m long.
std::vector<Aabb> random_boxes(std::uint32_t seed, double margin) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> size(0.05, 0.6);
    std::vector<Aabb> boxes;
    for (int i = 0; i < 300; ++i) {
        const CollisionShape b = box({size(rng), size(rng), size(rng)});
        const Vec3d x = random_vec(rng, 3.0);  // one draw after another: argument order is unspecified
        const Quat q = random_quat(rng);
        boxes.push_back(world_aabb(b, at(x, q), margin));
    }
    boxes.insert(boxes.begin() + 150, world_aabb(box({40, 2, 0.2}), at({0, 0, -1}, turn({0, 1, 0}, 10.0)), margin));
    return boxes;
}

TEST(BroadPhase, SameAsBruteForce) {
    std::vector<BodyPair> pairs;
    for (const std::uint32_t seed : {1u, 2u, 3u}) {
        const std::vector<Aabb> boxes = random_boxes(seed, 0.01);
        overlapping_pairs(boxes, pairs);
        const std::vector<BodyPair> expected = brute_pairs(boxes);
        EXPECT_EQ(pairs, expected) << "seed " << seed;
        EXPECT_GT(expected.size(), 150u);  // the ramp alone meets dozens
    }
    // A tower: 200 boxes stacked on one spot share one x range; the sweep takes z instead.
    std::vector<Aabb> tower;
    for (int i = 0; i < 200; ++i) tower.push_back(world_aabb(box({1, 1, 0.5}), at({0.01 * (i % 3), 0, 0.5 * i}), 0.01));
    overlapping_pairs(tower, pairs);
    EXPECT_EQ(pairs, brute_pairs(tower));
    EXPECT_EQ(pairs.size(), 199u);  // each box with the next
    // A box that is not a number overlaps nothing (and is kept out of the sweep, where its end
    // would never come).
    tower[5].hi.z = std::nan("");
    overlapping_pairs(tower, pairs);
    EXPECT_EQ(pairs, brute_pairs(tower));
    EXPECT_EQ(pairs.size(), 197u);
}

// A pile spread over a floor, as in a wide bin: 2,000 boxes of 0.1 to 0.5 m over 20 m by 16 m,
// up to 1.5 m high, four walls along its edges, a box every few on the walls' lines (each meets
// a wall) and a box that is a whole strip of floor. The sweep cuts such a pile into strips
// across it (broad_phase.h); the pairs are the same as every pair's test, each once, and those
// of two quiet boxes (asleep or fixed: every third, and the walls) are left out, on one thread
// and on a pool's.
TEST(BroadPhase, PileOverAFloorSameAsBruteForce) {
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Aabb> boxes;
    for (int i = 0; i < 2000; ++i) {
        const Vec3d c{20.0 * unit(rng) - 10.0, 16.0 * unit(rng) - 8.0, 1.5 * unit(rng)};
        const Vec3d half{0.05 + 0.2 * unit(rng), 0.05 + 0.2 * unit(rng), 0.05 + 0.2 * unit(rng)};
        boxes.push_back({c - half, c + half});
    }
    boxes.push_back({{-10.2, -8.2, 0.0}, {10.2, -8.0, 1.0}});
    boxes.push_back({{-10.2, 8.0, 0.0}, {10.2, 8.2, 1.0}});
    boxes.push_back({{-10.2, -8.0, 0.0}, {-10.0, 8.0, 1.0}});
    boxes.push_back({{10.0, -8.0, 0.0}, {10.2, 8.0, 1.0}});
    boxes.push_back({{-10.0, -0.3, -0.1}, {10.0, 0.3, 0.0}});  // a strip of floor across the pile
    std::vector<std::uint8_t> quiet(boxes.size(), 0);
    for (std::size_t i = 0; i < boxes.size(); i += 3) quiet[i] = 1;
    for (std::size_t i = 2000; i < 2004; ++i) quiet[i] = 1;
    std::vector<BodyPair> expected;
    for (const BodyPair& p : brute_pairs(boxes)) {
        if (!(quiet[p.a] && quiet[p.b])) expected.push_back(p);
    }
    EXPECT_GT(expected.size(), 500u);
    std::vector<BodyPair> pairs;
    overlapping_pairs(boxes, pairs, quiet);
    EXPECT_EQ(pairs, expected);
    ThreadPool pool(2);
    overlapping_pairs(boxes, pairs, quiet, &pool);
    EXPECT_EQ(pairs, expected);
    // Every pair of two overlapping boxes when none is quiet.
    overlapping_pairs(boxes, pairs);
    EXPECT_EQ(pairs, brute_pairs(boxes));
}

// The last sweep's order is a hint the next sort starts from (a pile moves little between two
// finds): the pairs are brute force's whatever it holds. From the last order after every box
// moved a little, after they were scattered anew (too far from it: a whole sort), and from
// orders that do not name the same boxes: another axis, too few, one named twice, one out of
// range, one that is no longer a number.
TEST(BroadPhase, PairsTheSameFromAnyLastOrder) {
    std::vector<Aabb> boxes = random_boxes(5, 0.01);
    SweepOrder order;
    std::vector<BodyPair> pairs;
    overlapping_pairs(boxes, pairs, {}, nullptr, &order);
    EXPECT_EQ(pairs, brute_pairs(boxes));
    ASSERT_GE(order.axis, 0);
    ASSERT_EQ(order.boxes.size(), boxes.size());
    std::mt19937 rng(6);
    std::uniform_real_distribution<double> nudge(-0.05, 0.05);
    for (Aabb& b : boxes) {
        const Vec3d d{nudge(rng), nudge(rng), nudge(rng)};
        b = {b.lo + d, b.hi + d};
    }
    overlapping_pairs(boxes, pairs, {}, nullptr, &order);
    EXPECT_EQ(pairs, brute_pairs(boxes));
    const std::vector<Aabb> scattered = random_boxes(7, 0.01);
    overlapping_pairs(scattered, pairs, {}, nullptr, &order);
    EXPECT_EQ(pairs, brute_pairs(scattered));
    const SweepOrder kept = order;
    const auto from = [&](SweepOrder hint) {
        overlapping_pairs(scattered, pairs, {}, nullptr, &hint);
        return pairs;
    };
    SweepOrder other_axis = kept;
    other_axis.axis = (kept.axis + 1) % 3;
    SweepOrder too_few = kept;
    too_few.boxes.pop_back();
    SweepOrder twice = kept;
    twice.boxes[1] = twice.boxes[0];
    SweepOrder out_of_range = kept;
    out_of_range.boxes[2] = std::uint32_t(scattered.size());
    for (const SweepOrder& hint : {other_axis, too_few, twice, out_of_range}) EXPECT_EQ(from(hint), brute_pairs(scattered));
    std::vector<Aabb> one_lost = scattered;
    one_lost[kept.boxes[3]].lo.y = std::nan("");
    SweepOrder last = kept;
    overlapping_pairs(one_lost, pairs, {}, nullptr, &last);
    EXPECT_EQ(pairs, brute_pairs(one_lost));
    EXPECT_EQ(last.boxes.size(), scattered.size() - 1);
}

// The pairs of a few boxes (bodies just woken) with all the others: the sweep's pairs that have
// one of them, in the same order, each pair of two of them once; a box that is not a number
// among them meets nothing.
TEST(BroadPhase, PairsOfAFewAreTheSweepsPairsThatHaveThem) {
    std::vector<BodyPair> all, some_pairs;
    std::vector<Aabb> boxes = random_boxes(4, 0.01);
    const std::vector<std::uint32_t> some{3, 17, 150, 151, 299};  // 150 is the ramp
    overlapping_pairs(boxes, all);
    overlapping_pairs_of(boxes, some, some_pairs);
    const auto has_some = [&](const BodyPair& p) {
        return std::count(some.begin(), some.end(), p.a) + std::count(some.begin(), some.end(), p.b) > 0;
    };
    std::vector<BodyPair> expected;
    std::copy_if(all.begin(), all.end(), std::back_inserter(expected), has_some);
    EXPECT_EQ(some_pairs, expected);
    EXPECT_GT(expected.size(), 20u);  // the ramp alone meets dozens
    EXPECT_TRUE(std::is_sorted(some_pairs.begin(), some_pairs.end()));
    boxes[150].lo.x = std::nan("");
    overlapping_pairs(boxes, all);
    overlapping_pairs_of(boxes, some, some_pairs);
    expected.clear();
    std::copy_if(all.begin(), all.end(), std::back_inserter(expected), has_some);
    EXPECT_EQ(some_pairs, expected);
    EXPECT_TRUE(std::none_of(some_pairs.begin(), some_pairs.end(), [](const BodyPair& p) { return p.a == 150 || p.b == 150; }));
}

// world_aabb: a turned box's half extents are sum_j |R_ij| s_j / 2 (its extreme corners), a
// ball's its radius, each grown by the margin.
TEST(BroadPhase, BoxesOfShapes) {
    const Vec3d size{1, 2, 3};
    const Pose pose = at({1, 2, 3}, turn({1, -2, 0.5}, 70.0));
    const Aabb b = world_aabb(box(size), pose, 0.1);
    const Mat3 R = pose.q.to_matrix();
    for (int i = 0; i < 3; ++i) {
        double half = 0.0;
        for (int j = 0; j < 3; ++j) half += std::abs(R.m[i][j]) * size[j] / 2.0;
        EXPECT_NEAR(b.hi[i], pose.x[i] + half + 0.1, kExact);
        EXPECT_NEAR(b.lo[i], pose.x[i] - half - 0.1, kExact);
    }
    const Aabb s = world_aabb(ball(0.5), pose, 0.1);
    const Vec3d reach{0.6, 0.6, 0.6};
    EXPECT_EQ(s.lo, pose.x - reach);
    EXPECT_EQ(s.hi, pose.x + reach);
}

// The pairs come in increasing (a, b) order, the same on every run, and the same set whatever
// order the boxes are given in. The boxes here are made of sixty-fourths of a metre (exact in
// binary) by integer arithmetic, so they are the same numbers on every machine, and so is the
// pair list: its hash is fixed.
TEST(BroadPhase, Deterministic) {
    std::vector<Aabb> boxes;
    std::uint32_t s = 12345;
    const auto next = [&] { return s = s * 1664525u + 1013904223u, (s >> 8) % 256u; };
    for (int i = 0; i < 400; ++i) {
        const Vec3d lo{next() / 64.0, next() / 64.0, next() / 64.0};
        const Vec3d extent{(1 + next() % 32) / 64.0, (1 + next() % 32) / 64.0, (1 + next() % 32) / 64.0};
        boxes.push_back({lo, lo + extent});
    }
    std::vector<BodyPair> pairs, again;
    overlapping_pairs(boxes, pairs);
    overlapping_pairs(boxes, again);
    EXPECT_EQ(pairs, again);
    EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));
    EXPECT_EQ(pairs, brute_pairs(boxes));
    // Shuffled: the same pairs once the indices are mapped back.
    std::vector<std::uint32_t> order(boxes.size());
    std::iota(order.begin(), order.end(), 0u);
    std::shuffle(order.begin(), order.end(), std::mt19937(9));
    std::vector<Aabb> shuffled;
    for (const std::uint32_t i : order) shuffled.push_back(boxes[i]);
    overlapping_pairs(shuffled, again);
    for (BodyPair& p : again) p = {std::min(order[p.a], order[p.b]), std::max(order[p.a], order[p.b])};
    std::sort(again.begin(), again.end());
    EXPECT_EQ(again, pairs);
    std::uint64_t hash = 1469598103934665603ull;  // FNV-1a over the pairs
    for (const BodyPair& p : pairs) {
        for (const std::uint32_t v : {p.a, p.b}) hash = (hash ^ v) * 1099511628211ull;
    }
    EXPECT_EQ(pairs.size(), 184u);
    EXPECT_EQ(hash, 5233339006696647776ull);
}

// collide keeps no state: the same calls on two threads at once give the same bits.
TEST(CollideDeterminism, SameBitsOnTwoThreads) {
    const std::vector<Scenario> all = scenarios();
    const auto run = [&](std::vector<ContactPoint>& out) {
        for (int round = 0; round < 200; ++round) {
            for (const Scenario& s : all) collide(s.a, s.pa, s.b, s.pb, s.margin, out);
        }
    };
    std::vector<ContactPoint> one, two, here;
    std::thread t1([&] { run(one); }), t2([&] { run(two); });
    t1.join();
    t2.join();
    run(here);
    ASSERT_EQ(one.size(), here.size());
    ASSERT_EQ(two.size(), here.size());
    for (std::size_t i = 0; i < here.size(); ++i) {
        for (const auto* other : {&one, &two}) {
            EXPECT_EQ((*other)[i].point, here[i].point);
            EXPECT_EQ((*other)[i].normal, here[i].normal);
            EXPECT_EQ((*other)[i].depth, here[i].depth);
            EXPECT_EQ((*other)[i].feature, here[i].feature);
        }
    }
}

}  // namespace
}  // namespace softbody::test
