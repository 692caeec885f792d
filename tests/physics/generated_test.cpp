// Bodies and scenes made from a name (physics/generated.h): what each name makes, the same
// every time, and a clear refusal for a name that makes nothing.
#include "physics/generated.h"
#include "test_support.h"

namespace softbody::test {
namespace {

TEST(Generated, NamesAreToldApartFromPaths) {
    EXPECT_TRUE(is_generated("cloud:5"));
    EXPECT_TRUE(is_generated("ball:3"));
    EXPECT_TRUE(is_generated("pile:100+cloud:1000"));
    EXPECT_FALSE(is_generated("assets/meshes/cube.obj"));
    EXPECT_FALSE(is_generated("cloud"));
    EXPECT_FALSE(is_generated("mesh:4"));
    EXPECT_FALSE(is_generated("pile:3+my.obj"));
    EXPECT_FALSE(is_generated(""));
}

// The choice between a name and a file is open_mesh's: the file reader reads files only, so a
// name handed to it is a file it cannot read, and a file is read the same either way.
TEST(Generated, OpenMeshTellsNamesFromFilesAndTheReaderReadsOnlyFiles) {
    EXPECT_EQ(open_mesh("cloud:50").positions, generated_mesh("cloud:50").positions);
    EXPECT_REFUSED_NAMING(load_mesh("cloud:50"), "cloud:50", "unsupported mesh format");
    TempDir dir;
    const std::string file = dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(open_mesh(file).positions, load_mesh(file).positions);
    EXPECT_EQ(open_mesh(file).particle_count(), 3u);
}

TEST(Generated, CloudHasNParticlesInsideABallAndIsTheSameEachTime) {
    const Mesh a = open_mesh("cloud:700"), b = generated_mesh("cloud:700");
    ASSERT_EQ(a.particle_count(), 700u);
    EXPECT_EQ(a.triangle_count(), 0u);
    for (std::size_t i = 0; i < a.positions.size(); ++i) {
        EXPECT_LE(length(a.positions[i]), 0.5f);
        EXPECT_EQ(a.positions[i], b.positions[i]);
    }
}

TEST(Generated, BallHasTenFourToTheSPlusTwoParticlesOnItsSphere) {
    for (int s = 0; s <= 3; ++s) {
        const Mesh ball = open_mesh("ball:" + std::to_string(s));
        EXPECT_EQ(ball.particle_count(), std::size_t(10 * (1 << (2 * s)) + 2));
        EXPECT_EQ(ball.triangle_count(), std::size_t(20 * (1 << (2 * s))));
        for (const Vec3& p : ball.positions) EXPECT_NEAR(length(p), 0.5f, 1e-6f);
    }
}

TEST(Generated, PileIsNBodiesInABinAndAddsUpWithACloud) {
    const Scene pile = load_scene("pile:30");
    ASSERT_EQ(pile.rigid_bodies.size(), 30u + 4u);  // and the bin's four walls
    std::size_t fixed = 0;
    for (const RigidBodyDef& body : pile.rigid_bodies) fixed += body.fixed;
    EXPECT_EQ(fixed, 4u);
    EXPECT_TRUE(pile.soft_bodies.empty());
    const Scene mixed = load_scene("pile:30+cloud:200");
    EXPECT_EQ(mixed.rigid_bodies.size(), 34u);
    ASSERT_EQ(mixed.soft_bodies.size(), 1u);
    EXPECT_EQ(mixed.soft_bodies[0].mesh, "cloud:200");
    EXPECT_TRUE(mixed.settings.auto_substeps);
    // It builds and runs: every body falls into the bin (or onto its walls, 0.1 m thick
    // outside the floor's 1.4 m) and none leaves it.
    World world((mixed));
    world.run(100);
    ASSERT_EQ(world.status(), Status::Ok);
    for (std::size_t b = 4; b < world.rigid_body_count(); ++b) {
        const Vec3d x = world.rigid_motion(b).x;
        EXPECT_LT(std::max(std::abs(x.x), std::abs(x.y)), 0.8) << world.rigid_body(b).name;
        EXPECT_GT(x.z, 0.0) << world.rigid_body(b).name;
    }
}

// The scenes built as another engine's comparison built them. bin:N: N bodies of the sizes and
// materials given, in a walled bin they stay in. stack:L: the
// pyramid of touching 1 kg cubes stands: after 10 s every cube is where it was put, within a
// millimetre (the contact slop), and the whole pyramid sleeps.
TEST(Generated, BinAndStackAreTheOtherEnginesScenesAndComeToRest) {
    const Scene bin = load_scene("bin:60");
    ASSERT_EQ(bin.rigid_bodies.size(), 60u + 4u);
    for (std::size_t b = 4; b < bin.rigid_bodies.size(); ++b) {
        const RigidBodyDef& def = bin.rigid_bodies[b];
        EXPECT_EQ(def.density, 1000.0);
        EXPECT_EQ(def.rolling_resistance, 0.0f);
        if (def.shape == ShapeKind::Box) {
            EXPECT_GE(def.size->x, 0.2);
            EXPECT_LE(def.size->x, 0.4);
        } else {
            EXPECT_GE(*def.radius, 0.1);
            EXPECT_LE(*def.radius, 0.2);
        }
    }
    // Every body ends in the bin, on or above its floor (balls without rolling resistance may
    // roll on for ever there, as real ones nearly do, so not everything sleeps).
    World heap((bin));
    heap.run(500);
    ASSERT_EQ(heap.status(), Status::Ok);
    const double half = std::abs(bin.rigid_bodies[2].position->x);  // the east wall's centre
    for (std::size_t b = 4; b < heap.rigid_body_count(); ++b) {
        const Vec3d x = heap.rigid_motion(b).x;
        EXPECT_LT(std::max(std::abs(x.x), std::abs(x.y)), half) << heap.rigid_body(b).name;
        EXPECT_GT(x.z, 0.09) << heap.rigid_body(b).name;  // the smallest half-size is 0.1 m
    }
    const Scene stack = load_scene("stack:5");
    ASSERT_EQ(stack.rigid_bodies.size(), 55u);  // 25 + 16 + 9 + 4 + 1
    World world((stack));
    world.run(500);
    ASSERT_EQ(world.status(), Status::Ok);
    for (std::size_t b = 0; b < world.rigid_body_count(); ++b) {
        const Vec3d x = world.rigid_motion(b).x, put = *stack.rigid_bodies[b].position;
        EXPECT_LT(length(x - put), 1e-3) << world.rigid_body(b).name;
    }
    EXPECT_EQ(world.sleeping_count(), 55u);
}

TEST(Generated, BadNamesAreRefusedWithWhatTheyTake) {
    const auto message = [](const std::string& name) {
        try {
            load_scene(name);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    EXPECT_EQ(message("pile:x"), "pile:x: 'x' is not a whole number (write pile:N)");
    EXPECT_EQ(message("pile:0"), "pile:0: pile takes 1 to 5000, not 0");
    EXPECT_EQ(message("ball:9"), "ball:9: ball takes 0 to 5 subdivisions (10 * 4^S + 2 particles)");
    EXPECT_EQ(message("cloud:3+ball:1"), "cloud:3+ball:1: one cloud or ball at most (it is the scene's soft body)");
    EXPECT_THROW(open_mesh("pile:3"), InputError);  // a scene, not a mesh
}

}  // namespace
}  // namespace softbody::test
