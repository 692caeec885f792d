// The pair tile with AVX-512: particle i against sixteen particles j at a time.
// This file alone is compiled with -mavx512f; pair_forces.cpp calls it only after the CPU has
// reported AVX-512F. It is pair_tile_avx2.cpp at twice the width, with mask registers. The formulas are those of pair_tiles.h; the readable version of the same
// physics is pair_forces_reference in pair_forces.cpp.
#include <immintrin.h>

#include "pair_tiles.h"

namespace softbody::detail {

namespace {

constexpr std::size_t kLanes = 16;

// Particle i, the same in every lane, and the force on it summed lane by lane.
struct RowI {
    __m512 x, y, z, vx, vy, vz, rx, ry, rz;
    __m512 fx, fy, fz;
};

// Pairs (i, j .. j+15). out_j points at the tile's x-forces for particle j (y and z follow at
// kTile and 2 kTile). With Masked, lanes outside `valid` contribute nothing.
template <bool Masked>
__attribute__((always_inline)) inline void pairs16(const PackedParticles& p, std::size_t j, RowI& row, __m512 k,
                                                  float* out_j, __mmask16 valid) {
    // e = x_i - x_j = -d: the sign cancels in l^2 and in (v_j - v_i) . d.
    const __m512 ex = _mm512_sub_ps(row.x, _mm512_load_ps(p.x + j));
    const __m512 ey = _mm512_sub_ps(row.y, _mm512_load_ps(p.y + j));
    const __m512 ez = _mm512_sub_ps(row.z, _mm512_load_ps(p.z + j));
    const __m512 l2 = _mm512_max_ps(_mm512_fmadd_ps(ez, ez, _mm512_fmadd_ps(ey, ey, _mm512_mul_ps(ex, ex))),
                                    _mm512_set1_ps(kMinLengthSq));
    // (k/2) l0 from the pre-scaled rest positions.
    const __m512 qx = _mm512_sub_ps(row.rx, _mm512_load_ps(p.rx + j));
    const __m512 qy = _mm512_sub_ps(row.ry, _mm512_load_ps(p.ry + j));
    const __m512 qz = _mm512_sub_ps(row.rz, _mm512_load_ps(p.rz + j));
    const __m512 half_k_l0 = _mm512_sqrt_ps(_mm512_fmadd_ps(qz, qz, _mm512_fmadd_ps(qy, qy, _mm512_mul_ps(qx, qx))));
    // (c/4) (v_j - v_i) . d
    const __m512 wx = _mm512_sub_ps(row.vx, _mm512_load_ps(p.vx + j));
    const __m512 wy = _mm512_sub_ps(row.vy, _mm512_load_ps(p.vy + j));
    const __m512 wz = _mm512_sub_ps(row.vz, _mm512_load_ps(p.vz + j));
    const __m512 dv_d = _mm512_fmadd_ps(wz, ez, _mm512_fmadd_ps(wy, ey, _mm512_mul_ps(wx, ex)));
    // g = 2 / l: a 14-bit 1/sqrt(l^2), then one Newton step y (3 - l^2 y^2) (float rounding).
    const __m512 y = _mm512_rsqrt14_ps(l2);
    const __m512 g = _mm512_mul_ps(y, _mm512_fnmadd_ps(_mm512_mul_ps(l2, y), y, _mm512_set1_ps(3.0f)));
    // s = k - (k l0 / 2) g + (c/4)(dv . d) g^2
    __m512 s = _mm512_fmadd_ps(_mm512_mul_ps(dv_d, g), g, _mm512_fnmadd_ps(half_k_l0, g, k));
    if constexpr (Masked) s = _mm512_maskz_mov_ps(valid, s);
    // Force on i: s d = -s e. On j, equal and opposite: +s e.
    row.fx = _mm512_fnmadd_ps(s, ex, row.fx);
    row.fy = _mm512_fnmadd_ps(s, ey, row.fy);
    row.fz = _mm512_fnmadd_ps(s, ez, row.fz);
    _mm512_store_ps(out_j, _mm512_fmadd_ps(s, ex, _mm512_load_ps(out_j)));
    _mm512_store_ps(out_j + kTile, _mm512_fmadd_ps(s, ey, _mm512_load_ps(out_j + kTile)));
    _mm512_store_ps(out_j + 2 * kTile, _mm512_fmadd_ps(s, ez, _mm512_load_ps(out_j + 2 * kTile)));
}

// Lanes j .. j+15 with lo < j < hi.
__mmask16 lanes_between(std::size_t j, long lo, long hi) {
    const __m512i index = _mm512_add_epi32(_mm512_set1_epi32(static_cast<int>(j)),
                                           _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15));
    return _mm512_cmpgt_epi32_mask(index, _mm512_set1_epi32(static_cast<int>(lo))) &
           _mm512_cmpgt_epi32_mask(_mm512_set1_epi32(static_cast<int>(hi)), index);
}

// Sum of the sixteen lanes, always in the same order.
float sum_lanes(__m512 v) {
    const __m256 h = _mm256_add_ps(_mm512_castps512_ps256(v),
                                   _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(v), 1)));
    __m128 s = _mm_add_ps(_mm256_castps256_ps128(h), _mm256_extractf128_ps(h, 1));
    s = _mm_add_ps(s, _mm_movehl_ps(s, s));
    s = _mm_add_ss(s, _mm_movehdup_ps(s));
    return _mm_cvtss_f32(s);
}

