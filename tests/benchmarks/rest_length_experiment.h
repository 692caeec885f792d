// The rest-length experiment: the same SIMD tile twice, once recomputing l0 = |r_j - r_i| from
// the rest positions (what PairForceKernel does) and once reading l0 from a stored table of
// one float per pair. Only the source of l0 differs, so the timings compare the two layouts.
//
// Plain functions only: the tile file is compiled with AVX flags, and nothing inline from a
// header may be shared between it and the files compiled without them.
#pragma once

#include <cstddef>

namespace softbody::experiment {

inline constexpr std::size_t kTile = 256;

struct Particles {
    const float *x, *y, *z, *vx, *vy, *vz, *rx, *ry, *rz;  // v scaled by c/4, r by k/2, padded
    std::size_t n = 0;
    float k = 0.0f;
};

// One tile, as detail::TileFunction in the physics library. With `stored_l0`, (k/2) l0 of pair
// (i, j) is read from stored_l0[(i - i0) * kTile + (j - j0)] instead of recomputed.
// width: 8 (AVX2 + FMA) or 16 (AVX-512F).
void tile(int width, const Particles& p, const float* stored_l0, std::size_t i0, std::size_t i1, std::size_t j0,
          std::size_t j1, bool diagonal, float* out_i, float* out_j);

}  // namespace softbody::experiment
