// Mass properties (Eq. 20 centre of mass, Eq. 29-31 inertia tensor, Table 1): the primitives'
// closed forms, and closed triangle meshes by volume integrals checked against Table 1, against
// the exact values of the polyhedra the meshes really are, against a published tetrahedron, and
// against themselves moved (Eq. 32) or turned inside out.
//
// Tolerances are relative to the largest entry compared, and come from one of two sources:
// rounding (double sums: 1e-13 and up; the meshes' float corners: each coordinate within 2^-24
// = 6e-8 of itself, which moves a volume, of degree 3 in them, by up to about 3 times that and
// an inertia, of degree 5, by up to about 5 times), or the known difference between a polyhedron
// and the curved solid it approximates, worked out below.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "physics/mass_properties.h"
#include "physics/quat.h"
#include "physics/shape_meshes.h"
#include "test_support.h"

namespace softbody::test {
namespace {

struct Solid {
    std::vector<Vec3d> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

// A welded mesh's particles and its triangles on them.
Solid solid_of(const Mesh& mesh) {
    Solid s;
    for (const Vec3& p : mesh.positions) s.vertices.push_back(Vec3d(p));
    s.triangles = particle_triangles(mesh);
    return s;
}

MassProperties of(const Solid& s) { return mesh_mass_properties(s.vertices, s.triangles); }

double largest(const Mat3& a) {
    double m = 0.0;
    for (const auto& row : a.m)
        for (double v : row) m = std::max(m, std::abs(v));
    return m;
}

// Every entry within `tolerance` times the largest entry of `expected`.
void expect_tensor_near(const Mat3& actual, const Mat3& expected, double tolerance, const std::string& what) {
    const double scale = largest(expected);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            EXPECT_NEAR(actual.m[i][j], expected.m[i][j], tolerance * scale) << what << ", J[" << i << "][" << j << "]";
        }
    }
}

void expect_same(const MassProperties& actual, const MassProperties& expected, double tolerance, const std::string& what) {
    EXPECT_NEAR(actual.volume, expected.volume, tolerance * expected.volume) << what << ", volume";
    const double size = std::cbrt(expected.volume);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(actual.center[k], expected.center[k], tolerance * size) << what << ", centre[" << k << "]";
    }
    expect_tensor_near(actual.inertia, expected.inertia, tolerance, what);
}

Solid transformed(Solid s, const Mat3& rotation, const Vec3d& translation) {
    for (Vec3d& v : s.vertices) v = rotation * v + translation;
    return s;
}

Solid inside_out(Solid s) {
    for (auto& t : s.triangles) std::swap(t[1], t[2]);
    return s;
}

// The tetrahedron of Tonon's worked example (see Tonon below), as a closed mesh.
Solid tonon_tetrahedron() {
    return {{{8.33220, -11.86875, 0.93355}, {0.75523, 5.00000, 16.37072}, {52.61236, 5.00000, -5.38580},
             {2.00000, 5.00000, 3.00000}},
            {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}}};
}

// --- Table 1 --------------------------------------------------------------------------------

// The closed forms against numbers worked out by hand. Only the last bits of a few double
// products can differ: 1e-15 relative.
TEST(Table1, PrimitivesByHand) {
    const MassProperties box = box_mass_properties({1.0, 2.0, 3.0});
    EXPECT_NEAR(box.volume, 6.0, 1e-15 * 6.0);
    // m (b^2 + c^2) / 12 = 6 * 13 / 12, 6 * 10 / 12, 6 * 5 / 12.
    expect_tensor_near(box.inertia, Mat3::diagonal({6.5, 5.0, 2.5}), 1e-15, "box 1 x 2 x 3");
    EXPECT_EQ(box.center, Vec3d{});

    // r = 2: V = 32 pi / 3, J = 2/5 V r^2 = 2/5 * 32 pi / 3 * 4 = 256 pi / 15.
    const MassProperties sphere = sphere_mass_properties(2.0);
    EXPECT_NEAR(sphere.volume, 32.0 * kPi / 3.0, 1e-15 * sphere.volume);
    expect_tensor_near(sphere.inertia, Mat3::identity() * (256.0 * kPi / 15.0), 1e-15, "sphere r 2");

    // r = 1, h = 2: V = 2 pi, J_zz = V r^2 / 2 = pi, J_xx = V (3 + 4) / 12 = 7 pi / 6.
    const MassProperties cylinder = cylinder_mass_properties(1.0, 2.0);
    EXPECT_NEAR(cylinder.volume, 2.0 * kPi, 1e-15 * cylinder.volume);
    expect_tensor_near(cylinder.inertia, Mat3::diagonal({7.0 * kPi / 6.0, 7.0 * kPi / 6.0, kPi}), 1e-15,
                       "cylinder r 1 h 2");
}

