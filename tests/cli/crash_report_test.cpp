// A crash says where it happened: softbody, ended by a fatal signal, writes the signal's name and
// its call stack to stderr, and still ends by that signal (app/crash_report.h).
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <sstream>
#include <thread>

#include "child_process.h"

namespace {

using namespace softbody_test;

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

TEST(CrashReport, AFatalSignalPrintsItsNameAndTheCallStackAndStillEndsTheProcess) {
    if (kSanitized) GTEST_SKIP() << "a sanitizer's build leaves crashes to the sanitizer's own report";
    TempDir dir;
    const std::string series = dir.file("series.csv"), out = dir.file("stdout"), err = dir.file("stderr");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> args{SOFTBODY_EXE, "simulate", "--scene", "pile:100", "--ticks", "1000000", "--threads", "1",
                                  "--series", series};
    std::vector<char*> argv;
    for (std::string& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    ASSERT_EQ(posix_spawn(&pid, SOFTBODY_EXE, &actions, nullptr, argv.data(), environ), 0);
    posix_spawn_file_actions_destroy(&actions);
    // Running (its series has rows) long after main() began: then the signal, as a bad memory
    // access in the middle of a tick would raise it.
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    std::error_code ec;
    while ((!fs::exists(series, ec) || fs::file_size(series, ec) == 0) && std::chrono::steady_clock::now() < give_up) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ASSERT_EQ(::kill(pid, SIGSEGV), 0);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    const std::string text = read_text(err);
    ASSERT_TRUE(WIFSIGNALED(status)) << "it should end by the signal, not exit; stderr:\n" << text;
    EXPECT_EQ(WTERMSIG(status), SIGSEGV);
    // One line naming the signal, then a line a frame, the executable's among them.
    EXPECT_EQ(text.rfind("softbody: crashed: SIGSEGV", 0), 0u) << text;
    std::istringstream lines(text);
    std::string line;
    int frames = 0, own = 0;
    std::getline(lines, line);
    while (std::getline(lines, line)) {
        ++frames;
        if (line.find(fs::path(SOFTBODY_EXE).filename().string()) != std::string::npos) ++own;
    }
    EXPECT_GE(frames, 3) << text;
    EXPECT_GE(own, 1) << "no frame of softbody itself:\n" << text;
}

}  // namespace
