// The integrators on their own: free fall, Verlet against symplectic Euler, conservation of
// momentum, and energy with nothing to dissipate it.
#include <cmath>
#include <vector>

#include "test_support.h"

namespace softbody::test {
namespace {

FlatKeys free_fall_params(Integrator integrator, float g, float dt) {
    FlatKeys p = bare_params();
    p.gravity = {0.0f, 0.0f, -g};
    p.dt = dt;
    p.integrator = integrator;
    return p;
}

// Free fall from rest with every number a power of two (g = 8, h = 1/64, z0 = 0): then every
// position and velocity is a multiple of 2^-9 below 2^15, which a float holds exactly, so each
// scheme must produce its discrete formula bit for bit:
//   Verlet + Euler velocities, symplectic Euler:  z_n = -g h^2 n(n+1)/2,  v_n = -g h n
//   explicit Euler (x from the old v):            z_n = -g h^2 n(n-1)/2
//   RK4 (exact for a constant force):             z_n = -g (n h)^2 / 2
TEST(FreeFall, ExactDiscreteFormulaForEachIntegrator) {
    const float g = 8.0f, h = 1.0f / 64.0f;
    for (Integrator integrator :
         {Integrator::Verlet, Integrator::SymplecticEuler, Integrator::ExplicitEuler, Integrator::RK4}) {
        OneBodyWorld world(free_fall_params(integrator, g, h), points({{0.0f, 0.0f, 0.0f}}));
        for (int n = 1; n <= 1000; ++n) {
            world.tick();
            const double nn = n;
            double expected = 0.0;
            switch (integrator) {
                case Integrator::Verlet:
                case Integrator::SymplecticEuler: expected = -g * h * h * nn * (nn + 1.0) / 2.0; break;
                case Integrator::ExplicitEuler: expected = -g * h * h * nn * (nn - 1.0) / 2.0; break;
                case Integrator::RK4: expected = -g * (nn * h) * (nn * h) / 2.0; break;
            }
            ASSERT_EQ(double(position(world, 0).z), expected) << to_string(integrator) << ", tick " << n;
            ASSERT_EQ(double(velocity(world, 0).z), -g * h * nn) << to_string(integrator) << ", tick " << n;
            ASSERT_EQ(position(world, 0).x, 0.0f);
            ASSERT_EQ(position(world, 0).y, 0.0f);
        }
    }
}

// The same with Listing 8's g = 9.81 and dt = 0.02, where floats round.
TEST(FreeFall, MatchesDiscreteFormulaTightlyAndParabolaLoosely) {
    const double g = 9.81, h = 0.02, z0 = 10.0;
    for (Integrator integrator : {Integrator::Verlet, Integrator::SymplecticEuler}) {
        FlatKeys p = free_fall_params(integrator, float(g), float(h));
        p.init_height = float(z0);
        OneBodyWorld world(p, points({{0.0f, 0.0f, 0.0f}}));
        for (int n = 1; n <= 200; ++n) {
            world.tick();
            const double z = position(world, 0).z, t = n * h, nn = n;
            // Semi-implicit Euler: v_n = -g h n, z_n = z0 - g h^2 n (n+1) / 2.
            const double discrete = z0 - g * h * h * nn * (nn + 1.0) / 2.0;
            // Float rounding: each step rounds v (|v| <= 40 m/s: half an ulp is 1.9e-6 m/s) and
            // z (|z| <= 70 m: 3.8e-6 m). An error in v moves z by h per later step, so after n
            // steps |error of v| <= 2e-6 n and |error of z| <= 4e-6 n + 2e-8 n^2 (1.6e-3 m at
            // tick 200; a few times 1e-4 m is typical). Both are far below the continuous error
            // g h t / 2 = 2e-3 n m that the next check allows for.
            ASSERT_NEAR(z, discrete, 4e-6 * nn + 2e-8 * nn * nn) << to_string(integrator) << ", tick " << n;
            ASSERT_NEAR(velocity(world, 0).z, -g * h * nn, 2e-6 * nn) << to_string(integrator) << ", tick " << n;
            // Against the parabola z0 - g t^2 / 2 the scheme is ahead by exactly g h t / 2 (the
            // n(n+1) above): allow twice that.
            ASSERT_NEAR(z, z0 - g * t * t / 2.0, g * h * t) << to_string(integrator) << ", tick " << n;
        }
        // And the discretisation error has the sign and size worked out above: z_n lies below
        // the parabola by g h t / 2 (39 cm at t = 4 s), within float rounding.
        const double t = 200 * h;
        EXPECT_NEAR(z0 - g * t * t / 2.0 - position(world, 0).z, g * h * t / 2.0, 1e-2);
    }
}

// A cloud hanging from two pins (so it swings and stretches), with dampers and drag on and no
// ground: no contacts. Then Verlet + Euler velocities and symplectic Euler are the same algebra,
// x_{n+1} = x_n + (v_n + a h) h, only rounded differently. The dampers are strong (c = 1 kg/s on
// 276 pairs) so that the body's own vibrations die out and cannot amplify the rounding; the
// swing about the pins is a regular pendulum motion, which does not amplify it either.
FlatKeys swinging_cloud_params(Integrator integrator) {
    FlatKeys p = listing8_params();
    p.ground = false;
    p.init_height = 0.0f;
    p.damping = 1.0f;
    p.pinned = {0, 1};
    p.initial_velocity = {0.5f, -0.3f, 0.2f};
    p.integrator = integrator;
    return p;
}

double max_difference(const Vec3Array& a, const Vec3Array& b) {
    double worst = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, double(length(a[i] - b[i])));
    return worst;
}

TEST(Verlet, EqualsSymplecticEulerWithoutContacts) {
    const Mesh mesh = points(random_cloud(24, 7));
    OneBodyWorld verlet(swinging_cloud_params(Integrator::Verlet), mesh);
    OneBodyWorld euler(swinging_cloud_params(Integrator::SymplecticEuler), mesh);
    double worst_x = 0.0, worst_v = 0.0, travelled = 0.0;
    const Vec3 start = position(verlet, 10);
    for (int n = 0; n < 3000; ++n) {
        verlet.tick();
        euler.tick();
        worst_x = std::max(worst_x, max_difference(verlet.soft_body(0).x, euler.soft_body(0).x));
        worst_v = std::max(worst_v, max_difference(verlet.soft_body(0).v, euler.soft_body(0).v));
        travelled = std::max(travelled, double(length(position(verlet, 10) - start)));
    }
    ASSERT_EQ(verlet.status(), Status::Ok);
    // Positions within 2.5 m of the origin have an ulp of 2.4e-7 m; the two schemes round at
    // different places (Verlet adds its carried step, Euler adds v h), a few ulps apart, and the
    // damped body forgets such differences instead of amplifying them. 1e-5 m (40 ulps) holds
    // that over 3000 steps; an O(h) difference in the scheme (explicit Euler, or a Verlet
    // start x_{-1} = x_0 that drops v_0) shows as v0 h = 0.012 m at the first step.
    EXPECT_LT(worst_x, 1e-5);
    EXPECT_LT(worst_v, 2e-5);  // velocities, ~1 m/s: the same rounding, divided by h, damped
    EXPECT_GT(travelled, 0.5);  // the body really moved, so the comparison means something
}

// The same identity must survive switching integrators mid-run: Verlet has to restart from
// the current x and v (x_{-1} = x_0 - v_0 h), not from a previous position left over from
// before the switch.
TEST(Verlet, RestartsCleanlyAfterSwitchingIntegrators) {
    const Mesh mesh = points(random_cloud(24, 7));
    FlatKeys verlet_params = swinging_cloud_params(Integrator::Verlet);
    FlatKeys euler_params = swinging_cloud_params(Integrator::SymplecticEuler);
    OneBodyWorld switching(verlet_params, mesh);
    OneBodyWorld euler(euler_params, mesh);
    for (int phase = 0; phase < 4; ++phase) {
        set_flat(switching, phase % 2 == 0 ? verlet_params : euler_params);
        for (int n = 0; n < 100; ++n) {
            switching.tick();
            euler.tick();
        }
        // As above: rounding-level differences only.
        EXPECT_LT(max_difference(switching.soft_body(0).x, euler.soft_body(0).x), 1e-5) << "after phase " << phase;
        EXPECT_LT(max_difference(switching.soft_body(0).v, euler.soft_body(0).v), 2e-5) << "after phase " << phase;
    }
}

// With no external force (no gravity, ground or drag; no pins) the springs and dampers act in
// equal and opposite pairs, so total momentum sum m v is constant and the centre of mass moves
// in a straight line at constant speed.
TEST(Momentum, ConservedWithoutExternalForces) {
    FlatKeys p = listing8_params();
    p.gravity = {0.0f, 0.0f, 0.0f};
    p.ground = false;
    p.drag_coefficient = 0.0f;
    p.init_height = 0.0f;
    p.initial_velocity = {0.3f, 0.1f, -0.2f};
    const std::size_t n = 40;
    OneBodyWorld world(p, points(random_cloud(n, 11)));
    // Random velocities: yank three particles about with a 10 N/m grab spring for a few ticks
    // each (an external force), then let go. From then on nothing external acts.
    const std::uint32_t grabbed[3] = {3, 17, 29};
    const Vec3 targets[3] = {{3.0f, 0.0f, 1.0f}, {-2.0f, 2.0f, 0.0f}, {0.0f, -1.0f, -3.0f}};
    for (int g = 0; g < 3; ++g) {
        Grab grab;
        grab.particle = grabbed[g];
        grab.target = targets[g];
        grab.stiffness = 10.0f;
        world.set_grab(grab);
        world.run(5);
    }
    world.set_grab(std::nullopt);

    auto momentum = [&] {
        double P[3] = {0.0, 0.0, 0.0};
        for (std::size_t i = 0; i < n; ++i) {
            const Vec3 v = velocity(world, i);
            P[0] += double(p.particle_mass) * v.x;
            P[1] += double(p.particle_mass) * v.y;
            P[2] += double(p.particle_mass) * v.z;
        }
        return std::vector<double>{P[0], P[1], P[2]};
    };
    double spread = 0.0;  // sum of |m v_i|: the scale rounding errors are relative to
    for (std::size_t i = 0; i < n; ++i) spread += p.particle_mass * length(velocity(world, i));
    const std::vector<double> P0 = momentum();
    const Vec3 com0 = world.center_of_mass();
    const double M = p.particle_mass * double(n);

    // The kick made the velocities differ: relative motion is several times the drift.
    const double drift = std::sqrt(P0[0] * P0[0] + P0[1] * P0[1] + P0[2] * P0[2]) / M;
    double relative = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 v = velocity(world, i);
        relative = std::max(relative, std::sqrt(std::pow(v.x - P0[0] / M, 2) + std::pow(v.y - P0[1] / M, 2) +
                                                std::pow(v.z - P0[2] / M, 2)));
    }
    ASSERT_GT(relative, 0.5);
    ASSERT_GT(drift, 0.1);

