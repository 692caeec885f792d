// See rest_length_experiment.h. Written with the compiler's vector types so one template
// serves both widths; compiled with -mavx512f -mavx2 -mfma -ffp-contract=fast and called only
// on a CPU that has the width asked for.
#include "rest_length_experiment.h"

#include <immintrin.h>

namespace softbody::experiment {

namespace {

typedef float F8 __attribute__((vector_size(32)));
typedef int I8 __attribute__((vector_size(32)));
typedef float F16 __attribute__((vector_size(64)));
typedef int I16 __attribute__((vector_size(64)));

inline F8 rsqrt(F8 a) { return F8(_mm256_rsqrt_ps(__m256(a))); }
inline F16 rsqrt(F16 a) { return F16(_mm512_rsqrt14_ps(__m512(a))); }
inline F8 sqrt_v(F8 a) { return F8(_mm256_sqrt_ps(__m256(a))); }
inline F16 sqrt_v(F16 a) { return F16(_mm512_sqrt_ps(__m512(a))); }
inline F8 max_v(F8 a, F8 b) { return F8(_mm256_max_ps(__m256(a), __m256(b))); }
inline F16 max_v(F16 a, F16 b) { return F16(_mm512_max_ps(__m512(a), __m512(b))); }

inline float hsum(F8 v) {
    const __m256 a = __m256(v);
    __m128 s = _mm_add_ps(_mm256_castps256_ps128(a), _mm256_extractf128_ps(a, 1));
    s = _mm_add_ps(s, _mm_movehl_ps(s, s));
    return _mm_cvtss_f32(_mm_add_ss(s, _mm_movehdup_ps(s)));
}
inline float hsum(F16 v) { return _mm512_reduce_add_ps(__m512(v)); }

template <class F>
F load(const float* p) {
    F v;
    __builtin_memcpy(&v, p, sizeof v);
    return v;
}
template <class F>
void store(float* p, F v) {
    __builtin_memcpy(p, &v, sizeof v);
}

template <class F, class I, bool Stored, bool Masked>
inline __attribute__((always_inline)) void pairs(const Particles& p, const float* l0_row, std::size_t j,
                                                 std::size_t j0, const F (&row)[9], F (&f)[3], F k, float* out_j,
                                                 I valid) {
    const F ex = row[0] - load<F>(p.x + j), ey = row[1] - load<F>(p.y + j), ez = row[2] - load<F>(p.z + j);
    const F l2 = max_v(ex * ex + ey * ey + ez * ez, F{} + 1.17549435e-38f);
    F half_k_l0;
    if constexpr (Stored) {
        half_k_l0 = load<F>(l0_row + (j - j0));
    } else {
        const F qx = row[6] - load<F>(p.rx + j), qy = row[7] - load<F>(p.ry + j), qz = row[8] - load<F>(p.rz + j);
        half_k_l0 = sqrt_v(qx * qx + qy * qy + qz * qz);
    }
    const F dv_d = (row[3] - load<F>(p.vx + j)) * ex + (row[4] - load<F>(p.vy + j)) * ey + (row[5] - load<F>(p.vz + j)) * ez;
    const F y = rsqrt(l2);
    const F g = y * (3.0f - l2 * y * y);
    F s = k - half_k_l0 * g + dv_d * g * g;
    if constexpr (Masked) s = F(I(s) & valid);
    f[0] -= s * ex;
    f[1] -= s * ey;
    f[2] -= s * ez;
    store(out_j, load<F>(out_j) + s * ex);
    store(out_j + kTile, load<F>(out_j + kTile) + s * ey);
    store(out_j + 2 * kTile, load<F>(out_j + 2 * kTile) + s * ez);
}

template <class F, class I, bool Stored>
void tile_w(const Particles& p, const float* stored_l0, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
            bool diagonal, float* out_i, float* out_j) {
    constexpr std::size_t W = sizeof(F) / sizeof(float);
    I lane{};
    for (std::size_t w = 0; w < W; ++w) lane[w] = static_cast<int>(w);
    const F k = F{} + p.k;
    const std::size_t full_end = j1 & ~(W - 1);
    for (std::size_t i = i0; i < i1; ++i) {
        const F row[9] = {F{} + p.x[i],  F{} + p.y[i],  F{} + p.z[i],  F{} + p.vx[i], F{} + p.vy[i],
                          F{} + p.vz[i], F{} + p.rx[i], F{} + p.ry[i], F{} + p.rz[i]};
        F f[3] = {F{}, F{}, F{}};
        const float* l0_row = stored_l0 ? stored_l0 + (i - i0) * kTile : nullptr;
        const int lo = diagonal ? static_cast<int>(i) : static_cast<int>(j0) - 1;
        auto mask = [&](std::size_t j) {
            const I index = lane + static_cast<int>(j);
            return I(index > lo) & I(index < static_cast<int>(j1));
        };
        std::size_t j = diagonal ? ((i + 1) & ~(W - 1)) : j0;
        if (diagonal && j <= i && j < j1) {
            pairs<F, I, Stored, true>(p, l0_row, j, j0, row, f, k, out_j + (j - j0), mask(j));
            j += W;
        }
        for (; j < full_end; j += W) pairs<F, I, Stored, false>(p, l0_row, j, j0, row, f, k, out_j + (j - j0), I{});
        if (j < j1) pairs<F, I, Stored, true>(p, l0_row, j, j0, row, f, k, out_j + (j - j0), mask(j));
        for (int a = 0; a < 3; ++a) out_i[a * kTile + (i - i0)] += hsum(f[a]);
    }
}

}  // namespace

void tile(int width, const Particles& p, const float* stored_l0, std::size_t i0, std::size_t i1, std::size_t j0,
          std::size_t j1, bool diagonal, float* out_i, float* out_j) {
    if (width == 16) {
        if (stored_l0) tile_w<F16, I16, true>(p, stored_l0, i0, i1, j0, j1, diagonal, out_i, out_j);
        else tile_w<F16, I16, false>(p, nullptr, i0, i1, j0, j1, diagonal, out_i, out_j);
    } else {
        if (stored_l0) tile_w<F8, I8, true>(p, stored_l0, i0, i1, j0, j1, diagonal, out_i, out_j);
        else tile_w<F8, I8, false>(p, nullptr, i0, i1, j0, j1, diagonal, out_i, out_j);
    }
}

}  // namespace softbody::experiment