// (l - l0)^2 of pairs (i, j .. j+15), added in double to acc_lo (lanes 0-7) and acc_hi (8-15).
template <bool Masked>
__attribute__((always_inline)) inline void stretch16(const PackedParticles& p, std::size_t j, const RowI& row,
                                                     __m512d& acc_lo, __m512d& acc_hi, __mmask16 valid) {
    const __m512 ex = _mm512_sub_ps(row.x, _mm512_load_ps(p.x + j));
    const __m512 ey = _mm512_sub_ps(row.y, _mm512_load_ps(p.y + j));
    const __m512 ez = _mm512_sub_ps(row.z, _mm512_load_ps(p.z + j));
    const __m512 qx = _mm512_sub_ps(row.rx, _mm512_load_ps(p.rx + j));
    const __m512 qy = _mm512_sub_ps(row.ry, _mm512_load_ps(p.ry + j));
    const __m512 qz = _mm512_sub_ps(row.rz, _mm512_load_ps(p.rz + j));
    const __m512 l = _mm512_sqrt_ps(_mm512_fmadd_ps(ez, ez, _mm512_fmadd_ps(ey, ey, _mm512_mul_ps(ex, ex))));
    const __m512 l0 = _mm512_sqrt_ps(_mm512_fmadd_ps(qz, qz, _mm512_fmadd_ps(qy, qy, _mm512_mul_ps(qx, qx))));
    __m512 stretch = _mm512_sub_ps(l, l0);
    if constexpr (Masked) stretch = _mm512_maskz_mov_ps(valid, stretch);
    const __m512d lo = _mm512_cvtps_pd(_mm512_castps512_ps256(stretch));
    const __m512d hi = _mm512_cvtps_pd(_mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(stretch), 1)));
    acc_lo = _mm512_fmadd_pd(lo, lo, acc_lo);
    acc_hi = _mm512_fmadd_pd(hi, hi, acc_hi);
}

}  // namespace

