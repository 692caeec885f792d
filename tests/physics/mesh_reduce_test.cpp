// A particle budget by reduction: at most the budget is kept, spread over the whole body; every
// full vertex follows its three particles so that the rest shape comes back to float rounding
// and a rigid motion of the particles moves the full mesh rigidly; point clouds reduce too; the
// same input always gives the same output. The meshes are generated (generated_meshes.h) and loaded as files.
#include <cmath>
#include <limits>
#include <numeric>

#include "generated_meshes.h"
#include "physics/error.h"
#include "physics/mesh_reduce.h"
#include "test_support.h"

namespace softbody::test {
namespace {

constexpr double kEps = std::numeric_limits<float>::epsilon();

Mesh load_text(const TempDir& dir, const std::string& name, const std::string& text) {
    return load_mesh(dir.write(name, text));
}

// The full mesh from the reduced particles, through the header's apply_skinning.
std::vector<Vec3> skin(const ReducedMesh& reduced, const std::vector<Vec3>& particles) {
    std::vector<float> x, y, z;
    for (const Vec3& p : particles) x.push_back(p.x), y.push_back(p.y), z.push_back(p.z);
    const std::size_t n = reduced.bindings.size();
    std::vector<float> ox(n), oy(n), oz(n);
    apply_skinning(reduced.bindings, x.data(), y.data(), z.data(), ox.data(), oy.data(), oz.data());
    std::vector<Vec3> out;
    for (std::size_t i = 0; i < n; ++i) out.push_back({ox[i], oy[i], oz[i]});
    return out;
}

double max_abs(const Vec3& v) { return std::max({std::abs(double(v.x)), std::abs(double(v.y)), std::abs(double(v.z))}); }

// What float rounding can cost one skinned point, from the particles it follows (`x`):
// - sum_k w_k x_k in float, with each w_k rounded to float: at most a few float epsilons of
//   sum_k |w_k| |x_k| (weights outside [0, 1] magnify the particles' own rounding);
// - the normal, from float differences and a cross product: its direction is off by a few
//   epsilons over s, the sine of the triangle's angle at p0 (a thin triangle turns its normal
//   more for the same rounding), which the offset multiplies.
// Eight epsilons of each is about four times the worst that adding up those steps gives: the
// test asserts the rounding, not a looser fit.
double skin_tolerance(const SkinBinding& b, const std::vector<Vec3>& x) {
    double scale = 0.0;
    for (int k = 0; k < 3; ++k) scale += std::abs(double(b.weights[k])) * max_abs(x[b.particles[k]]);
    if (b.offset != 0.0f) {
        const Vec3d p0(x[b.particles[0]]), e1 = Vec3d(x[b.particles[1]]) - p0, e2 = Vec3d(x[b.particles[2]]) - p0;
        const double s = length(cross(e1, e2)) / (length(e1) * length(e2));
        scale += std::abs(double(b.offset)) * (1.0 + 1.0 / s);
    }
    return 8.0 * kEps * scale;
}

// Every full vertex as the skinning gives it from the reduced particles at rest.
void expect_rest_shape(const Mesh& full, const ReducedMesh& reduced, const std::string& what) {
    const std::vector<Vec3> out = skin(reduced, reduced.positions);
    std::size_t bad = 0;
    for (std::size_t i = 0; i < full.particle_count(); ++i) {
        const double error = length(Vec3d(out[i]) - Vec3d(full.positions[i]));
        const double tolerance = skin_tolerance(reduced.bindings[i], reduced.positions) + kEps * max_abs(full.positions[i]);
        if (error > tolerance && bad++ < 5) {
            ADD_FAILURE() << what << ": vertex " << i << " is " << error << " from its rest position (tolerance " << tolerance
                          << ")";
        }
    }
    EXPECT_EQ(bad, 0u) << what;
}

// The reduction's own promises: the budget, the maps both ways, kept particles at their own
// places and bound to themselves, indices in range.
void expect_consistent(const Mesh& full, const ReducedMesh& reduced, std::size_t budget, const std::string& what) {
    ASSERT_LE(reduced.particle_count(), budget) << what;
    ASSERT_EQ(reduced.reduced_to_full.size(), reduced.particle_count()) << what;
    ASSERT_EQ(reduced.full_to_reduced.size(), full.particle_count()) << what;
    ASSERT_EQ(reduced.bindings.size(), full.particle_count()) << what;
    for (std::uint32_t r = 0; r < reduced.particle_count(); ++r) {
        const std::uint32_t f = reduced.reduced_to_full[r];
        ASSERT_LT(f, full.particle_count()) << what;
        ASSERT_EQ(reduced.full_to_reduced[f], r) << what;
        ASSERT_EQ(reduced.positions[r], full.positions[f]) << what;
        ASSERT_EQ(reduced.bindings[f], (SkinBinding{{r, r, r}, {1.0f, 0.0f, 0.0f}, 0.0f})) << what;
    }
    std::size_t kept = 0;
    for (std::size_t f = 0; f < full.particle_count(); ++f) {
        if (reduced.full_to_reduced[f] != kNotSimulated) ++kept;
        for (std::uint32_t p : reduced.bindings[f].particles) ASSERT_LT(p, reduced.particle_count()) << what;
        const auto& w = reduced.bindings[f].weights;
        // Sum to 1: each weight is rounded to float once, the first from the other two.
        EXPECT_NEAR(double(w[0]) + w[1] + w[2], 1.0, 4 * kEps * (1 + std::abs(w[0]) + std::abs(w[1]) + std::abs(w[2])));
    }
    EXPECT_EQ(kept, reduced.particle_count()) << what;
    for (std::uint32_t p : reduced.triangles) ASSERT_LT(p, reduced.particle_count()) << what;
}

// A rotation by `angle` about `axis`, then a translation, of a point (in double).
Vec3d moved(const Vec3d& p, const Vec3d& axis, double angle, const Vec3d& shift) {
    const Vec3d k = normalize(axis);
    const double c = std::cos(angle), s = std::sin(angle);
    return p * c + cross(k, p) * s + k * (dot(k, p) * (1.0 - c)) + shift;  // Rodrigues
}

// Moving the particles rigidly moves every full vertex rigidly: the skinned mesh from the moved
// particles is the moved rest mesh, within the rounding of skin_tolerance at the new places
// (plus the rounding of the moved particles to float, which the weights carry along).
void expect_rigid(const Mesh& full, const ReducedMesh& reduced, const std::string& what) {
    const Vec3d axis{1.0, 2.0, 3.0};
    const double angle = 0.7;
    Vec3 lo = full.positions[0], hi = lo;
    for (const Vec3& p : full.positions) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const Vec3d shift = Vec3d(hi - lo) * 3.0 + Vec3d{0.5, -0.25, 1.0} * length(Vec3d(hi - lo));
    std::vector<Vec3> particles;
    for (const Vec3& p : reduced.positions) {
        const Vec3d q = moved(Vec3d(p), axis, angle, shift);
        particles.push_back({float(q.x), float(q.y), float(q.z)});
    }
    const std::vector<Vec3> out = skin(reduced, particles);
    std::size_t bad = 0;
    for (std::size_t i = 0; i < full.particle_count(); ++i) {
        const Vec3d expected = moved(Vec3d(full.positions[i]), axis, angle, shift);
        const double error = length(Vec3d(out[i]) - expected);
        const double tolerance = 2.0 * skin_tolerance(reduced.bindings[i], particles) +
                                 kEps * std::max(max_abs(Vec3{float(expected.x), float(expected.y), float(expected.z)}),
                                                 max_abs(full.positions[i]));
        if (error > tolerance && bad++ < 5) {
            ADD_FAILURE() << what << ": vertex " << i << " is " << error << " from where a rigid motion takes it (tolerance "
                          << tolerance << ")";
        }
    }
    EXPECT_EQ(bad, 0u) << what;
}

// The 12,000-vertex torus (major radius 1 m, tube 0.3 m), as loaded from OBJ text.
Mesh torus_12000(const TempDir& dir) { return load_text(dir, "torus.obj", to_obj(torus(1.0, 0.3, 120, 100))); }

// --- The budget ---------------------------------------------------------------------------------

// At or below the budget nothing changes: every particle, in order, bound to itself; the
// skinned mesh is the simulated one exactly.
TEST(Reduce, AtOrBelowTheBudgetNothingChanges) {
    TempDir dir;
    const Mesh full = load_text(dir, "capsule.obj", to_obj(capsule(0.25, 1.8, UpAxis::Z)));
    for (const std::size_t budget : {full.particle_count(), full.particle_count() + 1, kMaxParticles}) {
        const ReducedMesh reduced = reduce_mesh(full, budget);
        EXPECT_EQ(reduced.positions, full.positions);
        std::vector<std::uint32_t> identity(full.particle_count());
        std::iota(identity.begin(), identity.end(), 0u);
        EXPECT_EQ(reduced.full_to_reduced, identity);
        EXPECT_EQ(reduced.reduced_to_full, identity);
        expect_consistent(full, reduced, budget, "identity");
        EXPECT_EQ(skin(reduced, reduced.positions), full.positions);  // exactly: copies
        EXPECT_EQ(reduced.triangles.size(), full.triangles.size());
    }
}

// The budget is never exceeded, for any budget from the least (4) to one below the count, and
// a budget of 50 or more is used at least half (clustering keeps 80 to 97% of it on the bunny,
// the armadillo and the others: half catches a reduction that collapsed).
TEST(Reduce, TheBudgetIsHonouredExactly) {
    TempDir dir;
    const Mesh full = torus_12000(dir);
    ASSERT_EQ(full.particle_count(), 12000u);
    for (const std::size_t budget : {4, 5, 7, 10, 50, 100, 999, 2500, 5000, 11999}) {
        const ReducedMesh reduced = reduce_mesh(full, budget);
        const std::string what = "budget " + std::to_string(budget);
        EXPECT_LE(reduced.particle_count(), budget) << what;
        EXPECT_GE(reduced.particle_count(), budget >= 50 ? budget / 2 : kMinReducedParticles) << what;
        expect_consistent(full, reduced, budget, what);
        expect_rest_shape(full, reduced, what);
    }
}

TEST(Reduce, ABudgetTooSmallForAShapeIsRefused) {
    TempDir dir;
    const Mesh full = torus_12000(dir);
    EXPECT_REFUSED_NAMING(reduce_mesh(full, 3), "torus.obj", "budget of 3");
    EXPECT_REFUSED_NAMING(reduce_mesh(full, 0), "torus.obj", "budget of 0");
    // Unless there is nothing to reduce.
    EXPECT_EQ(reduce_mesh(points({{0, 0, 0}, {1, 0, 0}}), 2).particle_count(), 2u);
}

// --- Spread over the whole body -----------------------------------------------------------------

// With h the spacing an even spread would have (sqrt(area / kept)), every full vertex lies
// within 2 h of a kept particle (1.0 to 1.3 h measured on the bunny, the armadillo, the mug
// and the others; a reduction that left a patch bare, or kept a cluster, goes past 2 h), and no
// kept particle stands for more than 4 times the mean area (2.5 to 5 measured on scans whose
// own vertices are uneven; the torus is even, so 4 is generous for it and still catches a
// cluster).
TEST(Reduce, ParticlesAreSpreadOverTheWholeBody) {
    TempDir dir;
    const Mesh full = torus_12000(dir);
    const ReducedMesh reduced = reduce_mesh(full, 1000);
    // Each full vertex's share of the area: a third of each triangle it is a corner of.
    std::vector<double> area(full.particle_count(), 0.0);
    double total = 0.0;
    for (std::size_t t = 0; t < full.triangles.size(); t += 3) {
        const std::uint32_t p[3] = {full.render_vertices[full.triangles[t]].particle,
                                    full.render_vertices[full.triangles[t + 1]].particle,
                                    full.render_vertices[full.triangles[t + 2]].particle};
        const double a = 0.5 * length(cross(Vec3d(full.positions[p[1]] - full.positions[p[0]]),
                                            Vec3d(full.positions[p[2]] - full.positions[p[0]])));
        for (std::uint32_t q : p) area[q] += a / 3.0;
        total += a;
    }
    const double h = std::sqrt(total / double(reduced.particle_count()));
    std::vector<double> owned(reduced.particle_count(), 0.0);
    double farthest = 0.0;
    for (std::size_t i = 0; i < full.particle_count(); ++i) {
        std::pair<double, std::size_t> best{std::numeric_limits<double>::infinity(), 0};
        for (std::size_t k = 0; k < reduced.particle_count(); ++k) {
            best = std::min(best, {length(Vec3d(reduced.positions[k]) - Vec3d(full.positions[i])), k});
        }
        farthest = std::max(farthest, best.first);
        owned[best.second] += area[i];
    }
    EXPECT_LT(farthest, 2.0 * h) << "h = " << h;
    const double mean = total / double(reduced.particle_count());
    EXPECT_LT(*std::max_element(owned.begin(), owned.end()), 4.0 * mean);
}

// --- Skinning -----------------------------------------------------------------------------------

// At rest every full vertex comes back where it was (skin_tolerance), and under a rigid motion
// of the particles the full mesh moves rigidly: for surfaces in any units and orientation,
// with the y-up capsule in millimetres and the z-up one in kilometres among them.
TEST(Reduce, SkinningKeepsTheRestShapeAndMovesRigidly) {
    TempDir dir;
    const std::vector<std::pair<std::string, Mesh>> meshes = {
        {"torus", torus_12000(dir)},
        {"capsule mm y-up", load_text(dir, "mm.obj", to_obj(scaled(capsule(0.25, 1.8, UpAxis::Y, 48, 16), 1000.0)))},
        {"capsule km z-up", load_text(dir, "km.off", to_off(scaled(capsule(0.25, 1.8, UpAxis::Z, 48, 16), 0.001)))},
    };
    for (const auto& [name, full] : meshes) {
        for (const std::size_t budget : {std::size_t{4}, std::size_t{60}, full.particle_count() / 5}) {
            const ReducedMesh reduced = reduce_mesh(full, budget);
            const std::string what = name + ", budget " + std::to_string(budget);
            expect_consistent(full, reduced, budget, what);
            expect_rest_shape(full, reduced, what);
            expect_rigid(full, reduced, what);
        }
    }
}

// A vertex bound to a triangle follows its normal: push the three particles apart along it
// and the vertex moves with them by the same amount (it rides at its offset above the plane).
TEST(Reduce, ABoundVertexRidesOnItsTriangle) {
    const std::vector<SkinBinding> bindings = {{{0, 1, 2}, {0.25f, 0.25f, 0.5f}, 2.0f}};
    const float x[3] = {0, 1, 0}, y[3] = {0, 0, 1}, z0[3] = {0, 0, 0}, z1[3] = {3, 3, 3};
    float ox, oy, oz;
    apply_skinning(bindings, x, y, z0, &ox, &oy, &oz);
    EXPECT_EQ(ox, 0.25f);  // 0.25 * 0 + 0.25 * 1 + 0.5 * 0, all exact in float
    EXPECT_EQ(oy, 0.5f);
    EXPECT_EQ(oz, 2.0f);  // the unit normal of a counter-clockwise triangle in the xy plane is +z
    apply_skinning(bindings, x, y, z1, &ox, &oy, &oz);
    EXPECT_EQ(oz, 5.0f);
    // Turned over (two corners swapped), the normal points down and the vertex goes under.
    const float x_swapped[3] = {0, 0, 1}, y_swapped[3] = {0, 1, 0};
    apply_skinning(bindings, x_swapped, y_swapped, z0, &ox, &oy, &oz);
    EXPECT_EQ(oz, -2.0f);
}

// --- Point clouds -----------------------------------------------------------------------------

// A cloud reduces too: its particles spread through it on a grid, every point bound to three
// nearby ones. A cloud on one line (no triangle has an area) is bound along the line.
TEST(Reduce, PointCloudsReduceToo) {
    const Mesh cloud = points(random_cloud(8000, 7, 2.0f), "cloud");
    for (const std::size_t budget : {std::size_t{4}, std::size_t{500}}) {
        const ReducedMesh reduced = reduce_mesh(cloud, budget);
        const std::string what = "cloud, budget " + std::to_string(budget);
        EXPECT_TRUE(reduced.triangles.empty());
        EXPECT_GE(reduced.particle_count(), budget / 2) << what;
        expect_consistent(cloud, reduced, budget, what);
        expect_rest_shape(cloud, reduced, what);
        expect_rigid(cloud, reduced, what);
    }
    std::vector<Vec3> line;
    for (int i = 0; i < 1000; ++i) line.push_back({0.001f * float(i), 0.002f * float(i), -0.001f * float(i)});
    const Mesh on_a_line = points(line, "line");
    const ReducedMesh reduced = reduce_mesh(on_a_line, 20);
    expect_consistent(on_a_line, reduced, 20, "line");
    expect_rest_shape(on_a_line, reduced, "line");
    expect_rigid(on_a_line, reduced, "line");
}

// A cloud that is a line but for bumps of 1e-44 m (a float's smallest numbers), with points
// 1 mm beside it: the only triangles among the particles kept on the line are a 1e-44 m bump
// high, and binding a point 1 mm off to one asks for weights near 1e41, beyond float. Such a
// point is put on the line through its nearest two particles instead: every number finite,
// every point drawn within its 1 mm of where it is. (Found by fuzz_mesh.)
TEST(Reduce, APointBesideANearlyFlatTriangleGetsFiniteWeights) {
    std::vector<Vec3> cloud;
    for (int i = 0; i < 16; ++i) cloud.push_back({float(i), i % 2 == 0 ? 1e-44f : 0.0f, 0.0f});
    for (int i = 0; i < 16; ++i) cloud.push_back({float(i) + 0.5f, 1e-3f, 0.0f});
    const Mesh full = points(cloud, "bumpy line");
    const ReducedMesh reduced = reduce_mesh(full, 16);
    expect_consistent(full, reduced, 16, "bumpy line");
    const std::vector<Vec3> out = skin(reduced, reduced.positions);
    for (std::size_t i = 0; i < full.particle_count(); ++i) {
        const SkinBinding& b = reduced.bindings[i];
        for (float w : b.weights) ASSERT_TRUE(std::isfinite(w)) << "point " << i;
        ASSERT_TRUE(std::isfinite(b.offset)) << "point " << i;
        EXPECT_LE(length(Vec3d(out[i]) - Vec3d(full.positions[i])), 1e-3 * (1.0 + 1e-5)) << "point " << i;
    }
}

// A surface with points beside it (vertices in no face): both get particles, in proportion to
// their numbers, and every vertex of either follows.
TEST(Reduce, StrayPointsBesideASurfaceGetTheirShare) {
    PolyMesh mesh = torus(1.0, 0.3, 120, 100);
    for (const Vec3& p : random_cloud(3000, 11, 0.5f)) mesh.positions.push_back({p.x + 3.0, double(p.y), double(p.z)});
    TempDir dir;
    const Mesh full = load_text(dir, "mixed.obj", to_obj(mesh));
    const ReducedMesh reduced = reduce_mesh(full, 1500);
    std::size_t stray_kept = 0;
    for (std::uint32_t f : reduced.reduced_to_full) stray_kept += f >= 12000 ? 1 : 0;
    // 3,000 of 15,000 vertices are points: a fifth of the budget, 300, and the points' grid
    // keeps most of it (the grid may fall short, never over).
    EXPECT_LE(stray_kept, 300u);
    EXPECT_GE(stray_kept, 150u);
    EXPECT_GE(reduced.particle_count() - stray_kept, 600u);  // the surface's 1,200, at least half
    expect_consistent(full, reduced, 1500, "mixed");
    expect_rest_shape(full, reduced, "mixed");
    expect_rigid(full, reduced, "mixed");
}

// --- Determinism and speed ------------------------------------------------------------------------

// The same mesh, loaded twice into separate memory, reduces to exactly the same particles,
// bindings and triangles (no randomness, threads or hash order inside).
TEST(Reduce, SameInputSameOutput) {
    TempDir dir;
    const std::string text = to_obj(torus(1.0, 0.3, 120, 100));
    const Mesh a = load_text(dir, "a.obj", text);
    const Mesh b = load_text(dir, "b.obj", text);
    const ReducedMesh first = reduce_mesh(a, 1234);
    EXPECT_EQ(first, reduce_mesh(b, 1234));
    EXPECT_EQ(first, reduce_mesh(a, 1234));
    const Mesh cloud = points(random_cloud(5000, 3), "cloud");
    EXPECT_EQ(reduce_mesh(cloud, 300), reduce_mesh(cloud, 300));
}

// 40,000 vertices (a 200 x 200 torus) to 4,000 particles: the budget held, every vertex bound
// (how long it takes is tests/benchmarks/mesh_benchmarks' BM_Reduce/40000/4000).
TEST(Reduce, FortyThousandVertices) {
    TempDir dir;
    const Mesh full = load_text(dir, "big.obj", to_obj(torus(1.0, 0.3, 200, 200)));
    ASSERT_EQ(full.particle_count(), 40000u);
    const ReducedMesh reduced = reduce_mesh(full, 4000);
    expect_consistent(full, reduced, 4000, "40,000-vertex torus");
    EXPECT_GE(reduced.particle_count(), 3000u);  // the grid may fall short of the budget, not far
    expect_rest_shape(full, reduced, "40,000-vertex torus");
}

// max_particles=all asks for a particle per vertex, which no body gets above kMaxParticles: the
// world says so in one note naming the cap, the particles used and how to ask for fewer. A
// budget given as a number, or a mesh under the cap, is what was asked for: no note.
TEST(Reduce, AllAboveTheCapIsSaidInANote) {
    const Mesh cloud = points(random_cloud(kMaxParticles + 500, 5, 1.0f), "big cloud");
    FlatKeys all;
    all.max_particles = 0;
    const OneBodyWorld capped(all, cloud);
    ASSERT_LE(capped.soft_body(0).particle_count(), kMaxParticles);
    ASSERT_EQ(capped.notes().size(), 1u);
    const std::string& note = capped.notes()[0];
    EXPECT_EQ(note, "big cloud: max_particles=all is capped at 20000 particles: its 20500 distinct vertices run on " +
                        std::to_string(capped.soft_body(0).particle_count()) + " (--set max_particles=N, 4 to 20000, for fewer)");
    EXPECT_EQ(note.find('\n'), std::string::npos);

    FlatKeys numbered;
    numbered.max_particles = 3000;
    EXPECT_TRUE(OneBodyWorld(numbered, cloud).notes().empty());
    EXPECT_TRUE(OneBodyWorld(all, points(random_cloud(500, 5, 1.0f), "small cloud")).notes().empty());
}

}  // namespace
}  // namespace softbody::test