TEST(Table1, RefusesSizesThatAreNotPositive) {
    EXPECT_REFUSED_NAMING(box_mass_properties({1.0, 0.0, 2.0}), "box size", "1 x 0 x 2");
    EXPECT_REFUSED_NAMING(box_mass_properties({1.0, -1.0, 2.0}), "box size", "-1");
    EXPECT_REFUSED_NAMING(box_mass_properties({1.0, std::nan(""), 2.0}), "box size", "nan");
    EXPECT_REFUSED_NAMING(sphere_mass_properties(0.0), "sphere radius", "0");
    EXPECT_REFUSED_NAMING(sphere_mass_properties(INFINITY), "sphere radius", "inf");
    EXPECT_REFUSED_NAMING(cylinder_mass_properties(1.0, -2.0), "cylinder height", "-2");
    EXPECT_REFUSED_NAMING(cylinder_mass_properties(0.0, 2.0), "cylinder radius", "0");
}

// --- The primitives' meshes -----------------------------------------------------------------

TEST(ShapeMeshes, CountsSourcesAndOrientation) {
    const Mesh box = box_mesh({1.0, 2.0, 3.0});
    EXPECT_EQ(box.source, "box 1 x 2 x 3");
    EXPECT_EQ(box.particle_count(), 8u);
    EXPECT_EQ(box.triangle_count(), 12u);
    EXPECT_EQ(box.normal_slot_count, 24u);  // three faces meet at 90 degrees at each corner: hard

    const Mesh sphere = sphere_mesh(0.5, 2);
    EXPECT_EQ(sphere.source, "sphere r 0.5 (icosphere, 2 subdivisions)");
    EXPECT_EQ(sphere.particle_count(), 10u * 16u + 2u);  // 10 * 4^s + 2
    EXPECT_EQ(sphere.triangle_count(), 20u * 16u);
    EXPECT_EQ(sphere.normal_slot_count, sphere.particle_count());  // smooth everywhere

    const Mesh cylinder = cylinder_mesh(0.5, 2.0, 16);
    EXPECT_EQ(cylinder.source, "cylinder r 0.5 h 2 (16 segments)");
    EXPECT_EQ(cylinder.particle_count(), 2u * 16u + 2u);
    EXPECT_EQ(cylinder.triangle_count(), 4u * 16u);
    // Hard at the rims (90 degrees), smooth around the side (22.5 degrees between segments):
    // each rim corner has one slot for the side and one for its cap, each centre one.
    EXPECT_EQ(cylinder.normal_slot_count, 2u * 2u * 16u + 2u);

    for (const Mesh* mesh : {&box, &sphere, &cylinder}) {
        const Solid s = solid_of(*mesh);
        EXPECT_TRUE(is_closed_oriented(s.triangles)) << mesh->source;
        // Facing outward: a positive volume before any flip. Sum of det(p0, p1, p2) / 6.
        double volume6 = 0.0;
        for (const auto& t : s.triangles) volume6 += dot(s.vertices[t[0]], cross(s.vertices[t[1]], s.vertices[t[2]]));
        EXPECT_GT(volume6, 0.0) << mesh->source;
    }
}

TEST(ShapeMeshes, RefusesBadSizes) {
    EXPECT_REFUSED_NAMING(box_mesh({0.0, 1.0, 1.0}), "box size");
    EXPECT_REFUSED_NAMING(sphere_mesh(-1.0), "sphere radius", "-1");
    EXPECT_REFUSED_NAMING(sphere_mesh(1.0, 6), "sphere subdivisions", "6");
    EXPECT_REFUSED_NAMING(cylinder_mesh(1.0, 1.0, 2), "cylinder segments", "2");
    EXPECT_REFUSED_NAMING(cylinder_mesh(1.0, 0.0), "cylinder height", "0");
}

// --- Meshes against exact answers -----------------------------------------------------------

