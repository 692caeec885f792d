// What the kernel tests share: random clouds and meshes built in code, and the comparison of
// two force fields with the tolerance every test uses.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "physics/generated.h"
#include "physics/mesh.h"
#include "physics/pair_forces.h"
#include "../physics/test_support.h"  // random_cloud and the other shared helpers

namespace softbody::test {

// A state for the pair loop: positions x, velocities v, rest positions r.
struct PairState {
    Vec3Array x, v, r;
    float k = 10.0f, c = 0.1f;
    std::size_t size() const { return x.size(); }
    PairInput input() const {
        return {x.x.data(), x.y.data(), x.z.data(), v.x.data(), v.y.data(), v.z.data(),
                r.x.data(), r.y.data(), r.z.data(), x.size(), k, c};
    }
};

// Rest positions from `rest`; positions moved from them by up to `stretch` (m) on each axis,
// velocities up to 1 m/s on each axis, all from a fixed seed.
inline PairState deformed(const std::vector<Vec3>& rest, std::uint32_t seed, float stretch = 0.05f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    PairState s;
    const std::size_t n = rest.size();
    s.x.resize(n);
    s.v.resize(n);
    s.r.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        s.r.set(i, rest[i]);
        s.x.set(i, rest[i] + stretch * Vec3{u(rng), u(rng), u(rng)});
        s.v.set(i, {u(rng), u(rng), u(rng)});
    }
    return s;
}

// A closed torus of rings x segments vertices, welded and indexed as load_mesh gives it: the
// shared generator's (physics/generated.h), the body `softbody bench` and the app know too.
inline Mesh torus(int rings, int segments) {
    return generated_mesh("torus:" + std::to_string(rings) + "x" + std::to_string(segments));
}

// Tolerance of the fast kernel against the reference, relative to the scale of particle i's
// sum, S_i = sum over j of (k (l_ij + l0_ij) + c |v_j - v_i|): the sum of the magnitudes of
// what enters its pair terms. Both kernels round each pair term to a few units of float
// precision (2^-24 = 6e-8) of that scale (the fast one also takes 1/l from an approximate
// inverse square root refined once, relative error about 4e-7 with AVX2) and add the terms
// in different orders. The worst seen is about 5e-8 S_i; 1e-6 S_i leaves a wide margin for
// rounding, yet is far below what one wrong, missing or doubled pair would leave (about
// S_i / N, 1e-4 at N = 10,000), so any mistake in the pairs or formulas fails.
inline constexpr double kRelativeTolerance = 1e-6;

inline std::vector<double> force_scales(const PairState& s) {
    const std::size_t n = s.size();
    std::vector<double> scale(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = i + 1; j < n; ++j) {
            const double term = double(s.k) * (double(length(s.x[j] - s.x[i])) + double(length(s.r[j] - s.r[i]))) +
                                double(s.c) * double(length(s.v[j] - s.v[i]));
            scale[i] += term;
            scale[j] += term;
        }
    }
    return scale;
}

// Largest |f_i - g_i| / S_i over the particles (0 when both are exactly zero), with the scales
// S_i from force_scales.
inline double worst_relative_difference(const std::vector<double>& scale, const Vec3Array& f, const Vec3Array& g) {
    double worst = 0.0;
    for (std::size_t i = 0; i < scale.size(); ++i) {
        const double dx = double(f.x[i]) - g.x[i], dy = double(f.y[i]) - g.y[i], dz = double(f.z[i]) - g.z[i];
        const double diff = std::sqrt(dx * dx + dy * dy + dz * dz);
        if (!std::isfinite(diff)) return INFINITY;
        if (diff > 0.0) worst = std::max(worst, scale[i] > 0.0 ? diff / scale[i] : INFINITY);
    }
    return worst;
}

inline std::vector<PairKernelVariant> variants_here() {
    std::vector<PairKernelVariant> out;
    for (auto v : {PairKernelVariant::Scalar, PairKernelVariant::Avx2, PairKernelVariant::Avx512, PairKernelVariant::WasmSimd128}) {
        if (PairForceKernel::supported(v)) out.push_back(v);
    }
    return out;
}

inline bool same_bits(const Vec3Array& a, const Vec3Array& b) {
    return a.x.size() == b.x.size() && std::memcmp(a.x.data(), b.x.data(), a.x.size() * sizeof(float)) == 0 &&
           std::memcmp(a.y.data(), b.y.data(), a.y.size() * sizeof(float)) == 0 &&
           std::memcmp(a.z.data(), b.z.data(), a.z.size() * sizeof(float)) == 0;
}

}  // namespace softbody::test
