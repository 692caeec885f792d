// Rolling resistance (contact_solver.cpp, physics/README.md, "Choices the physics makes"): a round body
// turning on a contact is held back by a torque of at most C_rr |F_n| r. Checked against the
// closed forms of a ball rolling to a stop and of a ball spinning in place to a stop, and that it
// does nothing when C_rr is 0 or the body does not roll.
#include <cmath>
#include <string>

#include "physics/error.h"
#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

constexpr double kRadius = 0.1;

// A solid ball of radius 0.1 m resting on the ground, moving at v (m/s, along x) and turning at
// w (rad/s, world axes).
std::string ball(double rolling_resistance, double v, const Vec3d& w) {
    return "{\"rigid_bodies\": [{\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": 0.1, \"density\": 1000,"
           " \"friction\": 0.5, \"restitution\": 0, \"rolling_resistance\": " + std::to_string(rolling_resistance) +
           ", \"position\": [0, 0, 0.1], \"velocity\": [" + std::to_string(v) + ", 0, 0], \"angular_velocity\": [" +
           std::to_string(w.x) + ", " + std::to_string(w.y) + ", " + std::to_string(w.z) + "]}]}";
}

// Rolling without slipping (v = w r), friction f at the contact and the torque C_rr N r:
// m a = -f, I a / r = f r - C_rr m g r, so a = -C_rr g / (1 + I / (m r^2)) = -5/7 C_rr g for a
// solid ball (I = 2/5 m r^2): the speed falls linearly and it stops after v0^2 / (2 |a|).
TEST(RollingResistance, RollingBallSlowsAtFiveSeventhsCrrGAndStopsWhereTheClosedFormSays) {
    const double c_rr = 0.05, v0 = 1.0;
    World world = world_of(ball(c_rr, v0, {0.0, v0 / kRadius, 0.0}));
    const double a = 5.0 / 7.0 * c_rr * kG;  // 0.350 m/s^2: it stops after 2.86 s, 1.43 m on
    world.run(50);                            // 1 s
    ASSERT_EQ(world.status(), Status::Ok);
    // The speed after 1 s: within 0.1% of the closed form (measured: 2e-8 m/s off).
    EXPECT_NEAR(world.rigid_motion(0).v.x, v0 - a * 1.0, 1e-3 * (v0 - a));
    // Still rolling, not sliding: the contact point is at rest (1 mm/s).
    const RigidMotion m = world.rigid_motion(0);
    EXPECT_NEAR(m.v.x - m.omega.y * kRadius, 0.0, 1e-3);
    world.run(150);  // 4 s in all: long stopped
    const double distance = world.rigid_motion(0).x.x;
    EXPECT_LT(length(world.rigid_motion(0).v), 1e-3);
    // Within 1% (measured: 0.2% short, the last tick's stop taking what is left of the speed).
    EXPECT_NEAR(distance, v0 * v0 / (2.0 * a), 0.01 * v0 * v0 / (2.0 * a)) << "stopped after " << distance << " m";
}

// Spinning in place about the normal: I dw/dt = -C_rr m g r, so w falls at 5/2 C_rr g / r.
TEST(RollingResistance, BallSpinningInPlaceStopsAtFiveHalvesCrrGOverR) {
    const double c_rr = 0.05, w0 = 10.0;
    World world = world_of(ball(c_rr, 0.0, {0.0, 0.0, w0}));
    const double alpha = 2.5 * c_rr * kG / kRadius;  // 12.3 rad/s^2: it stops after 0.82 s
    world.run(20);                                    // 0.4 s
    EXPECT_NEAR(world.rigid_motion(0).omega.z, w0 - alpha * 0.4, 1e-3 * (w0 - alpha * 0.4));
    world.run(30);
    EXPECT_LT(length(world.rigid_motion(0).omega), 1e-3);
    // It spun in place: the ball did not move off.
    EXPECT_LT(length(world.rigid_motion(0).x - Vec3d{0.0, 0.0, kRadius}), 1e-3);
}

// Without it a ball rolls on at its speed (nothing else slows it: no drag, a flat floor), and a
// box's contacts take none (it does not roll: it tips, on its corners).
TEST(RollingResistance, NoneWithoutTheCoefficientOrForABox) {
    World rolling = world_of(ball(0.0, 1.0, {0.0, 1.0 / kRadius, 0.0}));
    rolling.run(100);
    EXPECT_NEAR(rolling.rigid_motion(0).v.x, 1.0, 1e-6);
    // A box sliding on friction 0.5 slows at mu g, with or without C_rr.
    for (double c_rr : {0.0, 0.5}) {
        World box = world_of("{\"rigid_bodies\": [{\"name\": \"box\", \"shape\": \"box\", \"size\": [0.2, 0.2, 0.2], \"density\": 1000,"
                             " \"friction\": 0.5, \"restitution\": 0, \"rolling_resistance\": " + std::to_string(c_rr) +
                             ", \"position\": [0, 0, 0.1], \"velocity\": [3, 0, 0]}]}");
        box.run(25);  // 0.5 s: 3 - 0.5 g 0.5 = 0.55 m/s
        EXPECT_NEAR(box.rigid_motion(0).v.x, 3.0 - 0.5 * kG * 0.5, 0.02) << "C_rr " << c_rr;
    }
}

TEST(RollingResistance, KeyOutsideZeroToOneIsRefused) {
    const std::string message = error_of([] { world_of(ball(2.0, 0.0, {})); });
    EXPECT_NE(message.find("rolling_resistance"), std::string::npos) << message;
}

}  // namespace
}  // namespace softbody::test