// A box mesh is exactly the box, so only rounding separates it from Table 1. Its corners are
// +-size/2 stored in float: exact for 1 x 2 x 3, not for 0.3 x 0.7 x 1.1, so the exact answer
// is Table 1 for the sides the mesh really has (twice its +x+y+z corner), and what is left is
// double rounding over 12 triangles: 1e-13.
TEST(MeshMassProperties, BoxMeshIsTable1) {
    for (const Vec3d size : {Vec3d{1.0, 2.0, 3.0}, Vec3d{0.3, 0.7, 1.1}}) {
        const Mesh mesh = box_mesh(size);
        const Vec3d sides = Vec3d(mesh.positions[7]) * 2.0;  // corner 7 is +x+y+z
        EXPECT_NEAR(sides.x, size.x, 1e-7 * size.x);
        expect_same(of(solid_of(mesh)), box_mass_properties(sides), 1e-13, mesh.source);
    }
}

// The icosphere's level 0 is the regular icosahedron, whose volume is known in closed form:
// V = 5/12 (3 + sqrt 5) a^3 with edge a = 4 r / sqrt(10 + 2 sqrt 5) for circumradius r. The
// float corners allow 3 * 6e-8 of it: 2e-7. Its symmetry makes the tensor j 1 with
// j = 2/3 int |x|^2. Cut into 20 pyramids from the centre, each a tetrahedron (0, p, q, s) with
// int x x^T = V_t/20 (p p^T + q q^T + s s^T + (p + q + s)(p + q + s)^T), corners at r and the
// base's centroid at the inradius h: int |x|^2 = V (3 r^2 + 9 h^2) / 20, so
// j = V (r^2 + 3 h^2) / 10 = phi^2 / 10 V a^2, with r^2 = (5 + sqrt 5) / 8 a^2,
// h^2 = (7 + 3 sqrt 5) / 24 a^2 and phi the golden ratio. The float corners allow 5 * 6e-8: 4e-7.
TEST(MeshMassProperties, IcosahedronIsExact) {
    const double r = 1.5;
    const MassProperties m = of(solid_of(sphere_mesh(r, 0)));
    const double a = 4.0 * r / std::sqrt(10.0 + 2.0 * std::sqrt(5.0));
    const double volume = 5.0 / 12.0 * (3.0 + std::sqrt(5.0)) * a * a * a;
    EXPECT_NEAR(m.volume, volume, 2e-7 * volume);
    const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
    expect_tensor_near(m.inertia, Mat3::identity() * (phi * phi / 10.0 * volume * a * a), 4e-7, "icosahedron");
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(m.center[k], 0.0, 1e-14 * r);  // symmetric (see below)
}

// Finer icosphere: no closed form, but exact bounds. The polyhedron is convex and contains the
// ball of radius r_in (the nearest face plane's distance from the centre) and lies in the ball
// of radius r_out (the farthest corner), so its volume and its moments of inertia (integrals of
// positive functions) lie between those balls' Table 1 values. The tensor is again a multiple
// of the identity and the centre at the origin: rounding to float keeps the corners' symmetry
// under swapping and negating coordinates (the icosahedron's vertices are the cyclic
// permutations of (0, +-1, +-phi)), and that symmetry alone (three-fold turns about a
// diagonal, half turns about the axes) forces J = j 1, so only double rounding is left: 1e-13
// of J, 1e-14 of r for the centre. And the error
// against the sphere falls as the square of the edge: a quarter per subdivision (the ratio
// tends to 4 from below as the next-order term fades: 3.74, 3.93, 3.98, 4.00 for levels 2 to
// 5, so from level 3 on it is checked to within 4 +- 0.15).
TEST(MeshMassProperties, IcosphereLiesBetweenItsBallsAndConvergesToTable1) {
    const double r = 1.0;
    const MassProperties ball = sphere_mass_properties(r);
    double previous_error = 0.0;
    for (int level = 1; level <= 5; ++level) {
        const Solid s = solid_of(sphere_mesh(r, level));
        const MassProperties m = of(s);
        double r_in = INFINITY, r_out = 0.0;
        for (const auto& t : s.triangles) {
            const Vec3d n = normalize(cross(s.vertices[t[1]] - s.vertices[t[0]], s.vertices[t[2]] - s.vertices[t[0]]));
            r_in = std::min(r_in, dot(n, s.vertices[t[0]]));
        }
        for (const Vec3d& v : s.vertices) r_out = std::max(r_out, length(v));
        const MassProperties inner = sphere_mass_properties(r_in), outer = sphere_mass_properties(r_out);
        // 1e-13: double rounding at the bounds' edges.
        EXPECT_GE(m.volume, inner.volume * (1 - 1e-13)) << "level " << level;
        EXPECT_LE(m.volume, outer.volume * (1 + 1e-13)) << "level " << level;
        for (int k = 0; k < 3; ++k) {
            EXPECT_GE(m.inertia.m[k][k], inner.inertia.m[k][k] * (1 - 1e-13)) << "level " << level << ", axis " << k;
            EXPECT_LE(m.inertia.m[k][k], outer.inertia.m[k][k] * (1 + 1e-13)) << "level " << level << ", axis " << k;
        }
        expect_tensor_near(m.inertia, Mat3::identity() * m.inertia.m[0][0], 1e-13, "icosphere level " + std::to_string(level));
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(m.center[k], 0.0, 1e-14 * r) << "level " << level;

        const double error = 1.0 - m.volume / ball.volume;
        if (level >= 3) {
            EXPECT_NEAR(previous_error / error, 4.0, 0.15) << "level " << level;
        }
        previous_error = error;
    }
    EXPECT_LT(previous_error, 6e-4);  // level 5: 5.4e-4 below Table 1
}

