// What a world holds, made and unmade while it runs: typed ids that name nothing once their
// thing is gone, names unique across bodies and springs, springs that go with their bodies, keys
// by name, and time travel (snapshots and the history) across a body made or unmade.
#include "physics/history.h"
#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

// A box resting on the ground and a soft ball falling beside it, a fixed point and a ball on a
// named spring: one of each kind.
Scene small_world() {
    return parse_scene(R"({
      "world": {"auto_substeps": true},
      "soft_bodies": [{"name": "jelly", "mesh": "ball:1", "scale": 0.5, "up_axis": "z", "particle_mass": 0.05,
                       "stiffness": 60, "damping": 0.5, "position": [0.8, 0, 1.0]}],
      "rigid_bodies": [{"name": "crate", "shape": "box", "size": [0.4, 0.4, 0.4], "position": [-0.6, 0, 0.5]},
                       {"name": "bob", "shape": "sphere", "radius": 0.1, "mass": 1, "position": [0, 1, 1.5]}],
      "springs": [{"name": "coil", "a": {"point": [0, 1, 2.5]}, "b": {"body": "bob"}, "stiffness": 40}]
    })",
                       "small.json");
}

RigidBodyDef thrown_ball() {
    RigidBodyDef ball;
    ball.name = "thrown";
    ball.shape = ShapeKind::Sphere;
    ball.radius = 0.12;
    ball.position = Vec3d{-0.6, 0.0, 1.6};
    ball.velocity = Vec3d{0.0, 0.0, -2.0};
    return ball;
}

TEST(WorldThings, IdsNameWhatTheyMadeAndNothingOnceItIsGone) {
    World world(small_world());
    const RigidBodyId crate = *world.find_rigid_body("crate");
    const RigidBodyId thrown = world.create_rigid_body(thrown_ball());
    EXPECT_EQ(world.rigid_body_count(), 3u);
    EXPECT_EQ(world.index(thrown), 2u);
    EXPECT_EQ(world.def(thrown).name, "thrown");
    world.destroy(crate);
    // The others keep their ids, and move down in the order.
    EXPECT_FALSE(world.contains(crate));
    EXPECT_EQ(world.index(thrown), 1u);
    EXPECT_REFUSED_NAMING(world.index(crate), "no longer exists");
    // The slot comes back with the next generation: the old id still names nothing.
    const RigidBodyId again = world.create_rigid_body(small_world().rigid_bodies[0]);
    EXPECT_EQ(again.slot, crate.slot);
    EXPECT_NE(again.generation, crate.generation);
    EXPECT_FALSE(world.contains(crate));
    EXPECT_TRUE(world.contains(again));
    world.run(10);
    EXPECT_EQ(world.status(), Status::Ok) << world.divergence();
}

TEST(WorldThings, NamesAreUniqueAndARefusalChangesNothing) {
    World world(small_world());
    const std::uint64_t hash = world.state_hash();
    RigidBodyDef twin = thrown_ball();
    twin.name = "coil";  // the spring's name
    EXPECT_REFUSED_NAMING(world.create_rigid_body(twin), "'coil'", "unique");
    SoftBodyDef bad;
    bad.name = "blob";
    bad.mesh = "ball:1";
    bad.stiffness = -1.0f;
    EXPECT_REFUSED_NAMING(world.create_soft_body(bad), "soft body 'blob'", "'stiffness'");
    bad.stiffness = 10.0f;
    bad.mesh = "/no/such/mesh.obj";
    EXPECT_REFUSED_NAMING(world.create_soft_body(bad), "soft body 'blob'", "/no/such/mesh.obj");
    EXPECT_EQ(world.soft_body_count(), 1u);
    EXPECT_EQ(world.rigid_body_count(), 2u);
    EXPECT_EQ(world.state_hash(), hash);
}

// A spring goes with the body it holds; the world's other springs stay.
TEST(WorldThings, DestroyingABodyDestroysItsSprings) {
    World world(small_world());
    SpringDef tie;
    tie.name = "tie";
    tie.a.body = "crate";
    tie.b.body = "jelly";
    tie.b.vertex = 0;
    tie.stiffness = 5.0;
    const SpringId tie_id = world.create_spring(tie);
    EXPECT_EQ(world.spring_count(), 2u);
    world.destroy(*world.find_soft_body("jelly"));
    EXPECT_EQ(world.spring_count(), 1u);
    EXPECT_FALSE(world.contains(tie_id));
    EXPECT_TRUE(world.find_spring("coil"));
    world.run(20);
    EXPECT_EQ(world.status(), Status::Ok) << world.divergence();
}

