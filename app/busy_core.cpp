#include "busy_core.h"

#include <cerrno>
#include <csignal>
#include <cstdint>
#include <stdexcept>

#if !defined(__EMSCRIPTEN__)
#include <sys/wait.h>
#include <unistd.h>
#endif
#if defined(__linux__)
#include <sys/prctl.h>
#endif

namespace softbody::app {

BusyCore::BusyCore() {
#if defined(__EMSCRIPTEN__)
    throw std::runtime_error("a browser page cannot start a process to keep a core busy");
#else
    const pid_t parent = getpid();
    pid_ = fork();
    if (pid_ < 0) throw std::runtime_error("could not start a process to keep a core busy");
    if (pid_ == 0) {
#if defined(__linux__)
        // Dies with the bench, should the bench die before it stops this: a spinning orphan would
        // slow everything after it.
        prctl(PR_SET_PDEATHSIG, SIGKILL);
#endif
        if (getppid() != parent) _exit(0);
        // volatile: the loop must run, not be folded away.
        volatile std::uint64_t spins = 0;
        for (;;) spins = spins + 1;
    }
#endif
}

BusyCore::~BusyCore() {
#if !defined(__EMSCRIPTEN__)
    if (pid_ > 0) {
        kill(pid_, SIGKILL);
        int status = 0;
        while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
        }
    }
#endif
}

}  // namespace softbody::app