// The cylinder mesh is a prism on a regular n-gon inscribed in the circle of radius r, with
// exact values: the n-gon is n triangles (centre, p_k, p_k+1) of area r^2 sin(t) / 2, t = 2 pi / n,
// and a triangle with a corner at the origin and the others at a, b has polar moment
// (area / 6)(a.a + b.b + a.b) = r^4 sin(t) (2 + cos t) / 12, so
//     A = n r^2 sin(t) / 2,   V = A h,   J_zz = h n r^4 sin(t) (2 + cos t) / 12,
// and (a regular polygon's second moments are the same about every in-plane axis)
//     J_xx = J_yy = J_zz / 2 + A h^3 / 12.
// The float corners allow 5 * 6e-8 = 3e-7 (see the top of the file).
TEST(MeshMassProperties, CylinderMeshIsItsPrismExactly) {
    const double r = 0.8, h = 2.5;
    for (const int n : {3, 5, 7, 32, 100}) {
        const MassProperties m = of(solid_of(cylinder_mesh(r, h, n)));
        const double t = 2.0 * kPi / n;
        const double area = n * r * r * std::sin(t) / 2.0;
        const double j_zz = h * n * std::pow(r, 4) * std::sin(t) * (2.0 + std::cos(t)) / 12.0;
        const double j_xx = j_zz / 2.0 + area * h * h * h / 12.0;
        MassProperties prism;
        prism.volume = area * h;
        prism.inertia = Mat3::diagonal({j_xx, j_xx, j_zz});
        expect_same(m, prism, 3e-7, std::to_string(n) + "-gon prism");
    }
}

// ...and as n grows the prism tends to Table 1's cylinder. With x = 2 pi / n its volume falls
// short by exactly 1 - sin(x) / x = x^2 / 6 - x^4 / 120 + ..., and its J_zz by
// 1 - sin(x)(2 + cos x) / (3 x) = x^2 / 3 - x^4 / 20 + ..., so each doubling of n divides the
// shortfall by 4, and the shortfall over its leading term is 1 within x^2 / 5 (the next terms'
// share: x^2 / 20 for V, 3 x^2 / 20 for J_zz) plus 1% (the float corners' 3e-7 against the
// smallest shortfall, 1e-4 at n = 256, is 0.3%).
TEST(MeshMassProperties, CylinderMeshConvergesToTable1) {
    const double r = 0.8, h = 2.5;
    const MassProperties cylinder = cylinder_mass_properties(r, h);
    double previous_v = 0.0, previous_j = 0.0;
    for (const int n : {32, 64, 128, 256}) {
        const MassProperties m = of(solid_of(cylinder_mesh(r, h, n)));
        const double x = 2.0 * kPi / n;
        const double short_v = 1.0 - m.volume / cylinder.volume;
        const double short_j = 1.0 - m.inertia.m[2][2] / cylinder.inertia.m[2][2];
        EXPECT_NEAR(short_v / (x * x / 6.0), 1.0, x * x / 5.0 + 0.01) << n << " segments";
        EXPECT_NEAR(short_j / (x * x / 3.0), 1.0, x * x / 5.0 + 0.01) << n << " segments";
        EXPECT_LT(m.inertia.m[0][0], cylinder.inertia.m[0][0]) << n << " segments";  // inscribed: less
        if (previous_v > 0.0) {
            EXPECT_NEAR(previous_v / short_v, 4.0, 0.1) << n << " segments";
            EXPECT_NEAR(previous_j / short_j, 4.0, 0.1) << n << " segments";
        }
        previous_v = short_v;
        previous_j = short_j;
    }
}

