// Islands and sleeping (physics/src/sleep.h): a pyramid stands and sleeps, a settled pile
// sleeps, a ball thrown into it wakes what it touches and they sleep again, the same bits at
// any thread count and on time travel, and a scene that never comes to rest runs exactly as it
// does with sleeping off. No test here asserts a speed: what sleeping saves is in the bench.
#include <cmath>
#include <set>

#include "physics/error.h"
#include "physics/generated.h"
#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

constexpr std::uint64_t kTicksPerSecond = 50;  // dt 0.02 s, every scene here
// m: two bodies closer than this touch (sleep.h: they are in one island, and a sleeping one
// wakes the tick an awake one touches it).
constexpr double kTouching = 1e-4;

// A body's fastest point: |v| + |w| r (the bench's "moving", app/soundness.h).
double fastest_point(const World& world, std::size_t b) {
    const RigidMotion m = world.rigid_motion(b);
    return length(m.v) + length(m.omega) * world.rigid_body(b).bounding_radius;
}

std::size_t dynamic_bodies(const World& world) {
    std::size_t n = 0;
    for (std::size_t b = 0; b < world.rigid_body_count(); ++b) n += world.rigid_body(b).fixed ? 0 : 1;
    return n;
}

Vec3d position_of(const World& world, std::size_t b) { return world.rigid_motion(b).x; }

// The pyramid: it stands 10 s, its top box within 1 cm of where it started, no box
// faster than 1 cm/s at any point after 2 s; and it is at rest, so it all sleeps.
TEST(Sleep, PyramidStandsTenSecondsAndSleeps) {
    World world((generated_scene("pyramid:10")));
    ASSERT_EQ(world.rigid_body_count(), 385u);
    std::size_t top = 0;
    for (std::size_t b = 1; b < world.rigid_body_count(); ++b) {
        if (position_of(world, b).z > position_of(world, top).z) top = b;
    }
    const Vec3d top_start = position_of(world, top);
    double fastest_after_2s = 0.0;
    for (std::uint64_t t = 0; t < 10 * kTicksPerSecond; ++t) {
        world.tick();
        ASSERT_EQ(world.status(), Status::Ok) << world.divergence();
        if (world.ticks() >= 2 * kTicksPerSecond) {
            for (std::size_t b = 0; b < world.rigid_body_count(); ++b) fastest_after_2s = std::max(fastest_after_2s, fastest_point(world, b));
        }
    }
    EXPECT_LT(length(position_of(world, top) - top_start), 0.01);
    EXPECT_LT(fastest_after_2s, 0.01);
    EXPECT_EQ(world.sleeping_count(), 385u);
    // Asleep, nothing moves: another second changes no bit.
    const std::uint64_t before = world.state_hash();
    world.run(kTicksPerSecond);
    EXPECT_EQ(world.state_hash(), before);
}

// The bundled pyramid.json is pyramid:10 written out: the same boxes in the same places (to the
// micrometre its decimals are written to).
TEST(Sleep, PyramidSceneFileIsTheGeneratedPyramid) {
    const Scene file = load_scene(std::string(SOFTBODY_ASSETS) + "/scenes/pyramid.json");
    const Scene made = generated_scene("pyramid:10");
    ASSERT_EQ(file.rigid_bodies.size(), made.rigid_bodies.size());
    for (std::size_t b = 0; b < made.rigid_bodies.size(); ++b) {
        const RigidBodyDef &f = file.rigid_bodies[b], &m = made.rigid_bodies[b];
        SCOPED_TRACE(m.name);
        EXPECT_EQ(f.name, m.name);
        EXPECT_EQ(f.shape, m.shape);
        EXPECT_EQ(f.size, m.size);
        EXPECT_EQ(f.density, m.density);
        EXPECT_EQ(f.friction, m.friction);
        EXPECT_EQ(f.restitution, m.restitution);
        ASSERT_TRUE(f.position && m.position);
        EXPECT_LT(length(*f.position - *m.position), 1e-6);
    }
}

