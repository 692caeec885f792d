#include "physics/thread_pool.h"

namespace softbody {

namespace {

void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

using Clock = std::chrono::steady_clock;

thread_local int this_slot = 0;

// Longer than 64 polls and a yield take on a core of one's own, far shorter than the time slice
// another program gets when it shares the core (milliseconds). Under a hypervisor the polls and
// the yield take a few microseconds but now and then 50 to 300: with 50 here, a worker took those
// for a crowded machine about once in 15 ticks of a pile, and slept after every batch for kCrowded,
// so the caller spent a twentieth of its time waking it (60 wakes a tick instead of 3).
constexpr std::chrono::microseconds kDescheduled{500};

enum class Spun {
    Ready,        // ready() became true
    Idle,         // ThreadPool::kSpin passed, the thread on its core all along
    Descheduled,  // the system gave the core to another thread while this one spun
};

// Polls ready() until it returns true or ThreadPool::kSpin has passed. Every 64 polls it looks at
// the clock and offers the core to another thread: on a machine with more runnable threads than
// cores, the thread it waits for may be the one that needs it. A gap between two looks at the
// clock means the core went to another thread: spinning on is then taking time someone needs.
template <class Ready>
Spun spin_until(Ready ready) {
    auto last = Clock::now();
    const auto until = last + ThreadPool::kSpin;
    for (unsigned i = 1;; ++i) {
        if (ready()) return Spun::Ready;
        cpu_relax();
        if (i % 64 == 0) {
            const auto now = Clock::now();
            if (now - last > kDescheduled) return ready() ? Spun::Ready : Spun::Descheduled;
            if (now >= until) return ready() ? Spun::Ready : Spun::Idle;
            last = now;
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
    for (int t = 1; t < threads; ++t) {
        workers_.emplace_back([this, t] {
            this_slot = t;
            worker_loop();
        });
    }
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard lock(mutex_);
        stopping_.store(true);
    }
    wake_.notify_all();
    for (auto& worker : workers_) worker.join();
}

int ThreadPool::slot() { return this_slot; }

bool ThreadPool::claim(std::uint32_t& index) {
    std::uint64_t word = batch_.load(std::memory_order_acquire);
    for (;;) {
        const auto next = static_cast<std::uint32_t>(word);
        // count_ may already be a later batch's; then the word has changed too, and the swap fails.
        if (next >= count_.load(std::memory_order_acquire)) return false;
        if (batch_.compare_exchange_weak(word, word + 1, std::memory_order_acq_rel, std::memory_order_acquire)) {
            index = next;
            return true;
        }
    }
}

ThreadPool::WakeHistory& ThreadPool::wake_history(const std::function<void(std::size_t)>& task) {
    // The type's name is a string the program holds once (should it hold two copies, a site only
    // keeps two histories): its address is enough to tell sites apart.
    const char* site = task.target_type().name();
    WakeHistory& history = wake_histories_[(reinterpret_cast<std::uintptr_t>(site) >> 4) % wake_histories_.size()];
    if (history.site != site) history = {site, 0, 0};
    return history;
}

bool ThreadPool::worth_waking() const {
    return stopping_.load() || static_cast<std::uint32_t>(batch_.load()) < count_.load();
}

void ThreadPool::worker_loop() {
    // Until then the worker sleeps as soon as it runs out of tasks, without spinning: it was
    // descheduled while spinning, so the cores are wanted by other threads (the caller among them).
    Clock::time_point no_spin_until{};
    for (;;) {
        std::uint32_t index = 0;
        while (claim(index)) {
            (*task_)(index);
            finished_.fetch_add(1);
            // Paired with the caller's store of caller_asleep_ before it looks at finished_ (both
            // sequentially consistent): one of the two sees the other, so no wake-up is lost.
            if (caller_asleep_.load()) {
                std::lock_guard lock(mutex_);
                done_.notify_one();
            }
        }
        Spun spun = Spun::Idle;
        if (Clock::now() >= no_spin_until) {
            spun = spin_until([this] { return worth_waking(); });
            if (spun == Spun::Descheduled) no_spin_until = Clock::now() + kCrowded;
        }
        if (spun != Spun::Ready) {
            std::unique_lock lock(mutex_);
            sleepers_.fetch_add(1);  // before the last look at the batch: run() reads it after opening one
            wake_.wait(lock, [this] { return worth_waking(); });
            sleepers_.fetch_sub(1);
        }
        if (stopping_.load()) return;
    }
}

void ThreadPool::run(std::size_t count, const std::function<void(std::size_t)>& task) {
    if (count == 0) return;
    if (workers_.empty() || count == 1) {
        for (std::size_t i = 0; i < count; ++i) task(i);
        return;
    }
    for (std::size_t first = 0; first < count; first += kMostTasks) {
        const std::size_t n = std::min(kMostTasks, count - first);
        if (first == 0) {
            run_batch(static_cast<std::uint32_t>(n), task);
        } else {
            const std::function<void(std::size_t)> shifted = [&](std::size_t i) { task(first + i); };
            run_batch(static_cast<std::uint32_t>(n), shifted);
        }
    }
}

void ThreadPool::run_batch(std::uint32_t count, const std::function<void(std::size_t)>& task) {
    // Close the last batch before count_ changes: a worker that reads the new count has, through
    // its acquire, seen the closed word, so it cannot claim with the new count in the old batch.
    const std::uint64_t number = (batch_.load(std::memory_order_relaxed) >> 32) + 1;
    batch_.store(((number - 1) << 32) | kClosed, std::memory_order_relaxed);
    task_ = &task;
    finished_.store(0, std::memory_order_relaxed);
    count_.store(count, std::memory_order_release);
    batch_.store(number << 32);  // opens the batch; publishes task_, finished_ and count_
    // Waking a sleeper is a system call on this thread's time, and the sleeper takes tens of
    // microseconds to come, or longer when other programs hold the cores. When the last wake for
    // this call site's batches did not pay, its next few batches are left to the workers already
    // awake, and to the caller.
    WakeHistory* woke = nullptr;
    if (sleepers_.load() > 0) {
        WakeHistory& history = wake_history(task);
        if (history.skipped < history.backoff) {
            ++history.skipped;
        } else {
            // Taking the mutex orders this against a worker between its last look and its sleep.
            { std::lock_guard lock(mutex_); }
            wake_.notify_all();
            woke = &history;
            history.skipped = 0;
        }
    }
    const Clock::time_point start = woke ? Clock::now() : Clock::time_point{};
    std::uint32_t mine = 0, index = 0;
    while (claim(index)) {
        task(index);
        ++mine;
    }
    // Every task is claimed. Those the workers took may still be running: wait for those alone.
    const std::uint32_t theirs = count - mine;
    const Clock::time_point claimed = woke ? Clock::now() : Clock::time_point{};
    const auto finished = [&] { return finished_.load() == theirs; };
    if (theirs > 0 && spin_until(finished) != Spun::Ready) {
        std::unique_lock lock(mutex_);
        caller_asleep_.store(true);
        done_.wait(lock, finished);
        caller_asleep_.store(false);
    }
    task_ = nullptr;
    if (woke) {
        // The wake paid when the batch ended sooner than on the caller alone: the workers' tasks,
        // at the caller's own pace, would have taken longer than the caller then waited for them.
        // A worker that took every task did not share the batch: it ran while the caller was off
        // its core (the system had put the two on one core).
        const auto waited = Clock::now() - claimed;
        const bool paid = mine > 0 && theirs > 0 && (claimed - start) / mine * theirs > waited;
        woke->backoff = paid ? 0 : std::min(2 * woke->backoff + 1, kMostWakesSkipped);
    }
}

}  // namespace softbody
