// The searches and sorts of lists that come nearly in order (physics/src/nearly_sorted.h),
// against the standard library's answers on every key and every hint: a wrong answer would
// start a contact from another's impulses or carry the wrong pair's points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "nearly_sorted.h"

namespace {

using softbody::lower_bound_from;
using softbody::sort_nearly_sorted;

TEST(NearlySorted, LowerBoundFromAnyHintIsTheWholeRangesAnswer) {
    // Keys with repeats and gaps, so that a search can land on the first of equals, between two
    // items, before the first and past the last.
    std::mt19937 random(7);
    for (int size : {0, 1, 2, 3, 7, 64, 301}) {
        std::vector<int> items(static_cast<std::size_t>(size));
        for (int& x : items) x = int(random() % 97u);
        std::sort(items.begin(), items.end());
        for (int key = -2; key <= 99; ++key) {
            const auto want = std::lower_bound(items.begin(), items.end(), key);
            for (auto hint = items.begin();; ++hint) {
                const auto got = lower_bound_from(items.begin(), items.end(), hint, key, std::less<int>());
                ASSERT_EQ(got - items.begin(), want - items.begin()) << "size " << size << ", key " << key << ", hint at "
                                                                       << (hint - items.begin());
                if (hint == items.end()) break;
            }
        }
    }
}

TEST(NearlySorted, SortOfStretchesIsASort) {
    // A few stretches each in order, as a tick's contacts come: the result must be the sort's.
    std::mt19937 random(11);
    for (int stretches : {1, 2, 3, 8}) {
        std::vector<std::uint32_t> items;
        for (int s = 0; s < stretches; ++s) {
            std::vector<std::uint32_t> stretch(40);
            for (std::uint32_t& x : stretch) x = std::uint32_t(random());
            std::sort(stretch.begin(), stretch.end());
            items.insert(items.end(), stretch.begin(), stretch.end());
        }
        std::vector<std::uint32_t> want = items;
        std::sort(want.begin(), want.end());
        sort_nearly_sorted(items, std::less<std::uint32_t>());
        EXPECT_EQ(items, want) << stretches << " stretches";
    }
}

}  // namespace