    const int ticks = 1000;
    for (int t = 1; t <= ticks; ++t) {
        world.tick();
        const std::vector<double> P = momentum();
        for (int axis = 0; axis < 3; ++axis) {
            // Each step rounds every velocity (by up to 6e-8 of it) and every force sum. These
            // roundings are not systematic: after N T of them (N = 40 particles, T = 1000
            // steps) the sum has wandered by about sqrt(N T) * 6e-8 * |m v| = 3e-7 * sum |m v|
            // (measured: 1e-7). 1e-5 * sum |m v| leaves a wide margin; a spring or damper that
            // pushed one end 1% harder than it pulled the other breaks it within a tick.
            ASSERT_NEAR(P[std::size_t(axis)], P0[std::size_t(axis)], 1e-5 * spread) << "axis " << axis << ", tick " << t;
        }
    }
    ASSERT_EQ(world.status(), Status::Ok);
    // The centre of mass has moved by P t / M (Verlet's positions follow the Euler velocities).
    const double t = ticks * double(p.dt);
    const Vec3 com = world.center_of_mass();
    // Positions of up to 10 m (ulp 1e-6 m), rounded every step: a few ulps in all (measured:
    // under 1e-6 m). 1e-4 m holds that; the motion itself is drift * t > 2 m.
    EXPECT_NEAR(com.x, com0.x + P0[0] / M * t, 1e-4);
    EXPECT_NEAR(com.y, com0.y + P0[1] / M * t, 1e-4);
    EXPECT_NEAR(com.z, com0.z + P0[2] / M * t, 1e-4);
}