// boxes:100: fifty boxes and fifty balls dropped into a bin, the balls with rolling resistance
// 0.01 (without it a ball keeps rolling, or spinning in place about the normal of its one
// contact point, and keeps its island awake: physics/README.md, "Islands and sleeping").
Scene box_pile() { return generated_scene("boxes:100"); }

// A ball dropped into a settled pile from above its middle, at 4 m/s: the pile's state with one
// body more (the app's Add menu does the same: World::restore with more_bodies).
struct Pile {
    Scene scene = box_pile();
    std::unique_ptr<World> world;
    explicit Pile(int threads = 1) : world(std::make_unique<World>((scene), WorldOptions{threads})) {}
    std::size_t throw_ball() {
        Vec3d centre;
        double top = 0.0;
        std::size_t n = 0;
        for (std::size_t b = 0; b < world->rigid_body_count(); ++b) {
            if (world->rigid_body(b).fixed) continue;
            const Vec3d x = position_of(*world, b);
            centre += x;
            top = std::max(top, x.z);
            ++n;
        }
        centre = centre / double(n);
        RigidBodyDef ball;
        ball.name = "thrown";
        ball.shape = ShapeKind::Sphere;
        ball.radius = 0.15;
        ball.density = 1000.0;
        ball.rolling_resistance = 0.01f;
        ball.position = Vec3d{centre.x, centre.y, top + 0.6};
        ball.velocity = Vec3d{0.0, 0.0, -4.0};
        world->create_rigid_body(ball);  // into the running world, the pile going on where it is
        scene.rigid_bodies.push_back(ball);
        return world->rigid_body_count() - 1;
    }
};

TEST(Sleep, SettledPileSleepsAndAThrownBallWakesWhatItTouchesThenItSleepsAgain) {
    Pile pile;
    pile.world->run(10 * kTicksPerSecond);
    World* world = pile.world.get();
    ASSERT_EQ(world->status(), Status::Ok) << world->divergence();
    const std::size_t bodies = dynamic_bodies(*world);
    std::printf("a pile of %zu boxes and balls after 10 s: %zu asleep\n", bodies, world->sleeping_count());
    EXPECT_GE(world->sleeping_count() * 10, bodies * 9) << world->sleeping_count() << " of " << bodies << " asleep";
    // A sleeping body is still: its P and L are 0.
    for (std::size_t b = 0; b < world->rigid_body_count(); ++b) {
        if (world->rigid_asleep(b)) {
            EXPECT_EQ(fastest_point(*world, b), 0.0);
        }
    }

    std::vector<bool> asleep_before(world->rigid_body_count());
    for (std::size_t b = 0; b < asleep_before.size(); ++b) asleep_before[b] = world->rigid_asleep(b);
    const std::size_t ball = pile.throw_ball();
    world = pile.world.get();
    EXPECT_FALSE(world->rigid_asleep(ball));
    for (std::size_t b = 0; b < asleep_before.size(); ++b) EXPECT_EQ(world->rigid_asleep(b), asleep_before[b]) << b;
    // Every body the ball touches (a contact closer than kTouching as the tick began) is awake
    // in the tick it does, and had been asleep: it woke.
    std::set<std::size_t> touched, woke;
    for (std::uint64_t t = 0; t < 10 * kTicksPerSecond; ++t) {
        world->tick();
        ASSERT_EQ(world->status(), Status::Ok) << world->divergence();
        for (const RigidContact& c : world->contacts()) {
            if (c.soft >= 0 || c.separation > kTouching) continue;
            const std::int64_t other = c.a == ball ? c.b : std::int64_t(c.b) == std::int64_t(ball) ? std::int64_t(c.a) : -1;
            if (other < 0 || world->rigid_body(std::size_t(other)).fixed) continue;
            touched.insert(std::size_t(other));
        }
        for (std::size_t b = 0; b < asleep_before.size(); ++b) {
            if (asleep_before[b] && !world->rigid_asleep(b)) woke.insert(b);
        }
    }
    ASSERT_FALSE(touched.empty()) << "the ball touched no body of the pile";
    for (std::size_t b : touched) {
        if (asleep_before[b]) {
            EXPECT_TRUE(woke.count(b)) << "body " << b << " was touched and never woke";
        }
    }
    // ... and 10 s later the pile, the ball and what it woke have settled and sleep again.
    std::printf("the ball touched %zu bodies, %zu woke; 10 s on, %zu of %zu asleep\n", touched.size(), woke.size(),
                world->sleeping_count(), dynamic_bodies(*world));
    EXPECT_GE(world->sleeping_count() * 10, dynamic_bodies(*world) * 9) << world->sleeping_count() << " asleep";
    std::size_t woke_asleep = 0;
    for (std::size_t b : woke) woke_asleep += world->rigid_asleep(b) ? 1 : 0;
    EXPECT_GE(woke_asleep * 10, woke.size() * 9) << woke_asleep << " of the " << woke.size() << " woken asleep again";
}

