// A small pool of worker threads for the pair loop. Work is split into tasks whose results go
// to separate buffers, so which thread runs which task never changes the answer.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace softbody {

class ThreadPool {
public:
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
    std::mutex mutex_;
    std::condition_variable wake_;
    std::condition_variable done_;
    const std::function<void(std::size_t)>* task_ = nullptr;
    std::size_t count_ = 0;
    std::atomic<std::size_t> next_{0};
    std::size_t pending_ = 0;       // workers that have not finished the current batch
    std::uint64_t generation_ = 0;  // bumps once per run(); every worker joins every batch
    bool stopping_ = false;
};

// Hardware threads, at least 1.
int hardware_threads();

}  // namespace softbody
