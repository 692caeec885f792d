// Micro-benchmarks of the pair loop (built, not run by CTest):
//   BM_Kernel/<variant>/<N>/<threads>     PairForceKernel::compute on a random cloud
//   BM_Reference/<N>                      pair_forces_reference, one thread
//   BM_RestLength/<layout>/<width>/<N>/<threads>
//                                         the same SIMD tile with l0 recomputed from rest
//                                         positions (layout 0) or read from a stored float per
//                                         pair (layout 1): the measurement behind the kernel's
//                                         choice to recompute.
// Run: kernel_benchmarks [--benchmark_filter=REGEX] [--benchmark_repetitions=5]. The counter
// pairs/s is unique pairs (N(N-1)/2 per force pass) per second of wall time.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>
#include <string>

#include "physics/generated.h"
#include "physics/pair_forces.h"
#include "rest_length_experiment.h"

namespace {

using namespace softbody;

struct Cloud {
    Vec3Array x, v, r;
    PairInput input() const {
        return {x.x.data(), x.y.data(), x.z.data(), v.x.data(), v.y.data(), v.z.data(),
                r.x.data(), r.y.data(), r.z.data(), x.size(), 10.0f, 0.1f};
    }
};

// The shared cloud:N (physics/generated.h: N particles in a ball 1 m across, the body
// `softbody bench` times and `--scene cloud:N` opens) as rest positions, each particle moved a
// little from rest and moving, as the bench's kernel rows have it.
Cloud make_cloud(std::size_t n) {
    const Mesh mesh = generated_mesh("cloud:" + std::to_string(n));
    std::mt19937 rng(7u);
    std::uniform_real_distribution<float> u(-0.05f, 0.05f);
    Cloud c;
    c.x.resize(n);
    c.v.resize(n);
    c.r.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        c.r.set(i, mesh.positions[i]);
        c.x.set(i, mesh.positions[i] + Vec3{u(rng), u(rng), u(rng)});
        c.v.set(i, Vec3{u(rng), u(rng), u(rng)} * 20.0f);
    }
    return c;
}

void set_rate(benchmark::State& state, std::size_t n) {
    state.counters["pairs/s"] = benchmark::Counter(double(n) * double(n - 1) / 2.0 * double(state.iterations()),
                                                   benchmark::Counter::kIsRate);
}

void BM_Kernel(benchmark::State& state) {
    const auto variant = static_cast<PairKernelVariant>(state.range(0));
    const auto n = static_cast<std::size_t>(state.range(1));
    if (!PairForceKernel::supported(variant)) {
        state.SkipWithError("this CPU lacks the instructions");
        return;
    }
    const Cloud cloud = make_cloud(n);
    ThreadPool pool(static_cast<int>(state.range(2)));
    PairForceKernel kernel(pool, variant);
    Vec3Array f;
    for (auto _ : state) {
        kernel.compute(cloud.input(), f);
        benchmark::DoNotOptimize(f.x.data());
    }
    set_rate(state, n);
    state.SetLabel(kernel.variant());
}

void BM_Reference(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const Cloud cloud = make_cloud(n);
    Vec3Array f;
    for (auto _ : state) {
        pair_forces_reference(cloud.input(), f);
        benchmark::DoNotOptimize(f.x.data());
    }
    set_rate(state, n);
}