// pile:100, boxes, balls, cylinders and icosahedra: settled, it sleeps too. (Its cylinders are
// 32-sided prisms: before manifolds kept a resting facet's touching corners over the next
// facets' corners a few millimetres up, a cylinder tipped onto those and was pushed back every
// sixth tick, for ever, and 47 of the 100 slept; manifold.h.)
TEST(Sleep, MixedPileOfBoxesBallsCylindersAndHullsSleeps) {
    World world((generated_scene("pile:100")), WorldOptions{1});
    world.run(10 * kTicksPerSecond);
    ASSERT_EQ(world.status(), Status::Ok) << world.divergence();
    std::printf("pile:100 after 10 s: %zu of %zu asleep\n", world.sleeping_count(), dynamic_bodies(world));
    EXPECT_GE(world.sleeping_count() * 10, dynamic_bodies(world) * 9);
}

// The same bits at 1, 2 and 3 threads, through falling asleep, a throw that wakes, and sleeping
// again; and the same islands asleep.
TEST(Sleep, SameHashAndSleepersAtOneTwoAndThreeThreads) {
    std::uint64_t hash[3] = {};
    std::size_t sleeping[3] = {};
    for (int threads = 1; threads <= 3; ++threads) {
        Pile pile(threads);
        pile.world->run(6 * kTicksPerSecond);
        pile.throw_ball();
        pile.world->run(3 * kTicksPerSecond);
        ASSERT_EQ(pile.world->status(), Status::Ok);
        hash[threads - 1] = pile.world->state_hash();
        sleeping[threads - 1] = pile.world->sleeping_count();
    }
    EXPECT_GT(sleeping[0], 0u);
    EXPECT_EQ(hash[0], hash[1]);
    EXPECT_EQ(hash[0], hash[2]);
    EXPECT_EQ(sleeping[0], sleeping[1]);
    EXPECT_EQ(sleeping[0], sleeping[2]);
}

// Time travel: restored to a moment with bodies asleep, the world goes on to the same bits, the
// same bodies falling asleep and waking.
TEST(Sleep, RestoredSnapshotReplaysTheSameSleep) {
    Pile pile;
    World& world = *pile.world;
    world.run(2 * kTicksPerSecond);
    const WorldSnapshot then = world.snapshot();
    ASSERT_GT(world.sleeping_count(), 0u);
    ASSERT_LT(world.sleeping_count(), dynamic_bodies(world));  // some still settling: more sleep later
    world.run(5 * kTicksPerSecond);
    const std::uint64_t hash = world.state_hash();
    const std::size_t sleeping = world.sleeping_count();
    std::vector<bool> asleep(world.rigid_body_count());
    for (std::size_t b = 0; b < asleep.size(); ++b) asleep[b] = world.rigid_asleep(b);

    world.restore(then);
    world.run(5 * kTicksPerSecond);
    EXPECT_EQ(world.state_hash(), hash);
    EXPECT_EQ(world.sleeping_count(), sleeping);
    for (std::size_t b = 0; b < asleep.size(); ++b) EXPECT_EQ(world.rigid_asleep(b), asleep[b]) << b;
    // And in another world built from the same scene.
    World other((pile.scene));
    other.restore(then);
    other.run(5 * kTicksPerSecond);
    EXPECT_EQ(other.state_hash(), hash);
}