void tile_avx512(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
               bool diagonal, float* out_i, float* out_j) {
    const __m512 k = _mm512_set1_ps(p.k);
    const std::size_t full_end = j1 & ~(kLanes - 1);  // vectors wholly below j1
    for (std::size_t i = i0; i < i1; ++i) {
        RowI row{_mm512_set1_ps(p.x[i]),  _mm512_set1_ps(p.y[i]),  _mm512_set1_ps(p.z[i]),
                 _mm512_set1_ps(p.vx[i]), _mm512_set1_ps(p.vy[i]), _mm512_set1_ps(p.vz[i]),
                 _mm512_set1_ps(p.rx[i]), _mm512_set1_ps(p.ry[i]), _mm512_set1_ps(p.rz[i]),
                 _mm512_setzero_ps(),     _mm512_setzero_ps(),     _mm512_setzero_ps()};
        const long lo = diagonal ? static_cast<long>(i) : static_cast<long>(j0) - 1;  // valid: lo < j < j1
        std::size_t j = diagonal ? ((i + 1) & ~(kLanes - 1)) : j0;
        if (diagonal && j <= i && j < j1) {  // the vector holding i itself: only the lanes after it
            pairs16<true>(p, j, row, k, out_j + (j - j0), lanes_between(j, lo, static_cast<long>(j1)));
            j += kLanes;
        }
        for (; j < full_end; j += kLanes) pairs16<false>(p, j, row, k, out_j + (j - j0), __mmask16(0));
        if (j < j1) pairs16<true>(p, j, row, k, out_j + (j - j0), lanes_between(j, lo, static_cast<long>(j1)));
        out_i[i - i0] += sum_lanes(row.fx);
        out_i[kTile + i - i0] += sum_lanes(row.fy);
        out_i[2 * kTile + i - i0] += sum_lanes(row.fz);
    }
}

}  // namespace softbody::detail

namespace softbody::detail {

double stretch_tile_avx512(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
                           bool diagonal) {
    __m512d acc_lo = _mm512_setzero_pd(), acc_hi = _mm512_setzero_pd();
    const std::size_t full_end = j1 & ~(kLanes - 1);
    for (std::size_t i = i0; i < i1; ++i) {
        const __m512 zero = _mm512_setzero_ps();
        const RowI row{_mm512_set1_ps(p.x[i]),  _mm512_set1_ps(p.y[i]),  _mm512_set1_ps(p.z[i]),  zero, zero, zero,
                       _mm512_set1_ps(p.rx[i]), _mm512_set1_ps(p.ry[i]), _mm512_set1_ps(p.rz[i]), zero, zero, zero};
        const long lo = diagonal ? static_cast<long>(i) : static_cast<long>(j0) - 1;
        std::size_t j = diagonal ? ((i + 1) & ~(kLanes - 1)) : j0;
        if (diagonal && j <= i && j < j1) {
            stretch16<true>(p, j, row, acc_lo, acc_hi, lanes_between(j, lo, static_cast<long>(j1)));
            j += kLanes;
        }
        for (; j < full_end; j += kLanes) stretch16<false>(p, j, row, acc_lo, acc_hi, __mmask16(0));
        if (j < j1) stretch16<true>(p, j, row, acc_lo, acc_hi, lanes_between(j, lo, static_cast<long>(j1)));
    }
    alignas(64) double lanes[16];
    _mm512_store_pd(lanes, acc_lo);
    _mm512_store_pd(lanes + 8, acc_hi);
    double sum = 0.0;
    for (double lane : lanes) sum += lane;
    return sum;
}

}  // namespace softbody::detail

namespace softbody::detail {

float probe_avx512(std::size_t rounds, float seed) {
    __m512 a[kProbeChains];
    for (std::size_t c = 0; c < kProbeChains; ++c) a[c] = _mm512_set1_ps(seed + 0.001f * float(c));
    const __m512 b = _mm512_set1_ps(0.999f), c = _mm512_set1_ps(0.001f);  // a stays bounded: a -> 1
    for (std::size_t r = 0; r < rounds; ++r) {
#pragma GCC unroll 24
        for (std::size_t k = 0; k < kProbeChains; ++k) a[k] = _mm512_fmadd_ps(a[k], b, c);
    }
    __m512 sum = a[0];
    for (std::size_t k = 1; k < kProbeChains; ++k) sum = _mm512_add_ps(sum, a[k]);
    alignas(64) float lanes[16];
    _mm512_store_ps(lanes, sum);
    return lanes[0] + lanes[15];
}

}  // namespace softbody::detail
