// The pair tile with AVX2 and FMA: particle i against eight particles j at a time.
// This file alone is compiled with -mavx2 -mfma; pair_forces.cpp calls it only after the CPU
// has reported both. The formulas are those of pair_tiles.h; the readable version of the same
// physics is pair_forces_reference in pair_forces.cpp.
#include <immintrin.h>

#include "pair_tiles.h"

namespace softbody::detail {

namespace {

constexpr std::size_t kLanes = 8;

// Particle i, the same in every lane, and the force on it summed lane by lane.
struct RowI {
    __m256 x, y, z, vx, vy, vz, rx, ry, rz;
    __m256 fx, fy, fz;
};

// Pairs (i, j .. j+7). out_j points at the tile's x-forces for particle j (y and z follow at
// kTile and 2 kTile). With Masked, lanes outside `valid` contribute nothing.
template <bool Masked>
__attribute__((always_inline)) inline void pairs8(const PackedParticles& p, std::size_t j, RowI& row, __m256 k,
                                                  float* out_j, __m256 valid) {
    // e = x_i - x_j = -d: the sign cancels in l^2 and in (v_j - v_i) . d.
    const __m256 ex = _mm256_sub_ps(row.x, _mm256_load_ps(p.x + j));
    const __m256 ey = _mm256_sub_ps(row.y, _mm256_load_ps(p.y + j));
    const __m256 ez = _mm256_sub_ps(row.z, _mm256_load_ps(p.z + j));
    const __m256 l2 = _mm256_max_ps(_mm256_fmadd_ps(ez, ez, _mm256_fmadd_ps(ey, ey, _mm256_mul_ps(ex, ex))),
                                    _mm256_set1_ps(kMinLengthSq));
    // (k/2) l0 from the pre-scaled rest positions.
    const __m256 qx = _mm256_sub_ps(row.rx, _mm256_load_ps(p.rx + j));
    const __m256 qy = _mm256_sub_ps(row.ry, _mm256_load_ps(p.ry + j));
    const __m256 qz = _mm256_sub_ps(row.rz, _mm256_load_ps(p.rz + j));
    const __m256 half_k_l0 = _mm256_sqrt_ps(_mm256_fmadd_ps(qz, qz, _mm256_fmadd_ps(qy, qy, _mm256_mul_ps(qx, qx))));
    // (c/4) (v_j - v_i) . d
    const __m256 wx = _mm256_sub_ps(row.vx, _mm256_load_ps(p.vx + j));
    const __m256 wy = _mm256_sub_ps(row.vy, _mm256_load_ps(p.vy + j));
    const __m256 wz = _mm256_sub_ps(row.vz, _mm256_load_ps(p.vz + j));
    const __m256 dv_d = _mm256_fmadd_ps(wz, ez, _mm256_fmadd_ps(wy, ey, _mm256_mul_ps(wx, ex)));
    // g = 2 / l: a 12-bit 1/sqrt(l^2), then one Newton step y (3 - l^2 y^2) (error about 4e-7).
    const __m256 y = _mm256_rsqrt_ps(l2);
    const __m256 g = _mm256_mul_ps(y, _mm256_fnmadd_ps(_mm256_mul_ps(l2, y), y, _mm256_set1_ps(3.0f)));
    // s = k - (k l0 / 2) g + (c/4)(dv . d) g^2
    __m256 s = _mm256_fmadd_ps(_mm256_mul_ps(dv_d, g), g, _mm256_fnmadd_ps(half_k_l0, g, k));
    if constexpr (Masked) s = _mm256_and_ps(s, valid);
    // Force on i: s d = -s e. On j, equal and opposite: +s e.
    row.fx = _mm256_fnmadd_ps(s, ex, row.fx);
    row.fy = _mm256_fnmadd_ps(s, ey, row.fy);
    row.fz = _mm256_fnmadd_ps(s, ez, row.fz);
    _mm256_store_ps(out_j, _mm256_fmadd_ps(s, ex, _mm256_load_ps(out_j)));
    _mm256_store_ps(out_j + kTile, _mm256_fmadd_ps(s, ey, _mm256_load_ps(out_j + kTile)));
    _mm256_store_ps(out_j + 2 * kTile, _mm256_fmadd_ps(s, ez, _mm256_load_ps(out_j + 2 * kTile)));
}

// Lanes j .. j+7 with lo < j < hi.
__m256 lanes_between(std::size_t j, long lo, long hi) {
    const __m256i index = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(j)), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    const __m256i above = _mm256_cmpgt_epi32(index, _mm256_set1_epi32(static_cast<int>(lo)));
    const __m256i below = _mm256_cmpgt_epi32(_mm256_set1_epi32(static_cast<int>(hi)), index);
    return _mm256_castsi256_ps(_mm256_and_si256(above, below));
}

// Sum of the eight lanes, always in the same order.
float sum_lanes(__m256 v) {
    __m128 s = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
    s = _mm_add_ps(s, _mm_movehl_ps(s, s));
    s = _mm_add_ss(s, _mm_movehdup_ps(s));
    return _mm_cvtss_f32(s);
}

// (l - l0)^2 of pairs (i, j .. j+7), added in double to acc_lo (lanes 0-3) and acc_hi (4-7).
template <bool Masked>
__attribute__((always_inline)) inline void stretch8(const PackedParticles& p, std::size_t j, const RowI& row, __m256d& acc_lo,
                                                    __m256d& acc_hi, __m256 valid) {
    const __m256 ex = _mm256_sub_ps(row.x, _mm256_load_ps(p.x + j));
    const __m256 ey = _mm256_sub_ps(row.y, _mm256_load_ps(p.y + j));
    const __m256 ez = _mm256_sub_ps(row.z, _mm256_load_ps(p.z + j));
    const __m256 qx = _mm256_sub_ps(row.rx, _mm256_load_ps(p.rx + j));
    const __m256 qy = _mm256_sub_ps(row.ry, _mm256_load_ps(p.ry + j));
    const __m256 qz = _mm256_sub_ps(row.rz, _mm256_load_ps(p.rz + j));
    const __m256 l = _mm256_sqrt_ps(_mm256_fmadd_ps(ez, ez, _mm256_fmadd_ps(ey, ey, _mm256_mul_ps(ex, ex))));
    const __m256 l0 = _mm256_sqrt_ps(_mm256_fmadd_ps(qz, qz, _mm256_fmadd_ps(qy, qy, _mm256_mul_ps(qx, qx))));
    __m256 stretch = _mm256_sub_ps(l, l0);
    if constexpr (Masked) stretch = _mm256_and_ps(stretch, valid);
    const __m256d lo = _mm256_cvtps_pd(_mm256_castps256_ps128(stretch));
    const __m256d hi = _mm256_cvtps_pd(_mm256_extractf128_ps(stretch, 1));
    acc_lo = _mm256_fmadd_pd(lo, lo, acc_lo);
    acc_hi = _mm256_fmadd_pd(hi, hi, acc_hi);
}

}  // namespace

