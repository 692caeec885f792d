// Internal to the pair kernel: what one tile of pairs reads and writes, shared by the portable
// tile (pair_forces.cpp) and the SIMD tiles (pair_tile_avx2.cpp, pair_tile_avx512.cpp, and
// pair_tile_wasm.cpp in the browser build), which are compiled with their own instruction-set
// flags.
//
// Keep this header free of inline functions and templates from the standard library: a
// function compiled once with AVX flags and once without may be merged by the linker, and the
// AVX copy would then run on a CPU that lacks AVX.
#pragma once

#include <cstddef>

namespace softbody::detail {

// Particles as the tiles want them: one float array per quantity, each padded with zeros to
// a multiple of kPad, and pre-scaled so that the inner loop saves two multiplications:
//   v' = (c / 4) v   and   r' = (k / 2) r.
// With g = 2 / l (what one Newton step on an approximate 1/sqrt(l^2) gives cheapest), the
// force on i is s d, d = x_j - x_i, with
//   s = k (l - l0) / l + c ((v_j - v_i) . d) / l^2          (Eq. 21 and Eq. 22 over d_hat = d / l)
//     = k - (k l0 / 2) g + (c / 4) ((v_j - v_i) . d) g^2
//     = k - |r'_j - r'_i| g + ((v'_j - v'_i) . d) g^2.
struct PackedParticles {
    const float *x, *y, *z;     // positions
    const float *vx, *vy, *vz;  // (c / 4) v
    const float *rx, *ry, *rz;  // (k / 2) r, rest positions
    std::size_t n = 0;          // particles; arrays hold a multiple of kPad
    float k = 0.0f;
};

inline constexpr std::size_t kPad = 16;       // widest SIMD lane count used
inline constexpr std::size_t kTile = 512;     // the largest block: floats from one axis's partial forces to the next
inline constexpr float kMinLengthSq = 1.17549435e-38f;  // smallest normal float: below it, coincident

// One tile: pairs (i, j) with i in [i0, i1), j in [j0, j1), and j > i when `diagonal` (then
// i0 == j0). i0 and j0 are multiples of kPad; i1 - i0 and j1 - j0 at most kTile. Adds the force on i to
// out_i[axis * kTile + (i - i0)] and the force on j to out_j[axis * kTile + (j - j0)]
// (axis 0, 1, 2 = x, y, z); on a diagonal tile out_i == out_j.
// Coincident particles (l^2 below kMinLengthSq) exert no force on each other.
using TileFunction = void (*)(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0,
                              std::size_t j1, bool diagonal, float* out_i, float* out_j);

// The elastic energy's tile: the sum over the same pairs of (l - l0)^2 in double, from particles
// packed with v and r unscaled (the caller multiplies by k / 2).
using StretchTileFunction = double (*)(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0,
                                       std::size_t j1, bool diagonal);

void tile_portable(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
                   bool diagonal, float* out_i, float* out_j);
double stretch_tile_portable(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
                             bool diagonal);
// The peak probe: `rounds` rounds of kProbeChains independent multiply-add chains
// (a <- a b + c) at the tile's vector width, with the tile's own instructions (a fused
// multiply-add on the SIMD tiles, a multiply and an add in the portable one). Chains that do
// not wait on one another keep every multiply-add unit busy, so rounds x kProbeChains x lanes
// x 2 flops over the time taken is the most this core can do at that width. Returns a value
// that depends on every chain, so none is optimised away.
inline constexpr std::size_t kProbeChains = 24;
float probe_portable(std::size_t rounds, float seed);

#if defined(SOFTBODY_HAVE_AVX2_TILE)
float probe_avx2(std::size_t rounds, float seed);
void tile_avx2(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
               bool diagonal, float* out_i, float* out_j);
double stretch_tile_avx2(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
                         bool diagonal);
#endif
#if defined(SOFTBODY_HAVE_WASM_TILE)
// WebAssembly SIMD: the portable tile's results bit for bit, four rows at a time.
float probe_wasm(std::size_t rounds, float seed);
void tile_wasm(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
               bool diagonal, float* out_i, float* out_j);
double stretch_tile_wasm(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
                         bool diagonal);
#endif
#if defined(SOFTBODY_HAVE_AVX512_TILE)
float probe_avx512(std::size_t rounds, float seed);
void tile_avx512(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
                 bool diagonal, float* out_i, float* out_j);
double stretch_tile_avx512(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
                           bool diagonal);
#endif

}  // namespace softbody::detail
