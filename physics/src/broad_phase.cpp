// The broad phase: boxes, and sort and sweep (broad_phase.h).
#include "physics/broad_phase.h"

#include <algorithm>
#include <cmath>

#include "collide_internal.h"

namespace softbody {

Aabb world_aabb(const CollisionShape& shape, const Pose& pose, double margin) {
    Aabb box;
    if (shape.is_sphere()) {
        const Vec3d r{shape.radius + margin, shape.radius + margin, shape.radius + margin};
        return {pose.x - r, pose.x + r};
    }
    const Transform T = world_transform(pose);
    box.lo = box.hi = T.apply(shape.hull->vertices.front());
    for (const Vec3d& v : shape.hull->vertices) {
        const Vec3d p = T.apply(v);
        for (int k = 0; k < 3; ++k) {
            box.lo[k] = std::min(box.lo[k], p[k]);
            box.hi[k] = std::max(box.hi[k], p[k]);
        }
    }
    const Vec3d m{margin, margin, margin};
    return {box.lo - m, box.hi + m};
}

namespace {

bool finite(const Aabb& b) { return is_finite(b.lo) && is_finite(b.hi); }

// The axis along which the boxes' centres spread most (largest variance).
int sweep_axis(std::span<const Aabb> boxes) {
    Vec3d sum, sum2;
    double n = 0.0;
    for (const Aabb& b : boxes) {
        if (!finite(b)) continue;
        const Vec3d c = (b.lo + b.hi) * 0.5;
        sum += c;
        for (int k = 0; k < 3; ++k) sum2[k] += c[k] * c[k];
        n += 1.0;
    }
    if (n == 0.0) return 0;
    int axis = 0;
    double widest = -1.0;
    for (int k = 0; k < 3; ++k) {
        const double variance = sum2[k] / n - (sum[k] / n) * (sum[k] / n);
        if (variance > widest) {
            widest = variance;
            axis = k;
        }
    }
    return axis;
}

// The pairs (a < b, each once, a and b below `bodies`) in increasing order of (a, b), as a sort
// would leave them: counted by a, placed a after a, then each a's few sorted by b. In linear
// time: a sort of them all was the longest part of the broad phase on one thread (a pile's
// thousands of pairs, every tick).
void sort_pairs(std::vector<BodyPair>& pairs, std::size_t bodies) {
    std::vector<std::uint32_t> start(bodies + 1, 0);
    for (const BodyPair& p : pairs) ++start[p.a + 1];
    for (std::size_t a = 0; a < bodies; ++a) start[a + 1] += start[a];
    std::vector<BodyPair> placed(pairs.size());
    std::vector<std::uint32_t> at(start.begin(), start.end() - 1);
    for (const BodyPair& p : pairs) placed[at[p.a]++] = p;
    for (std::size_t a = 0; a < bodies; ++a) {
        std::sort(placed.begin() + start[a], placed.begin() + start[a + 1], [](const BodyPair& x, const BodyPair& y) { return x.b < y.b; });
    }
    pairs.swap(placed);
}

}  // namespace

void overlapping_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out, std::span<const std::uint8_t> quiet,
                       ThreadPool* pool) {
    out.clear();
    const int axis = sweep_axis(boxes);
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    // Each finite box's interval on the sweep axis and its extent on the other two, side by
    // side in memory, in order of its start on the axis (only finite boxes: a comparison with a
    // NaN is no order).
    struct Entry {
        double lo, hi, lo_u, hi_u, lo_v, hi_v;
        std::uint32_t index;
    };
    // (The starts sorted with their boxes' indices, then the entries laid out in that order:
    // sorting the entries themselves moved seven times the memory.)
    std::vector<std::pair<double, std::uint32_t>> starts;
    starts.reserve(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (finite(boxes[i])) starts.push_back({boxes[i].lo[axis], std::uint32_t(i)});
    }
    std::sort(starts.begin(), starts.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<Entry> sweep(starts.size());
    for (std::size_t k = 0; k < starts.size(); ++k) {
        const Aabb& b = boxes[starts[k].second];
        sweep[k] = {b.lo[axis], b.hi[axis], b.lo[u], b.hi[u], b.lo[v], b.hi[v], starts[k].second};
    }
    // Each box meets the ones that start after it and before it ends. Boxes that start together
    // may come in either order (either way finds their pair), and the pairs are sorted at the
    // end, so nothing depends on how the sort breaks ties.
    const auto sweep_from = [&](std::size_t begin, std::size_t end, std::vector<BodyPair>& found) {
        for (std::size_t i = begin; i < end; ++i) {
            const Entry& a = sweep[i];
            const bool a_quiet = !quiet.empty() && quiet[a.index];
            for (std::size_t j = i + 1; j < sweep.size() && sweep[j].lo <= a.hi; ++j) {
                const Entry& b = sweep[j];
                if (a_quiet && quiet[b.index]) continue;
                if (a.lo_u <= b.hi_u && b.lo_u <= a.hi_u && a.lo_v <= b.hi_v && b.lo_v <= a.hi_v) {
                    found.push_back({std::min(a.index, b.index), std::max(a.index, b.index)});
                }
            }
        }
    };
    std::vector<std::vector<BodyPair>> found(pool ? std::size_t(4 * pool->threads()) : 1);
    const std::size_t chunks = for_chunks(pool, sweep.size(), 256, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        sweep_from(begin, end, chunk == 0 ? out : found[chunk]);
    });
    for (std::size_t chunk = 1; chunk < chunks; ++chunk) out.insert(out.end(), found[chunk].begin(), found[chunk].end());
    sort_pairs(out, boxes.size());
}

void overlapping_pairs_of(std::span<const Aabb> boxes, std::span<const std::uint32_t> some, std::vector<BodyPair>& out) {
    out.clear();
    for (const std::uint32_t a : some) {
        if (!finite(boxes[a])) continue;
        for (std::size_t b = 0; b < boxes.size(); ++b) {
            if (b != a && finite(boxes[b]) && boxes[a].overlaps(boxes[b])) {
                out.push_back({std::min(a, std::uint32_t(b)), std::max(a, std::uint32_t(b))});
            }
        }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());  // two of `some` meet twice
}

}  // namespace softbody