// Bodies that never come to rest: boxes and balls sliding, spinning and rolling on a frictionless
// ground (two at 6 cm/s, just over the 5 cm/s threshold), and a box falling past them from high up.
// Their rest times never fill, nothing sleeps, and every bit is as with sleeping off.
TEST(Sleep, SceneInConstantMotionRunsAsWithSleepingOff) {
    Scene scene;
    scene.settings.dynamic_friction = 0.0f;
    scene.settings.static_friction = 0.0f;
    const auto add = [&](ShapeKind shape, Vec3d at, Vec3d v, Vec3d w) {
        RigidBodyDef def;
        def.name = "body" + std::to_string(scene.rigid_bodies.size());
        def.shape = shape;
        if (shape == ShapeKind::Sphere) def.radius = 0.2;
        else def.size = Vec3d{0.4, 0.3, 0.2};
        def.position = at;
        def.velocity = v;
        def.angular_velocity = w;
        def.friction = 0.0f;
        scene.rigid_bodies.push_back(def);
    };
    add(ShapeKind::Box, {0, 0, 0.1}, {0.06, 0, 0}, {0, 0, 0});
    add(ShapeKind::Box, {0, 2, 0.1}, {0, -0.06, 0}, {0, 0, 0});
    add(ShapeKind::Box, {3, 0, 0.1}, {0, 0, 0}, {0, 0, 0.5});
    add(ShapeKind::Sphere, {-3, 0, 0.2}, {0.5, 0.5, 0}, {0, 0, 0});
    add(ShapeKind::Box, {6, 6, 400}, {0, 0, 0}, {0, 0, 0});
    Scene off = scene;
    off.settings.sleeping = false;
    World on_world((scene)), off_world((off));
    for (std::uint64_t t = 0; t < 8 * kTicksPerSecond; ++t) {
        on_world.tick();
        off_world.tick();
        ASSERT_EQ(on_world.sleeping_count(), 0u) << "at tick " << t;
    }
    ASSERT_EQ(on_world.status(), Status::Ok);
    EXPECT_EQ(on_world.state_hash(), off_world.state_hash());
    // The slow ones did move all along: 6 cm/s for 8 s.
    EXPECT_NEAR(position_of(on_world, 0).x, 0.48, 1e-3);
}

// A box drifting slowly through empty space (no gravity, no ground) is in motion nothing will
// stop: it leans on nothing, so it never sleeps however slow it is.
TEST(Sleep, BodyDriftingThroughEmptySpaceNeverSleeps) {
    Scene scene;
    scene.settings.gravity = {0.0f, 0.0f, 0.0f};
    scene.settings.ground = false;
    RigidBodyDef box;
    box.name = "drifter";
    box.size = Vec3d{0.5, 0.5, 0.5};
    box.velocity = Vec3d{0.005, 0.0, 0.0};
    scene.rigid_bodies.push_back(box);
    World world((scene));
    world.run(5 * kTicksPerSecond);
    EXPECT_FALSE(world.rigid_asleep(0));
    EXPECT_GE(world.rigid_rest_time(0), 4.9);  // slow all along: only leaning on nothing keeps it awake
    EXPECT_NEAR(position_of(world, 0).x, 0.025, 1e-9);
}

