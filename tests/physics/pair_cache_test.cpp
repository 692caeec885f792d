// The narrow phase's answers carried from find to find (rigid_contacts.h): two hulls that have
// not moved relative to each other keep their points, which follow the bodies; a change of
// either shape has them found again.
#include <algorithm>
#include <cmath>

#include "physics/generated.h"
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

}  // namespace
}  // namespace softbody::test