// Energy with nothing to dissipate it (c = 0, no drag, no ground).
//
// One spring first, where everything is closed-form: the hanging mass of spring_test.cpp,
// m = 2 kg, k = 50 N/m, released at rest from the unstretched length, so its oscillation
// energy E_osc = 1/2 k (m g / k)^2 = 3.85 J (the total minus its value at rest at the
// equilibrium). With w = omega u (u: displacement from equilibrium), symplectic Euler keeps
//     Q = w^2 + v^2 - h omega w v
// exactly, so the measured energy E = m/2 (w^2 + v^2) differs from its start by
// m/2 h omega w v, at most E_osc h omega / (2 - h omega) (where w = v on the ellipse Q): it
// oscillates by that much, for ever, and never drifts. Explicit Euler instead multiplies
// w^2 + v^2 by exactly 1 + (h omega)^2 every step.
struct Oscillator {
    double m = 2.0, k = 50.0, g = 9.81, L = 1.0, h = 0.02;
    double omega() const { return std::sqrt(k / m); }
    double E_osc0() const { return 0.5 * k * (m * g / k) * (m * g / k); }
    // Total energy at rest at the equilibrium: gravity -m g (L + s_eq) plus 1/2 k s_eq^2.
    double E_rest() const { return -m * g * L - 0.5 * (m * g) * (m * g) / k; }
};

