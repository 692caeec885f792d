// Time travel (World::snapshot and restore, history.h): going back to any recorded tick gives
// the world that was there, bit for bit, under every integrator, with soft and rigid bodies
// touching and a spring between them; playing on from it gives the future that happened, grabs
// and key changes included; changing the past drops the recorded future; the record keeps what
// it promises.
#include <vector>

#include "physics/history.h"
#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

// A soft cloud, a rigid ball on a spring and a fixed table: every kind of state a tick carries.
World travel_world() {
    const std::string scene =
        "{\"stiffness\": 0.5, \"damping\": 0.01, \"particle_mass\": 0.05, \"rigid_bodies\": ["
        "{\"name\": \"table\", \"shape\": \"box\", \"size\": [1, 1, 0.6], \"fixed\": true, \"position\": [0.2, 0, 0.3]},"
        "{\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": 0.2, \"position\": [-0.4, 0.1, 1.5], \"velocity\": [0.5, 0, 0]}],"
        " \"springs\": [{\"a\": {\"body\": \"ball\", \"point\": [0, 0, 0.2]}, \"b\": {\"point\": [-0.4, 0.1, 2.5]},"
        " \"stiffness\": 20, \"damping\": 0.5}]}";
    WorldDef def = parse_scene(scene, "travel.json");
    std::vector<Vec3> cloud = random_cloud(150, 5, 0.3f);
    for (Vec3& p : cloud) p += Vec3{0.0f, 0.0f, 1.2f};
    SoftBodyDef body = flat_body_of(scene, points(cloud));
    body.init_height = 0.0f;
    def.soft_bodies.push_back(std::move(body));
    return World(def);
}

// What a user does during the live run, tick by tick: a grab dragged across ticks 30-60, the
// stiffness raised at 90, the ball's restitution changed at 110.
void user_inputs(World& world) {
    const std::uint64_t t = world.ticks();
    if (t >= 30 && t < 60) {
        Grab grab;
        grab.particle = 3;
        grab.target = {0.1f * float(t - 30) / 30.0f, 0.0f, 2.0f};
        world.set_grab(grab);
    } else if (t == 60) {
        world.set_grab(std::nullopt);
    }
    if (t == 90) {
        FlatKeys p = flat_keys(world);
        p.stiffness = 0.8f;
        set_flat(world, p);
    }
    if (t == 110) set_material(world, 1, 0.9f, 0.2f);
}

// The live run, recorded: the state hash after every tick (hashes[t] is the hash at tick t).
std::vector<std::uint64_t> live_run(World& world, History& history, std::uint64_t ticks) {
    std::vector<std::uint64_t> hashes{world.state_hash()};
    history.start(world);
    while (world.ticks() < ticks && world.status() == Status::Ok) {
        user_inputs(world);
        history.before_tick(world);
        world.tick();
        history.after_tick(world);
        hashes.push_back(world.state_hash());
    }
    return hashes;
}

void play(World& world, History& history, std::uint64_t ticks) {
    for (std::uint64_t k = 0; k < ticks; ++k) {
        history.before_tick(world);
        world.tick();
        history.after_tick(world);
    }
}

TEST(History, GoingBackGivesTheWorldThatWasThereAndPlayingOnTheFutureThatHappened) {
    for (const char* integrator : {"verlet", "symplectic_euler", "explicit_euler", "rk4"}) {
        World world = travel_world();
        FlatKeys p = flat_keys(world);
        p.integrator = *integrator_from_string(integrator);
        if (p.integrator == Integrator::ExplicitEuler) {
            // The grab's pull excites it past its limit at the automatic substeps (it gains
            // energy at every step): four fixed substeps hold it.
            p.auto_substeps = false;
            p.substeps = 4;
        }
        set_flat(world, p);
        History history;
        const std::vector<std::uint64_t> hashes = live_run(world, history, 200);
        ASSERT_EQ(world.status(), Status::Ok) << integrator << ": " << world.divergence();
        // Back to moments inside the grab, before and after the key changes, and on keyframes.
        for (std::uint64_t t : {0u, 7u, 45u, 60u, 95u, 113u, 150u, 199u}) {
            EXPECT_EQ(history.go_to(world, t), t);
            EXPECT_EQ(world.state_hash(), hashes[t]) << integrator << " at tick " << t;
        }
        // Play on from the middle of the grab: the recorded grab, stiffness and restitution replay.
        history.go_to(world, 40);
        EXPECT_TRUE(history.in_past(world));
        play(world, history, 160);
        EXPECT_EQ(world.ticks(), 200u);
        EXPECT_EQ(world.state_hash(), hashes[200]) << integrator;
        EXPECT_FALSE(history.in_past(world));
        EXPECT_FLOAT_EQ(world.soft_body(0).def.stiffness, 0.8f);
    }
}

