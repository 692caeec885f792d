#include "physics/thread_pool.h"

namespace softbody {

namespace {

void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

// Polls ready() until it returns true (then true) or ThreadPool::kSpin has passed (then false).
// Every 64 polls it looks at the clock and offers the core to another thread: on a machine with
// more runnable threads than cores, the thread it waits for may be the one that needs it.
template <class Ready>
bool spin_until(Ready ready) {
    const auto until = std::chrono::steady_clock::now() + ThreadPool::kSpin;
    for (unsigned i = 1;; ++i) {
        if (ready()) return true;
        cpu_relax();
        if (i % 64 == 0) {
            if (std::chrono::steady_clock::now() >= until) return ready();
            std::this_thread::yield();
        }
    }
}

}  // namespace

int hardware_threads() {
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
    return 1;  // the browser build without threads (for a page that is not cross-origin isolated)
#else
    const unsigned n = std::thread::hardware_concurrency();
#if defined(__EMSCRIPTEN__)
    // In the browser every thread is a worker the page starts before the app does (a thread
    // cannot start while the page waits for it): at most kBrowserThreads a world, so that the
    // page's pool (web/CMakeLists.txt) serves the compared worlds too.
    constexpr unsigned kBrowserThreads = 4;
    if (n > kBrowserThreads) return static_cast<int>(kBrowserThreads);
#endif
    return n == 0 ? 1 : static_cast<int>(n);
#endif
}

ThreadPool::ThreadPool(int threads) {
    for (int t = 1; t < threads; ++t) workers_.emplace_back([this] { worker_loop(); });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard lock(mutex_);
        stopping_.store(true);
    }
    wake_.notify_all();
    for (auto& worker : workers_) worker.join();
}

void ThreadPool::drain() {
    for (std::size_t i = next_.fetch_add(1); i < count_; i = next_.fetch_add(1)) (*task_)(i);
}

void ThreadPool::worker_loop() {
    std::uint64_t seen = 0;
    const auto called = [&] { return stopping_.load(std::memory_order_acquire) || generation_.load(std::memory_order_acquire) != seen; };
    for (;;) {
        if (!spin_until(called)) {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, called);  // run() bumps the generation under the mutex: no wake-up is lost
        }
        if (stopping_.load(std::memory_order_acquire)) return;
        seen = generation_.load(std::memory_order_acquire);
        drain();
        if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
            // The last one out. Taking the mutex orders this against a caller that has checked
            // pending_ and is about to sleep: it is either still awake to see 0 or already waiting.
            std::lock_guard lock(mutex_);
            done_.notify_one();
        }
    }
}

void ThreadPool::run(std::size_t count, const std::function<void(std::size_t)>& task) {
    if (count == 0) return;
    if (workers_.empty() || count == 1) {
        for (std::size_t i = 0; i < count; ++i) task(i);
        return;
    }
    task_ = &task;
    count_ = count;
    next_.store(0, std::memory_order_relaxed);
    pending_.store(workers_.size(), std::memory_order_relaxed);
    {
        std::lock_guard lock(mutex_);
        generation_.fetch_add(1, std::memory_order_release);  // publishes task_, count_, next_, pending_
    }
    wake_.notify_all();  // no system call when every worker is still spinning
    drain();
    // Wait until every worker has finished this batch, so none can wander into the next one.
    const auto finished = [&] { return pending_.load(std::memory_order_acquire) == 0; };
    if (!spin_until(finished)) {
        std::unique_lock lock(mutex_);
        done_.wait(lock, finished);
    }
    task_ = nullptr;
}

}  // namespace softbody