void tile_avx2(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
               bool diagonal, float* out_i, float* out_j) {
    const __m256 k = _mm256_set1_ps(p.k);
    const std::size_t full_end = j1 & ~(kLanes - 1);  // vectors wholly below j1
    for (std::size_t i = i0; i < i1; ++i) {
        RowI row{_mm256_set1_ps(p.x[i]),  _mm256_set1_ps(p.y[i]),  _mm256_set1_ps(p.z[i]),
                 _mm256_set1_ps(p.vx[i]), _mm256_set1_ps(p.vy[i]), _mm256_set1_ps(p.vz[i]),
                 _mm256_set1_ps(p.rx[i]), _mm256_set1_ps(p.ry[i]), _mm256_set1_ps(p.rz[i]),
                 _mm256_setzero_ps(),     _mm256_setzero_ps(),     _mm256_setzero_ps()};
        const long lo = diagonal ? static_cast<long>(i) : static_cast<long>(j0) - 1;  // valid: lo < j < j1
        std::size_t j = diagonal ? ((i + 1) & ~(kLanes - 1)) : j0;
        if (diagonal && j <= i && j < j1) {  // the vector holding i itself: only the lanes after it
            pairs8<true>(p, j, row, k, out_j + (j - j0), lanes_between(j, lo, static_cast<long>(j1)));
            j += kLanes;
        }
        for (; j < full_end; j += kLanes) pairs8<false>(p, j, row, k, out_j + (j - j0), _mm256_setzero_ps());
        if (j < j1) pairs8<true>(p, j, row, k, out_j + (j - j0), lanes_between(j, lo, static_cast<long>(j1)));
        out_i[i - i0] += sum_lanes(row.fx);
        out_i[kTile + i - i0] += sum_lanes(row.fy);
        out_i[2 * kTile + i - i0] += sum_lanes(row.fz);
    }
}

}  // namespace softbody::detail

namespace softbody::detail {

double stretch_tile_avx2(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
                         bool diagonal) {
    __m256d acc_lo = _mm256_setzero_pd(), acc_hi = _mm256_setzero_pd();
    const std::size_t full_end = j1 & ~(kLanes - 1);
    for (std::size_t i = i0; i < i1; ++i) {
        const __m256 zero = _mm256_setzero_ps();
        const RowI row{_mm256_set1_ps(p.x[i]),  _mm256_set1_ps(p.y[i]),  _mm256_set1_ps(p.z[i]),  zero, zero, zero,
                       _mm256_set1_ps(p.rx[i]), _mm256_set1_ps(p.ry[i]), _mm256_set1_ps(p.rz[i]), zero, zero, zero};
        const long lo = diagonal ? static_cast<long>(i) : static_cast<long>(j0) - 1;
        std::size_t j = diagonal ? ((i + 1) & ~(kLanes - 1)) : j0;
        if (diagonal && j <= i && j < j1) {
            stretch8<true>(p, j, row, acc_lo, acc_hi, lanes_between(j, lo, static_cast<long>(j1)));
            j += kLanes;
        }
        for (; j < full_end; j += kLanes) stretch8<false>(p, j, row, acc_lo, acc_hi, zero);
        if (j < j1) stretch8<true>(p, j, row, acc_lo, acc_hi, lanes_between(j, lo, static_cast<long>(j1)));
    }
    alignas(32) double lanes[8];
    _mm256_store_pd(lanes, acc_lo);
    _mm256_store_pd(lanes + 4, acc_hi);
    double sum = 0.0;
    for (double lane : lanes) sum += lane;
    return sum;
}

}  // namespace softbody::detail

namespace softbody::detail {

float probe_avx2(std::size_t rounds, float seed) {
    __m256 a[kProbeChains];
    for (std::size_t c = 0; c < kProbeChains; ++c) a[c] = _mm256_set1_ps(seed + 0.001f * float(c));
    const __m256 b = _mm256_set1_ps(0.999f), c = _mm256_set1_ps(0.001f);  // a stays bounded: a -> 1
    for (std::size_t r = 0; r < rounds; ++r) {
#pragma GCC unroll 24
        for (std::size_t k = 0; k < kProbeChains; ++k) a[k] = _mm256_fmadd_ps(a[k], b, c);
    }
    __m256 sum = a[0];
    for (std::size_t k = 1; k < kProbeChains; ++k) sum = _mm256_add_ps(sum, a[k]);
    return sum_lanes(sum);
}

}  // namespace softbody::detail
