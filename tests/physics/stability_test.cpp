// The stability estimate (see physics/README.md#stability) and divergence detection.
//
// Linearised about the rest shape, the all-pairs springs have stiffness k G with
//     G = sum over pairs (e_i - e_j)(e_i - e_j)^T (x) d_hat d_hat^T     (3N x 3N),
// and the fastest mode has omega^2 = k lambda_max(M^-1 G). For equal masses World states
// lambda_max = N / m. Here that claim is checked against a brute-force computation: G built
// densely from the rest positions, and power iteration on M^-1 G.
#include <cmath>
#include <random>
#include <vector>

#include "test_support.h"

namespace softbody::test {
namespace {

// Dense M^-1 G for the free particles only (pinned ones have 1/m = 0: their rows vanish, and
// their columns multiply coordinates that never move). Row-major, size 3F x 3F.
struct Dense {
    std::size_t n = 0;
    std::vector<double> a;
    double& at(std::size_t r, std::size_t c) { return a[r * n + c]; }
};

Dense mass_weighted_G(const World& world) {
    const std::size_t N = world.soft_body(0).particle_count();
    std::vector<std::size_t> free_index(N, SIZE_MAX);
    std::size_t F = 0;
    for (std::size_t i = 0; i < N; ++i) {
        if (world.soft_body(0).inv_mass[i] != 0.0f) free_index[i] = F++;
    }
    Dense A;
    A.n = 3 * F;
    A.a.assign(A.n * A.n, 0.0);
    const Vec3Array& r = world.soft_body(0).rest;
    for (std::size_t i = 0; i < N; ++i) {
        for (std::size_t j = i + 1; j < N; ++j) {
            double d[3] = {double(r.x[j]) - r.x[i], double(r.y[j]) - r.y[i], double(r.z[j]) - r.z[i]};
            const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (double& component : d) component /= l;
            // The pair's block: +P on (i,i) and (j,j), -P on (i,j) and (j,i), P = d_hat d_hat^T.
            for (int p = 0; p < 3; ++p) {
                for (int q = 0; q < 3; ++q) {
                    const double P = d[p] * d[q];
                    const std::size_t fi = free_index[i], fj = free_index[j];
                    if (fi != SIZE_MAX) A.at(3 * fi + std::size_t(p), 3 * fi + std::size_t(q)) += P;
                    if (fj != SIZE_MAX) A.at(3 * fj + std::size_t(p), 3 * fj + std::size_t(q)) += P;
                    if (fi != SIZE_MAX && fj != SIZE_MAX) {
                        A.at(3 * fi + std::size_t(p), 3 * fj + std::size_t(q)) -= P;
                        A.at(3 * fj + std::size_t(p), 3 * fi + std::size_t(q)) -= P;
                    }
                }
            }
        }
    }
    // Equal masses: M^-1 G = G / m, still symmetric.
    const double inv_m = 1.0 / double(world.soft_body(0).def.particle_mass);
    for (double& value : A.a) value *= inv_m;
    return A;
}

// Largest eigenvalue of a symmetric positive semi-definite matrix by power iteration, with the
// residual |A v - lambda v| / lambda that certifies it (for a symmetric matrix an eigenvalue
// lies within the residual of lambda).
std::pair<double, double> power_iteration(Dense& A) {
    std::mt19937 rng(5);
    std::normal_distribution<double> normal;
    std::vector<double> v(A.n), w(A.n);
    for (double& value : v) value = normal(rng);
    double lambda = 0.0;
    auto multiply = [&] {
        for (std::size_t r = 0; r < A.n; ++r) {
            double sum = 0.0;
            for (std::size_t c = 0; c < A.n; ++c) sum += A.at(r, c) * v[c];
            w[r] = sum;
        }
    };
    for (int iteration = 0; iteration < 20000; ++iteration) {
        double norm = 0.0;
        for (double value : v) norm += value * value;
        norm = std::sqrt(norm);
        for (double& value : v) value /= norm;
        multiply();
        lambda = 0.0;  // Rayleigh quotient v^T A v with |v| = 1
        for (std::size_t r = 0; r < A.n; ++r) lambda += v[r] * w[r];
        v.swap(w);
    }
    double norm = 0.0;
    for (double value : v) norm += value * value;
    norm = std::sqrt(norm);
    for (double& value : v) value /= norm;
    multiply();
    lambda = 0.0;
    for (std::size_t r = 0; r < A.n; ++r) lambda += v[r] * w[r];
    double residual = 0.0;
    for (std::size_t r = 0; r < A.n; ++r) residual += (w[r] - lambda * v[r]) * (w[r] - lambda * v[r]);
    return {lambda, std::sqrt(residual) / lambda};
}

FlatKeys cloud_params(float m, std::vector<std::uint32_t> pinned) {
    FlatKeys p = listing8_params();
    p.particle_mass = m;
    p.pinned = std::move(pinned);
    return p;
}

TEST(Stability, LambdaMaxIsNOverMForEqualMasses) {
    for (const float m : {1.0f, 0.25f}) {
        const std::size_t N = 20;
        OneBodyWorld world(cloud_params(m, {}), points(random_cloud(N, 3)));
        Dense A = mass_weighted_G(world);
        const auto [lambda, residual] = power_iteration(A);
        // Power iteration converged to an eigenvalue: the residual bounds its error.
        ASSERT_LT(residual, 1e-9);
        const double claimed = double(N) / m;
        // The rest positions are floats; d_hat computed from them in double is exact to 1e-7,
        // so lambda is N/m to about 1e-7 relative: 1e-6.
        EXPECT_NEAR(lambda, claimed, 1e-6 * claimed) << "m = " << m;
        // And World reports it: omega_max^2 = k lambda_max, gamma_max = c lambda_max.
        const Stability s = world.stability();
        const FlatKeys& p = flat_keys(world);
        EXPECT_NEAR(s.omega_max * s.omega_max, p.stiffness * lambda, 1e-6 * p.stiffness * lambda);
        EXPECT_NEAR(s.gamma_max, p.damping * lambda, 1e-6 * p.damping * lambda);
    }
}

TEST(Stability, EstimateBoundsTheFastestModeWithPins) {
    const std::size_t N = 20;
    for (const std::vector<std::uint32_t>& pinned :
         {std::vector<std::uint32_t>{0}, std::vector<std::uint32_t>{0, 7}, std::vector<std::uint32_t>{1, 2, 3, 4, 5}}) {
        OneBodyWorld world(cloud_params(1.0f, pinned), points(random_cloud(N, 3)));
        Dense A = mass_weighted_G(world);
        const auto [lambda, residual] = power_iteration(A);
        ASSERT_LT(residual, 1e-9);
        const Stability s = world.stability();
        const double estimate = s.omega_max * s.omega_max / world.soft_body(0).def.stiffness;
        // Pinning removes rows and columns of the symmetric G / m: by Cauchy interlacing its
        // largest eigenvalue cannot rise, so N/m bounds it (1e-9 for rounding).
        EXPECT_LE(lambda, estimate * (1.0 + 1e-9)) << pinned.size() << " pinned";
        // ...and the bound is not wildly pessimistic: a handful of pins out of 20 particles
        // keeps a near-uniform expansion of the free ones, within a fifth of N/m.
        EXPECT_GT(lambda, 0.8 * estimate) << pinned.size() << " pinned";
    }
}

// The bound N (k h^2 + 2 c h) < 4 m: with Listing 8's constants, N < 500.
TEST(Stability, Listing8ConstantsAreStableBelow500Particles) {
    for (const std::size_t N : {490u, 510u}) {
        OneBodyWorld world(listing8_params(), points(random_cloud(N, 17, 2.0f)));
        const Stability s = world.stability();
        // The fastest mode: h omega_eff = sqrt(N (k h^2 + 2 c h)) against the limit 2.
        const double expected = std::sqrt(double(N) * (10.0 * 0.02 * 0.02 + 2.0 * 0.1 * 0.02));
        EXPECT_NEAR(s.h_omega, expected, 1e-6 * expected);
        EXPECT_EQ(s.stable, N < 500) << N << " particles";
        // Two substeps halve h: 510 (k h^2 + 2 c h) = 1.5 < 4, stable with any sensible safety
        // margin; one step is past the limit (510) or too close to it for the margin (490).
        EXPECT_EQ(s.substeps_needed, 2) << N << " particles";
    }
}

// A 600-particle cloud with Listing 8's constants at one substep is past the limit: it must
// blow up, be caught, say why and what to change, and never show a NaN.
TEST(Divergence, DetectedAndExplained) {
    FlatKeys p = listing8_params();
    ASSERT_EQ(p.substeps, 1);
    OneBodyWorld world(p, points(random_cloud(600, 23, 1.5f)));
    ASSERT_FALSE(world.stability().stable);
    int n = 0;
    for (; n < 2000 && world.status() == Status::Ok; ++n) {
        world.tick();
        ASSERT_TRUE(all_finite(world)) << "tick " << n;
    }
    ASSERT_EQ(world.status(), Status::Diverged) << "still running after " << n << " ticks";
    const std::string& why = world.divergence();
    EXPECT_NE(why.find("limit"), std::string::npos) << why;
    EXPECT_NE(why.find("substeps to at least 2"), std::string::npos) << why;  // 2 halve h: 600 (k h^2 + 2 c h) = 1.8 < 4
    // Once diverged, ticks do nothing and the last finite state stays on show.
    const std::uint64_t hash = world.state_hash(), ticks = world.ticks();
    world.run(10);
    EXPECT_EQ(world.state_hash(), hash);
    EXPECT_EQ(world.ticks(), ticks);
    EXPECT_TRUE(all_finite(world));
}

TEST(Divergence, SubstepsItSuggestsKeepTheSameCloudStable) {
    FlatKeys p = listing8_params();
    p.substeps = 2;
    OneBodyWorld world(p, points(random_cloud(600, 23, 1.5f)));
    ASSERT_TRUE(world.stability().stable);
    world.run(250);  // through the landing, which is what set the first run off
    EXPECT_EQ(world.status(), Status::Ok) << world.divergence();
    EXPECT_TRUE(all_finite(world));
    EXPECT_GE(world.min_z(), 0.0f);
}

// Automatic substeps give a step that does not grow, under every integrator, for stiffness and
// damping across the range the sliders give. With damping RK4's (and explicit Euler's) region
// of stability is not a disc: a mode may be stable with the springs 25% stiffer and grow at
// the stiffness itself, and three soft cubes stacked under RK4 (k 60, c 0.5, 98 particles of
// 50 g each) got 6 substeps, grew 2.2% a step and diverged in tick 9.
TEST(Stability, AutomaticSubstepsAreStableAtEveryStiffnessAndDamping) {
    for (Integrator integrator : {Integrator::Verlet, Integrator::SymplecticEuler, Integrator::RK4, Integrator::ExplicitEuler}) {
        for (float k : {2.0f, 15.0f, 60.0f, 300.0f}) {
            for (float c : {0.005f, 0.05f, 0.2f, 0.5f, 2.0f}) {
                FlatKeys p = listing8_params();
                p.integrator = integrator;
                p.auto_substeps = true;
                p.stiffness = k;
                p.damping = c;
                p.particle_mass = 0.05f;
                const OneBodyWorld world(p, points(random_cloud(98, 7, 0.25f)));
                const Stability s = world.stability();
                if (s.substeps_needed == 0) {
                    // None is enough: only explicit Euler's limit c >= h k (whatever the mode)
                    // can ask for more than 1000 substeps, here k 300 with c 0.005.
                    EXPECT_EQ(integrator, Integrator::ExplicitEuler);
                    EXPECT_LT(c, k * p.dt / 1000.0f);
                    continue;
                }
                EXPECT_TRUE(s.stable) << to_string(integrator) << " k " << k << " c " << c << ": " << s.substeps
                                      << " substeps grow " << s.growth << " a step";
            }
        }
    }
}

}  // namespace
}  // namespace softbody::test
