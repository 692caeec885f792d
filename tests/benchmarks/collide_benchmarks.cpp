// Micro-benchmarks of the collision geometry (built, not run by CTest):
//   BM_Pile                  one step's collision work on 100 boxes resting in a pile on a
//                            slab: boxes, broad phase, then collide() on every pair it finds
//   BM_PileNarrowPhase       collide() alone on the pile's pairs (found once)
//   BM_Pair/<case>           collide() on one pair: box on box (face), crossed boxes (edges),
//                            cylinder standing on a box, two cylinders crossed, a 64-vertex
//                            hull on a box, two 64-vertex hulls
//   BM_BroadPhase/<layout>/<n>  world boxes and sort and sweep: n boxes scattered (layout 0) or
//                            stacked in one tower (layout 1)
// Run: collide_benchmarks [--benchmark_filter=REGEX] [--benchmark_repetitions=5]. The counter
// pairs/s is narrow-phase pairs per second of wall time.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "physics/broad_phase.h"
#include "physics/collide.h"
#include "physics/convex_hull.h"
#include "physics/rigid_body.h"
#include "../physics/test_shapes.h"

namespace {

using namespace softbody;
using softbody::test::box;
using softbody::test::cylinder;
using softbody::test::turn;

constexpr double kMargin = 0.02;  // m: about a step's relative motion at 1 m/s and 50 Hz

// The hull of 2,000 points on a sphere, cut to the 64-vertex budget: the largest hull a mesh
// body collides with.
CollisionShape hull64(double radius) {
    std::mt19937 rng(3);
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<Vec3d> points;
    for (int i = 0; i < 2000; ++i) {
        const Vec3d p{g(rng), g(rng), g(rng)};
        points.push_back(normalize(p) * radius);
    }
    return hull_shape(std::make_shared<const ConvexHull>(convex_hull(points)));
}

// 100 boxes of 0.4 m in 5 x 5 columns of 4, each a little turned and tilted, each sunk 1 mm
// into the one below, the bottom layer 1 mm into a 20 m slab (body 0, fixed).
struct Pile {
    std::vector<CollisionShape> shapes;
    std::vector<Pose> poses;
};

Pile make_pile() {
    Pile pile;
    pile.shapes.push_back(box({20, 20, 1}));
    pile.poses.push_back({{0, 0, -0.5}, {}});
    const CollisionShape block = box({0.4, 0.4, 0.4});
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int column = 0; column < 25; ++column) {
        for (int layer = 0; layer < 4; ++layer) {
            const double yaw = 10.0 * u(rng), tilt = 0.5 * u(rng), dx = 0.01 * u(rng), dy = 0.01 * u(rng);
            const Vec3d x{(column % 5) * 0.41 + dx, (column / 5) * 0.41 + dy, 0.2 + layer * 0.399 - 0.001};
            pile.shapes.push_back(block);
            pile.poses.push_back({x, turn({1, 0, 0}, tilt) * turn({0, 0, 1}, yaw)});
        }
    }
    return pile;
}

std::vector<BodyPair> pile_pairs(const Pile& pile) {
    std::vector<Aabb> boxes;
    for (std::size_t i = 0; i < pile.shapes.size(); ++i) boxes.push_back(world_aabb(pile.shapes[i], pile.poses[i], kMargin));
    std::vector<BodyPair> pairs;
    overlapping_pairs(boxes, pairs);
    return pairs;
}

