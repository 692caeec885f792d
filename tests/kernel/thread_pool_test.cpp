// The thread pool's promises: every task of a batch runs exactly once, whichever threads turn up;
// the caller runs whatever nobody else claimed; and a worker that the system does not run (here
// held in a signal handler, as a busy machine would hold it off its core) never keeps a batch from
// finishing. Nothing here is timed: a pool that waited for the held worker would hang, and the
// test's timeout would report it.
#include <gtest/gtest.h>

#include <pthread.h>
#include <sched.h>
#include <signal.h>

#include <atomic>
#include <cstddef>
#include <map>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "physics/thread_pool.h"

namespace softbody::test {
namespace {

// Runs batches of many sizes, each with a task of its own writing to counters of its own, and
// checks that every task of every batch ran once: also after the later batches, so that a worker
// that came late to one batch and ran its task in the next would show.
void expect_each_task_once(ThreadPool& pool, int batches) {
    const std::vector<std::size_t> sizes{1, 2, 3, 5, 8, 13, 64, 257};
    std::vector<std::size_t> first{0};  // batch b's counters start at first[b]
    for (int b = 0; b < batches; ++b) first.push_back(first.back() + sizes[std::size_t(b) % sizes.size()]);
    std::vector<std::atomic<int>> runs(first.back());
    for (int b = 0; b < batches; ++b) {
        const std::size_t count = first[b + 1] - first[b];
        std::atomic<int>* mine = runs.data() + first[b];
        pool.run(count, [mine, count](std::size_t i) {
            if (i < count) mine[i].fetch_add(1);
        });
        for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(mine[i].load(), 1) << "batch " << b << ", task " << i << " of " << count;
    }
    for (int b = 0; b < batches; ++b) {
        for (std::size_t k = first[b]; k < first[b + 1]; ++k) ASSERT_EQ(runs[k].load(), 1) << "batch " << b << ", task " << k - first[b];
    }
}

TEST(ThreadPool, RunsEveryTaskExactlyOnceAtAnyThreadCount) {
    // 4 and 6 threads on a machine of 2 cores: workers are often late, the case the pool is for.
    for (int threads : {1, 2, 3, 4, 6}) {
        ThreadPool pool(threads);
        EXPECT_EQ(pool.threads(), threads);
        pool.run(0, [](std::size_t) { FAIL() << "a batch of no tasks ran one"; });
        expect_each_task_once(pool, 2000);
    }
}

TEST(ThreadPool, ChunksCoverTheRangeInOrderAtAnyThreadCount) {
    for (int threads : {1, 2, 3}) {
        ThreadPool pool(threads);
        for (std::size_t count : {0, 1, 9, 10, 100, 1001}) {
            std::vector<std::pair<std::size_t, std::size_t>> ranges(64, {0, 0});
            const std::size_t chunks = for_chunks(&pool, count, 5, [&](std::size_t c, std::size_t begin, std::size_t end) {
                ranges[c] = {begin, end};
            });
            ASSERT_GE(chunks, 1u);
            ASSERT_LE(chunks, ranges.size());
            std::size_t next = 0;
            for (std::size_t c = 0; c < chunks; ++c) {
                EXPECT_EQ(ranges[c].first, next) << count << " items, chunk " << c;
                if (count > 0) {
                    EXPECT_LT(ranges[c].first, ranges[c].second) << count << " items, chunk " << c;
                }
                next = ranges[c].second;
            }
            EXPECT_EQ(next, count);
        }
    }
}

// Each thread of a pool has a slot of its own (the caller 0, the workers 1 on), the same all its
// life, and for_chunks still runs every chunk once when each thread takes its own share first.
TEST(ThreadPool, EachThreadKeepsItsSlotAndEveryChunkRunsOnce) {
    EXPECT_EQ(ThreadPool::slot(), 0);
    for (int threads : {2, 3, 20}) {
        ThreadPool pool(threads);
        std::mutex mutex;
        std::map<std::thread::id, int> slot_of;
        for (int round = 0; round < 300; ++round) {
            const std::size_t count = 100 + std::size_t(round);
            std::vector<std::atomic<int>> runs(count);
            for_chunks(&pool, count, 1, [&](std::size_t, std::size_t begin, std::size_t end) {
                for (std::size_t i = begin; i < end; ++i) runs[i].fetch_add(1);
                const int slot = ThreadPool::slot();
                std::lock_guard lock(mutex);
                const auto [at, added] = slot_of.emplace(std::this_thread::get_id(), slot);
                EXPECT_EQ(at->second, slot) << "a thread changed its slot";
            });
            for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(runs[i].load(), 1) << threads << " threads, item " << i << " of " << count;
        }
        std::set<int> slots;
        for (const auto& [thread, slot] : slot_of) {
            EXPECT_GE(slot, 0);
            EXPECT_LT(slot, threads);
            EXPECT_TRUE(slots.insert(slot).second) << "two threads share slot " << slot;
        }
        const auto caller = slot_of.find(std::this_thread::get_id());
        if (caller != slot_of.end()) {
            EXPECT_EQ(caller->second, 0);
        }
    }
}

// A task the caller runs waits until a worker has started the other task, so the batch can only
// end once a worker has run one: its thread is returned.
pthread_t some_worker(ThreadPool& pool) {
    const std::thread::id caller = std::this_thread::get_id();
    std::atomic<bool> seen{false};
    pthread_t worker{};
    pool.run(2, [&](std::size_t) {
        if (std::this_thread::get_id() == caller) {
            while (!seen.load()) std::this_thread::yield();
        } else {
            worker = pthread_self();
            seen.store(true);
        }
    });
    return worker;
}

TEST(ThreadPool, CallerRunsWhatAWorkerHeldInATaskLeaves) {
    ThreadPool pool(2);
    const std::thread::id caller = std::this_thread::get_id();
    for (int round = 0; round < 50; ++round) {
        // A worker that claims a task stays in it until the caller has run every other one: the
        // caller must not wait for it before taking the rest.
        constexpr std::size_t kCount = 40;
        std::atomic<std::size_t> by_caller{0}, by_workers{0};
        std::vector<std::atomic<int>> runs(kCount);
        pool.run(kCount, [&](std::size_t i) {
            runs[i].fetch_add(1);
            if (std::this_thread::get_id() == caller) {
                by_caller.fetch_add(1);
            } else {
                by_workers.fetch_add(1);
                while (by_caller.load() + by_workers.load() < kCount) std::this_thread::yield();
            }
        });
        // One worker holds one task at a time, and holds it to the end of the batch.
        EXPECT_LE(by_workers.load(), 1u);
        EXPECT_EQ(by_caller.load() + by_workers.load(), kCount);
        for (std::size_t i = 0; i < kCount; ++i) ASSERT_EQ(runs[i].load(), 1) << "task " << i;
    }
}

// The held worker's signal handler: it says it is held, then stays until released.
std::atomic<bool> g_held{false};
std::atomic<bool> g_release{false};
static_assert(std::atomic<bool>::is_always_lock_free);  // safe to touch in a signal handler

extern "C" void hold_here(int) {
    g_held.store(true);
    while (!g_release.load()) sched_yield();
}

TEST(ThreadPool, BatchesFinishWhileTheOnlyWorkerIsHeldOffItsCore) {
    struct sigaction hold {}, previous{};
    hold.sa_handler = hold_here;
    sigemptyset(&hold.sa_mask);
    ASSERT_EQ(sigaction(SIGUSR2, &hold, &previous), 0);
    {
        ThreadPool pool(2);
        const pthread_t worker = some_worker(pool);
        g_held.store(false);
        g_release.store(false);
        // Between batches the worker holds no task: it is spinning or asleep when the signal stops it.
        ASSERT_EQ(pthread_kill(worker, SIGUSR2), 0);
        while (!g_held.load()) std::this_thread::yield();

        // The worker cannot run now: the caller must run every task of every batch itself.
        const std::thread::id caller = std::this_thread::get_id();
        for (std::size_t count : {2, 3, 17, 100, 1000}) {
            std::vector<std::atomic<int>> runs(count);
            std::atomic<std::size_t> elsewhere{0};
            pool.run(count, [&](std::size_t i) {
                runs[i].fetch_add(1);
                if (std::this_thread::get_id() != caller) elsewhere.fetch_add(1);
            });
            EXPECT_EQ(elsewhere.load(), 0u) << count << " tasks";
            for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(runs[i].load(), 1) << "task " << i << " of " << count;
        }

        // Let go, the worker returns to the pool, finds nothing left of those batches and serves
        // the next ones.
        g_release.store(true);
        expect_each_task_once(pool, 200);
        some_worker(pool);  // returns only once the worker has run a task
    }
    ASSERT_EQ(sigaction(SIGUSR2, &previous, nullptr), 0);
}

}  // namespace
}  // namespace softbody::test
