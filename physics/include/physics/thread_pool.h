// A small pool of worker threads for the loops of a tick. Work is split into tasks whose results
// go to separate buffers, so which thread runs which task never changes the answer.
//
// The caller never waits for a thread that has not started. The tasks of a batch are claimed one
// at a time, by index, from one shared counter; the caller claims and runs them like any worker,
// so when the workers are asleep, or the system has not scheduled them (other programs busy on the
// cores), the caller simply runs the whole batch itself, at the speed of one thread. At the end it
// waits only for the tasks that a worker has claimed and is running. A worker that wakes late finds
// every task taken and goes back to waiting. for_chunks goes one step further: each thread (its
// slot) takes its own share of a loop's chunks first, the same share in every loop over the same
// items, and then helps with what is left of the others'.
//
// Waking a sleeping thread costs tens of microseconds (a futex wake, more under a hypervisor), as
// long as a whole force pass on a few hundred particles. So a worker that has run out of tasks
// first spins for kSpin, watching for the next batch, and only then sleeps: the substeps of a
// tick, a few microseconds apart, find the workers awake. A pool that nobody calls for kSpin goes
// back to costing nothing. Where other programs want the cores, spinning takes time they, or
// the caller, need: a worker that finds it was descheduled while it spun sleeps straight after
// each batch for kCrowded. And the caller wakes sleeping workers for a call site's batches only
// while that pays (the batch ends sooner than on the caller alone); else it leaves the next few
// of them to itself and to the workers already awake.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace softbody {

class ThreadPool {
public:
    // How long an idle worker (or the caller, waiting for a claimed task) watches before sleeping.
    static constexpr std::chrono::microseconds kSpin{200};

    // `threads` counts the calling thread: 1 runs everything on the caller.
    explicit ThreadPool(int threads = 1);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int threads() const { return static_cast<int>(workers_.size()) + 1; }

    // Which thread of its pool this is: 1 up to threads() - 1 on a worker, 0 on any other thread
    // (the caller).
    static int slot();

    // Calls task(0) ... task(count - 1), each exactly once, on the caller and whichever workers
    // turn up in time; returns when all are done. Tasks must not call run() themselves.
    void run(std::size_t count, const std::function<void(std::size_t)>& task);

private:
    // One batch of at most kMostTasks tasks (run() splits a larger count).
    void run_batch(std::uint32_t count, const std::function<void(std::size_t)>& task);
    // Takes the next unclaimed task of the open batch: true and its index, or false when none is left.
    bool claim(std::uint32_t& index);
    // True when the open batch has a task left to claim, or the pool is stopping.
    bool worth_waking() const;
    void worker_loop();

    static constexpr std::uint32_t kClosed = 0xFFFFFFFFu;  // the "next task" of a batch that is over
    static constexpr std::size_t kMostTasks = kClosed - 1;
    // How long a worker that was descheduled while it spun sleeps straight away after a batch.
    static constexpr std::chrono::milliseconds kCrowded{50};
    // The most batches of one call site in a row that open without waking the sleeping workers.
    static constexpr std::uint32_t kMostWakesSkipped = 63;

    // Whether waking the sleepers has paid for one call site's batches (the task's type names the
    // site: each call passes a lambda of its own). Kept by the caller alone.
    struct WakeHistory {
        const char* site = nullptr;
        std::uint32_t skipped = 0;  // batches opened without waking since the last wake
        std::uint32_t backoff = 0;  // how many to skip: 0 while wakes pay, 2 b + 1 after one that did not
    };
    WakeHistory& wake_history(const std::function<void(std::size_t)>& task);

    std::vector<std::thread> workers_;

    // The batch: its number in the high 32 bits, the next task to claim in the low 32. A claim is a
    // compare-and-swap of the whole word, so it names its batch: a worker that read the word of a
    // batch now over cannot take a task of the next one by mistake.
    std::atomic<std::uint64_t> batch_{0};
    std::atomic<std::uint32_t> count_{0};     // the open batch's task count
    std::atomic<std::uint32_t> finished_{0};  // tasks of the open batch that workers have finished
    // Read only by a thread holding a claim on the open batch: it cannot change under it, since the
    // caller does not start the next batch before every claimed task has finished.
    const std::function<void(std::size_t)>* task_ = nullptr;

    std::mutex mutex_;               // guards sleeping and waking only; the batch is in atomics
    std::condition_variable wake_;   // sleeping workers wait here for the next batch
    std::condition_variable done_;   // a sleeping caller waits here for the claimed tasks' end
    std::atomic<int> sleepers_{0};              // workers asleep on wake_ (or about to be)
    std::atomic<bool> caller_asleep_{false};    // the caller is asleep on done_ (or about to be)
    std::atomic<bool> stopping_{false};
    std::array<WakeHistory, 16> wake_histories_{};  // by call site; one that collides starts afresh
};

// Hardware threads, at least 1.
int hardware_threads();

// The threads a world runs on unless told otherwise: two, whatever the machine (the same scene
// gives the same bits at any count; a default that followed the machine would make runs differ in
// speed, never in results, but the setting would still not be the same everywhere). The pool
// yields when a core is busy, so two is never much slower than one. The browser build without
// threads (a page that is not cross-origin isolated) can start none: one there.
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
inline constexpr int kDefaultThreads = 1;
#else
inline constexpr int kDefaultThreads = 2;
#endif

// Splits [0, count) into consecutive chunks of at least `grain` items (one when there are too
// few to share, or no pool), a few a thread, and calls f(chunk, begin, end) for each on the
// pool's threads. Returns the number of chunks. Results kept per chunk and joined in chunk order
// are the same whatever the thread count.
template <class F>
std::size_t for_chunks(ThreadPool* pool, std::size_t count, std::size_t grain, const F& f) {
    const std::size_t threads = pool ? std::size_t(pool->threads()) : 1;
    const std::size_t chunks = threads == 1 || count < 2 * grain ? 1 : std::min((count + grain - 1) / grain, 4 * threads);
    if (chunks == 1) {
        f(std::size_t{0}, std::size_t{0}, count);
        return 1;
    }
    // Each thread takes its own share of the chunks first (thread t of T: chunks t chunks / T up to
    // (t + 1) chunks / T), then what is left of the others'. A loop over the same items in the next
    // phase gives each thread the same items again: they are still in its core's cache.
    struct alignas(64) Share {
        std::atomic<std::size_t> next{0};
        std::size_t end = 0;
    };
    std::array<Share, 16> shares;
    const std::size_t parts = std::min(threads, shares.size());
    for (std::size_t t = 0; t < parts; ++t) {
        shares[t].next.store(chunks * t / parts, std::memory_order_relaxed);
        shares[t].end = chunks * (t + 1) / parts;
    }
    const auto take = [&](Share& share) {
        for (std::size_t c = share.next.fetch_add(1); c < share.end; c = share.next.fetch_add(1)) {
            f(c, count * c / chunks, count * (c + 1) / chunks);
        }
    };
    pool->run(parts, [&](std::size_t) {
        const std::size_t home = std::size_t(ThreadPool::slot()) % parts;
        for (std::size_t k = 0; k < parts; ++k) take(shares[(home + k) % parts]);
    });
    return chunks;
}

}  // namespace softbody
