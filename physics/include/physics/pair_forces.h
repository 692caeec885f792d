// The spring (Eq. 21) and damper (Eq. 22) between every unique pair of particles: the O(N^2)
// heart of Listing 8. Two implementations compute the same sums:
//   pair_forces_reference  the readable version, one pair at a time (read this first);
//   PairForceKernel        the fast one: blocks of pairs, spread over threads, with results
//                          that do not depend on the number of threads.
#pragma once

#include <cstddef>
#include <vector>

#include "physics/arrays.h"
#include "physics/thread_pool.h"

namespace softbody {

// Everything the pair loop reads. Rest lengths are not stored: l0 = |r_j - r_i| is recomputed
// from the rest positions r, which costs O(N) memory instead of N(N-1)/2 floats.
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

class PairForceKernel {
public:
    static constexpr std::size_t kBlock = 256;  // particles per block: a tile's data fits in L1/L2

    explicit PairForceKernel(ThreadPool& pool) : pool_(pool) {}

    // Same contract as pair_forces_reference. Deterministic: bit-identical for any thread count.
    void compute(const PairInput& in, Vec3Array& f);
    double elastic_energy(const PairInput& in);

    // Name of the tile code in use ("avx2", "scalar").
    static const char* variant();

private:
    void prepare(std::size_t n);

    ThreadPool& pool_;
    std::size_t n_ = 0, blocks_ = 0;
    std::vector<std::size_t> tile_i_, tile_j_;  // block indices of each tile, tile_i_ <= tile_j_
    FloatArray partial_;                         // per tile: 2 x kBlock x 3 partial forces
    std::vector<double> partial_energy_;
};

}  // namespace softbody
