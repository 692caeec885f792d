// Rolling stays on the surface (contact_solver.h, ground_contact.h): a ball or a cylinder rolling
// on the ground, and a box sliding on it, stand as deep in it as a ball at rest does, whatever
// the speed and whatever the integrator; and a ball rolling freely keeps its speed (nothing in
// a flat, frictionless-in-rolling world takes it). A soft ball thrown along it stays on it too.
#include <algorithm>
#include <cmath>
#include <string>

#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

std::string exact_number(double x) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", x);
    return text;
}

// A solid ball (1,000 kg/m^3) of radius r resting on the ground, rolling along x at v (w = v / r).
std::string rolling_ball(double r, double v) {
    return "{\"rigid_bodies\": [{\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": " + exact_number(r) +
           ", \"density\": 1000, \"position\": [0, 0, " + exact_number(r) + "], \"velocity\": [" + exact_number(v) +
           ", 0, 0], \"angular_velocity\": [0, " + exact_number(v / r) + ", 0]}]}";
}

// How deep a ball stands at rest on the ground under an integrator, m (the push apart's slop:
// 0.07 mm under Verlet).
double depth_at_rest(double r, const char* integrator) {
    World world = world_of(rolling_ball(r, 0.0), integrator);
    double deepest = 0.0;
    for (int t = 0; t < 100; ++t) {
        world.tick();
        deepest = std::max(deepest, r - world.rigid_motion(0).x.z);
    }
    return deepest;
}

// A ball's contact point is not a point of the ball: it is r below its centre however it turns.
// Held in the ball's axes, it rose with the turn and the ball sank into the gap it seemed to
// leave: r 0.15 m sank 13 mm at 2.2 m/s (9 mm under RK4) and 33 mm at 5 m/s; r 0.05 m 23 mm at
// 2.2 m/s, and at 5 m/s (100 rad/s) it went through the ground, 13 cm below it after 2 s.
// Explicit Euler lifted it instead, by up to 20 mm (its lowest point found through a q longer
// than 1). Now, every tick of 2 s: no deeper than at rest (plus 0.01 mm), never above the ground
// by more than 0.01 mm, and the speed it started with (to 1e-6 of it: nothing slows it).
TEST(RollingStaysOnTheSurface, BallsOfTwoSizesAtTwoSpeedsUnderEveryIntegrator) {
    for (const char* integrator : kIntegrators) {
        for (double r : {0.15, 0.05}) {
            const double rest = depth_at_rest(r, integrator);
            EXPECT_LT(rest, 1e-4) << integrator << " r " << r;
            for (double v : {2.2, 5.0}) {
                World world = world_of(rolling_ball(r, v), integrator);
                double deepest = 0.0, highest = 0.0;
                for (int t = 0; t < 100; ++t) {
                    world.tick();
                    ASSERT_EQ(world.status(), Status::Ok) << world.divergence();
                    const double depth = r - world.rigid_motion(0).x.z;
                    deepest = std::max(deepest, depth);
                    highest = std::max(highest, -depth);
                }
                const std::string what = std::string(integrator) + " r " + std::to_string(r) + " v " + std::to_string(v);
                EXPECT_LE(deepest, rest + 1e-5) << what << ": " << deepest * 1e3 << " mm deep (at rest " << rest * 1e3 << ")";
                EXPECT_LE(highest, 1e-5) << what << ": " << highest * 1e3 << " mm above the ground";
                const RigidMotion m = world.rigid_motion(0);
                EXPECT_NEAR(m.v.x, v, 1e-6 * v) << what;
                EXPECT_NEAR(m.omega.y * r, v, 1e-6 * v) << what << ": rolls without slipping";
            }
        }
    }
}

// The deepest of a hull body's vertices below the ground, m (its orientation made unit).
double deepest_vertex(const World& world, std::size_t b) {
    const RigidMotion m = world.rigid_motion(b);
    const Mat3 R = m.q.normalized().to_matrix();
    double lowest = 1e300;
    for (const Vec3d& v : world.rigid_body(b).hull->vertices) lowest = std::min(lowest, (m.x + R * v).z);
    return -lowest;
}

