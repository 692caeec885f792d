// Automatic substeps: Listing 8's constants with every pair connected are stable only while
// N (k h^2 + 2 c h) < 4 m (physics/README.md#stability): one step of 0.02 s holds up to about 500 particles,
// so a 2,000-particle body needs h of a third of that or less (more with the safety margin
// World::stability() keeps).
#include <gtest/gtest.h>

#include "kernel_support.h"
#include "../physics/one_body_world.h"
#include "physics/world.h"

namespace softbody::test {
namespace {

Mesh cloud(std::size_t n) {
    RawMesh raw;
    raw.positions = random_cloud(n, 2000u, 0.5f);
    return build_mesh(raw, "cloud");
}

TEST(AutoSubsteps, KeepTwoThousandParticlesStableWhereOneStepDiverges) {
    FlatKeys params;  // m 1 kg, k 10 N/m, c 0.1 kg/s, dt 0.02 s, a ground plane, init_height 2 m
    ASSERT_EQ(params.particle_mass, 1.0f);
    ASSERT_EQ(params.stiffness, 10.0f);
    ASSERT_EQ(params.damping, 0.1f);
    ASSERT_EQ(params.dt, 0.02f);
    const Mesh mesh = cloud(2000);
    ASSERT_EQ(mesh.particle_count(), 2000u);

    // One step a tick: past the limit, and the world says so when it blows up.
    params.substeps = 1;
    params.auto_substeps = false;
    OneBodyWorld single(params, mesh, WorldOptions{2, false});
    const Stability before = single.stability();
    EXPECT_FALSE(before.stable);
    EXPECT_GT(before.h_omega, before.limit);
    EXPECT_EQ(before.substeps, 1);
    const int needed = before.substeps_needed;
    ASSERT_GE(needed, 3);  // N (k h^2 + 2 c h) < 4 m first holds at h = dt / 3 (2000 * 0.00178 = 3.6)
    ASSERT_LE(needed, 5);  // and a margin on the estimate should not ask for much more
    single.run(1000);
    ASSERT_EQ(single.status(), Status::Diverged) << "one step a tick survived 1000 ticks";
    EXPECT_LT(single.ticks(), 1000u);
    EXPECT_NE(single.divergence().find("substeps to at least " + std::to_string(needed)), std::string::npos)
        << single.divergence();

    // Automatic: the fewest substeps that are stable, and 1000 ticks (20 s) without trouble.
    params.auto_substeps = true;
    OneBodyWorld automatic(params, mesh, WorldOptions{2, false});
    EXPECT_EQ(automatic.substeps_in_use(), needed);
    const Stability s = automatic.stability();
    EXPECT_TRUE(s.stable);
    EXPECT_LT(s.h_omega, s.limit);
    EXPECT_EQ(s.substeps, needed);
    const double h = double(params.dt) / needed;  // the closed-form bound holds at the step in use
    EXPECT_LT(2000.0 * (10.0 * h * h + 2.0 * 0.1 * h), 4.0 * 1.0);
    automatic.run(1000);
    EXPECT_EQ(automatic.status(), Status::Ok) << automatic.divergence();
    EXPECT_EQ(automatic.ticks(), 1000u);
    // It came to rest on the ground: no particle below it, none flung away.
    EXPECT_GE(automatic.min_z(), params.ground_height);
    const Vec3 com = automatic.center_of_mass();
    EXPECT_LT(com.z, 1.0f);
    for (std::size_t i = 0; i < automatic.soft_body(0).particle_count(); ++i) {
        ASSERT_LT(length(automatic.soft_body(0).x[i] - com), 2.0f) << "particle " << i;
    }
}

// The same world at 1 and 2 threads, tick for tick: bit-identical states.
TEST(AutoSubsteps, WorldIsBitIdenticalAtOneAndTwoThreads) {
    FlatKeys params;
    params.auto_substeps = true;
    const Mesh mesh = cloud(1100);  // five blocks: fifteen tiles, shared out between the threads
    OneBodyWorld one(params, mesh, WorldOptions{1, false});
    OneBodyWorld two(params, mesh, WorldOptions{2, false});
    for (int t = 0; t < 60; ++t) {  // 1.2 s: it falls, hits the ground and bounces
        one.tick();
        two.tick();
        ASSERT_EQ(one.state_hash(), two.state_hash()) << "tick " << t;
    }
    ASSERT_EQ(one.status(), Status::Ok);
}

}  // namespace
}  // namespace softbody::test