// A published example: F. Tonon, "Explicit Exact Formulas for the 3-D Tetrahedron Inertia
// Tensor in Terms of Its Vertex Coordinates", Journal of Mathematics and Statistics 1 (1):
// 8-11, 2004, section "Numerical example". For unit density about the centroid it gives
//     a = int (y^2 + z^2) = 43520.33257,  b = int (x^2 + z^2) = 194711.28938,
//     c = int (x^2 + y^2) = 191168.76173,
//     a' = int y z = 4417.66150,  b' = int x z = -46343.16662,  c' = int x y = 11996.20119
// and the centroid (15.92492, 0.78281, 3.72962). Sign convention: the paper's a', b', c' are
// the plain integrals (its Eq. 9), so with Eq. 29-31's J_ij = -int x_i x_j off the diagonal,
// J_xy = -c', J_xz = -b', J_yz = -a'. (The matrix the paper prints puts b' at xy and c' at xz,
// which does not match its own definitions; its numbers do match them, as this test shows.)
//
// Tolerance: the paper's vertices are printed to 5 decimals, rounded from those it computed
// with: the mean of the printed x's is 15.9249475, not its 15.92492, and every entry of ours is
// larger in size than its value by 1.58e-8 to 1.69e-8 of it (as if from a scale of 3e-9 in the
// coordinates: J goes as their fifth power). 5e-8 of each entry allows that, and nothing like a
// wrong sign, a swapped product or a missing term. The centroid: its x to 3e-5 (that discrepancy),
// y and z to half the last printed digit, 5e-6.
TEST(MeshMassProperties, TetrahedronMatchesTonon2004) {
    const Solid tet = tonon_tetrahedron();
    const MassProperties m = of(tet);
    const Mat3 expected{{{43520.33257, -11996.20119, 46343.16662},
                         {-11996.20119, 194711.28938, -4417.66150},
                         {46343.16662, -4417.66150, 191168.76173}}};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            EXPECT_NEAR(m.inertia.m[i][j], expected.m[i][j], 5e-8 * std::abs(expected.m[i][j])) << "J[" << i << "][" << j << "]";
        }
    }
    EXPECT_NEAR(m.center.x, 15.92492, 3e-5);
    EXPECT_NEAR(m.center.y, 0.78281, 5e-6);
    EXPECT_NEAR(m.center.z, 3.72962, 5e-6);
    // The volume, which the paper does not print: |det(p1 - p0, p2 - p0, p3 - p0)| / 6, and the
    // centroid of a tetrahedron is the mean of its corners; both to double rounding.
    const Vec3d& p0 = tet.vertices[0];
    const double volume = std::abs(dot(tet.vertices[1] - p0, cross(tet.vertices[2] - p0, tet.vertices[3] - p0))) / 6.0;
    EXPECT_NEAR(m.volume, volume, 1e-13 * volume);
    const Vec3d mean = (tet.vertices[0] + tet.vertices[1] + tet.vertices[2] + tet.vertices[3]) / 4.0;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(m.center[k], mean[k], 1e-13 * 60.0);
}

// --- Moving and turning a mesh ----------------------------------------------------------------

// Eq. 32: turning the body by R turns its tensor to R J R^T and its centre to R c. The turned
// corners are rounded once (1e-16 relative), and the sums and the products with R round a few
// times more: 1e-13 (1.3e-15 seen).
TEST(MeshMassProperties, RotatedMeshGivesRJRt) {
    const Mat3 R = Quat::from_axis_angle(normalize(Vec3d{1.0, 2.0, 3.0}), 0.7).to_matrix();
    for (const Solid& body : {tonon_tetrahedron(), solid_of(box_mesh({1.0, 2.0, 3.0})),
                              solid_of(cylinder_mesh(0.5, 2.0, 7))}) {
        const MassProperties before = of(body);
        const MassProperties after = of(transformed(body, R, {}));
        MassProperties expected;
        expected.volume = before.volume;
        expected.center = R * before.center;
        expected.inertia = R * before.inertia * R.transposed();
        expect_same(after, expected, 1e-13, "turned");
        // Not a mere diagonal: the turn mixes the axes.
        EXPECT_GT(std::abs(after.inertia.m[0][1]), 1e-3 * largest(after.inertia));
    }
}

