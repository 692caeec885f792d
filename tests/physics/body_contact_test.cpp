// Bodies that meet (Eq. 37, 38, Figure 7): rigid against rigid and a soft body's particles
// against rigid bodies, checked against closed forms; no tunnelling, stacking, determinism.
#include <cmath>
#include <string>

#include "physics/scene_io.h"
#include "test_support.h"

namespace softbody::test {
namespace {

// A scene's rigid bodies and keys, with a soft body "body" of the given points added, placed
// where the points are (init_height 0), with the scene's top-level body keys (stiffness,
// damping, particle_mass).
World world_with_soft(const std::string& json, const std::vector<Vec3>& at, int threads = 1) {
    WorldDef def = parse_scene(json, "test.json");
    SoftBodyDef body = flat_body_of(json, points(at));
    body.init_height = 0.0f;
    def.soft_bodies.push_back(std::move(body));
    return World(def, WorldOptions{threads});
}

// Equal masses meeting along the normal, e and no friction: Eq. 38's lambda = (1 + e) m v_n / 2
// (Eq. 13): with e = 1 they exchange velocities.
TEST(RigidCollision, EqualSpheresHeadOnExchangeVelocities) {
    // Touching at the start (their gap 0), closing at 3 m/s: the first step is the collision.
    World world = world_of(
        "{\"gravity\": [0, 0, 0], \"ground\": false, \"restitution\": 1, \"dynamic_friction\": 0, \"rigid_bodies\": ["
        "{\"name\": \"a\", \"shape\": \"sphere\", \"radius\": 0.1, \"mass\": 2, \"position\": [-0.1, 0, 0], \"velocity\": [2, 0, 0]},"
        "{\"name\": \"b\", \"shape\": \"sphere\", \"radius\": 0.1, \"mass\": 2, \"position\": [0.1, 0, 0], \"velocity\": [-1, 0, 0]}]}");
    world.run(5);
    // One impulse of doubles: exact to rounding.
    EXPECT_NEAR(world.rigid_motion(0).v.x, -1.0, 1e-12);
    EXPECT_NEAR(world.rigid_motion(1).v.x, 2.0, 1e-12);
    EXPECT_LT(std::abs(world.rigid_motion(0).v.y) + std::abs(world.rigid_motion(0).v.z), 1e-15);
    EXPECT_LT(length(world.rigid_motion(0).omega) + length(world.rigid_motion(1).omega), 1e-15);
}

// Figure 7: a ball of mass m hits a free rod of the same mass at its end, e = 1, no friction, no
// gravity. In the thin-rod limit the rod's centre leaves at 0.4 v, it spins at 2.4 v / l, and the
// ball keeps 0.6 v. Here with the rod's actual inertia and where the ball actually hits: Eq. 38
// gives lambda = (1 + e) v / (1/m + 1/m + d^2 / J).
struct RodHit {
    double lambda, rod_v, rod_omega, ball_v;
};
RodHit rod_hit(double e, double m, double l, double w, double d, double v) {
    const double J = m * (l * l + w * w) / 12.0;  // Table 1, a box about its short axis
    const double lambda = (1.0 + e) * v / (1.0 / m + 1.0 / m + d * d / J);
    return {lambda, lambda / m, lambda * d / J, v - lambda / m};
}

std::string figure7(double e, double ball_x) {
    // The rod lies along x, 1 m long, 2 cm square; the ball (radius 5 cm) comes along +y at
    // 1 m/s, touching the rod's side face at the start.
    return "{\"gravity\": [0, 0, 0], \"ground\": false, \"dynamic_friction\": 0, \"restitution\": " + std::to_string(e) +
           ", \"rigid_bodies\": ["
           "{\"name\": \"rod\", \"shape\": \"box\", \"size\": [1, 0.02, 0.02], \"mass\": 1},"
           "{\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": 0.05, \"mass\": 1, \"position\": [" +
           std::to_string(ball_x) + ", -0.06, 0], \"velocity\": [0, 1, 0]}]}";
}

TEST(RigidCollision, Figure7BallHitsTheEndOfARod) {
    const double d = 0.49;  // where on the rod the ball hits, from its centre (the end is at 0.5)
    World world = world_of(figure7(1.0, d));
    world.tick();
    const RodHit want = rod_hit(1.0, 1.0, 1.0, 0.02, d, 1.0);
    const RigidMotion rod = world.rigid_motion(0), ball = world.rigid_motion(1);
    // The rod's centre moves off along the hit, and it turns about z (the ball hits the -y face
    // at +x, pushing it along +y: counter-clockwise).
    EXPECT_NEAR(rod.v.y, want.rod_v, 1e-12);
    EXPECT_NEAR(rod.omega.z, want.rod_omega, 1e-12);
    EXPECT_NEAR(ball.v.y, want.ball_v, 1e-12);
    // The read-out of Eq. 38 term by term (the app's "last collision") says the same: the
    // rod is body 1 (the normal points out of the ball toward it).
    ASSERT_EQ(world.contacts().size(), 1u);
    const ImpulseTerms terms = world.impulse_terms(world.contacts().front());
    EXPECT_NEAR(terms.v_rel_n, -1.0, 1e-12);
    EXPECT_NEAR(terms.inv_mass_1, 1.0, 1e-15);
    EXPECT_NEAR(terms.inv_mass_2, 1.0, 1e-15);
    EXPECT_NEAR(terms.rotation_1, d * d / ((1.0 + 0.0004) / 12.0), 1e-12);
    EXPECT_NEAR(terms.rotation_2, 0.0, 1e-15);  // a sphere's r is along n: no turn
    EXPECT_NEAR(terms.lambda, want.lambda, 1e-12);
    EXPECT_NEAR(terms.solver_lambda, want.lambda, 1e-12);
    // The thin-rod limit of the same formula, to see Figure 7's numbers: 0.4, 2.4, 0.6 within
    // what the 2 cm thickness and the 1 cm from the end change (under 4 %).
    EXPECT_NEAR(rod.v.y, 0.4, 0.4 * 0.04);
    EXPECT_NEAR(rod.omega.z, 2.4, 2.4 * 0.04);
    EXPECT_NEAR(ball.v.y, 0.6, 0.6 * 0.04);
    const RodHit thin = rod_hit(1.0, 1.0, 1.0, 0.0, 0.5, 1.0);
    EXPECT_NEAR(thin.rod_v, 0.4, 1e-15);
    EXPECT_NEAR(thin.rod_omega, 2.4, 1e-14);
    EXPECT_NEAR(thin.ball_v, 0.6, 1e-15);
    // Kinetic energy is kept with e = 1: 1/2 m v^2 = 1/2 m v_b^2 + 1/2 m v_r^2 + 1/2 J w^2.
    const double J = (1.0 + 0.0004) / 12.0;
    EXPECT_NEAR(0.5 * ball.v.y * ball.v.y + 0.5 * rod.v.y * rod.v.y + 0.5 * J * rod.omega.z * rod.omega.z, 0.5, 1e-12);
}

// e = 0: the contact points leave together, their relative velocity along the normal 0.
TEST(RigidCollision, Figure7PerfectlyInelasticLeavesNoNormalVelocity) {
    const double d = 0.49;
    World world = world_of(figure7(0.0, d));
    world.tick();
    const RodHit want = rod_hit(0.0, 1.0, 1.0, 0.02, d, 1.0);
    const RigidMotion rod = world.rigid_motion(0), ball = world.rigid_motion(1);
    EXPECT_NEAR(rod.v.y, want.rod_v, 1e-12);
    EXPECT_NEAR(rod.omega.z, want.rod_omega, 1e-12);
    // The rod's point where the ball hit, r = (d, -0.01, 0) from its centre when the step began:
    // v + w x r along y against the ball's.
    const double rod_point = rod.v.y + rod.omega.z * d;
    EXPECT_NEAR(ball.v.y - rod_point, 0.0, 1e-12);
}

// Momentum and angular momentum about the origin through a collision in zero gravity: a ball
// strikes a spinning box's face off-centre and at a slant, with friction. Each impulse acts
// equally and oppositely at one point, with each body's r from its centre where the step began
// (Eq. 37), and the positions then move from there with the new momenta: P and L are kept to
// rounding. They touch as the step begins: a contact still apart bounces from part-way through
// the step, and the bodies are moved back for it along the normal (apply_bounce_shifts) without
// a matching change of L, an error of the order of that shift times P (a few per cent of L for
// a hit a centimetre early), which this test keeps out of the way.
TEST(RigidCollision, MomentumAndAngularMomentumAreKeptThroughAnOffCentreHit) {
    const double turn = 30.0 * kPi / 180.0;
    const Vec3d n{std::cos(turn), std::sin(turn), 0.0}, side{-std::sin(turn), std::cos(turn), 0.0};
    // The box's +x face (0.3 m from its centre), a point 12 cm along it and 8 cm up, and the
    // ball's centre its radius out from there.
    const Vec3d on_face = Vec3d{0.2, -0.1, 0.0} + n * 0.3 + side * 0.12 + Vec3d{0, 0, 0.08};
    const Vec3d ball = on_face + n * 0.1;
    const Vec3d v = n * -3.0 + side * 1.0 + Vec3d{0, 0, 0.5};
    char json[1024];
    std::snprintf(json, sizeof json,
                  "{\"gravity\": [0, 0, 0], \"ground\": false, \"restitution\": 0.5, \"dynamic_friction\": 0.3, \"rigid_bodies\": ["
                  "{\"name\": \"box\", \"shape\": \"box\", \"size\": [0.6, 0.4, 0.3], \"mass\": 2, \"position\": [0.2, -0.1, 0],"
                  " \"rotation\": [0, 0, 30], \"angular_velocity\": [0.5, 0.2, 1]},"
                  "{\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": 0.1, \"mass\": 1, \"position\": [%.17g, %.17g, %.17g],"
                  " \"velocity\": [%.17g, %.17g, %.17g], \"angular_velocity\": [0, 3, 0]}]}",
                  ball.x, ball.y, ball.z, v.x, v.y, v.z);
    World world = world_of(json);
    const Vec3d P0 = world.momentum(), L0 = world.angular_momentum();
    world.tick();
    ASSERT_FALSE(world.contacts().empty());
    const RigidContact& c = world.contacts().front();
    EXPECT_NEAR(c.separation, 0.0, 1e-12);
    EXPECT_GT(c.normal_impulse, 1.0);                                         // a real hit: ~ (1 + e) m v_n
    EXPECT_GT(std::hypot(c.tangent_impulse[0], c.tangent_impulse[1]), 0.01);  // with friction
    world.run(30);
    EXPECT_LT(length(world.momentum() - P0), 1e-13);
    EXPECT_LT(length(world.angular_momentum() - L0), 1e-13);
    // They parted: the ball goes back out along the normal.
    EXPECT_GT(dot(world.rigid_motion(1).v - world.rigid_motion(0).v, n), 0.0);
}

// --- No tunnelling ---------------------------------------------------------------------------

// A 5 cm ball at 20 m/s moves 40 cm a step, twenty times the thickness of a 2 cm plank: found
// where the step begins with a margin of its whole step, the contact stops it at the surface.
TEST(Tunnelling, FastBallDoesNotPassThroughAThinPlank) {
    for (const char* integrator : {"verlet", "symplectic_euler", "explicit_euler", "rk4"}) {
        World world = world_of(std::string("{\"gravity\": [0, 0, 0], \"integrator\": \"") + integrator +
                               "\", \"restitution\": 0.5, \"rigid_bodies\": ["
                               "{\"name\": \"plank\", \"shape\": \"box\", \"size\": [1, 1, 0.02], \"fixed\": true, \"position\": [0, 0, 1]},"
                               "{\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": 0.025, \"position\": [0.1, 0.2, 1.93],"
                               " \"velocity\": [0, 0, -20]}]}");
        double lowest = 10.0;
        for (int t = 0; t < 50; ++t) {
            world.tick();
            lowest = std::min(lowest, world.rigid_motion(1).x.z);
        }
        // Never below the plank's top (1.01) by more than the solver's slop and a step's rounding.
        EXPECT_GT(lowest, 1.01 + 0.025 - 1e-3) << integrator;
        EXPECT_GT(world.rigid_motion(1).v.z, 0.0) << integrator;  // it bounced back up
    }
}

// A 12-particle soft ball dropped from 5 m onto a fixed box lands on top of it, whatever its
// particles' speed (9.9 m/s, 20 cm a step).
TEST(Tunnelling, SoftBodyDroppedFromFiveMetresStaysOnTopOfABox) {
    std::vector<Vec3> ball;
    const float g = 0.5f * (1.0f + std::sqrt(5.0f));  // an icosahedron's corners, 0.3 m across
    for (float a : {-1.0f, 1.0f}) {
        for (float b : {-g, g}) {
            ball.push_back(Vec3{0, a, b} * 0.079f + Vec3{0, 0, 5.5f});
            ball.push_back(Vec3{a, b, 0} * 0.079f + Vec3{0, 0, 5.5f});
            ball.push_back(Vec3{b, 0, a} * 0.079f + Vec3{0, 0, 5.5f});
        }
    }
    World world = world_with_soft("{\"stiffness\": 15, \"damping\": 0.2, \"particle_mass\": 0.05, \"auto_substeps\": false, \"rigid_bodies\": ["
                                  "{\"name\": \"box\", \"shape\": \"box\", \"size\": [1, 1, 1], \"fixed\": true, \"position\": [0, 0, 0.5]}]}",
                                  ball);
    float deepest = 0.0f;
    for (int t = 0; t < 250; ++t) {
        world.tick();
        for (std::size_t i = 0; i < world.soft_body(0).particle_count(); ++i) deepest = std::max(deepest, 1.0f - position(world, i).z);
    }
    ASSERT_EQ(world.status(), Status::Ok);
    // Caught at the top face: at most the solver's slop and a step's fall of squash below it.
    EXPECT_LT(deepest, 0.01f);
    // Resting on it: its centre above the top by at most its radius (0.15 m) and at least 5 cm
    // (it sags under its weight on springs of 15 N/m; measured 9.5 cm).
    EXPECT_GT(world.center_of_mass().z, 1.05f);
    EXPECT_LT(world.center_of_mass().z, 1.0f + 0.15f);
}

// --- Stacking --------------------------------------------------------------------------------

// Five unit boxes stacked on the ground stand for 20 s with the top one within 1 cm of where it
// started; a box resting on another does not jitter (its speed at rest below 1 mm/s).
TEST(Stacking, TowerOfFiveBoxesStands) {
    std::string json = "{\"rigid_bodies\": [";
    for (int i = 0; i < 5; ++i) {
        json += std::string(i ? "," : "") + "{\"name\": \"b" + std::to_string(i) +
                "\", \"shape\": \"box\", \"size\": [1, 1, 1], \"position\": [0, 0, " + std::to_string(0.5 + i) + "]}";
    }
    World world = world_of(json + "]}");
    const Vec3d top0 = world.rigid_motion(4).x;
    double fastest_late = 0.0;
    for (int t = 0; t < 1000; ++t) {
        world.tick();
        if (t >= 500) {
            for (std::size_t b = 0; b < 5; ++b) fastest_late = std::max(fastest_late, length(world.rigid_motion(b).v));
        }
    }
    ASSERT_EQ(world.status(), Status::Ok);
    EXPECT_LT(length(world.rigid_motion(4).x - top0), 0.01);
    EXPECT_LT(fastest_late, 1e-3);
}

TEST(Stacking, BoxOnABoxDoesNotJitter) {
    World world = world_of("{\"rigid_bodies\": ["
                           "{\"name\": \"low\", \"shape\": \"box\", \"size\": [1, 1, 0.5], \"mass\": 20, \"position\": [0, 0, 0.25]},"
                           "{\"name\": \"high\", \"shape\": \"box\", \"size\": [0.6, 0.4, 0.3], \"mass\": 5, \"position\": [0.1, 0.1, 0.66],"
                           " \"rotation\": [0, 0, 20]}]}");
    world.run(100);  // lands (from 1 cm) and settles
    const Vec3d x0 = world.rigid_motion(1).x;
    double fastest = 0.0, turn = 0.0;
    for (int t = 0; t < 250; ++t) {
        world.tick();
        fastest = std::max(fastest, length(world.rigid_motion(1).v));
        turn = std::max(turn, length(world.rigid_motion(1).omega));
    }
    EXPECT_LT(fastest, 1e-3);
    EXPECT_LT(turn, 1e-3);
    EXPECT_LT(length(world.rigid_motion(1).x - x0), 1e-3);  // over 5 s
}

// --- Soft bodies against rigid ones ----------------------------------------------------------

// The eight corners of a cube of side `side`, lying on a plane through `base` with unit normal
// `up` and in-plane axis `along`, `lift` above it.
std::vector<Vec3> cube_on(const Vec3d& base, const Vec3d& along, const Vec3d& up, double side, double lift) {
    const Vec3d across = cross(up, along);
    std::vector<Vec3> out;
    for (int i = 0; i < 8; ++i) {
        const double a = (i & 1 ? 0.5 : -0.5) * side, b = (i & 2 ? 0.5 : -0.5) * side, c = (i & 4 ? side : 0.0) + lift;
        out.push_back(to_float(base + along * a + across * b + up * c));
    }
    return out;
}

// A soft cube (30 cm, eight particles) on a fixed ramp, a turned box whose face's normal comes
// from its hull as the body turns it. Eq. 24 holds each particle while the tangential impulse it
// needs is within mu_s times the normal one; for the body as a whole, while tan theta <= mu_s.
// Past that, Eq. 25 lets it slide, with acceleration g (sin theta - mu_d cos theta).
constexpr double kRampDegrees = 20.0;
struct Ramp {
    Vec3d along, up;  // downhill along the face, and its outward normal
};
Ramp ramp_axes(double degrees) {
    const double theta = degrees * kPi / 180.0;
    return {{std::cos(theta), 0.0, -std::sin(theta)}, {std::sin(theta), 0.0, std::cos(theta)}};
}
World cube_on_ramp(double degrees) {
    const Ramp r = ramp_axes(degrees);
    const Vec3d face = Vec3d{0.0, 0.0, 1.0} + r.up * 0.1;  // the ramp's centre is 1 m up, 0.2 m thick
    return world_with_soft(
        "{\"static_friction\": 0.6, \"dynamic_friction\": 0.4, \"restitution\": 0, \"ground\": false,"
        " \"stiffness\": 200, \"damping\": 0.5, \"particle_mass\": 0.05, \"drag_coefficient\": 0, \"auto_substeps\": true,"
        " \"rigid_bodies\": ["
        "{\"name\": \"ramp\", \"shape\": \"box\", \"size\": [8, 1, 0.2], \"fixed\": true, \"position\": [0, 0, 1],"
        " \"rotation\": [0, " + std::to_string(degrees) + ", 0]}]}",
        cube_on(face, r.along, r.up, 0.3, 0.0));
}
// Where the four particles on the ramp (0 to 3: the bottom face) are along it, on average.
double downhill(const Vec3Array& a, const Vec3d& along) {
    double sum = 0.0;
    for (std::size_t i = 0; i < 4; ++i) sum += dot(Vec3d(a[i]), along);
    return sum / 4.0;
}

// The inclined-plane experiment: tilt slowly (gravity turned at 2 degrees a second, the same as
// tilting the ramp) from 20 degrees until the cube slides. It must hold until tan theta is near
// mu_s and go once it is past. Measured: it goes at 30.88 degrees (tan 0.598; atan 0.6 = 30.96),
// its uphill particles, pressed least, slipping a little first. Using mu_d for particles at rest
// would let it go at 21.8 degrees; no friction, at once.
TEST(SoftOnRigid, CubeOnATiltingRampHoldsUntilTanThetaReachesMuS) {
    World world = cube_on_ramp(kRampDegrees);
    const Vec3d along = ramp_axes(kRampDegrees).along;
    world.run(50);  // settles into its springs
    const double s0 = downhill(world.soft_body(0).x, along);
    double went_at = 0.0;
    for (int t = 0; t < 1000 && went_at == 0.0; ++t) {
        const double extra = 2.0 * (t + 1) * 0.02 * kPi / 180.0;
        WorldSettings p = world.settings();
        p.gravity = {float(9.81 * std::sin(extra)), 0.0f, float(-9.81 * std::cos(extra))};
        world.set_settings(p);
        world.tick();
        ASSERT_EQ(world.status(), Status::Ok);
        if (downhill(world.soft_body(0).x, along) - s0 > 1e-3) went_at = kRampDegrees * kPi / 180.0 + extra;
    }
    ASSERT_GT(went_at, 0.0) << "it never slid";
    EXPECT_GT(std::tan(went_at), 0.95 * 0.6);
    EXPECT_LT(std::tan(went_at), 0.6 + 0.01);
}

// Steeper than mu_s allows from the start: it slides, all four particles at mu_d.
TEST(SoftOnRigid, SlidesDownASteepRampWithTheAccelerationOfMuD) {
    const double degrees = 40.0;  // tan 40 = 0.84 > 0.6
    World world = cube_on_ramp(degrees);
    const Vec3d along = ramp_axes(degrees).along;
    world.run(25);  // landed on its springs, sliding
    const double v1 = downhill(world.soft_body(0).v, along);
    world.run(50);
    ASSERT_EQ(world.status(), Status::Ok);
    const double v2 = downhill(world.soft_body(0).v, along);
    // g (sin 40 - 0.4 cos 40) = 3.30 m/s^2. Within 2 %: the body's springs still ring a little.
    const double a = 9.81 * (std::sin(degrees * kPi / 180.0) - 0.4 * std::cos(degrees * kPi / 180.0));
    EXPECT_NEAR((v2 - v1) / 1.0, a, 0.02 * a);
}

// Momentum and angular momentum about the origin through a soft body's hit on a free rigid body
// in zero gravity: Eq. 38 with the particle as body 1, the equal and opposite impulse on the
// box at its surface point. A soft cube flying at 2 m/s with its front face touching the box's
// face off-centre as the step begins (no position correction, as for two rigid bodies above).
TEST(SoftOnRigid, MomentumAndAngularMomentumAreKeptThroughAHit) {
    // The box's -x face is x = -0.3; the cube's front face (its +x particles) lies on it, 15 cm
    // off the box's centre in y and z, so the hit turns the box.
    std::vector<Vec3> cube;
    for (int i = 0; i < 8; ++i) {
        cube.push_back({i & 1 ? -0.3f : -0.6f, (i & 2 ? 0.15f : -0.15f) + 0.15f, (i & 4 ? 0.15f : -0.15f) + 0.15f});
    }
    World world = world_with_soft(
        "{\"gravity\": [0, 0, 0], \"ground\": false, \"restitution\": 0.5, \"static_friction\": 0.6,"
        " \"dynamic_friction\": 0.4, \"stiffness\": 100, \"damping\": 0.2, \"particle_mass\": 0.1, \"drag_coefficient\": 0,"
        " \"auto_substeps\": false,"
        " \"initial_velocity\": [2, 0.5, 0], \"rigid_bodies\": [{\"name\": \"box\", \"shape\": \"box\", \"size\": [0.6, 0.6, 0.6],"
        " \"mass\": 1, \"angular_velocity\": [0, 0, 1]}]}",
        cube);
    const Vec3d P0 = world.momentum(), L0 = world.angular_momentum();
    world.tick();
    ASSERT_EQ(world.contacts().size(), 4u);
    for (const RigidContact& c : world.contacts()) {
        EXPECT_EQ(c.soft, 0);
        EXPECT_NEAR(c.separation, 0.0, 1e-7);  // the particles' float positions on the face
        EXPECT_GT(c.normal_impulse, 0.05);      // each hit, ~ (1 + e) m v_n less what the springs share
    }
    // The box took a real share: it moves and turns about more than its own spin.
    EXPECT_GT(world.rigid_motion(0).v.x, 0.5);
    EXPECT_GT(length(world.rigid_motion(0).omega - Vec3d{0, 0, 1}), 0.1);
    // Particles' velocities are floats: each impulse rounds to 1e-7 of v. |P| = 1.65 N s, |L|
    // about the origin 0.44 kg m^2/s; measured 6e-8 and 3e-8.
    EXPECT_LT(length(world.momentum() - P0), 1e-6);
    EXPECT_LT(length(world.angular_momentum() - L0), 1e-6);
    // The cube rings, and its particles meet the box again, some still apart as the step
    // begins: those bounce from part-way through the step and are moved back for it along the
    // normal, which keeps P (equal and opposite moves) but not L exactly (measured 6e-4 after
    // 60 ticks). P stays to rounding.
    world.run(60);
    ASSERT_EQ(world.status(), Status::Ok);
    EXPECT_LT(length(world.momentum() - P0), 1e-6);
    EXPECT_LT(length(world.angular_momentum() - L0), 1e-2 * length(L0));
}

// --- The seesaw ------------------------------------------------------------------------------

// A plank laid on a fixed fulcrum (a square bar turned 45 degrees, edge up), 30 cm off centre:
// it tips toward its heavier side, starting with angular acceleration tau / J about the
// fulcrum, tau = M g d and J = M (L^2 + t^2) / 12 + M (d^2 + (t/2)^2) (the parallel axis). The
// contacts hold the plank's point on the edge still, as a pin would at that instant.
TEST(Seesaw, TipsTowardItsHeavierEndWithTauOverJ) {
    const double d = 0.3, M = 4.0, L = 2.0, t = 0.04, g = 9.81;
    const double edge = 0.5 + 0.1 * std::sqrt(2.0);
    char json[1024];
    std::snprintf(json, sizeof json,
                  "{\"drag_coefficient\": 0, \"restitution\": 0, \"rigid_bodies\": ["
                  "{\"name\": \"fulcrum\", \"shape\": \"box\", \"size\": [0.2, 1, 0.2], \"fixed\": true, \"friction\": 1,"
                  " \"position\": [0, 0, 0.5], \"rotation\": [0, 45, 0]},"
                  "{\"name\": \"plank\", \"shape\": \"box\", \"size\": [%g, 0.4, %g], \"mass\": %g, \"friction\": 1,"
                  " \"position\": [%g, 0, %.17g]}]}",
                  L, t, M, d, edge + t / 2);
    World world = world_of(json);
    const double J = M * (L * L + t * t) / 12.0 + M * (d * d + t * t / 4.0);
    const double alpha = M * g * d / J;
    world.tick();
    ASSERT_EQ(world.contacts().size(), 2u);  // the edge across the plank: its two ends
    // The +x side goes down: a turn about +y. One step from rest: omega = alpha h, as the
    // impulses that hold the pin give it (measured to 1e-7; the solver's iterations converge).
    EXPECT_NEAR(world.rigid_motion(1).omega.y, alpha * 0.02, 1e-5 * alpha * 0.02);
    // And on: over 0.2 s the plank rolls over the edge a little (J grows with the pivot's
    // distance): within 0.2 % (measured 0.1 %).
    world.run(9);
    EXPECT_NEAR(world.rigid_motion(1).omega.y, alpha * 0.2, 2e-3 * alpha * 0.2);
}

// --- Determinism -----------------------------------------------------------------------------

// A soft body of 550 particles (three kernel blocks) lands on a fixed box and a free ball: the
// contacts are found and solved in one order whatever the thread count, so the bits agree.
TEST(ContactDeterminism, SoftOnRigidHashIsTheSameAtAnyThreadCount) {
    const auto hash_after = [](int threads) {
        std::vector<Vec3> cloud = random_cloud(550, 7, 0.5f);
        for (Vec3& p : cloud) p += Vec3{0.0f, 0.0f, 2.0f};
        World world = world_with_soft(
            "{\"stiffness\": 0.2, \"damping\": 0.002, \"particle_mass\": 0.05, \"rigid_bodies\": ["
            "{\"name\": \"table\", \"shape\": \"box\", \"size\": [1, 1, 0.8], \"fixed\": true, \"position\": [0.3, 0, 0.4]},"
            "{\"name\": \"ball\", \"shape\": \"sphere\", \"radius\": 0.2, \"position\": [-0.4, 0.1, 1.0], \"velocity\": [0.5, 0, 0]}]}",
            cloud, threads);
        world.run(100);
        EXPECT_EQ(world.status(), Status::Ok);
        std::size_t soft_contacts = 0;
        for (const RigidContact& c : world.contacts()) soft_contacts += c.soft >= 0;
        EXPECT_GT(soft_contacts, 20u);  // it is lying on them
        return world.state_hash();
    };
    const std::uint64_t one = hash_after(1);
    EXPECT_EQ(one, hash_after(2));
    EXPECT_EQ(one, hash_after(3));
}

}  // namespace
}  // namespace softbody::test
