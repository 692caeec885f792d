#include "gui/recorder.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <filesystem>

#include "physics/error.h"
#include "render/renderer.h"
#include "video.h"

namespace softbody::app {

namespace {

namespace fs = std::filesystem;

// softbody-YYYYMMDD-HHMMSS.mp4 in the current folder, or -2, -3, ... after it when that name (or,
// without ffmpeg, its frames folder) is taken: a recording never replaces anything.
std::string free_name() {
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "softbody-%Y%m%d-%H%M%S", &local);
    for (int n = 1;; ++n) {
        const std::string stem = n == 1 ? std::string(stamp) : std::string(stamp) + "-" + std::to_string(n);
        std::error_code ec;
        if (!fs::exists(fs::symlink_status(stem + ".mp4", ec)) && !fs::exists(fs::symlink_status(stem + "_frames", ec))) {
            return stem + ".mp4";
        }
    }
}

}  // namespace

Recorder::Recorder() = default;
Recorder::~Recorder() = default;  // an unfinished video is abandoned by its writer

std::size_t Recorder::frames() const { return writer_ ? writer_->frames() : 0; }

void Recorder::begin(const render::Renderer& renderer, int crop_left, double sim_time) {
    const render::Image view = renderer.read_back();
    // The part of the view right of the panel, cut to even sides for H.264.
    crop_left_ = std::clamp(crop_left, 0, std::max(0, view.width - 2));
    const int width = (view.width - crop_left_) & ~1, height = view.height & ~1;
    const std::string path = wanted_path_.empty() ? free_name() : wanted_path_;
    try {
        writer_ = std::make_unique<VideoWriter>(path, width, height, kFps, false);
    } catch (const std::exception& e) {
        wanted_ = false;
        error_ = std::string("cannot record: ") + e.what();
        return;
    }
    last_time_ = sim_time;
    elapsed_ = 0.0;
    last_.reset();
}

void Recorder::frame(const render::Renderer& renderer, int crop_left, double sim_time) {
    if (wanted_ && !writer_) begin(renderer, crop_left, sim_time);
    if (!wanted_ && writer_) finish();
    if (!writer_) return;

    // Simulated time since the last frame. Going back (a reset, another scene) or leaping more
    // than a second ahead is a cut: the clip goes on from the new state without a gap.
    const double step = sim_time - last_time_;
    last_time_ = sim_time;
    if (step > 0.0 && step <= 1.0) elapsed_ += step;
    // Frame k shows simulated time k / kFps after the start: frames 0 .. floor(elapsed * kFps).
    const auto due = static_cast<std::size_t>(std::floor(elapsed_ * kFps + 1e-6)) + 1;
    if (writer_->frames() >= due) return;

    const render::Image view = renderer.read_back();
    render::Image clip(writer_->width(), writer_->height());  // black where a smaller window leaves a gap
    const int columns = std::max(0, std::min(clip.width, view.width - crop_left_));
    for (int y = 0; y < std::min(clip.height, view.height); ++y) {
        if (columns > 0) std::copy_n(view.pixel(crop_left_, y), std::size_t(columns) * 4, clip.pixel(0, y));
    }
    for (std::size_t i = 3; i < clip.rgba.size(); i += 4) clip.rgba[i] = 255;
    try {
        while (writer_->frames() < due) writer_->write(clip);
    } catch (const std::exception& e) {
        error_ = std::string("recording stopped: ") + e.what();
        writer_.reset();  // abandons the partial file
        wanted_ = false;
    }
}

void Recorder::finish() {
    wanted_ = false;
    if (!writer_) return;
    RecordingResult result;
    result.video = writer_->has_ffmpeg();
    result.frames = writer_->frames();
    std::error_code ec;
    try {
        writer_->finish();
        const fs::path where = result.video ? fs::path(writer_->path()) : fs::path(writer_->frames_folder());
        result.path = fs::absolute(where, ec).lexically_normal().string();
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%.1f s", double(result.frames) / kFps);
        result.message = result.video ? "saved " + result.path + " (" + std::to_string(result.frames) + " frames, " + seconds + ")"
                                      : writer_->missing_ffmpeg_message();
        last_ = result;
    } catch (const std::exception& e) {
        error_ = std::string("recording failed: ") + e.what();
    }
    writer_.reset();
}

void recorder_controls(Recorder& recorder, bool paused, float ui_scale) {
    const bool on = recorder.recording();
    if (on) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.70f, 0.15f, 0.15f, 1.0f));
    if (ImGui::Button(on ? "Stop" : "Record", ImVec2(100 * ui_scale, 0))) recorder.toggle();
    if (on) ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) {
#if defined(__EMSCRIPTEN__)  // the browser's recorder (app/web/video_browser.cpp)
        ImGui::SetTooltip("M: the 3D view into softbody-<date>-<time>.webm, downloaded when you stop, %.0f frames\n"
                          "per simulated second. While paused nothing is recorded.", Recorder::kFps);
#else
        ImGui::SetTooltip("M: the 3D view into softbody-<date>-<time>.mp4 in the current folder, %.0f frames per\n"
                          "simulated second, so the clip plays at true speed (needs ffmpeg: sudo apt install ffmpeg).\n"
                          "While paused nothing is recorded.", Recorder::kFps);
#endif
    }
    if (on) {
        ImGui::SameLine();
        ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.40f, 1.0f), "recording... %zu frames", recorder.frames());
        ImGui::TextDisabled("%.1f s simulated%s", recorder.seconds(), paused ? " (paused: waiting)" : "");
    } else if (const auto& last = recorder.last()) {
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextDisabled("%s", last->message.c_str());
        ImGui::PopTextWrapPos();
    }
}

}  // namespace softbody::app