// Keys by name: a spring's, a rigid body's, every soft body's; the one path a slider takes.
TEST(WorldThings, KeysAreSetByName) {
    World world(small_world());
    world.set_key_text("coil.stiffness", "160");
    EXPECT_EQ(world.links()[0].k, 160.0);
    world.set_key("coil.damping", 0.5);
    EXPECT_EQ(world.links()[0].c, 0.5);
    world.set_key_text("stiffness", "90");
    EXPECT_EQ(world.soft_body(0).stiffness, 90.0f);
    world.set_key_text("dt", "0.01");
    EXPECT_EQ(world.settings().dt, 0.01f);
    EXPECT_EQ(std::get<double>(world.key("coil.stiffness")), 160.0);
    // A key that applies on reset waits for it, and the world says so.
    EXPECT_FALSE(world.reset_pending());
    world.set_key_text("bob.mass", "0.25");
    EXPECT_TRUE(world.reset_pending());
    EXPECT_EQ(world.rigid_body(1).mass, 1.0);
    world.reset();
    EXPECT_FALSE(world.reset_pending());
    EXPECT_EQ(world.rigid_body(1).mass, 0.25);
    EXPECT_REFUSED_NAMING(world.set_key_text("coil.mass", "1"), "spring 'coil'", "'mass'");
    EXPECT_REFUSED_NAMING(world.set_key_text("nobody.mass", "1"), "'nobody'");
}

// A snapshot holds what the world held: restored after a body was made, the body is gone; the
// same add then gives the same bits as the first time.
TEST(WorldThings, ASnapshotBeforeAnAddTakesTheWorldBackWithoutIt) {
    World world(small_world());
    world.run(20);
    const WorldSnapshot before = world.snapshot();
    const std::uint64_t at_20 = world.state_hash();
    world.create_rigid_body(thrown_ball());
    world.run(30);
    const std::uint64_t at_50 = world.state_hash();
    world.restore(before);
    EXPECT_EQ(world.rigid_body_count(), 2u);
    EXPECT_EQ(world.state_hash(), at_20);
    world.create_rigid_body(thrown_ball());
    world.run(30);
    EXPECT_EQ(world.state_hash(), at_50);
}

// And after a body was unmade, it is made again as it was then.
TEST(WorldThings, ASnapshotBeforeARemoveMakesTheBodyAgain) {
    for (int threads : {1, 2}) {
        World world(small_world(), WorldOptions{threads});
        world.run(15);
        const WorldSnapshot before = world.snapshot();
        world.run(25);
        const std::uint64_t straight = world.state_hash();
        world.restore(before);
        world.destroy(*world.find_soft_body("jelly"));
        world.destroy(*world.find_rigid_body("bob"));  // and its spring with it
        world.run(25);
        EXPECT_EQ(world.soft_body_count(), 0u);
        world.restore(before);
        EXPECT_EQ(world.soft_body_count(), 1u);
        EXPECT_EQ(world.spring_count(), 1u);
        world.run(25);
        EXPECT_EQ(world.state_hash(), straight) << threads << " threads";
    }
}

// The history across a body made at tick 25: back before it, the body is gone; playing on
// through tick 25 makes it again there, and the future is the one that happened.
TEST(WorldThings, TimeTravelGoesBackAcrossAnAdd) {
    World world(small_world());
    History history;
    history.start(world);
    std::vector<std::uint64_t> hashes{world.state_hash()};
    for (int t = 0; t < 60; ++t) {
        if (world.ticks() == 25) {
            world.create_rigid_body(thrown_ball());
            history.keyframe_now(world);
        }
        history.before_tick(world);
        world.tick();
        history.after_tick(world);
        hashes.push_back(world.state_hash());
    }
    history.go_to(world, 12);
    EXPECT_EQ(world.rigid_body_count(), 2u);
    EXPECT_EQ(world.state_hash(), hashes[12]);
    history.go_to(world, 40);
    EXPECT_EQ(world.rigid_body_count(), 3u);
    EXPECT_EQ(world.state_hash(), hashes[40]);
    history.go_to(world, 20);
    while (world.ticks() < 60) {
        history.before_tick(world);
        world.tick();
        history.after_tick(world);
    }
    EXPECT_EQ(world.rigid_body_count(), 3u);
    EXPECT_EQ(world.state_hash(), hashes[60]);
}

}  // namespace
}  // namespace softbody::test