// Two towers of two boxes, 5 m apart, fall asleep in one tick as two islands, each with its own
// contacts set aside. Woken one at a time, each island gets back its own contacts and no other's
// (the other tower still asleep with its own kept), and, warm-started from them, its boxes hold
// still in the tick after it wakes.
TEST(Sleep, EachIslandWakesWithItsOwnContacts) {
    Scene scene;
    for (const double x : {0.0, 5.0}) {
        for (const double z : {0.25, 0.75}) {
            RigidBodyDef box;
            box.name = "box " + std::to_string(scene.rigid_bodies.size());
            box.size = Vec3d{0.5, 0.5, 0.5};
            box.position = Vec3d{x, 0.0, z};
            scene.rigid_bodies.push_back(box);
        }
    }
    World world((scene));
    for (std::uint64_t t = 0; t < 2 * kTicksPerSecond && world.sleeping_count() < 4; ++t) world.tick();
    ASSERT_EQ(world.sleeping_count(), 4u);
    ASSERT_NE(world.rigid_asleep(0), false);
    const auto contacts_of = [&](std::uint32_t first) {
        std::size_t n = 0;
        for (const RigidContact& c : world.contacts()) n += c.a == first || c.a == first + 1 ? 1 : 0;
        return n;
    };
    EXPECT_EQ(contacts_of(0), 0u);
    EXPECT_EQ(contacts_of(2), 0u);
    for (const std::uint32_t first : {0u, 2u}) {
        const std::size_t before = world.contacts().size();
        world.wake_rigid(first);
        EXPECT_FALSE(world.rigid_asleep(first));
        EXPECT_FALSE(world.rigid_asleep(first + 1));
        // Four corners on the ground and four between the boxes, at least.
        EXPECT_GE(contacts_of(first), 8u) << first;
        EXPECT_EQ(world.contacts().size() - before, contacts_of(first)) << first;
        if (first == 0) {
            EXPECT_TRUE(world.rigid_asleep(2));
            EXPECT_TRUE(world.rigid_asleep(3));
        }
        const Vec3d top = position_of(world, first + 1);
        world.tick();
        EXPECT_LT(length(position_of(world, first + 1) - top), 1e-4) << first;
    }
}

// A box resting 3 mm from a ball that spins in place for ever (about the vertical, on one
// point: nothing holds that turn back) is within the ball's reach, but they do not touch: they
// are two islands, and the box sleeps while the ball spins on. A ball rolling into the box from
// 20 cm away at 0.2 m/s wakes it the tick they touch, and pushes it a little.
TEST(Sleep, ABodyWithinReachOfARestlessOneSleepsUntilItIsTouched) {
    for (const bool rolling : {false, true}) {
        const double gap = rolling ? 0.2 : 0.003, v = rolling ? 0.2 : 0.0;
        World world = World(parse_scene(
            "{\"rigid_bodies\": [{\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": 0.1, \"position\": [0, 0, 0.1],"
            " \"velocity\": [" + std::to_string(v) + ", 0, 0], \"angular_velocity\": [0, " + std::to_string(v / 0.1) + ", " +
                (rolling ? "0" : "10") + "]},"
            " {\"name\": \"box\", \"size\": [0.2, 0.2, 0.2], \"position\": [" + std::to_string(0.2 + gap) + ", 0, 0.1]}]}",
            "test.json"));
        bool within_reach = false, touched = false, woke_on_touch = true;
        for (std::uint64_t t = 0; t < 3 * kTicksPerSecond; ++t) {
            world.tick();
            ASSERT_EQ(world.status(), Status::Ok) << world.divergence();
            for (const RigidContact& c : world.contacts()) {
                if (c.soft >= 0 || c.b < 0 || std::min<std::int64_t>(c.a, c.b) != 0 || std::max<std::int64_t>(c.a, c.b) != 1) continue;
                within_reach = true;
                if (c.separation <= kTouching) {
                    touched = true;
                    woke_on_touch = woke_on_touch && !world.rigid_asleep(1);
                }
            }
            if (!rolling && t + 1 == kTicksPerSecond) {
                EXPECT_TRUE(world.rigid_asleep(1)) << "the box beside the spinning ball sleeps within a second";
            }
            if (rolling && t + 1 == kTicksPerSecond / 2 + 5) {
                EXPECT_TRUE(world.rigid_asleep(1)) << "the box sleeps before the ball arrives";
            }
        }
        if (!rolling) {
            EXPECT_FALSE(world.rigid_asleep(0)) << "the ball never rests";
            EXPECT_TRUE(within_reach) << "the ball and the box are within reach of each other";
            EXPECT_FALSE(touched) << "and never touch";
            EXPECT_TRUE(world.rigid_asleep(1));
            EXPECT_NEAR(position_of(world, 1).x, 0.203, 1e-6);
        } else {
            EXPECT_TRUE(touched) << "the ball reaches the box";
            EXPECT_TRUE(woke_on_touch) << "and the box is awake every tick they touch";
            // The two share the ball's momentum (about 7 cm/s), and friction stops the box
            // within half a millimetre.
            EXPECT_GT(position_of(world, 1).x, 0.4 + 1e-4) << "the box is pushed along";
        }
    }
}

