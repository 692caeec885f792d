// Writing a video: frames go to ffmpeg (Debian's package `ffmpeg`, looked for on PATH when the
// video starts, not at build time), which makes an H.264 MP4 that slides and browsers play.
//
//   VideoWriter video("clip.mp4", 800, 600, 30.0, false);   // refuses an existing clip.mp4
//   for (...) video.write(image);                            // RGBA, top row first
//   video.finish();                                          // clip.mp4 appears only now
//
// How: ffmpeg runs as a child process, started directly (no shell, so no file name is ever
// read as a command), reading raw RGB frames on its standard input at a fixed frame rate.
// It writes into a hidden file beside the target; finish() waits for it and only then gives
// the file its name, without replacing an existing file unless asked to. A video that fails
// or is abandoned leaves nothing behind.
//
// Without ffmpeg the frames become PNG files in a folder beside the target instead (named in
// missing_ffmpeg_message()), so a recording is never lost.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <sys/types.h>
#include <vector>

#include "render/image.h"

namespace softbody::app {

// ffmpeg failed or stopped: the message is one line with its exit status and its last words.
struct VideoError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The full path of the program `name` in one of PATH's folders, or "" when it is in none.
std::string find_program(std::string_view name);

class VideoWriter {
public:
    // Prepares `path` for a video of width x height pixels (both even: H.264 stores colour at
    // half resolution) at `fps` frames a second. Throws InputError (one line) when the file, or
    // without ffmpeg its frames folder, exists and `overwrite` is false, when the sizes are odd
    // or the folder cannot take files; VideoError when ffmpeg is there but will not start.
    VideoWriter(const std::string& path, int width, int height, double fps, bool overwrite);
    // An unfinished video is abandoned: ffmpeg is stopped and its partial file removed.
    ~VideoWriter();
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;

    bool has_ffmpeg() const { return frames_folder_.empty(); }
    const std::string& path() const { return path_; }
    const std::string& frames_folder() const { return frames_folder_; }  // the PNGs' folder without ffmpeg
    // "ffmpeg was not found ...: install it ...; the frames are PNGs in <folder> instead".
    std::string missing_ffmpeg_message() const;
    std::size_t frames() const { return frames_; }
    int width() const { return width_; }
    int height() const { return height_; }

    // Adds one frame (the writer's size, top row first; alpha is dropped). Throws VideoError
    // when ffmpeg has stopped (with its message), std::runtime_error when a PNG cannot be written.
    void write(const render::Image& image);
    // Ends the video: ffmpeg finishes the file, which then takes its name. Throws VideoError
    // when ffmpeg reports a failure, InputError when the name was taken meanwhile.
    void finish();

private:
    void start_ffmpeg(const std::string& program);
    int wait_for_ffmpeg();                 // closes its input, returns its wait status
    std::string ffmpeg_failure(int status) const;  // the one-line message for a wait status
    void abandon();

    std::string path_;
    int width_, height_;
    double fps_;
    bool overwrite_;
    std::string frames_folder_;  // without ffmpeg
    std::string frame_stem_;     // file names in it: <stem>_00000.png
    std::string partial_;        // with ffmpeg: the hidden file it writes into
    pid_t child_ = -1;
    int input_ = -1;             // the pipe to ffmpeg's standard input
    int messages_ = -1;          // a temporary file holding ffmpeg's standard error
    bool finished_ = false;
    std::size_t frames_ = 0;
    std::vector<unsigned char> rgb_;  // one frame without alpha, reused
};

}  // namespace softbody::app
