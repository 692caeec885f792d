// `softbody render --video` from the outside: the clip it writes is a real H.264 video that
// ffprobe (Debian's ffmpeg package) reads frame by frame, with the frames and size asked for;
// without ffmpeg it says how to install it and leaves PNG frames instead; it never replaces a
// file unless told to; bad input is one line and exit 2.
//
// The tests that need ffmpeg skip with a message where it is missing, except in CI (CI=true),
// where a missing ffmpeg fails them: dev.sh installs it, so its absence there is a fault.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "child_process.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using softbody_test::describe;
using softbody_test::read_text;
using softbody_test::Result;
using softbody_test::run;
using softbody_test::run_program;
using softbody_test::TempDir;

const std::string kScene = std::string(SOFTBODY_ASSETS_DIR) + "/scenes/tetrahedron.json";

bool on_path(const std::string& program) {
    const char* path = std::getenv("PATH");
    if (!path) return false;
    std::string folders = path;
    for (std::size_t start = 0; start <= folders.size();) {
        std::size_t end = folders.find(':', start);
        if (end == std::string::npos) end = folders.size();
        const fs::path candidate = fs::path(folders.substr(start, end - start)) / program;
        if (end > start && ::access(candidate.c_str(), X_OK) == 0) return true;
        start = end + 1;
    }
    return false;
}

bool in_ci() {
    const char* ci = std::getenv("CI");
    return ci && std::string(ci) == "true";
}

#define REQUIRE_FFMPEG()                                                                                     \
    if (!on_path("ffmpeg") || !on_path("ffprobe")) {                                                         \
        if (in_ci()) FAIL() << "ffmpeg is not installed; ./dev.sh installs it (Debian package ffmpeg)";      \
        GTEST_SKIP() << "ffmpeg is not installed (sudo apt install ffmpeg): the video itself is not checked"; \
    }

// The test's environment with PATH pointing only at `folder`: softbody finds no ffmpeg.
std::vector<std::string> environment_without_ffmpeg(const fs::path& folder) {
    std::vector<std::string> env;
    for (char** entry = environ; *entry; ++entry) {
        if (std::string(*entry).rfind("PATH=", 0) != 0) env.emplace_back(*entry);
    }
    env.push_back("PATH=" + folder.string());
    return env;
}

// The video's first stream as ffprobe reads it, decoding every frame to count them.
json probe(const std::string& file) {
    const Result r = run_program("ffprobe", {"-v", "error", "-select_streams", "v:0", "-count_frames", "-show_entries",
                                             "stream=codec_name,pix_fmt,width,height,nb_read_frames,avg_frame_rate",
                                             "-of", "json", file});
    EXPECT_EQ(r.exit_code, 0) << describe(r);
    const json out = json::parse(r.out, nullptr, false);
    if (out.is_discarded() || !out.contains("streams") || out["streams"].empty()) {
        ADD_FAILURE() << "ffprobe found no video stream in " << file << ": " << describe(r);
        return json::object();
    }
    return out["streams"][0];
}

std::vector<std::string> files_in(const fs::path& folder) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// A bad-input run: exit 2, nothing on stdout, one line on stderr naming the problem.
void expect_refused(const std::vector<std::string>& args, const std::string& says) {
    std::string command;
    for (const auto& arg : args) command += " " + arg;
    SCOPED_TRACE("softbody" + command);
    const Result r = run(args);
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_EQ(r.out, "") << describe(r);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr is not one line:\n" << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << "stderr lacks '" << says << "': " << r.err;
}

