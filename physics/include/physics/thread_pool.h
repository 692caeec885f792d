// A small pool of worker threads for the pair loop. Work is split into tasks whose results go
// to separate buffers, so which thread runs which task never changes the answer.
//
// Waking a sleeping thread costs tens of microseconds (a futex wake, more under a hypervisor),
// as long as a whole force pass on a few hundred particles. So a worker that has finished a
// batch first spins for kSpin, watching for the next one, and only then sleeps: the substeps
// of a tick, a few microseconds apart, find the workers awake. The caller waits for the last
// task the same way. A pool that nobody calls for kSpin goes back to costing nothing.
#pragma once

#include <algorithm>
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
    // How long a worker (or the caller, waiting for the batch to end) watches before sleeping.
    static constexpr std::chrono::microseconds kSpin{200};

    // `threads` counts the calling thread: 1 runs everything on the caller.
    explicit ThreadPool(int threads = 1);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int threads() const { return static_cast<int>(workers_.size()) + 1; }

    // Calls task(0) ... task(count - 1), each exactly once, spread over the threads; returns
    // when all are done. Tasks must not call run() themselves.
    void run(std::size_t count, const std::function<void(std::size_t)>& task);

private:
    void worker_loop();
    void drain();

    std::vector<std::thread> workers_;
    std::mutex mutex_;               // guards sleeping and waking only; the batch is in atomics
    std::condition_variable wake_;   // a sleeping worker waits here for the next batch
    std::condition_variable done_;   // a sleeping caller waits here for the batch's end
    const std::function<void(std::size_t)>* task_ = nullptr;
    std::size_t count_ = 0;
    std::atomic<std::size_t> next_{0};
    std::atomic<std::size_t> pending_{0};      // workers that have not finished the current batch
    std::atomic<std::uint64_t> generation_{0};  // bumps once per run(); every worker joins every batch
    std::atomic<bool> stopping_{false};
};

// Hardware threads, at least 1.
int hardware_threads();

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
    pool->run(chunks, [&](std::size_t c) { f(c, count * c / chunks, count * (c + 1) / chunks); });
    return chunks;
}

}  // namespace softbody
