// The app's Record button: the 3D view into a video (video.h), at a fixed rate of simulated
// time, so the clip plays at the true speed of the physics however fast the app draws.
//
// - What: the 3D view as the renderer drew it, without the panels and the help drawn over it,
//   and without the part of it the panel covered when recording began (the body is framed in
//   the rest). The size is fixed when recording begins; a resized window is cut or padded.
// - When: a video frame for every 1/30 s of simulated time. A slow app (fewer frames than that)
//   shows a frame more than once; a fast one, or slow motion, skips frames; either way one
//   second of the clip is one simulated second. While paused no simulated time passes, so
//   nothing is recorded: the clip goes on from where it was when the simulation plays again
//   (a single tick adds its 0.02 s). A reset, another scene or a step back on the timeline is
//   a cut: the clip goes on from there.
// - Where: softbody-YYYYMMDD-HHMMSS.mp4 in the current folder (-2, -3, ... when taken), never
//   replacing a file; without ffmpeg the frames are PNGs in softbody-..._frames/ instead.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>

namespace softbody::render {
class Renderer;
}

namespace softbody::app {

class VideoWriter;

// How a finished recording went, for the panel and the app's summary.
struct RecordingResult {
    std::string path;         // the video, or without ffmpeg the folder of PNG frames
    bool video = true;        // false: ffmpeg was missing and the frames are PNGs
    std::size_t frames = 0;
    std::string message;      // one line for the panel
};

class Recorder {
public:
    static constexpr double kFps = 30.0;  // video frames per simulated second

    Recorder();
    ~Recorder();

    // The button, the key and the script ask here; it happens at the next frame().
    void toggle() { wanted_ = !wanted_; }
    void start(std::string path = {}) {  // path empty: softbody-<date>-<time>.mp4 here
        wanted_ = true;
        wanted_path_ = std::move(path);
    }
    void stop() { wanted_ = false; }

    // Once a frame, after the 3D view is drawn and before the UI goes over it: starts or stops
    // as asked, and adds as many frames as the simulated time since the last one calls for.
    // crop_left: pixels on the left the panel covers. sim_time: the world's time, s.
    void frame(const render::Renderer& renderer, int crop_left, double sim_time);
    // Ends a recording now (when the app closes).
    void finish();

    bool recording() const { return writer_ != nullptr; }
    std::size_t frames() const;
    double seconds() const { return double(frames()) / kFps; }
    const std::optional<RecordingResult>& last() const { return last_; }
    // A failure to show as the app's error (ffmpeg failed, no file could be made), taken once.
    std::string take_error() { return std::exchange(error_, {}); }

private:
    void begin(const render::Renderer& renderer, int crop_left, double sim_time);

    bool wanted_ = false;
    std::string wanted_path_;
    std::unique_ptr<VideoWriter> writer_;
    int crop_left_ = 0;
    double last_time_ = 0.0;  // the world's time at the previous frame()
    double elapsed_ = 0.0;    // simulated seconds recorded since the start
    std::optional<RecordingResult> last_;
    std::string error_;
};

// The Simulation panel's row: the Record / Stop button and what the recording is doing.
// paused: no simulated time passes (paused or diverged), so the recording waits.
void recorder_controls(Recorder& recorder, bool paused, float ui_scale);

}  // namespace softbody::app
