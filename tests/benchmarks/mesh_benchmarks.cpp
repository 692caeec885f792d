// Micro-benchmarks of what a brought mesh goes through before it simulates (built, not run by
// CTest; the unit tests assert what these produce, never how fast):
//   BM_LoadObj/<vertices>        an OBJ's text to a welded Mesh (parse_obj_text, build_mesh):
//                                a torus of that many vertices
//   BM_Reduce/<vertices>/<budget>  reduce_mesh on such a torus: choose the particles, bind
//                                every vertex (40,000 -> 4,000 is the particle budget's case)
//   BM_ConvexHull/<points>       a rigid body's hull of points on a sphere, at most 64 vertices
// Run: mesh_benchmarks [--benchmark_filter=REGEX] [--benchmark_repetitions=5].
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "generated_meshes.h"
#include "physics/convex_hull.h"
#include "physics/mesh.h"
#include "physics/mesh_reduce.h"

namespace {

using namespace softbody;

// A square torus of about `vertices` vertices, as an OBJ file's text.
std::string torus_obj(int vertices) {
    const int side = static_cast<int>(std::lround(std::sqrt(double(vertices))));
    return test::to_obj(test::torus(1.0, 0.3, side, side));
}

void BM_LoadObj(benchmark::State& state) {
    const std::string text = torus_obj(static_cast<int>(state.range(0)));
    for (auto _ : state) {
        const Mesh mesh = build_mesh(parse_obj_text(text, "torus.obj"), "torus");
        benchmark::DoNotOptimize(mesh.positions.data());
    }
    state.counters["vertices/s"] = benchmark::Counter(double(state.range(0)), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_LoadObj)->Arg(10000)->Arg(40000)->Unit(benchmark::kMillisecond);

void BM_Reduce(benchmark::State& state) {
    const Mesh full = build_mesh(parse_obj_text(torus_obj(static_cast<int>(state.range(0))), "torus.obj"), "torus");
    for (auto _ : state) {
        const ReducedMesh reduced = reduce_mesh(full, static_cast<std::size_t>(state.range(1)));
        benchmark::DoNotOptimize(reduced.bindings.data());
    }
}
BENCHMARK(BM_Reduce)->Args({12100, 3000})->Args({40000, 4000})->Unit(benchmark::kMillisecond);

void BM_ConvexHull(benchmark::State& state) {
    std::mt19937 rng(7);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<Vec3d> points;
    while (points.size() < static_cast<std::size_t>(state.range(0))) {
        const Vec3d p{normal(rng), normal(rng), normal(rng)};
        if (length(p) > 1e-3) points.push_back(p / length(p));
    }
    for (auto _ : state) {
        const ConvexHull hull = convex_hull(points);
        benchmark::DoNotOptimize(hull.vertices.data());
    }
}
BENCHMARK(BM_ConvexHull)->Arg(3000)->Arg(30000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
