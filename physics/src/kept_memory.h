// Internal to the physics library: arrays that live from tick to tick and are sized afresh each
// tick (a pile's contacts, their points, the solver's manifolds).
//
// Why it matters: such an array holds megabytes in a large pile (stack:20: 78,000 contact
// points). Allocated afresh each tick, or grown to exactly the count whenever the count passes
// the largest so far, it comes back as new pages from the kernel, each one a page fault and a
// page cleared. In stack:20 on one thread that was about 3,000 faults and 4% of a tick.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "physics/thread_pool.h"

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

// Runs `place(c, to)` for each of the first `chunks` of `parts`, `to` where part c's items go in
// `out` (they follow one another in the parts' order from position `at` on), each part on one of
// the pool's threads. `out` grows where it is short and never shrinks; returns the position
// after the last item. (What the two place_chunks below share.)
template <class T, class U, class Place>
std::size_t place_parts(std::vector<T>& out, std::size_t at, const std::vector<std::vector<U>>& parts, std::size_t chunks,
                        ThreadPool* pool, const Place& place) {
    std::vector<std::size_t> begin(chunks + 1, at);
    for (std::size_t c = 0; c < chunks; ++c) begin[c + 1] = begin[c] + parts[c].size();
    if (out.size() < begin[chunks]) resize_with_room(out, begin[chunks]);
    const auto one = [&](std::size_t c) { place(c, out.data() + begin[c]); };
    if (pool && chunks > 1) {
        pool->run(chunks, one);
    } else {
        for (std::size_t c = 0; c < chunks; ++c) one(c);
    }
    return begin[chunks];
}

// Writes the first `chunks` of `parts` into `out` from position `at` on, in their order, each
// part copied by one of the pool's threads (a pile's contacts are tens of megabytes, and copying
// them on one thread was the longest stretch of a tick the other thread sat out), then
// `fix(item, c)` for each item copied from part c. What `out` holds there is overwritten: a list
// kept from tick to tick still holds the last tick's items, and items overwritten need no
// construction first (constructing 80,000 contacts anew took a millisecond, on one thread).
// `out` grows where it is short and never shrinks; returns the position after the last item
// written. The same result whatever the thread count.
template <class T, class Fix>
std::size_t place_chunks(std::vector<T>& out, std::size_t at, const std::vector<std::vector<T>>& parts, std::size_t chunks,
                         ThreadPool* pool, const Fix& fix) {
    return place_parts(out, at, parts, chunks, pool, [&](std::size_t c, T* to) {
        std::copy(parts[c].begin(), parts[c].end(), to);
        for (std::size_t k = 0; k < parts[c].size(); ++k) fix(to[k], c);
    });
}

// The same, each item of `out` made where it goes from a part's smaller record: `make(record, c)`
// (a pile's narrow phase keeps each point in a quarter of a contact's bytes, and the contact is
// written once, in its place, instead of written whole and then copied).
template <class T, class U, class Make>
std::size_t place_made(std::vector<T>& out, std::size_t at, const std::vector<std::vector<U>>& parts, std::size_t chunks,
                       ThreadPool* pool, const Make& make) {
    return place_parts(out, at, parts, chunks, pool, [&](std::size_t c, T* to) {
        for (const U& record : parts[c]) *to++ = make(record, c);
    });
}

// A chunk's own list from a table of them (one list a chunk, as place_chunks joins), taken out
// of the table while the chunk's work appends to it and put back when it ends. The table's lists
// sit side by side, two or three to a cache line: two threads appending to neighbouring ones
// would each write the line the other keeps its list's end in, and hand it back and forth at
// every append (in pyramid:10 at two threads the narrow phase took 2.7 times as long as on one).
// Taken out, a list's ends live on its own thread's stack; its memory stays its own.
template <class T>
class ChunkList {
public:
    explicit ChunkList(std::vector<T>& home) : home_(home), list_(std::move(home)) { list_.clear(); }
    ~ChunkList() { home_ = std::move(list_); }
    ChunkList(const ChunkList&) = delete;
    ChunkList& operator=(const ChunkList&) = delete;

    std::vector<T>& operator*() { return list_; }

private:
    std::vector<T>& home_;
    std::vector<T> list_;
};

// The same with nothing to fix.
template <class T>
std::size_t place_chunks(std::vector<T>& out, std::size_t at, const std::vector<std::vector<T>>& parts, std::size_t chunks,
                         ThreadPool* pool) {
    return place_chunks(out, at, parts, chunks, pool, [](T&, std::size_t) {});
}

}  // namespace softbody
