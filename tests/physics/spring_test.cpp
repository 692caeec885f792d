// One spring (Eq. 21) and one damper (Eq. 22): a mass hanging from a pinned particle.
//
// Particle 0 is pinned at the origin, particle 1 hangs L below it, so the spring's rest length
// is L and it starts unstretched and at rest. With the other end pinned the reduced mass is m,
// and along z the free particle obeys exactly (the spring stays vertical, so it is linear):
//     m u'' = -k u - c u',   u = z_1 - z_eq,   z_eq = -L - m g / k
// starting from u(0) = +m g / k, u'(0) = 0.
//
// For the default integrator (Verlet positions + Euler velocities, identical to symplectic
// Euler on a linear system) one step maps (u, v) by
//     A = [[1 - h^2 w2, h (1 - h gamma)], [-h w2, 1 - h gamma]],  w2 = k/m,  gamma = c/m,
// whose eigenvalues have |lambda|^2 = det A = 1 - h gamma and, for c = 0, phase theta with
// cos theta = 1 - h^2 w2 / 2. These give the scheme's exact period and decay; the continuous
// answers differ from them by O((h omega)^2), which sets the loose tolerances below.
#include <cmath>
#include <vector>

#include "test_support.h"

namespace softbody::test {
namespace {

constexpr float kL = 1.0f;  // m, rest length

FlatKeys hanging_params(float m, float k, float c) {
    FlatKeys p = bare_params();
    p.particle_mass = m;
    p.stiffness = k;
    p.damping = c;
    p.gravity = {0.0f, 0.0f, -9.81f};
    p.pinned = {0};
    return p;
}

Mesh hanging_mesh() { return points({{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -kL}}, "hanging mass"); }

// u(t) = z_1 - z_eq at every tick, t = n dt.
std::vector<double> displacement(World& world, int ticks, double z_eq) {
    std::vector<double> u;
    u.push_back(double(position(world, 1).z) - z_eq);
    for (int n = 0; n < ticks; ++n) {
        world.tick();
        u.push_back(double(position(world, 1).z) - z_eq);
    }
    return u;
}

TEST(HangingMass, RestsAtStretchMgOverK) {
    // Two (m, k) pairs, so swapping m and k, or dropping g, cannot pass by luck.
    for (const auto& [m, k] : {std::pair{2.0f, 50.0f}, std::pair{0.5f, 20.0f}}) {
        // c = 2 kg/s: decay rate c/(2m) >= 0.5 /s, so after 40 s the start-up oscillation of
        // amplitude m g / k < 0.4 m has shrunk by e^-20 (below 1e-9 m).
        OneBodyWorld world(hanging_params(m, k, 2.0f), hanging_mesh());
        world.run(2000);
        ASSERT_EQ(world.status(), Status::Ok);
        const double stretch = -double(position(world, 1).z) - kL;
        // At rest a = 0, so the step leaves the state alone: the discrete equilibrium is the
        // exact one. What remains is float rounding of a position near 1.4 m (ulp 1.2e-7 m)
        // and of the spring force's l - l0: 1e-5 m is far above that and far below m g / k.
        EXPECT_NEAR(stretch, m * 9.81 / k, 1e-5) << "m = " << m << ", k = " << k;
        // The pinned particle never moves.
        EXPECT_EQ(position(world, 0).z, 0.0f);
        EXPECT_EQ(velocity(world, 0).z, 0.0f);
        // And the motion stays on the z axis.
        EXPECT_EQ(position(world, 1).x, 0.0f);
        EXPECT_EQ(position(world, 1).y, 0.0f);
    }
}

TEST(HangingMass, PeriodIsTwoPiSqrtMOverK) {
    const double m = 2.0, k = 50.0, g = 9.81, h = 0.02;
    OneBodyWorld world(hanging_params(float(m), float(k), 0.0f), hanging_mesh());
    const double z_eq = -kL - m * g / k;
    const int ticks = 1300;  // about 20 periods of 1.2566 s
    const std::vector<double> u = displacement(world, ticks, z_eq);
    ASSERT_EQ(world.status(), Status::Ok);

    // Upward zero crossings of u, placed by linear interpolation between ticks. Near a zero
    // crossing u is a sine at its steepest, with no curvature, so the interpolation error is
    // O((h omega)^3) of a step: negligible here.
    std::vector<double> crossings;
    for (std::size_t n = 0; n + 1 < u.size(); ++n) {
        if (u[n] < 0.0 && u[n + 1] >= 0.0) crossings.push_back(h * (double(n) + u[n] / (u[n] - u[n + 1])));
    }
    ASSERT_GE(crossings.size(), 15u);
    const double period = (crossings.back() - crossings.front()) / double(crossings.size() - 1);

    const double omega = std::sqrt(k / m);
    const double continuous = 2.0 * kPi / omega;  // 2 pi sqrt(m/k) = 1.2566 s
    const double theta = std::acos(1.0 - h * h * omega * omega / 2.0);
    const double discrete = 2.0 * kPi * h / theta;  // the scheme's own period
    // Against the scheme's period: only float rounding and interpolation remain; 1e-5
    // relative (13 microseconds) holds them with room.
    EXPECT_NEAR(period, discrete, 1e-5 * discrete);
    // Against 2 pi sqrt(m/k): the scheme runs slow by (h omega)^2 / 24 = 4.2e-4 relative (h omega
    // = 0.1); 1e-3 allows that and nothing like a wrong m, k or factor of 2.
    EXPECT_NEAR(period, continuous, 1e-3 * continuous);

    // Without a damper the oscillation keeps its size. The scheme conserves
    // Q = w^2 + v^2 - h omega w v exactly (w = omega u; see integrator_test.cpp), which puts the
    // extremes of u at +-A / sqrt(1 - (h omega)^2 / 4) = +-1.00125 A, A = m g / k, centred on
    // z_eq: a wrong equilibrium would shift them, a wrong energy balance would grow them. Ticks
    // sample each peak to within 1 - cos(h omega / 2) = 0.125%: 0.13% holds that.
    double u_max = 0.0, u_min = 0.0;
    for (double value : u) {
        u_max = std::max(u_max, value);
        u_min = std::min(u_min, value);
    }
    const double peak = m * g / k / std::sqrt(1.0 - h * h * omega * omega / 4.0);
    EXPECT_NEAR(u_max, peak, 1.3e-3 * peak);
    EXPECT_NEAR(u_min, -peak, 1.3e-3 * peak);
}

TEST(HangingMass, DamperDecaysAsExpOfMinusCtOver2m) {
    const double m = 2.0, k = 50.0, c = 0.4, g = 9.81, h = 0.02;
    OneBodyWorld world(hanging_params(float(m), float(k), float(c)), hanging_mesh());
    const double z_eq = -kL - m * g / k;
    const std::vector<double> u = displacement(world, 900, z_eq);  // 18 s: e^-1.8 of the start
    ASSERT_EQ(world.status(), Status::Ok);

    // Peaks (local maxima) of u, refined by a parabola through the three ticks around each.
    struct Peak {
        double t, amplitude;
    };
    std::vector<Peak> peaks;
    for (std::size_t n = 1; n + 1 < u.size(); ++n) {
        if (u[n] > u[n - 1] && u[n] >= u[n + 1]) {
            const double a = u[n - 1], b = u[n], d = u[n + 1];
            const double offset = 0.5 * (a - d) / (a - 2.0 * b + d);  // in ticks, within [-0.5, 0.5]
            peaks.push_back({h * (double(n) + offset), b - 0.25 * (a - d) * offset});
        }
    }
    ASSERT_GE(peaks.size(), 10u);

    const double gamma = c / m;
    for (std::size_t p = 1; p < peaks.size(); ++p) {
        const double t = peaks[p].t - peaks[0].t;
        const double ratio = peaks[p].amplitude / peaks[0].amplitude;
        // The scheme multiplies the amplitude by sqrt(det A) = sqrt(1 - h gamma) per step.
        const double discrete = std::pow(1.0 - h * gamma, t / h / 2.0);
        // The continuous envelope: exp(-c t / (2 m)), reduced mass m (the other end is pinned).
        const double continuous = std::exp(-c * t / (2.0 * m));
        // A parabola through three samples of a sine 0.1 rad apart finds its peak to about
        // (h omega)^4 / 100 = 1e-6 relative, and positions near 1.4 m carry float noise of
        // 1e-7 m, 2e-6 of the smallest amplitude (0.065 m): 5e-5 holds both (measured 4e-6).
        EXPECT_NEAR(ratio, discrete, 5e-5) << "peak " << p << " at t = " << t;
        // ln sqrt(1 - x) = -x/2 - x^2/4 - ...: the scheme decays faster than exp(-x/2) by
        // x^2/4 = 4e-6 per step (x = h gamma = 0.004), 3.6e-3 relative over 900 steps. 1e-2
        // relative holds that; the wrong rate c/m (or c/(4m)) would miss by 50% or more.
        EXPECT_NEAR(ratio, continuous, 1e-2 * continuous) << "peak " << p << " at t = " << t;
    }
}

}  // namespace
}  // namespace softbody::test
