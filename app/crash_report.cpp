#include "crash_report.h"

#include <csignal>
#include <cstring>

#if defined(__has_include)
#if __has_include(<execinfo.h>) && __has_include(<unistd.h>)
#include <execinfo.h>
#include <unistd.h>
#define SOFTBODY_CRASH_REPORT 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__) || defined(__EMSCRIPTEN__)
#undef SOFTBODY_CRASH_REPORT
#endif
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#undef SOFTBODY_CRASH_REPORT
#endif
#endif

namespace softbody::app {

#ifdef SOFTBODY_CRASH_REPORT
namespace {

constexpr int kSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
constexpr int kMostFrames = 64;

void write_text(const char* text) {
    // Only write(2) here: in a signal handler the heap and stdio may be the broken thing.
    std::size_t left = std::strlen(text);
    while (left > 0) {
        const ssize_t wrote = ::write(STDERR_FILENO, text, left);
        if (wrote <= 0) return;
        text += wrote;
        left -= std::size_t(wrote);
    }
}

void report(int signal_number) {
    const char* name = signal_number == SIGSEGV ? "SIGSEGV (a bad memory access)"
                     : signal_number == SIGBUS  ? "SIGBUS (a bad memory access)"
                     : signal_number == SIGFPE  ? "SIGFPE (an arithmetic fault)"
                     : signal_number == SIGILL  ? "SIGILL (an instruction this processor lacks)"
                                                : "SIGABRT (aborted: a failed check, often a corrupted heap)";
    write_text("softbody: crashed: ");
    write_text(name);
    write_text("; the call stack (addr2line -C -f -e softbody OFFSET names a frame of it):\n");
    void* frames[kMostFrames];
    const int count = ::backtrace(frames, kMostFrames);
    ::backtrace_symbols_fd(frames, count, STDERR_FILENO);
    // SA_RESETHAND put the default action back: raised again, the signal ends the process as it
    // would have.
    std::raise(signal_number);
}

}  // namespace

void install_crash_report() {
    // The first call loads what backtrace needs, so that a crash does not have to.
    void* frame[1];
    ::backtrace(frame, 1);
    struct sigaction action {};
    action.sa_handler = report;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND | SA_NODEFER;
    for (const int signal_number : kSignals) ::sigaction(signal_number, &action, nullptr);
}
#else
void install_crash_report() {}
#endif

}  // namespace softbody::app
