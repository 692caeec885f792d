// The narrow phase's answers carried from find to find (rigid_contacts.h): two hulls that have
// not moved relative to each other keep their points, which follow the bodies; a change of
// either shape has them found again. And the boxes of the broad phase kept from find to find: a
// hull's box is made again when its pose or its shape has changed.
#include <algorithm>
#include <cmath>
#include <vector>

#include "physics/generated.h"
#include "rigid_contacts.h"
#include "test_support.h"

namespace softbody::test {
namespace {

// A resting 6-layer pyramid with sleeping off, so that every pair is tested every tick.
Scene resting_stack() {
    Scene scene = generated_scene("stack:6");
    scene.settings.sleeping = false;
    return scene;
}

// While the boxes rest their answers are carried from tick to tick. A reset puts them back
// where they started, micrometres from where they rest: answers carried across it would make
// the reset world run otherwise than a new one. It runs as a new one, to the bit.
TEST(PairCache, AResetWorldRunsAsANewOne) {
    World world(resting_stack());
    world.run(100);
    world.reset();
    world.run(60);
    World fresh(resting_stack());
    fresh.run(60);
    EXPECT_EQ(world.state_hash(), fresh.state_hash());
}

// Carried answers keep the stack as found ones do: after 4 s no box is deeper than the loaded
// slop (0.5 mm) in the ground, and the top box has moved less than a millimetre.
TEST(PairCache, ARestingStackStaysAsItStood) {
    World world(resting_stack());
    const Vec3d top = world.rigid_motion(world.rigid_body_count() - 1).x;
    world.run(200);
    ASSERT_EQ(world.status(), Status::Ok) << world.divergence();
    EXPECT_LT(length(world.rigid_motion(world.rigid_body_count() - 1).x - top), 1e-3);
    for (std::size_t b = 0; b < world.rigid_body_count(); ++b) {
        const RigidMotion m = world.rigid_motion(b);
        double lowest = 1e300;
        for (const Vec3d& v : world.rigid_body(b).hull->vertices) lowest = std::min(lowest, (m.x + m.q.normalized().to_matrix() * v).z);
        EXPECT_GT(lowest, -5e-4) << b;
    }
}

// A box asleep on top of another (its hull's box kept from find to find), then carried 3 m aside
// in the state while still asleep, then made a 7 m slab there, reaching back under the other:
// each find with the scratch kept from the last finds the same contacts, to the bit, as one with
// a scratch of its own (a kept box of the old pose or shape would pair the wrong bodies).
TEST(PairCache, KeptBoxesFollowPoseAndShape) {
    std::vector<RigidBody> bodies;
    for (const double z : {0.5, 1.5}) {
        RigidBodyDef def;
        def.name = z < 1.0 ? "lower" : "upper";
        def.size = Vec3d{1, 1, 1};
        def.position = Vec3d{0, 0, z};
        bodies.push_back(make_rigid_body(def));
    }
    std::vector<CollisionShape> shapes{collision_shape(bodies[0]), collision_shape(bodies[1])};
    std::vector<double> state(bodies.size() * rigid::kStateSize);
    for (std::size_t b = 0; b < bodies.size(); ++b) std::copy(bodies[b].initial.begin(), bodies[b].initial.end(), &state[b * rigid::kStateSize]);
    const std::vector<std::uint8_t> asleep{0, 1};  // the upper box
    const WorldSettings settings;
    RigidContactScratch kept;
    const auto same_as_fresh = [&](const char* when, std::size_t pairs) {
        std::vector<RigidContact> with_kept, with_fresh;
        RigidContactScratch fresh;
        with_kept.resize(rigid_body_contacts(bodies, shapes, state, settings, 0.02, kept, with_kept, 0, asleep));
        with_fresh.resize(rigid_body_contacts(bodies, shapes, state, settings, 0.02, fresh, with_fresh, 0, asleep));
        EXPECT_EQ(kept.pairs.size(), pairs) << when;
        ASSERT_EQ(with_kept.size(), with_fresh.size()) << when;
        for (std::size_t k = 0; k < with_kept.size(); ++k) {
            EXPECT_EQ(with_kept[k].point, with_fresh[k].point) << when << " " << k;
            EXPECT_EQ(with_kept[k].separation, with_fresh[k].separation) << when << " " << k;
        }
    };
    same_as_fresh("resting", 1);
    same_as_fresh("resting again", 1);
    state[1 * rigid::kStateSize + rigid::X] = 3.0;
    same_as_fresh("carried aside", 0);
    RigidBodyDef slab;
    slab.name = "slab";
    slab.size = Vec3d{7, 1, 1};
    slab.position = Vec3d{3, 0, 1.5};
    bodies[1] = make_rigid_body(slab);
    shapes[1] = collision_shape(bodies[1]);
    same_as_fresh("a slab", 1);
}

}  // namespace
}  // namespace softbody::test
