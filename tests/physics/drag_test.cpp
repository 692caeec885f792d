// Aerodynamic drag, Eq. 23: F_drag = -1/2 rho C_D S |v| v on the centre of mass, with S = pi r^2
// the cross-section of the bounding sphere (r: largest distance of a rest particle from the rest
// centre of mass), shared among particles by mass. A single particle has r = 0 and no drag, so
// the body here is a cube of 8 particles (r = sqrt(3)/2 for side 1).
#include <cmath>

#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

FlatKeys drag_params(float rho, float C_D, float m) {
    FlatKeys p = bare_params();
    p.gravity = {0.0f, 0.0f, float(-kG)};
    p.air_density = rho;
    p.drag_coefficient = C_D;
    p.particle_mass = m;
    p.stiffness = 10.0f;  // all particles feel the same forces, so the springs never stretch
    p.damping = 0.1f;
    return p;
}

TEST(Drag, FallingBodyReachesTerminalVelocity) {
    struct Case {
        float rho, C_D, m, side;
    };
    for (const Case c : {Case{1.2f, 0.4f, 0.1f, 1.0f}, Case{1.2f, 0.2f, 0.05f, 0.5f}, Case{5.0f, 0.3f, 0.2f, 2.0f}}) {
        OneBodyWorld world(drag_params(c.rho, c.C_D, c.m), points(cube_corners(c.side)));
        const double M = 8.0 * c.m;
        const double r = std::sqrt(3.0) / 2.0 * c.side;
        const double S = kPi * r * r;
        const double v_t = std::sqrt(2.0 * M * kG / (c.rho * c.C_D * S));
        // Approach to v_t goes like tanh(g t / v_t): time constant v_t / g < 0.8 s for these
        // cases, so 10 s is more than 12 time constants: closer than 1e-10.
        world.run(500);
        ASSERT_EQ(world.status(), Status::Ok);
        // The body's velocity: the mean of its particles' (equal masses). The drag acts on it
        // alone (internal forces cancel in pairs), and the discrete update
        // v += h (g - D |v| v / M) has the same fixed point v_t, so only float rounding
        // remains: pi and S in float (1e-7), v itself (6e-8): 1e-5 relative.
        Vec3 v_com;
        for (std::size_t i = 0; i < world.soft_body(0).particle_count(); ++i) v_com += velocity(world, i) / 8.0f;
        EXPECT_NEAR(-v_com.z, v_t, 1e-5 * v_t) << "rho " << c.rho << ", C_D " << c.C_D << ", side " << c.side;
        EXPECT_NEAR(v_com.x, 0.0, 1e-6);
        EXPECT_NEAR(v_com.y, 0.0, 1e-6);
        // Every particle moves with the body: drag is shared by mass, so it cannot shake the
        // body, and positions of up to 70 m (ulp 8e-6 m) leave the springs only rounding to act
        // on. 1e-4 relative is far below any real internal motion a wrong share would excite.
        for (std::size_t i = 0; i < world.soft_body(0).particle_count(); ++i) {
            EXPECT_NEAR(length(velocity(world, i) - v_com), 0.0, 1e-4 * v_t) << "particle " << i;
        }
    }
}