// A resting body twitched for a moment (as one in a loaded pile is now and then, when a contact
// beside it is found again with other points) keeps its rest as long as it goes nowhere. A box
// on friction 0.05, at rest for 0.3 s, set sliding at 8 cm/s: faster than kSleepSpeed for three
// ticks, it stops within v^2 / (2 mu g) = 6.5 mm (less than kSleepDrift, 2.5 cm) and sleeps
// 0.5 s after its rest began, as it would have. Set sliding at 20 cm/s it goes 4 cm: it begins
// its rest again where it slows down, and sleeps 0.5 s after that.
TEST(Sleep, ATwitchThatGoesNowhereKeepsTheRest) {
    for (const double kick : {0.08, 0.2}) {
        Scene scene;
        RigidBodyDef box;
        box.name = "crate";
        box.size = Vec3d{0.5, 0.5, 0.5};
        box.position = Vec3d{0.0, 0.0, 0.25};
        box.friction = 0.05;
        scene.rigid_bodies.push_back(box);
        World world((scene));
        // (A rest time is a sum of dt, a float: 15 ticks of it come a few ns short of 0.3 s.)
        while (world.rigid_rest_time(0) < 0.3 - 1e-6) world.tick();
        ASSERT_LT(world.ticks(), 30u);
        const std::uint64_t rest_began = world.ticks() - 14;  // 15 ticks of rest: the first counts dt
        WorldSnapshot snapshot = world.snapshot();
        snapshot.rigid[rigid::P] += kick / world.rigid_body(0).inv_mass;
        world.restore(snapshot);
        std::uint64_t asleep_at = 0;
        for (int t = 0; t < 100 && asleep_at == 0; ++t) {
            world.tick();
            if (world.rigid_asleep(0)) asleep_at = world.ticks();
        }
        ASSERT_NE(asleep_at, 0u) << "kick " << kick;
        const double slid = world.rigid_motion(0).x.x, stops = kick * kick / (2.0 * 0.05 * 9.81);
        EXPECT_NEAR(slid, stops, 0.1 * stops) << "kick " << kick;
        if (slid < 0.025) {  // kSleepDrift (physics/src/sleep.h)
            EXPECT_EQ(asleep_at, rest_began + 24) << "kick " << kick;  // 25 ticks of rest: 0.5 s
        } else {
            // Its rest begins again once it is slower than kSleepSpeed, (v - 0.05) / (mu g) after the kick.
            const std::uint64_t slowed = rest_began + 14 + std::uint64_t((kick - 0.05) / (0.05 * 9.81) / 0.02);
            EXPECT_GE(asleep_at, slowed + 24) << "kick " << kick;
        }
    }
}