TEST(Video, WritesAPlayableH264FileWithTheFramesAndSizeAskedFor) {
    REQUIRE_FFMPEG();
    TempDir dir;
    const std::string video = dir.file("out.mp4");
    const Result r = run({"render", "--scene", kScene, "--video", video, "--frames", "30", "--fps", "30", "--size", "320x240"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(r.err, "");
    const json line = json::parse(r.out, nullptr, false);
    ASSERT_FALSE(line.is_discarded()) << r.out;
    EXPECT_EQ(line["video"], video);
    EXPECT_EQ(line["frames"], 30);
    EXPECT_DOUBLE_EQ(line["seconds"].get<double>(), 1.0);

    const json stream = probe(video);
    EXPECT_EQ(stream.value("codec_name", ""), "h264");
    EXPECT_EQ(stream.value("pix_fmt", ""), "yuv420p");  // what every player reads
    EXPECT_EQ(stream.value("width", 0), 320);
    EXPECT_EQ(stream.value("height", 0), 240);
    EXPECT_EQ(stream.value("nb_read_frames", ""), "30");  // every frame decodes
    EXPECT_EQ(stream.value("avg_frame_rate", ""), "30/1");
    // Nothing else is left beside it (ffmpeg's partial file took the name).
    EXPECT_EQ(files_in(dir.path()), std::vector<std::string>{"out.mp4"});
}

TEST(Video, SecondsGiveTheFramesOfThatLong) {
    // Frames at 0, 1/F, ... before T: 0.5 s at 30 a second is 15 frames (counted without ffmpeg too).
    TempDir dir, empty;
    const auto env = environment_without_ffmpeg(empty.path());
    const Result r = run({"render", "--scene", kScene, "--video", dir.file("half.mp4"), "--seconds", "0.5", "--fps", "30",
                          "--size", "64x48"}, &env);
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(json::parse(r.out)["frames"], 15);
}

TEST(Video, WithoutFfmpegSaysHowToInstallItAndWritesThePngFrames) {
    TempDir dir, empty;
    const auto env = environment_without_ffmpeg(empty.path());
    const std::string video = dir.file("clip.mp4");
    const Result r = run({"render", "--scene", kScene, "--video", video, "--frames", "12", "--fps", "30", "--size", "64x48"}, &env);
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    // One line: what is missing, how to get it, and where the frames went.
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("ffmpeg was not found"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("sudo apt install ffmpeg"), std::string::npos) << r.err;
    const fs::path frames = dir.path() / "clip_frames";
    EXPECT_NE(r.err.find(frames.string()), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(video));
    ASSERT_TRUE(fs::is_directory(frames));
    const auto names = files_in(frames);
    ASSERT_EQ(names.size(), 12u);
    EXPECT_EQ(names.front(), "clip_00000.png");
    EXPECT_EQ(names.back(), "clip_00011.png");
    const json line = json::parse(r.out);
    EXPECT_TRUE(line["video"].is_null());
    EXPECT_EQ(line["frames_folder"], frames.string());
    EXPECT_EQ(line["frames"], 12);

    // Again: the frames folder is not overwritten either.
    const Result again = run({"render", "--scene", kScene, "--video", video, "--frames", "3", "--size", "64x48"}, &env);
    EXPECT_EQ(again.exit_code, 2) << describe(again);
    EXPECT_NE(again.err.find("already exists"), std::string::npos) << again.err;
    EXPECT_EQ(files_in(frames).size(), 12u);
}

TEST(Video, NeverReplacesAnExistingFileUnlessToldTo) {
    TempDir dir;
    const std::string video = dir.write("taken.mp4", "the teacher's own clip");
    expect_refused({"render", "--scene", kScene, "--video", video, "--frames", "3", "--size", "64x48"}, "already exists");
    EXPECT_EQ(read_text(video), "the teacher's own clip");

    REQUIRE_FFMPEG();
    const Result r = run({"render", "--scene", kScene, "--video", video, "--frames", "3", "--size", "64x48", "--overwrite"});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(probe(video).value("nb_read_frames", ""), "3");
}

TEST(Video, BadInputIsOneLineAndExitTwo) {
    TempDir dir;
    const std::string video = dir.file("v.mp4");
    expect_refused({"render", "--scene", kScene, "--video", dir.file("v.avi"), "--frames", "3"}, "ending in .mp4");
    expect_refused({"render", "--scene", kScene, "--video", video, "--at", "0.5"}, "--video needs --frames N or --seconds T");
    expect_refused({"render", "--scene", kScene, "--video", video, "--frames", "3", "--out", dir.file("pngs")},
                   "give one or the other");
    expect_refused({"render", "--scene", kScene, "--video", video, "--frames", "3", "--size", "65x48"}, "even sides");
    expect_refused({"render", "--scene", kScene, "--video", video, "--frames", "3", "--seconds", "1"}, "--seconds");
    expect_refused({"render", "--scene", kScene, "--frames", "3", "--out", dir.file("pngs"), "--overwrite"},
                   "--overwrite goes with --video");
    expect_refused({"render", "--scene", kScene, "--video", dir.path().string() + "/", "--frames", "3"}, "ending in .mp4");
    EXPECT_FALSE(fs::exists(video));
}

}  // namespace
