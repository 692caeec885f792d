// Velocities that are the motion (ground_contact.h): a soft body's particle lying on the ground
// reports the velocity its next positions follow, and at rest that is nothing. Before, a
// particle pressed into the ground by its springs counted as an impact every step (the
// velocity the step ended with held the whole step's pressing) and bounced up at e times it:
// it reported up to 0.2 m/s upward for as long as it lay there, unmoving, and the kinetic
// energy, the inspector and the time series with it.
#include <algorithm>
#include <cmath>
#include <string>

#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

// A soft ball (ball:2, 162 particles, 0.7 m across, k 120, c 2) set down on the
// ground: it settles within a second or two.
Scene soft_ball() {
    return parse_scene(
        "{\"auto_substeps\": true, \"soft_bodies\": [{\"name\": \"ball\", \"mesh\": \"ball:2\", \"scale\": 0.7,"
        " \"up_axis\": \"z\", \"particle_mass\": 0.05, \"stiffness\": 120, \"damping\": 2, \"position\": [0, 0, 0.36]}]}",
        "test.json");
}

struct Speeds {
    double reported = 0.0;  // the fastest |v| among the particles looked at, m/s
    double moved = 0.0;     // the fastest |x(t + dt) - x(t)| / dt among them over the next tick
};

// Over the particles of soft body b no higher than `top` (m) as the tick begins.
Speeds speeds(World& world, std::size_t b, float top) {
    const SoftBody& body = world.soft_body(b);
    const Vec3Array x = body.x, v = body.v;
    world.tick();
    Speeds out;
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (x.z[i] > top) continue;
        out.reported = std::max(out.reported, double(length(v[i])));
        out.moved = std::max(out.moved, double(length(body.x[i] - x[i])) / double(world.settings().dt));
    }
    return out;
}

// At rest on the ground after 4 s, under every integrator: every particle reports under 1 mm/s,
// moves under 1 mm/s, and the kinetic energy is under 1e-6 J. Measured: under 0.1 mm/s and
// 5e-9 J; before, one particle under the ball reported 0.11 m/s up (Verlet, symplectic Euler;
// 3e-4 J), and under RK4 every particle up to 0.16 m/s (0.01 J), none of them moving.
TEST(VelocitiesAreTheMotion, SoftBallAtRestOnTheGround) {
    for (const char* integrator : kIntegrators) {
        World world = world_of(soft_ball(), integrator);
        world.run(200);
        ASSERT_EQ(world.status(), Status::Ok) << integrator;
        EXPECT_LT(world.energy().kinetic, 1e-6) << integrator;
        const Speeds s = speeds(world, 0, 1e3f);
        EXPECT_LT(s.reported, 1e-3) << integrator;
        EXPECT_LT(s.moved, 1e-3) << integrator;
    }
}

// Verlet carries its step x_n - x_{n-1} beside v: at the ground the two stay one motion,
// step = v h (to float rounding of a step of at most 1e-4 m/s times h).
TEST(VelocitiesAreTheMotion, VerletStepIsVTimesHOnTheGround) {
    World world = world_of(soft_ball(), "verlet");
    world.run(30);  // landing: the particles underneath are pressed in, the rest still moving
    for (int t = 0; t < 20; ++t) {
        world.tick();
        const WorldSnapshot snap = world.snapshot();
        const WorldSnapshot::Soft& s = snap.soft[0];
        for (std::size_t i = 0; i < s.x.size(); ++i) {
            EXPECT_LT(length(s.verlet_step[i] / s.verlet_h - s.v[i]), 1e-4) << "particle " << i << " tick " << t;
        }
    }
}

// The three jelly cubes of soft_stack.json after 5 s: the bottom cube's particles on the ground
// report under 1 mm/s and move under 1 mm/s (measured: 0; before, 0.038 m/s up, unmoving)
// under Verlet and symplectic Euler. (RK4 and explicit Euler leave the cube creeping on the
// ground by stick and slip within a tick: reported up to 8 and 0.6 cm/s, moving 1.6 and 0 mm/s
// a tick; before, 31 and 64 cm/s.)
TEST(VelocitiesAreTheMotion, StackOfSoftCubesOnTheGround) {
    for (const char* integrator : {"verlet", "symplectic_euler"}) {
        World world = world_of(load_scene(SOFTBODY_ASSETS "/scenes/soft_stack.json"), integrator);
        world.run(250);
        ASSERT_EQ(world.status(), Status::Ok) << integrator;
        const Speeds s = speeds(world, 0, 1e-4f);
        EXPECT_LT(s.reported, 1e-3) << integrator;
        EXPECT_LT(s.moved, 1e-3) << integrator;
    }
}

}  // namespace
}  // namespace softbody::test
