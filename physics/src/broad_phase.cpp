// The broad phase: boxes, and sort and sweep (broad_phase.h).
#include "physics/broad_phase.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "collide_internal.h"
#include "kept_memory.h"

namespace softbody {

Aabb world_aabb(const CollisionShape& shape, const Pose& pose, double margin) {
    if (shape.is_sphere()) {
        const Vec3d r{shape.radius + margin, shape.radius + margin, shape.radius + margin};
        return {pose.x - r, pose.x + r};
    }
    return grown(hull_aabb(shape, pose), margin);
}

Aabb hull_aabb(const CollisionShape& hull, const Pose& pose) {
    const Transform T = world_transform(pose);
    Aabb box;
    box.lo = box.hi = T.apply(hull.hull->vertices.front());
    for (const Vec3d& v : hull.hull->vertices) {
        const Vec3d p = T.apply(v);
        for (int k = 0; k < 3; ++k) {
            box.lo[k] = std::min(box.lo[k], p[k]);
            box.hi[k] = std::max(box.hi[k], p[k]);
        }
    }
    return box;
}

Aabb grown(const Aabb& box, double margin) {
    const Vec3d m{margin, margin, margin};
    return {box.lo - m, box.hi + m};
}

namespace {

// The most strips overlapping_pairs cuts the boxes into.
constexpr int kMostStrips = 64;

bool finite(const Aabb& b) { return is_finite(b.lo) && is_finite(b.hi); }

// The axes by how much the boxes' centres spread along them (variance), most first.
std::array<int, 3> axes_by_spread(std::span<const Aabb> boxes) {
    Vec3d sum, sum2;
    double n = 0.0;
    for (const Aabb& b : boxes) {
        if (!finite(b)) continue;
        const Vec3d c = (b.lo + b.hi) * 0.5;
        sum += c;
        for (int k = 0; k < 3; ++k) sum2[k] += c[k] * c[k];
        n += 1.0;
    }
    std::array<int, 3> axes{0, 1, 2};
    if (n == 0.0) return axes;
    double variance[3];
    for (int k = 0; k < 3; ++k) variance[k] = sum2[k] / n - (sum[k] / n) * (sum[k] / n);
    // Most first; of two alike, the lower axis first.
    std::stable_sort(axes.begin(), axes.end(), [&](int x, int y) { return variance[x] > variance[y]; });
    return axes;
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
    // Each a's few by insertion where they are few (a handful each, mostly: a sort's set-up cost
    // more than the sorting), by a sort where they are many (a wall meets hundreds).
    for (std::size_t a = 0; a < bodies; ++a) {
        if (start[a + 1] - start[a] > 16) {
            std::sort(placed.begin() + start[a], placed.begin() + start[a + 1], [](const BodyPair& x, const BodyPair& y) { return x.b < y.b; });
            continue;
        }
        for (std::size_t i = start[a] + 1; i < start[a + 1]; ++i) {
            const BodyPair item = placed[i];
            std::size_t j = i;
            for (; j > start[a] && item.b < placed[j - 1].b; --j) placed[j] = placed[j - 1];
            placed[j] = item;
        }
    }
    pairs.swap(placed);
}

// `starts` (each finite box's start on `axis` and its index, in the boxes' order) sorted by
// start, from the order `last` holds where it names the same boxes: by insertion, which moves
// each box only past those it overtook since (a sort from nothing where that is too many).
// Boxes that start together may come in any order (overlapping_pairs does not depend on it).
void sort_starts(std::vector<std::pair<double, std::uint32_t>>& starts, std::span<const Aabb> boxes, int axis,
                 SweepOrder* last) {
    const auto by_start = [](const std::pair<double, std::uint32_t>& a, const std::pair<double, std::uint32_t>& b) {
        return a.first < b.first;
    };
    bool from_last = last && last->axis == axis && last->boxes.size() == starts.size();
    if (from_last) {
        // The same boxes when as many are named, each finite and named once.
        std::vector<std::uint8_t>& named = last->named;
        named.assign(boxes.size(), 0);
        for (std::size_t k = 0; k < starts.size() && from_last; ++k) {
            const std::uint32_t b = last->boxes[k];
            from_last = b < boxes.size() && finite(boxes[b]) && !named[b];
            if (from_last) named[b] = 1;
        }
    }
    if (from_last) {
        for (std::size_t k = 0; k < starts.size(); ++k) starts[k] = {boxes[last->boxes[k]].lo[axis], last->boxes[k]};
    }
    if (!from_last) {
        std::sort(starts.begin(), starts.end(), by_start);
        return;
    }
    std::size_t moves = 0;
    const std::size_t most_moves = 8 * starts.size() + 64;
    for (std::size_t i = 1; i < starts.size(); ++i) {
        const std::pair<double, std::uint32_t> item = starts[i];
        std::size_t j = i;
        for (; j > 0 && by_start(item, starts[j - 1]) && moves < most_moves; --j, ++moves) starts[j] = starts[j - 1];
        starts[j] = item;
        if (moves >= most_moves) {  // far from the last order: a whole sort after all
            std::sort(starts.begin(), starts.end(), by_start);
            return;
        }
    }
}

}  // namespace

void overlapping_pairs(std::span<const Aabb> boxes, std::vector<BodyPair>& out, std::span<const std::uint8_t> quiet,
                       ThreadPool* pool, SweepOrder* order) {
    out.clear();
    const std::array<int, 3> axes = axes_by_spread(boxes);
    const int axis = axes[0], u = axes[1], v = axes[2];
    // Each finite box's interval on the sweep axis and its extent on the other two, side by
    // side in memory, in order of its start on the axis (only finite boxes: a comparison with a
    // NaN is no order).
    struct Entry {
        double lo, hi, lo_u, hi_u, lo_v, hi_v;
        std::uint32_t index;
        std::int32_t first_strip;  // the first strip it reaches (below)
    };
    // (The starts sorted with their boxes' indices, then the entries laid out in that order:
    // sorting the entries themselves moved seven times the memory.)
    std::vector<std::pair<double, std::uint32_t>> starts;
    starts.reserve(boxes.size());
    double u_lo = 0.0, u_hi = 0.0, widths = 0.0;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const Aabb& b = boxes[i];
        if (!finite(b)) continue;
        u_lo = starts.empty() ? b.lo[u] : std::min(u_lo, b.lo[u]);
        u_hi = starts.empty() ? b.hi[u] : std::max(u_hi, b.hi[u]);
        widths += b.hi[u] - b.lo[u];
        starts.push_back({b.lo[axis], std::uint32_t(i)});
    }
    if (starts.empty()) return;
    sort_starts(starts, boxes, axis, order);
    if (order) {
        order->axis = axis;
        order->boxes.resize(starts.size());
        for (std::size_t k = 0; k < starts.size(); ++k) order->boxes[k] = starts[k].second;
    }
    // The strips: the boxes cut along the second axis into strips about twice a box as wide
    // (at most kMostStrips), each box in every strip it reaches, and each strip swept on its
    // own. A pile spread over a floor has most of its boxes overlapping a given one on the sweep
    // axis far from it on the other: in bin:3000, the strips leave a sixth of the comparisons.
    // A pair of boxes is noted in one strip only: the one where the later of their starts on
    // the second axis falls (both boxes reach it).
    const double extent = u_hi - u_lo, mean_width = widths / double(starts.size());
    const double wanted = extent / (2.0 * mean_width);
    const int strips = wanted >= 2.0 && wanted < double(kMostStrips) ? int(wanted) : wanted >= double(kMostStrips) ? kMostStrips : 1;
    // (By the width's reciprocal: a product never decreases in x either, and any such map
    // finds the same pairs.)
    const double per_width = strips > 1 ? double(strips) / extent : 0.0;
    const auto strip_of = [&](double x) {  // never decreasing in x
        if (strips == 1) return 0;
        const double k = std::floor((x - u_lo) * per_width);
        return !(k > 0.0) ? 0 : k >= double(strips - 1) ? strips - 1 : int(k);
    };
    // Each box's first and last strip; each strip's entries together (a strip's in order of
    // their start, as the boxes were sorted), and where each strip ends.
    std::vector<std::pair<std::int32_t, std::int32_t>> reach(starts.size());
    std::vector<std::uint32_t> strip_end(std::size_t(strips) + 1, 0);
    for (std::size_t k = 0; k < starts.size(); ++k) {
        const Aabb& b = boxes[starts[k].second];
        reach[k] = {strip_of(b.lo[u]), strip_of(b.hi[u])};
        for (int c = reach[k].first; c <= reach[k].second; ++c) ++strip_end[std::size_t(c) + 1];
    }
    for (int c = 0; c < strips; ++c) strip_end[std::size_t(c) + 1] += strip_end[std::size_t(c)];
    std::vector<std::uint32_t> at(strip_end.begin(), strip_end.end() - 1);
    std::vector<Entry> sweep(strip_end.back());
    std::vector<std::int32_t> strip_at(sweep.size());  // the strip each entry is in
    for (std::size_t k = 0; k < starts.size(); ++k) {
        const Aabb& b = boxes[starts[k].second];
        for (int c = reach[k].first; c <= reach[k].second; ++c) {
            strip_at[at[std::size_t(c)]] = c;
            sweep[at[std::size_t(c)]++] = {b.lo[axis], b.hi[axis], b.lo[u], b.hi[u], b.lo[v], b.hi[v], starts[k].second, reach[k].first};
        }
    }
    // Each box meets the ones of its strip that start after it and before it ends. Boxes that
    // start together may come in either order (either way finds their pair), and the pairs are
    // sorted at the end, so nothing depends on how the sort breaks ties.
    const auto sweep_from = [&](std::size_t begin, std::size_t end, std::vector<BodyPair>& found) {
        for (std::size_t i = begin; i < end; ++i) {
            const Entry& a = sweep[i];
            const bool a_quiet = !quiet.empty() && quiet[a.index];
            const std::int32_t strip = strip_at[i];
            const std::size_t last = strip_end[std::size_t(strip) + 1];
            for (std::size_t j = i + 1; j < last && sweep[j].lo <= a.hi; ++j) {
                const Entry& b = sweep[j];
                if (a_quiet && quiet[b.index]) continue;
                // Noted where the later start falls: the strip of the two's later first strip
                // (strip_of never decreases), which both reach when they overlap.
                if (a.lo_u <= b.hi_u && b.lo_u <= a.hi_u && a.lo_v <= b.hi_v && b.lo_v <= a.hi_v &&
                    std::max(a.first_strip, b.first_strip) == strip) {
                    found.push_back({std::min(a.index, b.index), std::max(a.index, b.index)});
                }
            }
        }
    };
    std::vector<std::vector<BodyPair>> found(pool ? std::size_t(4 * pool->threads()) : 1);
    const std::size_t chunks = for_chunks(pool, sweep.size(), 256, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        if (chunk == 0) {
            sweep_from(begin, end, out);
        } else {
            ChunkList taken(found[chunk]);
            sweep_from(begin, end, *taken);
        }
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