// A world that blew up can be taken back to before it did: explicit Euler at the automatic
// substeps, pulled by the grab, diverges at tick 78; at tick 60 it is whole again, the same bits.
TEST(History, GoingBackBeforeADivergenceGivesTheWorldBackWhole) {
    World world = travel_world();
    History history;
    std::vector<std::uint64_t> hashes = live_run(world, history, 100);
    // Then explicit Euler at a stiffness its single step cannot hold (it gains energy from every
    // spring a step, by sqrt(1 + (h omega)^2)): it blows up within a few ticks.
    FlatKeys p = flat_keys(world);
    p.integrator = Integrator::ExplicitEuler;
    p.auto_substeps = false;
    p.stiffness = 50.0f;
    set_flat(world, p);
    while (world.ticks() < 200 && world.status() == Status::Ok) {
        history.before_tick(world);
        world.tick();
        history.after_tick(world);
        hashes.push_back(world.state_hash());
    }
    ASSERT_EQ(world.status(), Status::Diverged);
    ASSERT_GT(hashes.size(), 61u);
    history.go_to(world, 60);
    EXPECT_EQ(world.status(), Status::Ok);
    EXPECT_TRUE(world.divergence().empty());
    EXPECT_EQ(world.state_hash(), hashes[60]);
}

TEST(History, StepsBackOneTickAtATime) {
    World world = travel_world();
    History history;
    const std::vector<std::uint64_t> hashes = live_run(world, history, 60);
    for (std::uint64_t t = 59; t + 1 > 0 && t <= 59; --t) {
        history.go_to(world, world.ticks() - 1);
        ASSERT_EQ(world.ticks(), t);
        EXPECT_EQ(world.state_hash(), hashes[t]) << "tick " << t;
        if (t == 0) break;
    }
    // At the oldest tick, a step back stays there.
    EXPECT_EQ(history.go_to(world, 0), 0u);
}

TEST(History, ChangingThePastDropsTheRecordedFuture) {
    World world = travel_world();
    History history;
    const std::vector<std::uint64_t> hashes = live_run(world, history, 150);
    history.go_to(world, 100);
    FlatKeys p = flat_keys(world);
    p.gravity.z = -3.0f;  // a what-if from tick 100
    history.branch(world);
    set_flat(world, p);
    EXPECT_EQ(history.newest_tick(), 100u);
    EXPECT_FALSE(history.in_past(world));
    play(world, history, 50);
    EXPECT_EQ(history.newest_tick(), 150u);
    EXPECT_NE(world.state_hash(), hashes[150]);
    // The new future is itself recorded: back and forth through it gives the same bits.
    const std::uint64_t now = world.state_hash();
    history.go_to(world, 120);
    history.go_to(world, 150);
    EXPECT_EQ(world.state_hash(), now);
}

TEST(History, APinSetInThePastIsReplayedFromItsKeyframe) {
    World world = travel_world();
    History history;
    history.start(world);
    play(world, history, 25);  // not on a keyframe
    world.set_pinned(0, 4, true);
    history.keyframe_now(world);
    play(world, history, 30);
    const std::uint64_t at_55 = world.state_hash();
    history.go_to(world, 27);
    EXPECT_TRUE(world.soft_body(0).is_pinned(4));
    history.go_to(world, 24);
    EXPECT_FALSE(world.soft_body(0).is_pinned(4));
    history.go_to(world, 55);
    EXPECT_EQ(world.state_hash(), at_55);
}

TEST(History, KeepsItsCapacityAndSaysWhatItCosts) {
    World world = travel_world();
    History history(10, 300);
    history.start(world);
    play(world, history, 1000);
    EXPECT_EQ(history.newest_tick(), 1000u);
    // At least the capacity, at most one keyframe interval more.
    EXPECT_LE(history.oldest_tick(), 700u);
    EXPECT_GE(history.oldest_tick(), 690u);
    EXPECT_EQ(history.keyframe_count(), 31u);
    EXPECT_EQ(history.go_to(world, 0), history.oldest_tick());  // clamped to the record
    const std::size_t snapshot = world.snapshot().bytes();
    EXPECT_GE(history.bytes(), 31 * snapshot);
    EXPECT_LE(history.bytes(), 31 * snapshot + 64 * 1024);
}

// A keyframe's size at 5,000 particles, as history.h states it: 52 bytes a particle.
TEST(History, AKeyframeOfFiveThousandParticlesIs260Kilobytes) {
    FlatKeys p = listing8_params();
    p.max_particles = 0;  // all: one particle per point
    OneBodyWorld world(p, points(random_cloud(5000, 3, 2.0f)));
    ASSERT_EQ(world.soft_body(0).particle_count(), 5000u);
    world.tick();  // Verlet's last step and the previous tick's positions exist from the first tick
    const double kb = double(world.snapshot().bytes()) / 1000.0;
    EXPECT_NEAR(kb, 260.0, 2.0);
}

}  // namespace
}  // namespace softbody::test
