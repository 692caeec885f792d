// The app's Record button, driven by scripts under a virtual display: the 3D view becomes an
// H.264 video at 30 frames per simulated second (nothing while paused), under a new name each
// time in the current folder; without ffmpeg the frames become PNGs and the app says so.
//
// The video is read back with ffprobe (Debian's ffmpeg package). Where ffmpeg is missing that
// test skips with a message, except in CI (CI=true), where it fails: dev.sh installs ffmpeg.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }

// This test process's scratch folder: removed when its test passes, kept to look at when not.
fs::path scratch() { return fs::temp_directory_path() / ("softbody_record_tests_" + std::to_string(::getpid())); }

void remove_scratch_if_passed() {
    if (!::testing::Test::HasFailure()) fs::remove_all(scratch());
}

// A fresh folder to run the app in (recordings land in the current folder).
fs::path fresh_folder(const std::string& name) {
    const fs::path dir = scratch() / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// Runs a shell command and returns its standard output; `status` gets its exit status.
std::string shell(const std::string& command, int& status) {
    std::string out;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) return out;
    std::array<char, 4096> buffer;
    while (std::fgets(buffer.data(), buffer.size(), pipe)) out += buffer.data();
    const int raw = ::pclose(pipe);
    status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    return out;
}

// `softbody run` in `folder` with the script, under a virtual display when there is none;
// `prefix` goes before the program (such as "env PATH=..."). Returns the summary line.
json run_app(const fs::path& folder, int frames, const std::string& script, const std::string& prefix = "") {
    std::ofstream(folder / "test.script") << script;
    std::string command = "cd " + quote(folder.string()) + " && ";
    if (!std::getenv("DISPLAY")) command += "xvfb-run -a -s '-screen 0 1280x800x24' ";
    // 640x360 and 0.05 s a frame keep it short; with 20 frames a simulated second against the
    // video's 30, the recorder has to repeat frames, as it does in an app slower than real time.
    command += prefix + std::string(SOFTBODY_EXE) + " run --size 640x360 --frame-time 0.05 --frames " + std::to_string(frames) +
               " --script test.script 2>stderr.txt";
    int status = -1;
    std::string out = shell(command, status);
    EXPECT_EQ(status, 0) << out;
    while (!out.empty() && out.back() == '\n') out.pop_back();
    const auto last_line = out.rfind('\n');
    const json summary = json::parse(last_line == std::string::npos ? out : out.substr(last_line + 1), nullptr, false);
    return summary.is_discarded() ? json::object() : summary;
}

std::vector<std::string> files_in(const fs::path& folder, const std::string& ending) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder)) {
        const std::string name = entry.path().filename().string();
        if (name.size() >= ending.size() && name.compare(name.size() - ending.size(), ending.size(), ending) == 0) names.push_back(name);
    }
    std::sort(names.begin(), names.end());
    return names;
}

bool has_ffmpeg() {
    int status = -1;
    shell("command -v ffmpeg >/dev/null && command -v ffprobe >/dev/null", status);
    return status == 0;
}

}  // namespace

TEST(Record, ButtonRecordsTheViewAtThirtyFramesPerSimulatedSecond) {
    if (!has_ffmpeg()) {
        const char* ci = std::getenv("CI");
        if (ci && std::string(ci) == "true") FAIL() << "ffmpeg is not installed; ./dev.sh installs it";
        GTEST_SKIP() << "ffmpeg is not installed (sudo apt install ffmpeg): the recording is not checked";
    }
    const fs::path folder = fresh_folder("video");
    // 0.05 s a frame: 19 frames playing after the first (0.95 s), 6 paused (nothing), 10
    // playing (0.5 s): 1.45 simulated seconds, 44 video frames give or take the tick (0.02 s)
    // the frames land on. Then the M key records a second, short clip, under a name of its own.
    const json summary = run_app(folder, 46,
                                 "0 record start\n"
                                 "20 pause\n"
                                 "26 play\n"
                                 "36 record stop\n"
                                 "38 key m\n"
                                 "42 key m\n");
    ASSERT_TRUE(summary.contains("recording")) << summary.dump();
    const std::vector<std::string> videos = files_in(folder, ".mp4");
    ASSERT_EQ(videos.size(), 2u) << "two recordings, two files";
    for (const std::string& name : videos) EXPECT_EQ(name.rfind("softbody-", 0), 0u) << name;

    // The summary tells of the last recording, the second: the first is the other file.
    const std::string second = fs::path(summary["recording"]["path"].get<std::string>()).filename().string();
    ASSERT_TRUE(second == videos.front() || second == videos.back()) << second;
    const std::string first = (folder / (second == videos.front() ? videos.back() : videos.front())).string();
    int status = -1;
    const std::string probed = shell("ffprobe -v error -select_streams v:0 -count_frames -show_entries "
                                     "stream=codec_name,width,height,nb_read_frames,avg_frame_rate -of json " + quote(first), status);
    ASSERT_EQ(status, 0) << probed;
    const json stream = json::parse(probed)["streams"][0];
    EXPECT_EQ(stream["codec_name"], "h264");
    EXPECT_EQ(stream["avg_frame_rate"], "30/1");
    // The view right of the panel (376 px of 640), as even sides.
    EXPECT_EQ(stream["width"], 264);
    EXPECT_EQ(stream["height"], 360);
    const int frames = std::stoi(stream["nb_read_frames"].get<std::string>());
    EXPECT_GE(frames, 42);
    EXPECT_LE(frames, 46);
    EXPECT_TRUE(summary["recording"]["video"].get<bool>());
    EXPECT_LE(summary["recording"]["frames"].get<int>(), 8);
    EXPECT_EQ(summary["error"], "");
    remove_scratch_if_passed();
}

TEST(Record, WithoutFfmpegTheFramesArePngsAndTheAppSaysSo) {
    const fs::path folder = fresh_folder("frames");
    const fs::path nothing = fresh_folder("empty_path");
    const json summary = run_app(folder, 12, "0 record start clip.mp4\n10 record stop\n", "env PATH=" + quote(nothing.string()) + " ");
    ASSERT_TRUE(summary.contains("recording")) << summary.dump();
    EXPECT_FALSE(summary["recording"]["video"].get<bool>());
    const std::string message = summary["recording"]["message"];
    EXPECT_NE(message.find("sudo apt install ffmpeg"), std::string::npos) << message;
    EXPECT_NE(message.find("clip_frames"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(folder / "clip.mp4"));
    const auto pngs = files_in(folder / "clip_frames", ".png");
    EXPECT_EQ(pngs.size(), summary["recording"]["frames"].get<std::size_t>());
    EXPECT_GE(pngs.size(), 12u);  // 9 frames of 0.05 s after the first: 0.45 simulated seconds
    EXPECT_EQ(summary["error"], "");
    remove_scratch_if_passed();
}
