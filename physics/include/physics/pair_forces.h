// The spring (Eq. 21) and damper (Eq. 22) between every unique pair of particles: the O(N^2)
// heart of Listing 8. Two implementations compute the same sums:
//   pair_forces_reference  the readable version, one pair at a time (read this first);
//   PairForceKernel        the fast one: blocks of pairs, SIMD (AVX2/AVX-512 when the CPU has
//                          them, WebAssembly SIMD in the browser, a portable loop
//                          otherwise), spread over threads, with
//                          results that do not depend on the number of threads.
#pragma once

#include <cstddef>
#include <vector>

#include "physics/arrays.h"
#include "physics/thread_pool.h"

namespace softbody {

namespace detail {
struct PackedParticles;  // the tiles' layout (physics/src/pair_tiles.h)
}

// Everything the pair loop reads. Rest lengths are not stored: l0 = |r_j - r_i| is recomputed
// from the rest positions r, which costs O(N) memory instead of N(N-1)/2 floats (200 MB at
// N = 10,000, 800 MB at 20,000); a stored table measured no faster at the sizes that decide
// real time (see pair_forces.cpp and BM_RestLength in tests/benchmarks).
struct PairInput {
    const float *x, *y, *z;     // positions
    const float *vx, *vy, *vz;  // velocities
    const float *rx, *ry, *rz;  // rest positions
    std::size_t n = 0;
    float k = 0.0f;             // stiffness, N/m
    float c = 0.0f;             // damping, kg/s
};

// Writes (not adds) the net spring + damper force on each particle into f.
void pair_forces_reference(const PairInput& in, Vec3Array& f);

// Sum over pairs of 1/2 k (l - l0)^2 (the springs' elastic energy).
double elastic_energy_reference(const PairInput& in);

// Which tile code the fast kernel runs. Auto picks the widest this CPU supports (checked at
// run time, so one binary runs everywhere); Scalar is the portable loop, for tests and bench.
// Results are bit-identical for one variant on one machine; variants agree to float rounding,
// except WasmSimd128 (the browser build's), which gives Scalar's bits.
//
// The environment variable SOFTBODY_KERNEL names the tile Auto picks instead: portable (or
// scalar), avx2, avx512 or simd128. SOFTBODY_KERNEL=portable makes a native build do the float
// operations of the browser build in the same order: the same state hash.
enum class PairKernelVariant { Auto, Scalar, Avx2, Avx512, WasmSimd128 };

class PairForceKernel {
public:
    // Particles per block, by body size only (never by thread count or machine, so the sums
    // and their bits are the same wherever the body runs). A tile's data (2 x 256 particles x
    // 9 floats, 18 KB, plus 6 KB of partial forces) fits in L1; small bodies keep blocks of
    // 256 so that two threads have tiles to share (N = 500: three tiles of near-equal work).
    // From kLargeBody particles on, blocks of 512: fewer once-a-row sums and half-empty
    // diagonal tiles, measured 4% faster at N = 2,500 on one core, with ten tiles or more
    // still to share out.
    static constexpr std::size_t kBlock = 256;
    static constexpr std::size_t kLargeBlock = 512;
    static constexpr std::size_t kLargeBody = 2048;
    static constexpr std::size_t block_size(std::size_t n) { return n >= kLargeBody ? kLargeBlock : kBlock; }

    explicit PairForceKernel(ThreadPool& pool, PairKernelVariant variant = PairKernelVariant::Auto);

    // Same contract as pair_forces_reference, to float rounding (see pair_forces.cpp).
    // Deterministic: bit-identical run to run and for any thread count, for one variant.
    void compute(const PairInput& in, Vec3Array& f);
    double elastic_energy(const PairInput& in);

    // Name of the tile code in use: "avx512", "avx2", "simd128" or "scalar".
    const char* variant() const { return name(variant_); }
    PairKernelVariant variant_id() const { return variant_; }

    // What this binary can run here (built in, and reported by the CPU), and the widest of it,
    // or what SOFTBODY_KERNEL names (InputError, one line, for a name that is not a tile or a
    // tile this binary cannot run here).
    static bool supported(PairKernelVariant variant);
    static PairKernelVariant best_variant();
    static const char* name(PairKernelVariant variant);

    // Floating-point operations the variant's tile spends on one pair, counted as it executes
    // them (a fused multiply-add is 2, a square root or an approximate reciprocal square
    // root 1; the once-a-row lane sums and the masks of ragged vectors are left out). See
    // pair_forces.cpp for the count, term by term.
    static int flops_per_pair(PairKernelVariant variant);

    // The peak of this CPU at the variant's vector width: flop/s of `threads` threads, each
    // running independent multiply-add chains with the tile's instructions (pair_tiles.h) in
    // short bursts for about `seconds`; each thread's rate is its median burst's, as the bench
    // takes the median call. A pair rate times flops_per_pair over this is the fraction of the
    // peak the tile reaches.
    static double peak_flops(PairKernelVariant variant, int threads, double seconds);

    // Bytes the kernel keeps for n particles (packed copy of the state, per-tile partials):
    // O(n^2 / block) for the partials, no per-pair storage.
    static std::size_t memory_bytes(std::size_t n);

private:
    void prepare(std::size_t n);
    detail::PackedParticles pack(const PairInput& in, float scale_v, float scale_r);

    ThreadPool& pool_;
    PairKernelVariant variant_;
    std::size_t n_ = 0, block_ = kBlock, blocks_ = 0;
    std::vector<std::size_t> tile_i_, tile_j_;  // block indices of each tile, tile_i_ <= tile_j_
    std::vector<std::size_t> order_;            // tiles in the order threads pick them up
    FloatArray packed_;                         // 9 arrays of padded particles (see pair_tiles.h)
    std::size_t stride_ = 0;                    // floats per packed array
    FloatArray partial_;                        // per tile: 2 x 3 partial forces, kTile floats apart
    std::vector<double> partial_energy_;
};

}  // namespace softbody