// Moving a body moves its centre with it and leaves its tensor about the centre alone. The
// bodies are turned first, so that their corners use every bit of a double and the move rounds
// them: 13 km from the origin to 1e-12 m (half an ulp of 12,000), which for a body a metre
// across moves the tensor by about 1e-12 of itself (1.1e-12 seen). 1e-10 allows that. Taken
// about the origin instead of a point near the body, the integrals would reach V |x|^2 ~ 2e8 V
// and cancel down to errors near 1e-8.
TEST(MeshMassProperties, TranslatedMeshKeepsItsTensor) {
    const Mat3 R = Quat::from_axis_angle(normalize(Vec3d{1.0, 2.0, 3.0}), 0.7).to_matrix();
    const Vec3d far{3000.3, -4000.7, 12000.1};
    for (const Solid& body : {solid_of(box_mesh({1.0, 2.0, 3.0})), solid_of(cylinder_mesh(0.5, 2.0, 7)),
                              solid_of(sphere_mesh(0.7, 2))}) {
        const Solid turned = transformed(body, R, {});
        const MassProperties before = of(turned);
        const MassProperties after = of(transformed(turned, Mat3::identity(), far));
        EXPECT_NEAR(after.volume, before.volume, 1e-10 * before.volume);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(after.center[k], before.center[k] + far[k], 1e-10 * std::abs(far[k]));
        expect_tensor_near(after.inertia, before.inertia, 1e-10, "moved 13 km");
    }
}

// A mesh facing inward (every triangle's corners in the other order) has the opposite signed
// volume and every integral with it: flipped back, the same answer, to rounding (the sums run
// over the corners in another order: 1e-13).
TEST(MeshMassProperties, InwardMeshGivesTheSameAnswer) {
    for (const Solid& body : {tonon_tetrahedron(), solid_of(sphere_mesh(1.0, 2)), solid_of(cylinder_mesh(0.5, 2.0, 7))}) {
        const Solid inward = inside_out(body);
        EXPECT_TRUE(is_closed_oriented(inward.triangles));
        expect_same(of(inward), of(body), 1e-13, "inside out");
    }
}

// --- Closed and oriented ----------------------------------------------------------------------

TEST(ClosedOriented, OpenOrInconsistentMeshesAreReported) {
    const Solid box = solid_of(box_mesh({1.0, 1.0, 1.0}));
    EXPECT_TRUE(is_closed_oriented(box.triangles));

    Solid open = box;  // a hole: one triangle gone
    open.triangles.pop_back();
    EXPECT_FALSE(is_closed_oriented(open.triangles));

    Solid flipped = box;  // one triangle the wrong way round
    std::swap(flipped.triangles[3][0], flipped.triangles[3][1]);
    EXPECT_FALSE(is_closed_oriented(flipped.triangles));

    Solid doubled = box;  // a triangle twice: its edges used three times
    doubled.triangles.push_back(doubled.triangles[0]);
    EXPECT_FALSE(is_closed_oriented(doubled.triangles));

    Solid degenerate = box;
    degenerate.triangles[0][1] = degenerate.triangles[0][0];
    EXPECT_FALSE(is_closed_oriented(degenerate.triangles));

    EXPECT_FALSE(is_closed_oriented({}));

    // Two boxes side by side, apart: still closed and oriented.
    Solid two = box;
    for (const auto& t : box.triangles) two.triangles.push_back({t[0] + 8, t[1] + 8, t[2] + 8});
    EXPECT_TRUE(is_closed_oriented(two.triangles));
}

TEST(MeshMassProperties, RefusesBrokenMeshes) {
    const Solid box = solid_of(box_mesh({1.0, 1.0, 1.0}));
    Solid bad_index = box;
    bad_index.triangles[5][2] = 99;
    EXPECT_REFUSED_NAMING(of(bad_index), "mesh mass properties", "triangle 5", "vertex 99", "8 vertices");

    Solid not_finite = box;
    not_finite.vertices[3].y = std::nan("");
    EXPECT_REFUSED_NAMING(of(not_finite), "mesh mass properties", "vertex 3", "not a finite");

    // Two triangles back to back: closed, but flat.
    const Solid flat{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 1}}};
    EXPECT_TRUE(is_closed_oriented(flat.triangles));
    EXPECT_REFUSED_NAMING(of(flat), "mesh mass properties", "encloses no volume");
    EXPECT_REFUSED_NAMING(of(Solid{}), "mesh mass properties", "encloses no volume");
}

}  // namespace
}  // namespace softbody::test
