// Internal to the physics library: arrays that live from tick to tick and are sized afresh each
// tick (a pile's contacts, their points, the solver's manifolds).
//
// Why it matters: such an array holds megabytes in a large pile (stack:20: 78,000 contact
// points). Allocated afresh each tick, or grown to exactly the count whenever the count passes
// the largest so far, it comes back as new pages from the kernel, each one a page fault and a
// page cleared. In stack:20 on one thread that was about 3,000 faults and 4% of a tick.
#pragma once

#include <cstddef>

namespace softbody {

// v.resize(n), with an eighth more room than n whenever it has to grow: a count that creeps up
// tick by tick (a pile settling into more contacts) then moves the array now and then instead
// of at every new largest count.
template <class V>
void resize_with_room(V& v, std::size_t n) {
    if (n > v.capacity()) v.reserve(n + n / 8);
    v.resize(n);
}

// Room for n elements in all, the same way (before appending to v up to n).
template <class V>
void reserve_with_room(V& v, std::size_t n) {
    if (n > v.capacity()) v.reserve(n + n / 8);
}

}  // namespace softbody
