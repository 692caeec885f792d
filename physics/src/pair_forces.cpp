#include "physics/pair_forces.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "pair_tiles.h"
#include "physics/error.h"

namespace softbody {

// ---------------------------------------------------------------------------------------------
// Reference: Listing 8's CalcForce, with each unordered pair visited once and its force applied
// to both ends (Newton's third law), as written in the book.
// ---------------------------------------------------------------------------------------------
void pair_forces_reference(const PairInput& in, Vec3Array& f) {
    f.resize(in.n);
    for (std::size_t i = 0; i < in.n; ++i) {
        const Vec3 x_i{in.x[i], in.y[i], in.z[i]};
        const Vec3 v_i{in.vx[i], in.vy[i], in.vz[i]};
        const Vec3 r_i{in.rx[i], in.ry[i], in.rz[i]};
        for (std::size_t j = i + 1; j < in.n; ++j) {
            const Vec3 d = Vec3{in.x[j], in.y[j], in.z[j]} - x_i;
            const float l = length(d);
            if (l == 0.0f) continue;  // coincident particles: no direction, no force
            const Vec3 d_hat = d / l;
            const float l0 = length(Vec3{in.rx[j], in.ry[j], in.rz[j]} - r_i);  // rest length

            // Eq. 21 (Hooke): stretched (l > l0) pulls i toward j, compressed pushes it away.
            const Vec3 F_spring = in.k * (l - l0) * d_hat;
            // Eq. 22 (dashpot): resists the relative velocity along the spring axis only.
            const Vec3 v_rel = Vec3{in.vx[j], in.vy[j], in.vz[j]} - v_i;
            const Vec3 F_damp = in.c * dot(v_rel, d_hat) * d_hat;

            f.add(i, F_spring + F_damp);   // on i
            f.add(j, -(F_spring + F_damp));  // equal and opposite on j
        }
    }
}

double elastic_energy_reference(const PairInput& in) {
    double energy = 0.0;
    for (std::size_t i = 0; i < in.n; ++i) {
        for (std::size_t j = i + 1; j < in.n; ++j) {
            const float l = length(Vec3{in.x[j] - in.x[i], in.y[j] - in.y[i], in.z[j] - in.z[i]});
            const float l0 = length(Vec3{in.rx[j] - in.rx[i], in.ry[j] - in.ry[i], in.rz[j] - in.rz[i]});
            energy += 0.5 * in.k * double(l - l0) * double(l - l0);
        }
    }
    return energy;
}

// ---------------------------------------------------------------------------------------------
// Fast kernel: the triangle of pairs (i < j) is cut into square tiles of B x B, B the block
// size for this N (256, or 512 from PairForceKernel::kLargeBody particles on).
// Each tile writes its partial forces into a buffer of its own; each block's total is then the
// sum of its tiles' partials in a fixed order. Threads only choose which tile to do next, so
// the sums, and the bits of the result, are the same for any number of threads.
//
// Inside a tile, particle i is held in registers against 8 (AVX2) or 16 (AVX-512) particles j
// at a time; the force on i is summed in registers, the equal and opposite force on j goes
// straight into the tile's buffer. The rest length l0 = |r_j - r_i| is recomputed from the
// rest positions. Storing one float per pair instead would cost 2 N^2 bytes (200 MB at
// N = 10,000, 800 MB at N = 20,000, against this kernel's 5 and 20 MB), and measured
// (BM_RestLength in tests/benchmarks, same tile loop, two threads): with the AVX-512 tile 3%
// faster at N = 2,500, where the table still fits in cache, but 9% and 7% slower at 5,000
// and 10,000, where it streams from memory; with the AVX2 tile 6 to 17% faster. The sizes
// that decide real time here are the large ones, so the kernel recomputes.
//
// Accuracy: the SIMD tiles take 1/l from the CPU's approximate reciprocal square root refined
// by one Newton step (relative error about 4e-7 with AVX2, float rounding with AVX-512), and
// fuse multiply-adds; the results match the reference to float rounding, not bit for bit.
// The browser's WebAssembly tile (four rows i against one j) keeps the portable tile's
// operations and the order of its sums, so it gives the portable tile's bits (pair_tile_wasm.cpp).
// ---------------------------------------------------------------------------------------------
namespace detail {

// The portable tile: the same formulas as the SIMD ones (see pair_tiles.h), one pair at a time,
// with an exact square root.
void tile_portable(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
                   bool diagonal, float* out_i, float* out_j) {
    for (std::size_t i = i0; i < i1; ++i) {
        float fx = 0.0f, fy = 0.0f, fz = 0.0f;
        for (std::size_t j = diagonal ? i + 1 : j0; j < j1; ++j) {
            const float ex = p.x[i] - p.x[j], ey = p.y[i] - p.y[j], ez = p.z[i] - p.z[j];  // -d
            const float l2 = ex * ex + ey * ey + ez * ez;
            if (l2 < kMinLengthSq) continue;  // coincident: no direction, no force
            const float g = 2.0f / std::sqrt(l2);
            const float qx = p.rx[i] - p.rx[j], qy = p.ry[i] - p.ry[j], qz = p.rz[i] - p.rz[j];
            const float half_k_l0 = std::sqrt(qx * qx + qy * qy + qz * qz);
            const float dv_d = (p.vx[i] - p.vx[j]) * ex + (p.vy[i] - p.vy[j]) * ey + (p.vz[i] - p.vz[j]) * ez;
            const float s = p.k - half_k_l0 * g + dv_d * g * g;
            fx -= s * ex;
            fy -= s * ey;
            fz -= s * ez;
            out_j[j - j0] += s * ex;
            out_j[kTile + j - j0] += s * ey;
            out_j[2 * kTile + j - j0] += s * ez;
        }
        out_i[i - i0] += fx;
        out_i[kTile + i - i0] += fy;
        out_i[2 * kTile + i - i0] += fz;
    }
}

double stretch_tile_portable(const PackedParticles& p, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1,
                             bool diagonal) {
    double sum = 0.0;
    for (std::size_t i = i0; i < i1; ++i) {
        for (std::size_t j = diagonal ? i + 1 : j0; j < j1; ++j) {
            const float ex = p.x[i] - p.x[j], ey = p.y[i] - p.y[j], ez = p.z[i] - p.z[j];
            const float qx = p.rx[i] - p.rx[j], qy = p.ry[i] - p.ry[j], qz = p.rz[i] - p.rz[j];
            const double stretch = double(std::sqrt(ex * ex + ey * ey + ez * ez)) - std::sqrt(qx * qx + qy * qy + qz * qz);
            sum += stretch * stretch;
        }
    }
    return sum;
}

float probe_portable(std::size_t rounds, float seed) {
    // Half the chains of the SIMD probes: a multiply then an add (6 cycles or so) on 12 chains
    // already keeps two multipliers and two adders busy, and 12 fit in the 16 registers.
    static_assert(kProbeChains == 24);
    const float b = 0.999f, c = 0.001f;
    float a0 = seed, a1 = seed + 0.001f, a2 = seed + 0.002f, a3 = seed + 0.003f, a4 = seed + 0.004f,
          a5 = seed + 0.005f, a6 = seed + 0.006f, a7 = seed + 0.007f, a8 = seed + 0.008f, a9 = seed + 0.009f,
          a10 = seed + 0.010f, a11 = seed + 0.011f;
    const auto step = [b, c](float& a) {
        a = a * b + c;
#if defined(__x86_64__) || defined(__i386__)
        asm("" : "+x"(a));  // one float per register: keeps the compiler from packing chains into vectors
#endif
    };
    for (std::size_t r = 0; r < rounds; ++r) {
        step(a0), step(a1), step(a2), step(a3), step(a4), step(a5);
        step(a6), step(a7), step(a8), step(a9), step(a10), step(a11);
    }
    return a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7 + a8 + a9 + a10 + a11;
}

}  // namespace detail

namespace {

constexpr std::size_t T = detail::kTile;  // floats from one axis's partial forces to the next
static_assert(PairForceKernel::kBlock % detail::kPad == 0 && PairForceKernel::kLargeBlock % detail::kPad == 0);
static_assert(PairForceKernel::kBlock <= T && PairForceKernel::kLargeBlock <= T);

detail::TileFunction tile_function(PairKernelVariant variant) {
    switch (variant) {
#if defined(SOFTBODY_HAVE_WASM_TILE)
        case PairKernelVariant::WasmSimd128: return detail::tile_wasm;
#endif
#if defined(SOFTBODY_HAVE_AVX512_TILE)
        case PairKernelVariant::Avx512: return detail::tile_avx512;
#endif
#if defined(SOFTBODY_HAVE_AVX2_TILE)
        case PairKernelVariant::Avx2: return detail::tile_avx2;
#endif
        default: return detail::tile_portable;
    }
}

detail::StretchTileFunction stretch_tile_function(PairKernelVariant variant) {
    switch (variant) {
#if defined(SOFTBODY_HAVE_WASM_TILE)
        case PairKernelVariant::WasmSimd128: return detail::stretch_tile_wasm;
#endif
#if defined(SOFTBODY_HAVE_AVX512_TILE)
        case PairKernelVariant::Avx512: return detail::stretch_tile_avx512;
#endif
#if defined(SOFTBODY_HAVE_AVX2_TILE)
        case PairKernelVariant::Avx2: return detail::stretch_tile_avx2;
#endif
        default: return detail::stretch_tile_portable;
    }
}

std::size_t tile_count(std::size_t n) {
    const std::size_t B = PairForceKernel::block_size(n);
    const std::size_t blocks = (n + B - 1) / B;
    return blocks * (blocks + 1) / 2;
}

std::size_t padded(std::size_t n) { return (n + detail::kPad - 1) / detail::kPad * detail::kPad; }

// pool.run, or a plain loop on the calling thread when `threaded` is false.
void run_tasks(ThreadPool& pool, bool threaded, std::size_t count, const std::function<void(std::size_t)>& task) {
    if (threaded) {
        pool.run(count, task);
    } else {
        for (std::size_t t = 0; t < count; ++t) task(t);
    }
}

}  // namespace

bool PairForceKernel::supported(PairKernelVariant variant) {
    switch (variant) {
        case PairKernelVariant::Auto:
        case PairKernelVariant::Scalar: return true;
        case PairKernelVariant::Avx2:
#if defined(SOFTBODY_HAVE_AVX2_TILE)
            return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
            return false;
#endif
        case PairKernelVariant::Avx512:
#if defined(SOFTBODY_HAVE_AVX512_TILE)
            return __builtin_cpu_supports("avx512f");
#else
            return false;
#endif
        case PairKernelVariant::WasmSimd128:
#if defined(SOFTBODY_HAVE_WASM_TILE)
            return true;  // a browser without SIMD does not load the module at all
#else
            return false;
#endif
    }
    return false;
}

namespace {

// SOFTBODY_KERNEL, when set: the tile to run instead of the widest (see pair_forces.h).
std::optional<PairKernelVariant> forced_variant() {
    const char* text = std::getenv("SOFTBODY_KERNEL");
    if (text == nullptr || *text == '\0') return std::nullopt;
    const std::string_view name = text;
    PairKernelVariant variant;
    if (name == "auto") return std::nullopt;
    if (name == "portable" || name == "scalar") variant = PairKernelVariant::Scalar;
    else if (name == "avx2") variant = PairKernelVariant::Avx2;
    else if (name == "avx512") variant = PairKernelVariant::Avx512;
    else if (name == "simd128") variant = PairKernelVariant::WasmSimd128;
    else throw InputError("SOFTBODY_KERNEL: '" + std::string(name) + "' is not a tile (portable, avx2, avx512, simd128 or auto)");
    if (!PairForceKernel::supported(variant)) {
        throw InputError("SOFTBODY_KERNEL=" + std::string(name) + ": this build cannot run that tile on this machine");
    }
    return variant;
}

}  // namespace

PairKernelVariant PairForceKernel::best_variant() {
    if (const auto forced = forced_variant()) return *forced;
    if (supported(PairKernelVariant::WasmSimd128)) return PairKernelVariant::WasmSimd128;
    if (supported(PairKernelVariant::Avx512)) return PairKernelVariant::Avx512;
    if (supported(PairKernelVariant::Avx2)) return PairKernelVariant::Avx2;
    return PairKernelVariant::Scalar;
}

const char* PairForceKernel::name(PairKernelVariant variant) {
    switch (variant) {
        case PairKernelVariant::Auto: return name(best_variant());
        case PairKernelVariant::Scalar: return "scalar";
        case PairKernelVariant::Avx2: return "avx2";
        case PairKernelVariant::Avx512: return "avx512";
        case PairKernelVariant::WasmSimd128: return "simd128";
    }
    return "?";
}

PairForceKernel::PairForceKernel(ThreadPool& pool, PairKernelVariant variant)
    : pool_(pool), variant_(variant == PairKernelVariant::Auto || !supported(variant) ? best_variant() : variant) {}

// Flops per pair, counted in the tiles as written (pair_tiles.h's formulas):
//   e = x_i - x_j, w = v_i - v_j, q = r_i - r_j      9 subtractions                      9
//   l^2 = e.e, |q|^2 = q.q, (w.e)                     3 x (a multiply + 2 multiply-adds)  15
//   l^2 kept above the smallest normal float          1 max                               1
//   (k/2) l0 = sqrt(|q|^2)                            1 square root                       1
//   g = 2/l: approximate 1/sqrt, one Newton step      1 + multiply, multiply-add, multiply 5
//   s = k - (k l0/2) g + (w.e) g^2                    multiply + 2 multiply-adds          5
//   force on i (-= s e) and on j (+= s e)             6 multiply-adds                     12
//                                                                                  total 48
// The portable tile has no fused multiply-add (the build forbids fusing), and takes 2/l
// as a square root and a division: the same 48, less the max and the Newton step's 4, is 44.
// The WebAssembly tile does the portable tile's operations: 44.
int PairForceKernel::flops_per_pair(PairKernelVariant variant) {
    const PairKernelVariant v = variant == PairKernelVariant::Auto ? best_variant() : variant;
    return v == PairKernelVariant::Scalar || v == PairKernelVariant::WasmSimd128 ? 44 : 48;
}

double PairForceKernel::peak_flops(PairKernelVariant variant, int threads, double seconds) {
    if (variant == PairKernelVariant::Auto || !supported(variant)) variant = best_variant();
    float (*probe)(std::size_t, float) = detail::probe_portable;
    double lanes = 0.5;  // the portable probe runs half the chains, one float wide
#if defined(SOFTBODY_HAVE_AVX512_TILE)
    if (variant == PairKernelVariant::Avx512) probe = detail::probe_avx512, lanes = 16.0;
#endif
#if defined(SOFTBODY_HAVE_AVX2_TILE)
    if (variant == PairKernelVariant::Avx2) probe = detail::probe_avx2, lanes = 8.0;
#endif
#if defined(SOFTBODY_HAVE_WASM_TILE)
    if (variant == PairKernelVariant::WasmSimd128) probe = detail::probe_wasm, lanes = 2.0;  // half the chains, 4 wide
#endif
    // Rounds of short bursts, one per thread, each round timed from its start until every
    // thread has finished its burst, as a call of the kernel is: a thread that the operating
    // system takes away (or that shares its core with another) makes the round longer.
    // Bursts of a few microseconds: short enough that most rounds run undisturbed, long enough
    // that the clock's resolution does not matter. The median round gives the rate.
    constexpr std::size_t kRounds = 2048;
    const double flops_per_burst = double(kRounds) * double(detail::kProbeChains) * lanes * 2.0;
    threads = std::max(1, threads);
    std::atomic<long> round{0};
    std::atomic<int> finished{0};
    std::atomic<bool> stop{false};
    std::atomic<float> sink{0.0f};
    const auto wait_for = [](const auto& ready) {
        for (unsigned i = 1; !ready(); ++i) {
            if (i % 64 == 0) std::this_thread::yield();
        }
    };
    std::vector<std::thread> others;
    for (int t = 1; t < threads; ++t) {
        others.emplace_back([&, t] {
            long seen = 0;
            float seed = 0.5f + 0.01f * float(t);
            for (;;) {
                wait_for([&] { return stop.load() || round.load() != seen; });
                if (stop.load()) break;
                seen = round.load();
                seed = 0.5f + 1e-3f * probe(kRounds, seed);
                finished.fetch_add(1);
            }
            sink.store(seed);
        });
    }
    using Clock = std::chrono::steady_clock;
    std::vector<double> times;
    float seed = 0.5f;
    const auto start = Clock::now();
    do {
        finished.store(0);
        const auto t0 = Clock::now();
        round.fetch_add(1);
        seed = 0.5f + 1e-3f * probe(kRounds, seed);
        wait_for([&] { return finished.load() == threads - 1; });
        times.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    } while (std::chrono::duration<double>(Clock::now() - start).count() < seconds || times.size() < 5);
    stop.store(true);
    for (std::thread& thread : others) thread.join();
    sink.store(seed);
    std::nth_element(times.begin(), times.begin() + std::ptrdiff_t(times.size() / 2), times.end());
    return double(threads) * flops_per_burst / times[times.size() / 2];
}

std::size_t PairForceKernel::memory_bytes(std::size_t n) {
    const std::size_t tiles = tile_count(n);
    return sizeof(float) * (9 * padded(n) + tiles * 6 * T) + sizeof(std::size_t) * 3 * tiles + sizeof(double) * tiles;
}

void PairForceKernel::prepare(std::size_t n) {
    if (n == n_ && !tile_i_.empty()) return;
    n_ = n;
    block_ = block_size(n);
    const std::size_t B = block_;
    blocks_ = (n + B - 1) / B;
    tile_i_.clear();
    tile_j_.clear();
    order_.clear();
    for (std::size_t I = 0; I < blocks_; ++I) {
        for (std::size_t J = I; J < blocks_; ++J) {
            tile_i_.push_back(I);
            tile_j_.push_back(J);
        }
    }
    // Largest tiles first (whole before diagonal halves before the ragged last block), so the
    // threads finish close together. The order changes who computes a tile, never the sums.
    auto pairs_in = [&](std::size_t t) {
        const std::size_t rows = std::min(B, n - tile_i_[t] * B), cols = std::min(B, n - tile_j_[t] * B);
        return tile_i_[t] == tile_j_[t] ? rows * (rows - 1) / 2 : rows * cols;
    };
    order_.resize(tile_i_.size());
    for (std::size_t t = 0; t < order_.size(); ++t) order_[t] = t;
    std::stable_sort(order_.begin(), order_.end(), [&](std::size_t a, std::size_t b) { return pairs_in(a) > pairs_in(b); });
    partial_.assign(tile_i_.size() * 6 * T, 0.0f);
    partial_energy_.assign(tile_i_.size(), 0.0);
    stride_ = padded(n);
    packed_.assign(9 * stride_, 0.0f);
}

// Copies the state into the tiles' layout (pair_tiles.h): padded arrays, v scaled by scale_v and
// r by scale_r. O(N), against the O(N^2) pairs.
detail::PackedParticles PairForceKernel::pack(const PairInput& in, float scale_v, float scale_r) {
    const float* from[9] = {in.x, in.y, in.z, in.vx, in.vy, in.vz, in.rx, in.ry, in.rz};
    const float scale[9] = {1.0f, 1.0f, 1.0f, scale_v, scale_v, scale_v, scale_r, scale_r, scale_r};
    for (std::size_t a = 0; a < 9; ++a) {
        float* to = packed_.data() + a * stride_;
        for (std::size_t i = 0; i < in.n; ++i) to[i] = from[a][i] * scale[a];
    }
    const float* b = packed_.data();
    const std::size_t S = stride_;
    return {b, b + S, b + 2 * S, b + 3 * S, b + 4 * S, b + 5 * S, b + 6 * S, b + 7 * S, b + 8 * S, in.n, in.k};
}

void PairForceKernel::compute(const PairInput& in, Vec3Array& f) {
    f.resize(in.n);
    if (in.n < 2) return;
    prepare(in.n);
    const detail::PackedParticles p = pack(in, 0.25f * in.c, 0.5f * in.k);  // see pair_tiles.h
    const detail::TileFunction tile = tile_function(variant_);
    const std::size_t B = block_;
    pool_.run(order_.size(), [&](std::size_t k) {
        const std::size_t t = order_[k];
        float* out = partial_.data() + t * 6 * T;
        for (std::size_t axis = 0; axis < 6; ++axis) std::fill(out + axis * T, out + axis * T + B, 0.0f);
        const std::size_t I = tile_i_[t], J = tile_j_[t];
        const std::size_t i0 = I * B, i1 = std::min(i0 + B, in.n);
        const std::size_t j0 = J * B, j1 = std::min(j0 + B, in.n);
        tile(p, i0, i1, j0, j1, I == J, out, I == J ? out : out + 3 * T);
    });
    // Block b's total: its tiles (min(b,J), max(b,J)) for J = 0, 1, ... in that order.
    auto reduce = [&](std::size_t b) {
        const std::size_t p0 = b * B, p1 = std::min(p0 + B, in.n);
        for (std::size_t J = 0; J < blocks_; ++J) {
            const std::size_t I = std::min(b, J), K = std::max(b, J);
            // index of tile (I, K) in the order prepare() lists them: row I holds blocks_ - I tiles
            const std::size_t t = I * (2 * blocks_ - I + 1) / 2 + (K - I);
            const float* part = partial_.data() + t * 6 * T + (b == I ? 0 : 3 * T);
            for (std::size_t q = p0; q < p1; ++q) {
                f.x[q] += part[q - p0];
                f.y[q] += part[T + q - p0];
                f.z[q] += part[2 * T + q - p0];
            }
        }
    };
    // Small bodies reduce on the calling thread: waking another one would cost more than the sums.
    run_tasks(pool_, blocks_ >= 8, blocks_, reduce);
}

double PairForceKernel::elastic_energy(const PairInput& in) {
    if (in.n < 2 || in.k == 0.0f) return 0.0;
    prepare(in.n);
    const detail::PackedParticles p = pack(in, 1.0f, 1.0f);
    const detail::StretchTileFunction tile = stretch_tile_function(variant_);
    const std::size_t B = block_;
    pool_.run(tile_i_.size(), [&](std::size_t t) {
        const std::size_t I = tile_i_[t], J = tile_j_[t];
        const std::size_t i0 = I * B, i1 = std::min(i0 + B, in.n);
        const std::size_t j0 = J * B, j1 = std::min(j0 + B, in.n);
        partial_energy_[t] = tile(p, i0, i1, j0, j1, I == J);
    });
    double sum = 0.0;  // in tile order: the same for any thread count
    for (double e : partial_energy_) sum += e;
    return 0.5 * double(in.k) * sum;
}

}  // namespace softbody
