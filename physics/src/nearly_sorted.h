// Internal to the physics library: a sort for lists that come as a few stretches already in
// order (a tick's contacts, the pair cache's answers).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace softbody {

// Sorts `items` by `less`, a strict total order (no two items equal), where they come as a few
// stretches already in order: a tick's contacts are the broad phase's pairs in order, then the
// ground's, then the particles' (in bin:1000, some 1,500 runs of one pair in 6 to 8 stretches).
// The stretches are merged, two neighbours at a time: the result is a sort's, in a fraction of
// its work.
template <class T, class Less>
void sort_nearly_sorted(std::vector<T>& items, const Less& less) {
    std::vector<std::size_t> edges{0};
    for (std::size_t i = 1; i < items.size(); ++i) {
        if (less(items[i], items[i - 1])) edges.push_back(i);
    }
    edges.push_back(items.size());
    while (edges.size() > 2) {
        std::vector<std::size_t> merged{0};
        for (std::size_t k = 0; k + 2 < edges.size(); k += 2) {
            std::inplace_merge(items.begin() + std::ptrdiff_t(edges[k]), items.begin() + std::ptrdiff_t(edges[k + 1]),
                               items.begin() + std::ptrdiff_t(edges[k + 2]), less);
            merged.push_back(edges[k + 2]);
        }
        if (edges.size() % 2 == 0) merged.push_back(edges.back());  // an odd stretch left over
        edges.swap(merged);
    }
}

// std::lower_bound(begin, end, key, less) (the first item not less than key), searched for from
// `hint`, an iterator into [begin, end] near where it should be: outward from the hint in steps
// that double, then by halves between the last two. The same answer as a search of the whole
// range, in a few steps where the keys asked for come in nearly the items' own order (each one
// a little after the last one's answer): a tick's contacts looked up among the last tick's, a
// pair among the cached ones.
template <class It, class Key, class Less>
It lower_bound_from(It begin, It end, It hint, const Key& key, const Less& less) {
    It low = begin, high = end;  // the answer is in [low, high]
    if (hint != end && less(*hint, key)) {
        low = hint + 1;
        for (std::ptrdiff_t step = 1; low != end; step *= 2) {
            const It probe = step < end - low ? low + (step - 1) : end - 1;
            if (!less(*probe, key)) {
                high = probe;
                break;
            }
            low = probe + 1;
        }
    } else {
        high = hint;
        for (std::ptrdiff_t step = 1; high != begin; step *= 2) {
            const It probe = step < high - begin ? high - step : begin;
            if (less(*probe, key)) {
                low = probe + 1;
                break;
            }
            high = probe;
        }
    }
    return std::lower_bound(low, high, key, less);
}

}  // namespace softbody