// A cylinder (a prism of 32 sides, radius 0.1 m, 0.2 m long) rolling on its side at 2.2 and
// 5 m/s: it rocks over its edges and hops, as a prism does, but none of its points goes deeper
// than 0.25 mm, half the loaded slop (ContactSettings::stack_depth). With the manifold cut to
// four by the gaps alone the points coming down ahead of its bottom edge were left out: they
// went 1 mm in at 2.2 m/s (0.9 mm under explicit Euler, 1.3 mm under RK4).
TEST(RollingStaysOnTheSurface, CylinderOnItsSideUnderEveryIntegrator) {
    for (const char* integrator : kIntegrators) {
        for (double v : {2.2, 5.0}) {
            World world = world_of("{\"rigid_bodies\": [{\"name\": \"c\", \"shape\": \"cylinder\", \"radius\": 0.1, \"height\": 0.2,"
                                   " \"density\": 1000, \"rotation\": [90, 0, 0], \"position\": [0, 0, 0.1],"
                                   " \"velocity\": [" + exact_number(v) + ", 0, 0], \"angular_velocity\": [0, " + exact_number(v / 0.1) + ", 0]}]}",
                                   integrator);
            double deepest = 0.0;
            for (int t = 0; t < 100; ++t) {
                world.tick();
                ASSERT_EQ(world.status(), Status::Ok) << world.divergence();
                deepest = std::max(deepest, deepest_vertex(world, 0));
            }
            EXPECT_LE(deepest, 2.5e-4) << integrator << " v " << v << ": " << deepest * 1e3 << " mm deep";
        }
    }
}

// A box sliding at 4 m/s on friction 0.5 until it stops (0.8 s) stands no deeper than half the
// loaded slop, 0.25 mm: friction loads its leading edge, 0.10 mm deep under Verlet (0.07 mm at
// rest), as before.
TEST(RollingStaysOnTheSurface, BoxSlidingFast) {
    for (const char* integrator : kIntegrators) {
        World world = world_of("{\"rigid_bodies\": [{\"name\": \"box\", \"shape\": \"box\", \"size\": [0.3, 0.3, 0.3],"
                               " \"density\": 1000, \"friction\": 0.5, \"position\": [0, 0, 0.15], \"velocity\": [4, 0, 0]}]}",
                               integrator);
        double deepest = 0.0;
        for (int t = 0; t < 100; ++t) {
            world.tick();
            deepest = std::max(deepest, deepest_vertex(world, 0));
        }
        EXPECT_LE(deepest, 2.5e-4) << integrator << ": " << deepest * 1e3 << " mm deep";
        EXPECT_LT(length(world.rigid_motion(0).v), 1e-3) << integrator << ": stopped";
    }
}

// A soft ball (162 particles, 0.5 m across, k 120) thrown along the ground at 5 m/s: it slides,
// then rolls, and no particle of it is ever below the ground at a tick's end, as at rest (the
// ground's contact puts a particle reaching it on it, whatever moved it there), and it goes on
// (more than 2 m in the second).
TEST(RollingStaysOnTheSurface, SoftBallThrownAlongTheGround) {
    for (const char* integrator : kIntegrators) {
        World world = world_of("{\"soft_bodies\": [{\"name\": \"ball\", \"mesh\": \"ball:2\", \"scale\": 0.5, \"up_axis\": \"z\","
                               " \"particle_mass\": 0.02, \"stiffness\": 120, \"damping\": 0.5, \"drag_coefficient\": 0,"
                               " \"position\": [0, 0, 0.2505], \"initial_velocity\": [5, 0, 0]}]}",
                               integrator);
        const SoftBody& ball = world.soft_body(0);
        double lowest = 0.0;
        for (int t = 0; t < 50; ++t) {
            world.tick();
            for (std::size_t i = 0; i < ball.particle_count(); ++i) lowest = std::min(lowest, double(ball.x.z[i]));
        }
        EXPECT_GE(lowest, -1e-6) << integrator << ": " << -lowest * 1e3 << " mm below the ground";
        double x = 0.0;
        for (std::size_t i = 0; i < ball.particle_count(); ++i) x += double(ball.x.x[i]);
        EXPECT_GT(x / double(ball.particle_count()), 2.0) << integrator << ": it went on";
    }
}

}  // namespace
}  // namespace softbody::test