// The experiment: tiles over a thread pool, partial buffers per tile, with or without stored l0.
void BM_RestLength(benchmark::State& state) {
    namespace ex = softbody::experiment;
    const bool stored = state.range(0) == 1;
    const int width = static_cast<int>(state.range(1));
    const auto n = static_cast<std::size_t>(state.range(2));
    const auto needs = width == 16 ? PairKernelVariant::Avx512 : PairKernelVariant::Avx2;
    if (!PairForceKernel::supported(needs)) {
        state.SkipWithError("this CPU lacks the instructions");
        return;
    }
    const Cloud cloud = make_cloud(n);
    const float k = 10.0f, c = 0.1f;
    const std::size_t B = ex::kTile, stride = (n + 15) / 16 * 16, blocks = (n + B - 1) / B;
    FloatArray packed(9 * stride, 0.0f);
    const FloatArray* from[9] = {&cloud.x.x, &cloud.x.y, &cloud.x.z, &cloud.v.x, &cloud.v.y,
                                 &cloud.v.z, &cloud.r.x, &cloud.r.y, &cloud.r.z};
    for (std::size_t a = 0; a < 9; ++a) {
        const float scale = a < 3 ? 1.0f : a < 6 ? 0.25f * c : 0.5f * k;
        for (std::size_t i = 0; i < n; ++i) packed[a * stride + i] = (*from[a])[i] * scale;
    }
    const float* b = packed.data();
    const ex::Particles p{b, b + stride, b + 2 * stride, b + 3 * stride, b + 4 * stride, b + 5 * stride,
                          b + 6 * stride, b + 7 * stride, b + 8 * stride, n, k};
    std::vector<std::size_t> tile_i, tile_j;
    for (std::size_t I = 0; I < blocks; ++I) {
        for (std::size_t J = I; J < blocks; ++J) {
            tile_i.push_back(I);
            tile_j.push_back(J);
        }
    }
    // Stored layout: per tile, kTile x kTile floats of (k/2) l0, row i then column j.
    FloatArray l0;
    if (stored) {
        l0.assign(tile_i.size() * B * B, 0.0f);
        for (std::size_t t = 0; t < tile_i.size(); ++t) {
            for (std::size_t i = tile_i[t] * B; i < std::min(n, tile_i[t] * B + B); ++i) {
                for (std::size_t j = tile_j[t] * B; j < std::min(n, tile_j[t] * B + B); ++j) {
                    l0[t * B * B + (i - tile_i[t] * B) * B + (j - tile_j[t] * B)] =
                        0.5f * k * length(cloud.r[j] - cloud.r[i]);
                }
            }
        }
    }
    FloatArray partial(tile_i.size() * 6 * B, 0.0f);
    ThreadPool pool(static_cast<int>(state.range(3)));
    for (auto _ : state) {
        pool.run(tile_i.size(), [&](std::size_t t) {
            float* out = partial.data() + t * 6 * B;
            std::fill(out, out + 6 * B, 0.0f);
            const std::size_t I = tile_i[t], J = tile_j[t];
            const std::size_t i0 = I * B, j0 = J * B;
            ex::tile(width, p, stored ? l0.data() + t * B * B : nullptr, i0, std::min(i0 + B, n), j0,
                     std::min(j0 + B, n), I == J, out, I == J ? out : out + 3 * B);
        });
        benchmark::DoNotOptimize(partial.data());
    }
    set_rate(state, n);
    state.counters["l0_MB"] = double(l0.size() * sizeof(float)) / 1e6;
    state.SetLabel(std::string(stored ? "stored l0" : "recomputed l0") + (width == 16 ? " avx512" : " avx2"));
}

void kernel_args(benchmark::internal::Benchmark* b) {
    for (auto variant : {PairKernelVariant::Scalar, PairKernelVariant::Avx2, PairKernelVariant::Avx512}) {
        for (int n : {500, 1000, 2500, 5000, 10000}) {
            for (int threads : {1, 2}) b->Args({static_cast<int>(variant), n, threads});
        }
    }
}

void rest_length_args(benchmark::internal::Benchmark* b) {
    for (int width : {8, 16}) {
        for (int n : {2500, 5000, 10000}) {
            for (int threads : {1, 2}) {
                for (int layout : {0, 1}) b->Args({layout, width, n, threads});
            }
        }
    }
}

// With --benchmark_repetitions=R, "min" is the least disturbed repetition (this machine is shared:
// other work only ever adds time), beside the usual mean, median and stddev.
double least(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }

BENCHMARK(BM_Kernel)->Apply(kernel_args)->UseRealTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", least);
BENCHMARK(BM_Reference)->Arg(500)->Arg(1000)->Arg(2500)->UseRealTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", least);
BENCHMARK(BM_RestLength)->Apply(rest_length_args)->UseRealTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", least);

}  // namespace

BENCHMARK_MAIN();