// Drag opposes the motion in any direction: a body thrown sideways without gravity slows as
// v(t) = v0 / (1 + kappa v0 t), kappa = D / M, D = rho C_D S / 2. The drag's backward-Euler
// step (forces.h) follows v_{n+1} + h kappa v_{n+1}^2 = v_n instead; with u = 1/v that is
// u_{n+1} = u_n + h kappa / (1 + h kappa v_{n+1}), so the discrete speed falls slightly slower,
// by a relative h kappa v ln(1 + kappa v0 t) at most, never more than 0.37 h kappa v0 (2.6%
// here, h kappa v0 = 0.071).
TEST(Drag, SlowsAHorizontalThrowAsOneOverT) {
    FlatKeys p = drag_params(1.2f, 0.4f, 0.1f);
    p.gravity = {0.0f, 0.0f, 0.0f};
    const Vec3 v0{3.0f, -4.0f, 0.0f};  // 5 m/s
    p.initial_velocity = v0;
    OneBodyWorld world(p, points(cube_corners(1.0f)));
    const double M = 0.8, r = std::sqrt(3.0) / 2.0, kappa = 0.5 * 1.2 * 0.4 * kPi * r * r / M;
    const double h = 0.02;
    double discrete = 5.0;
    for (int n = 1; n <= 250; ++n) {
        world.tick();
        discrete = 2.0 * discrete / (1.0 + std::sqrt(1.0 + 4.0 * h * kappa * discrete));
        const double t = n * h;
        const double continuous = 5.0 / (1.0 + kappa * 5.0 * t);
        Vec3 v;  // the body's velocity: the mean of its particles' (equal masses)
        for (std::size_t i = 0; i < world.soft_body(0).particle_count(); ++i) v += velocity(world, i) / 8.0f;
        // The scheme's own recurrence, computed here in double: float rounding only (1e-5).
        ASSERT_NEAR(length(v), discrete, 1e-5 * discrete) << "t = " << t;
        // The continuous law, within the bound above plus a little.
        ASSERT_NEAR(length(v), continuous, 0.4 * h * kappa * 5.0 * continuous) << "t = " << t;
        // Direction unchanged: drag is along -v (the cross product of v and v0, relative to
        // |v| |v0|, is float rounding only).
        ASSERT_NEAR((v.x * v0.y - v.y * v0.x) / (length(v) * 5.0), 0.0, 1e-5) << "t = " << t;
    }
}

// A large, light body: a square sheet 550 m across of four 1 kg particles, at the defaults.
// Explicit drag would change its velocity by h kappa |v| v a step with kappa |v| h far above 2
// (kappa = 2.1e4 per metre here) and blow it up within a few ticks, while the springs' stability
// estimate saw nothing wrong; the implicit step settles it at its terminal velocity instead.
TEST(Drag, LargeLightSheetSettlesAtItsTerminalVelocity) {
    FlatKeys p = drag_params(1.2f, 0.3f, 1.0f);
    const float half = 275.0f;
    OneBodyWorld world(p, points({{-half, -half, 0.0f}, {half, -half, 0.0f}, {-half, half, 0.0f}, {half, half, 0.0f}}));
    const double r = std::sqrt(2.0) * half, S = kPi * r * r, kappa = 0.5 * 1.2 * 0.3 * S / 4.0;
    const double v_t = std::sqrt(kG / kappa);  // 2.1 cm/s
    world.run(500);
    ASSERT_EQ(world.status(), Status::Ok) << world.divergence();
    Vec3 v;
    for (std::size_t i = 0; i < world.soft_body(0).particle_count(); ++i) v += velocity(world, i) / 4.0f;
    // The implicit step's fixed point is v_t exactly: float rounding only.
    EXPECT_NEAR(-v.z, v_t, 1e-4 * v_t);
}

// The same for a rigid body: a 20 m square plate 1 cm thick of 1 kg, C_D 1.
TEST(Drag, LargeLightPlateSettlesAtItsTerminalVelocity) {
    World world((parse_scene(
        "{\"ground\": false, \"rigid_bodies\": [{\"name\": \"plate\", \"shape\": \"box\", \"size\": [20, 20, 0.01],"
        " \"mass\": 1, \"drag_coefficient\": 1}]}",
        "plate.json")));
    const RigidBody& plate = world.rigid_body(0);
    const double kappa = 0.5 * 1.2 * 1.0 * plate.drag_area / 1.0;
    world.run(500);
    ASSERT_EQ(world.status(), Status::Ok) << world.divergence();
    // The fixed point is v_t exactly; rho and g are the world's floats (1.2f, 9.81f): 1e-7.
    const double v_t = std::sqrt(9.81f / kappa);
    EXPECT_NEAR(-world.rigid_motion(0).v.z, v_t, 1e-7 * v_t);
}

}  // namespace
}  // namespace softbody::test