// A resting box sleeps; grabbing it, changing a key or its material wakes it; with the key
// `sleeping` off nothing sleeps.
TEST(Sleep, GrabKeysAndMaterialWakeAndTheKeyTurnsItOff) {
    Scene scene;
    RigidBodyDef box;
    box.name = "crate";
    box.size = Vec3d{0.5, 0.5, 0.5};
    box.position = Vec3d{0.0, 0.0, 0.25};
    scene.rigid_bodies.push_back(box);
    box.name = "on_top";
    box.position = Vec3d{0.0, 0.0, 0.75};
    scene.rigid_bodies.push_back(box);
    World world((scene));
    world.run(kTicksPerSecond);
    ASSERT_TRUE(world.rigid_asleep(0));
    ASSERT_TRUE(world.rigid_asleep(1));  // one island: the crate and the box on it

    Grab grab;
    grab.rigid = true;
    grab.body = 1;
    grab.target = {0.0f, 0.0f, 0.75f};
    world.set_grab(grab);
    EXPECT_FALSE(world.rigid_asleep(0));  // its whole island
    EXPECT_FALSE(world.rigid_asleep(1));
    world.run(kTicksPerSecond);
    EXPECT_FALSE(world.rigid_asleep(1));  // held: never asleep while grabbed
    world.set_grab(std::nullopt);
    world.run(kTicksPerSecond);
    ASSERT_TRUE(world.rigid_asleep(1));

    set_material(world, 0, 0.5f, std::nullopt);
    EXPECT_FALSE(world.rigid_asleep(0));
    EXPECT_FALSE(world.rigid_asleep(1));
    world.run(kTicksPerSecond);
    ASSERT_TRUE(world.rigid_asleep(0));

    FlatKeys params = flat_keys(world);
    params.dynamic_friction = 0.5f;
    set_flat(world, params);
    EXPECT_EQ(world.sleeping_count(), 0u);
    set_flat(world, params);  // the same keys again: nothing changed, nothing to wake for
    world.run(kTicksPerSecond);
    ASSERT_EQ(world.sleeping_count(), 2u);
    set_flat(world, params);
    EXPECT_EQ(world.sleeping_count(), 2u);

    params.sleeping = false;
    set_flat(world, params);
    EXPECT_EQ(world.sleeping_count(), 0u);
    world.run(3 * kTicksPerSecond);
    EXPECT_EQ(world.sleeping_count(), 0u);
    EXPECT_GE(world.rigid_rest_time(0), 2.9);  // at rest all the same
}

// A soft body landing on a sleeping box wakes it (soft bodies never sleep).
TEST(Sleep, SoftBodyLandingOnASleepingBoxWakesIt) {
    Scene scene = generated_scene("ball:1");
    scene.soft_bodies[0].position = Vec3{0.0f, 0.0f, 4.0f};
    scene.soft_bodies[0].stiffness = 2000.0f;
    RigidBodyDef box;
    box.name = "crate";
    box.size = Vec3d{1.0, 1.0, 0.5};
    box.position = Vec3d{0.0, 0.0, 0.25};
    scene.rigid_bodies.push_back(box);
    World world((scene));
    bool slept = false, woke = false;
    for (std::uint64_t t = 0; t < 2 * kTicksPerSecond && !woke; ++t) {
        world.tick();
        ASSERT_EQ(world.status(), Status::Ok);
        slept = slept || world.rigid_asleep(0);
        woke = slept && !world.rigid_asleep(0);
    }
    EXPECT_TRUE(slept);
    EXPECT_TRUE(woke);
    float lowest = 1e9f;
    for (std::size_t i = 0; i < world.soft_body(0).particle_count(); ++i) lowest = std::min(lowest, world.soft_body(0).x[i].z);
    EXPECT_LT(lowest, 1.0f);  // it woke as the ball reached it, not while it fell from 3.5 m
}

TEST(Sleep, KeyIsCheckedLikeAnyOther) {
    const KeyInfo& info = *find_key(KeyOwner::World, "sleeping");
    WorldSettings p;
    set_key(p, info, parse_key_text(info, "false"));
    EXPECT_FALSE(p.sleeping);
    EXPECT_EQ(key_text(info, get_key(p, info)), "false");
    EXPECT_REFUSED_NAMING(parse_key_text(info, "maybe"), "'sleeping'");
    EXPECT_REFUSED_NAMING(parse_scene("{\"sleeping\": 1}", "s.json"), "s.json:1", "'sleeping'");
    EXPECT_FALSE(parse_scene("{\"sleeping\": false}", "s.json").settings.sleeping);
}

}  // namespace
}  // namespace softbody::test