World oscillator_world(Integrator integrator, const Oscillator& o) {
    FlatKeys p = bare_params();
    p.particle_mass = float(o.m);
    p.stiffness = float(o.k);
    p.gravity = {0.0f, 0.0f, float(-o.g)};
    p.pinned = {0};
    p.integrator = integrator;
    return World(one_body(p, points({{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -float(o.L)}})));
}

TEST(Energy, OneSpringOscillatesByTheShadowBoundAndNeverDrifts) {
    const Oscillator o;
    const double hw = o.h * o.omega();  // 0.1
    const double bound = o.E_osc0() * hw / (2.0 - hw);  // 0.203 J
    for (Integrator integrator : {Integrator::Verlet, Integrator::SymplecticEuler}) {
        World world = oscillator_world(integrator, o);
        const double E0 = world.energy().total();
        // The start is at rest at the top of the swing.
        EXPECT_NEAR(E0 - o.E_rest(), o.E_osc0(), 1e-5 * o.E_osc0());
        const int period = 63;  // ticks: 2 pi / (omega h) = 62.8
        double first = 0.0, last = 0.0;
        const int ticks = 1000 * period;  // a thousand periods
        for (int n = 1; n <= ticks; ++n) {
            world.tick();
            const double deviation = std::abs(world.energy().total() - E0);
            if (n <= 10 * period) first = std::max(first, deviation);
            if (n > ticks - 10 * period) last = std::max(last, deviation);
        }
        ASSERT_EQ(world.status(), Status::Ok);
        // Over the first ten periods and over the last ten, the largest deviation is the bound:
        // sampling 63 times a period finds the peak to 0.1%, and float rounding of energies of
        // ~30 J adds ~1e-5 J. 1% covers both; a drift of a thousandth of E_osc per period would
        // add 4 J by the end.
        EXPECT_NEAR(first, bound, 0.01 * bound) << to_string(integrator);
        EXPECT_NEAR(last, bound, 0.01 * bound) << to_string(integrator);
    }
}

