// The fast pair kernel (every tile variant this CPU runs) against pair_forces_reference.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "kernel_support.h"
#include "physics/error.h"
#include "physics/mesh.h"
#include "physics/pair_forces.h"
#include "physics/thread_pool.h"
#include "../physics/one_body_world.h"
#include "physics/world.h"

namespace softbody::test {
namespace {

std::string describe(PairKernelVariant variant, int threads, std::size_t n) {
    return std::string(PairForceKernel::name(variant)) + ", " + std::to_string(threads) + " threads, N = " +
           std::to_string(n);
}

void expect_matches_reference(const PairState& s, const std::string& what) {
    Vec3Array expected;
    pair_forces_reference(s.input(), expected);
    const std::vector<double> scale = force_scales(s);
    for (PairKernelVariant variant : variants_here()) {
        for (int threads : {1, 2}) {
            ThreadPool pool(threads);
            PairForceKernel kernel(pool, variant);
            ASSERT_STREQ(kernel.variant(), PairForceKernel::name(variant));
            Vec3Array f;
            kernel.compute(s.input(), f);
            ASSERT_EQ(f.size(), s.size());
            EXPECT_LE(worst_relative_difference(scale, f, expected), kRelativeTolerance)
                << what << ", " << describe(variant, threads, s.size());
        }
    }
}

// Sizes around every edge of the tiling: 1 to 3 particles, either side of the 8- and 16-wide
// SIMD vectors and of the 256-particle blocks, a few blocks with a ragged last one, and either
// side of kLargeBody, where the blocks become 512 particles (2,600: five whole and a ragged one).
TEST(PairKernel, MatchesReferenceOnRandomClouds) {
    static_assert(PairForceKernel::kLargeBody == 2048);
    for (std::size_t n : {1, 2, 3, 5, 7, 8, 9, 15, 16, 17, 31, 100, 255, 256, 257, 300, 511, 512, 513, 1000, 1025, 1337,
                          2047, 2048, 2600}) {
        expect_matches_reference(deformed(random_cloud(n, 7u + n), 100u + n), "random cloud");
    }
}

TEST(PairKernel, MatchesReferenceFarFromRest) {
    // Strongly stretched and squashed: l far from l0, large relative speeds.
    PairState s = deformed(random_cloud(700, 3u), 4u, 0.8f);
    for (std::size_t i = 0; i < s.size(); ++i) s.v.set(i, s.v[i] * 20.0f);
    expect_matches_reference(s, "far from rest");
}

TEST(PairKernel, MatchesReferenceOnMeshes) {
    const Mesh t = torus(48, 20);  // 960 particles
    ASSERT_EQ(t.particle_count(), 960u);
    expect_matches_reference(deformed(t.positions, 11u, 0.02f), "torus mesh");
    const Mesh cube = load_mesh(std::string(SOFTBODY_ASSETS_DIR) + "/meshes/cube.obj");
    expect_matches_reference(deformed(cube.positions, 12u, 0.1f), "cube.obj");
}

TEST(PairKernel, TwoParticlesClosedForm) {
    // Rest length 1, stretched to 1.5 along x, closing at 2 m/s along x:
    // spring k (l - l0) = 10 * 0.5 = 5 N toward each other; damper c (v_j - v_i).d_hat = 0.1 * -2
    // = -0.2 N, i.e. 0.2 N pushing them apart. Net on particle 0: +4.8 N along x.
    PairState s;
    s.x.resize(2);
    s.v.resize(2);
    s.r.resize(2);
    s.r.set(1, {1.0f, 0.0f, 0.0f});
    s.x.set(1, {1.5f, 0.0f, 0.0f});
    s.v.set(1, {-2.0f, 0.0f, 0.0f});
    for (PairKernelVariant variant : variants_here()) {
        ThreadPool pool(1);
        PairForceKernel kernel(pool, variant);
        Vec3Array f;
        kernel.compute(s.input(), f);
        EXPECT_NEAR(f.x[0], 4.8f, 4.8f * 1e-6f) << PairForceKernel::name(variant);
        EXPECT_EQ(f.x[1], -f.x[0]) << "Newton's third law, " << PairForceKernel::name(variant);
        EXPECT_EQ(f.y[0], 0.0f);
        EXPECT_EQ(f.z[1], 0.0f);
    }
}

TEST(PairKernel, CoincidentParticlesGiveNoForceAndNoNaN) {
    // Duplicates at exactly the same position (with different rest positions, so their rest
    // length is not zero), in a cloud whose size leaves ragged vectors and blocks.
    PairState s = deformed(random_cloud(300, 21u), 22u);
    for (std::size_t i = 0; i < 300; i += 7) s.x.set(i + 1 < 300 ? i + 1 : i, s.x[i]);  // pairs (i, i+1) coincide
    Vec3Array expected;
    pair_forces_reference(s.input(), expected);
    for (PairKernelVariant variant : variants_here()) {
        ThreadPool pool(2);
        PairForceKernel kernel(pool, variant);
        Vec3Array f;
        kernel.compute(s.input(), f);
        for (std::size_t i = 0; i < s.size(); ++i) {
            ASSERT_TRUE(is_finite(f[i])) << "particle " << i << ", " << PairForceKernel::name(variant);
        }
        EXPECT_LE(worst_relative_difference(force_scales(s), f, expected), kRelativeTolerance)
            << PairForceKernel::name(variant);
    }

    // Everything at one point: no pair has a direction, so no force at all.
    for (std::size_t n : {2, 17, 260}) {
        PairState same = deformed(random_cloud(n, 23u), 24u);
        for (std::size_t i = 0; i < n; ++i) same.x.set(i, {0.25f, -1.0f, 3.0f});
        for (PairKernelVariant variant : variants_here()) {
            ThreadPool pool(1);
            PairForceKernel kernel(pool, variant);
            Vec3Array f;
            kernel.compute(same.input(), f);
            for (std::size_t i = 0; i < n; ++i) {
                ASSERT_EQ(f[i], Vec3{}) << "particle " << i << " of " << n << ", " << PairForceKernel::name(variant);
            }
        }
    }
}

TEST(PairKernel, BitIdenticalAcrossRunsAndThreadCounts) {
    for (std::size_t n : {3, 257, 1100, 2000, 2600}) {  // 2,600: blocks of 512
        const PairState s = deformed(random_cloud(n, 31u), 32u);
        for (PairKernelVariant variant : variants_here()) {
            ThreadPool one(1);
            PairForceKernel kernel(one, variant);
            Vec3Array first, again;
            kernel.compute(s.input(), first);
            kernel.compute(s.input(), again);
            EXPECT_TRUE(same_bits(first, again)) << "run to run, " << describe(variant, 1, n);
            for (int threads : {2, 3}) {
                ThreadPool pool(threads);
                PairForceKernel parallel(pool, variant);
                Vec3Array f;
                parallel.compute(s.input(), f);
                EXPECT_TRUE(same_bits(first, f)) << describe(variant, threads, n);
            }
        }
    }
}

TEST(PairKernel, ElasticEnergyMatchesReference) {
    const PairState s = deformed(random_cloud(600, 41u), 42u, 0.1f);
    const double expected = elastic_energy_reference(s.input());
    ASSERT_GT(expected, 0.0);
    // Each stretch l - l0 is a difference of two float lengths: both kernels round it to within
    // about 2 units of 2^-24 of (l + l0), so a term 1/2 k (l - l0)^2 may differ by up to about
    // k |l - l0| (l + l0) 2^-23 between them.
    double bound = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        for (std::size_t j = i + 1; j < s.size(); ++j) {
            const double l = length(s.x[j] - s.x[i]), l0 = length(s.r[j] - s.r[i]);
            bound += double(s.k) * std::abs(l - l0) * (l + l0) * std::ldexp(1.0, -23);
        }
    }
    for (PairKernelVariant variant : variants_here()) {
        for (int threads : {1, 2}) {
            ThreadPool pool(threads);
            PairForceKernel kernel(pool, variant);
            const double energy = kernel.elastic_energy(s.input());
            EXPECT_NEAR(energy, expected, bound) << describe(variant, threads, s.size());
            EXPECT_EQ(energy, kernel.elastic_energy(s.input()));  // run to run
        }
    }
}

TEST(PairKernel, VariantsReportWhatTheyRun) {
    EXPECT_TRUE(PairForceKernel::supported(PairKernelVariant::Scalar));
    EXPECT_TRUE(PairForceKernel::supported(PairForceKernel::best_variant()));
    ThreadPool pool(1);
    EXPECT_STREQ(PairForceKernel(pool).variant(), PairForceKernel::name(PairForceKernel::best_variant()));
    EXPECT_STREQ(PairForceKernel(pool, PairKernelVariant::Scalar).variant(), "scalar");
    // Asking for a variant the CPU lacks gives the best one it has, never a crash.
    for (auto v : {PairKernelVariant::Avx2, PairKernelVariant::Avx512, PairKernelVariant::WasmSimd128}) {
        PairForceKernel kernel(pool, v);
        EXPECT_TRUE(PairForceKernel::supported(kernel.variant_id()));
    }
}

// SOFTBODY_KERNEL names the tile instead of the widest (pair_forces.h): portable is how a native
// build does the browser build's float operations. A name that is no tile, or a tile this
// build cannot run (the browser's, here), is one line naming the variable.
TEST(PairKernel, EnvironmentNamesTheTile) {
    struct Unset {
        ~Unset() { ::unsetenv("SOFTBODY_KERNEL"); }
    } unset;
    ThreadPool pool(1);
    ::setenv("SOFTBODY_KERNEL", "portable", 1);
    EXPECT_STREQ(PairForceKernel(pool).variant(), "scalar");
    EXPECT_EQ(PairForceKernel::best_variant(), PairKernelVariant::Scalar);
    ::setenv("SOFTBODY_KERNEL", "simd128", 1);
    EXPECT_THROW(PairForceKernel{pool}, InputError);
    ::setenv("SOFTBODY_KERNEL", "fastest", 1);
    try {
        PairForceKernel kernel(pool);
        ADD_FAILURE() << "accepted SOFTBODY_KERNEL=fastest";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "SOFTBODY_KERNEL: 'fastest' is not a tile (portable, avx2, avx512, simd128 or auto)");
    }
    ::setenv("SOFTBODY_KERNEL", "auto", 1);
    EXPECT_STREQ(PairForceKernel(pool).variant(), PairForceKernel::name(PairForceKernel::best_variant()));
    ::unsetenv("SOFTBODY_KERNEL");
    EXPECT_NE(PairForceKernel::best_variant(), PairKernelVariant::WasmSimd128);  // not in a native build
}

// The whole World with the fast kernel follows the reference kernel: a torus falling freely
// for 10 ticks (before it reaches the ground) stays within float rounding of it.
TEST(PairKernel, WorldFollowsReferenceKernel) {
    FlatKeys params;
    params.auto_substeps = true;
    OneBodyWorld fast(params, torus(40, 16), WorldOptions{2, false});
    OneBodyWorld reference(params, torus(40, 16), WorldOptions{1, true});
    fast.run(10);
    reference.run(10);
    ASSERT_EQ(fast.status(), Status::Ok);
    ASSERT_EQ(reference.status(), Status::Ok);
    float worst = 0.0f;
    for (std::size_t i = 0; i < fast.soft_body(0).particle_count(); ++i) {
        worst = std::max(worst, length(fast.soft_body(0).x[i] - reference.soft_body(0).x[i]));
    }
    // Positions near 2 m after 10 ticks: 1e-5 m is about 40 float roundings of them.
    EXPECT_LT(worst, 1e-5f);
}

}  // namespace
}  // namespace softbody::test