void BM_Pile(benchmark::State& state) {
    const Pile pile = make_pile();
    std::vector<Aabb> boxes(pile.shapes.size());
    std::vector<BodyPair> pairs;
    std::vector<ContactPoint> contacts;
    for (auto _ : state) {
        for (std::size_t i = 0; i < pile.shapes.size(); ++i) boxes[i] = world_aabb(pile.shapes[i], pile.poses[i], kMargin);
        overlapping_pairs(boxes, pairs);
        contacts.clear();
        for (const BodyPair& p : pairs) collide(pile.shapes[p.a], pile.poses[p.a], pile.shapes[p.b], pile.poses[p.b], kMargin, contacts);
        benchmark::DoNotOptimize(contacts.data());
    }
    state.counters["pairs"] = double(pairs.size());
    state.counters["contacts"] = double(contacts.size());
    state.counters["pairs/s"] = benchmark::Counter(double(pairs.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Pile)->Unit(benchmark::kMicrosecond);

void BM_PileNarrowPhase(benchmark::State& state) {
    const Pile pile = make_pile();
    const std::vector<BodyPair> pairs = pile_pairs(pile);
    std::vector<ContactPoint> contacts;
    for (auto _ : state) {
        contacts.clear();
        for (const BodyPair& p : pairs) collide(pile.shapes[p.a], pile.poses[p.a], pile.shapes[p.b], pile.poses[p.b], kMargin, contacts);
        benchmark::DoNotOptimize(contacts.data());
    }
    state.counters["pairs/s"] = benchmark::Counter(double(pairs.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PileNarrowPhase)->Unit(benchmark::kMicrosecond);

void BM_Pair(benchmark::State& state) {
    const CollisionShape cube = box({1, 1, 1}), slab = box({4, 4, 1});
    const double s2 = std::sqrt(2.0);
    CollisionShape a, b;
    Pose pa, pb;
    switch (state.range(0)) {
        case 0:
            state.SetLabel("box on box");
            a = cube, b = slab, pa = {{0.3, -0.2, 0.99}, turn({0, 0, 1}, 30.0)}, pb = {};
            break;
        case 1:
            state.SetLabel("crossed edges");
            a = cube, b = cube, pa = {{0, 0.1, s2 - 0.005}, turn({1, 0, 0}, 45.0)}, pb = {{0.2, 0, 0}, turn({0, 1, 0}, 45.0)};
            break;
        case 2:
            state.SetLabel("cylinder standing on box");
            a = cylinder(0.5, 1.0), b = slab, pa = {{0.2, -0.1, 0.998}, {}}, pb = {};
            break;
        case 3:
            state.SetLabel("cylinders crossed");
            a = cylinder(0.3, 2.0), b = a, pa = {{0, 0, 0.598}, turn({0, 1, 0}, 90.0)}, pb = {{0, 0, 0}, turn({1, 0, 0}, 90.0)};
            break;
        case 4:
            state.SetLabel("64-vertex hull on box");
            a = hull64(0.5), b = slab, pa = {{0, 0, 0.997}, turn({1, 2, 3}, 20.0)}, pb = {};
            break;
        default:
            state.SetLabel("two 64-vertex hulls");
            a = hull64(0.5), b = a, pa = {{0, 0, 0.995}, turn({1, 2, 3}, 20.0)}, pb = {{0, 0, 0}, turn({3, 1, 2}, 50.0)};
            break;
    }
    std::vector<ContactPoint> contacts;
    collide(a, pa, b, pb, kMargin, contacts);
    if (contacts.empty()) {
        state.SkipWithError("the pair does not touch");
        return;
    }
    for (auto _ : state) {
        contacts.clear();
        collide(a, pa, b, pb, kMargin, contacts);
        benchmark::DoNotOptimize(contacts.data());
    }
    state.counters["contacts"] = double(contacts.size());
}
BENCHMARK(BM_Pair)->DenseRange(0, 5)->Unit(benchmark::kNanosecond);

void BM_BroadPhase(benchmark::State& state) {
    const bool tower = state.range(0) == 1;
    const auto n = static_cast<std::size_t>(state.range(1));
    const CollisionShape block = box({0.4, 0.4, 0.4});
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double side = std::cbrt(double(n)) * 0.5;  // about one box per 0.125 m^3
    std::vector<Pose> poses;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3d x = tower ? Vec3d{0.01 * u(rng), 0.01 * u(rng), 0.399 * double(i)} : Vec3d{u(rng), u(rng), u(rng)} * side;
        const Vec3d axis{u(rng), u(rng), 1.0};
        const double degrees = 30.0 * u(rng);
        poses.push_back({x, turn(axis, degrees)});
    }
    std::vector<Aabb> boxes(n);
    std::vector<BodyPair> pairs;
    for (auto _ : state) {
        for (std::size_t i = 0; i < n; ++i) boxes[i] = world_aabb(block, poses[i], kMargin);
        overlapping_pairs(boxes, pairs);
        benchmark::DoNotOptimize(pairs.data());
    }
    state.counters["pairs"] = double(pairs.size());
}
BENCHMARK(BM_BroadPhase)->ArgsProduct({{0, 1}, {300, 1000, 3000}})->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
