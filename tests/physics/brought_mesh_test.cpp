// Meshes as users bring them (`--mesh FILE`, a dropped file): in millimetres or kilometres,
// written y-up or z-up, with normal indices that name nothing, above the particle budget, and a
// large light body with drag. Each loads at the defaults, is sized and stood up, and runs 10 s
// without diverging.
#include <cmath>

#include "generated_meshes.h"
#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

// What `softbody simulate --mesh FILE` builds: the default keys, the mesh fitted.
World brought(const std::string& path, const std::vector<std::pair<std::string, std::string>>& sets = {}) {
    Scene scene;
    set_scene_key(scene, "mesh", path);
    fit_brought_mesh(scene.soft_bodies.front());
    for (const auto& [key, value] : sets) set_scene_key(scene, key, value);
    return World(scene);
}

// The extent of the body's rest shape along each axis, m.
Vec3 rest_extent(const World& world) {
    const Vec3Array& r = world.soft_body(0).rest;
    Vec3 lo = r[0], hi = lo;
    for (std::size_t i = 0; i < r.size(); ++i) {
        lo = {std::min(lo.x, r.x[i]), std::min(lo.y, r.y[i]), std::min(lo.z, r.z[i])};
        hi = {std::max(hi.x, r.x[i]), std::max(hi.y, r.y[i]), std::max(hi.z, r.z[i])};
    }
    return hi - lo;
}

// A standing figure 1.8 m tall and 0.5 m across (a capsule), in millimetres written y-up, in
// kilometres written y-up, and with dangling normal indices: sized so its largest side is 1 m
// (the height: 1.8 m becomes 1 m, 0.5 m becomes 0.278 m), stood up (its height along z), and
// then it falls, lands and runs 10 s at the defaults.
TEST(BroughtMesh, AFigureInAnyUnitStandsUpAtOneMetreAndRuns) {
    TempDir dir;
    struct Case {
        std::string name, text;
        double metres_per_unit;
    };
    const std::vector<Case> cases = {
        {"figure_mm.obj", to_obj(scaled(capsule(0.25, 1.8, UpAxis::Y), 1000.0)), 0.001},
        {"figure_km.obj", to_obj(scaled(capsule(0.25, 1.8, UpAxis::Y), 0.001)), 1000.0},
        {"figure_dangling.obj", to_obj(scaled(capsule(0.25, 1.8, UpAxis::Y), 1000.0), {.dangling_normals = true}), 0.001},
    };
    for (const Case& c : cases) {
        World world = brought(dir.write(c.name, c.text));
        const SoftBody& body = world.soft_body(0);
        // The file's largest side (1.8 m in its units) becomes 1 m: to float rounding.
        EXPECT_NEAR(body.scale_used, c.metres_per_unit / 1.8, 1e-6 * c.metres_per_unit / 1.8) << c.name;
        const Vec3 size = rest_extent(world);
        EXPECT_NEAR(size.z, 1.0f, 1e-5f) << c.name << ": standing, 1 m tall";
        EXPECT_NEAR(size.x, 0.5f / 1.8f, 1e-5f) << c.name;
        EXPECT_LT(size.y, 0.5f / 1.8f * (1 + 1e-5f)) << c.name;
        // Centred over the origin, lifted by init_height (2 m): its middle at 2 m.
        EXPECT_NEAR(world.center_of_mass().z, 2.0f, 1e-3f) << c.name;
        EXPECT_NEAR(world.center_of_mass().x, 0.0f, 1e-4f) << c.name;
        world.run(500);
        ASSERT_EQ(world.status(), Status::Ok) << c.name << ": " << world.divergence();
        EXPECT_GE(world.min_z(), 0.0f) << c.name;
        EXPECT_LT(world.center_of_mass().z, 1.0f) << c.name << ": it fell and landed";
    }
}

// The rule is the exporters' (+y up); a file written z-up says so with up_axis, and then stands
// as written. Left at the default, the same file lies on its side.
TEST(BroughtMesh, AZUpFileStandsWithUpAxisZ) {
    TempDir dir;
    const std::string path = dir.write("figure_zup.off", to_off(scaled(capsule(0.25, 1.8, UpAxis::Z), 1000.0)));
    World standing = brought(path, {{"up_axis", "z"}});
    EXPECT_NEAR(rest_extent(standing).z, 1.0f, 1e-5f);
    World lying = brought(path);
    EXPECT_NEAR(rest_extent(lying).y, 1.0f, 1e-5f);  // +z of the file turned to -y
    EXPECT_LT(rest_extent(lying).z, 0.3f);
    // An explicit scale wins over the automatic one, and keeps the file's coordinates.
    World metres = brought(path, {{"up_axis", "z"}, {"scale", "0.001"}});
    EXPECT_NEAR(rest_extent(metres).z, 1.8f, 1e-5f);
}

// Above the particle budget: a torus of 12,000 vertices is simulated on at most 3,000 particles
// spread over it, every vertex bound to three of them, and runs 10 s; with max_particles all it
// has one particle per vertex.
TEST(BroughtMesh, AboveTheBudgetItRunsOnAReducedSet) {
    TempDir dir;
    const std::string path = dir.write("torus.obj", to_obj(torus(1.0, 0.3, 120, 100)));
    World world = brought(path);
    const SoftBody& body = world.soft_body(0);
    ASSERT_TRUE(body.reduced);
    EXPECT_LE(world.soft_body(0).particle_count(), 3000u);
    EXPECT_GT(world.soft_body(0).particle_count(), 2000u);  // the budget is used, not wasted
    EXPECT_EQ(body.mesh.particle_count(), 12000u);
    EXPECT_EQ(body.skin.size(), 12000u);  // every vertex follows the simulated ones
    world.run(500);
    ASSERT_EQ(world.status(), Status::Ok) << world.divergence();
    EXPECT_GE(world.min_z(), 0.0f);
    // Pinning a vertex pins the particle it moves with.
    World pinned = brought(path, {{"pinned", "0,5000"}, {"gravity", "0,0,-9.81"}});
    EXPECT_TRUE(pinned.soft_body(0).is_pinned(particle_of_vertex(pinned.soft_body(0), 0)));
    EXPECT_TRUE(pinned.soft_body(0).is_pinned(particle_of_vertex(pinned.soft_body(0), 5000)));
    // All: one particle per vertex (12,000 of them; fine to build, slow to run).
    World all = brought(path, {{"max_particles", "all"}});
    EXPECT_FALSE(all.soft_body(0).reduced);
    EXPECT_EQ(all.soft_body(0).particle_count(), 12000u);
}

// A large, light body with drag, as a scene with an explicit scale might bring it: a sheet
// 550 m across of four particles. Drag's implicit step keeps it stable (forces.h); it floats
// down at its terminal velocity and lands.
TEST(BroughtMesh, ALargeLightSheetWithDragRuns) {
    TempDir dir;
    const std::string path = dir.write("sheet.obj", "v 0 0 0\nv 550 0 0\nv 550 0 550\nv 0 0 550\nf 1 2 3 4\n");
    World world = brought(path, {{"scale", "1"}});
    world.run(500);
    ASSERT_EQ(world.status(), Status::Ok) << world.divergence();
    float fastest = 0.0f;
    for (std::size_t i = 0; i < world.soft_body(0).particle_count(); ++i) fastest = std::max(fastest, length(velocity(world, i)));
    EXPECT_LT(fastest, 0.1f);  // about 2 cm/s, its terminal velocity, or resting
}

}  // namespace
}  // namespace softbody::test