TEST(Energy, ExplicitEulerMultipliesOneSpringsEnergyBy1PlusHOmegaSquared) {
    const Oscillator o;
    const double hw = o.h * o.omega();
    World world = oscillator_world(Integrator::ExplicitEuler, o);
    for (int n = 1; n <= 300; ++n) {
        world.tick();
        const double E_osc = world.energy().total() - o.E_rest();
        const double expected = o.E_osc0() * std::pow(1.0 + hw * hw, n);  // 19.8 E_osc0 at n = 300
        // Exact in exact arithmetic; float positions and velocities (relative 6e-8 each step,
        // growing with the energy) keep it within 1e-4 relative over 300 steps.
        ASSERT_NEAR(E_osc, expected, 1e-4 * expected) << "tick " << n;
    }
    ASSERT_EQ(world.status(), Status::Ok);
}

// Then a body of many springs: a cube hanging from one pinned corner swings and stretches under
// gravity (7 free particles, 28 springs, motions from a slow swing to omega ~ 9 rad/s). Each
// mode's energy error is at most h omega / (2 - h omega) of its energy, as for the one spring:
// 5% at omega = 5 rad/s, 10% at the fastest, which carry little of it. The measured total stays
// within 5% of the energy in play (the largest kinetic plus the largest elastic energy seen,
// about 440 J here), for as long as it runs.
FlatKeys swinging_cube_params(Integrator integrator) {
    FlatKeys p = listing8_params();
    p.damping = 0.0f;
    p.drag_coefficient = 0.0f;
    p.ground = false;
    p.init_height = 0.0f;
    p.pinned = {0};
    p.initial_velocity = {1.0f, 0.0f, 0.0f};
    p.integrator = integrator;
    return p;
}

TEST(Energy, ManySpringsStayBoundedUnderVerletAndSymplecticEuler) {
    for (Integrator integrator : {Integrator::Verlet, Integrator::SymplecticEuler}) {
        OneBodyWorld world(swinging_cube_params(integrator), points(cube_corners()));
        const double E0 = world.energy().total();
        const int ticks = 50000, window = 10000;  // 1000 s: hundreds of swings
        double worst = 0.0, in_play = 0.0, kinetic = 0.0, elastic = 0.0, first_mean = 0.0, last_mean = 0.0;
        for (int n = 1; n <= ticks; ++n) {
            world.tick();
            const Energy e = world.energy();
            worst = std::max(worst, std::abs(e.total() - E0));
            kinetic = std::max(kinetic, e.kinetic);
            elastic = std::max(elastic, e.elastic);
            if (n <= window) first_mean += (e.total() - E0) / window;
            if (n > ticks - window) last_mean += (e.total() - E0) / window;
        }
        ASSERT_EQ(world.status(), Status::Ok);
        in_play = kinetic + elastic;
        ASSERT_GT(in_play, 100.0);  // it really swung and stretched
        EXPECT_LT(worst, 0.05 * in_play) << to_string(integrator);
        // No drift: the mean over the last 200 s matches the mean over the first 200 s. The
        // means of a bounded, irregular oscillation wander by a fraction of its size; 2% of
        // the energy in play (9 J) allows that, while explicit Euler gains that much within
        // 60 ticks here.
        EXPECT_NEAR(last_mean, first_mean, 0.02 * in_play) << to_string(integrator);
    }
}

TEST(Energy, ExplicitEulerGainsEnergyUntilStopped) {
    OneBodyWorld world(swinging_cube_params(Integrator::ExplicitEuler), points(cube_corners()));
    const double E0 = world.energy().total();
    world.run(300);
    ASSERT_EQ(world.status(), Status::Ok);
    // Every mode grows by sqrt(1 + (h omega)^2) a step: over 6 s the cube gains more energy
    // than it had in play (hundreds of joules; the symplectic schemes stay within 22 J).
    EXPECT_GT(world.energy().total() - E0, 100.0);
    // Left running, it grows without bound, and the divergence check stops it and says why.
    world.run(2000);
    EXPECT_EQ(world.status(), Status::Diverged);
    EXPECT_NE(world.divergence().find("explicit_euler"), std::string::npos) << world.divergence();
    EXPECT_TRUE(all_finite(world));
}

}  // namespace
}  // namespace softbody::test
