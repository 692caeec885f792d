#include "video.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "physics/error.h"

extern char** environ;

namespace softbody::app {

namespace fs = std::filesystem;

namespace {

std::string errno_text() { return std::strerror(errno); }

// A number as ffmpeg reads it: 30, 29.97, 12.5.
std::string number_text(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

// The last line of text that is not blank, without its line end.
std::string last_line(const std::string& text) {
    std::size_t end = text.find_last_not_of(" \t\r\n");
    if (end == std::string::npos) return "";
    const std::size_t start = text.find_last_of('\n', end);
    return text.substr(start == std::string::npos ? 0 : start + 1, end - (start == std::string::npos ? 0 : start + 1) + 1);
}

// Everything written to the file behind fd so far.
std::string read_all(int fd) {
    std::string text;
    if (fd < 0 || ::lseek(fd, 0, SEEK_SET) < 0) return text;
    char buffer[4096];
    for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) != 0;) {
        if (n < 0) {
            if (errno == EINTR) continue;
            break;
        }
        text.append(buffer, static_cast<std::size_t>(n));
    }
    return text;
}

}  // namespace

std::string find_program(std::string_view name) {
    const char* path = std::getenv("PATH");
    if (!path) return "";
    const std::string_view folders(path);
    std::size_t start = 0;
    while (start <= folders.size()) {
        std::size_t end = folders.find(':', start);
        if (end == std::string_view::npos) end = folders.size();
        // An empty entry means the current folder (a shell's rule); it is not searched here, so
        // that a program lying in whatever folder the app was started from is never run.
        const std::string_view folder = folders.substr(start, end - start);
        if (!folder.empty()) {
            const std::string candidate = std::string(folder) + "/" + std::string(name);
            struct stat info {};
            if (::stat(candidate.c_str(), &info) == 0 && S_ISREG(info.st_mode) && ::access(candidate.c_str(), X_OK) == 0) {
                return candidate;
            }
        }
        start = end + 1;
    }
    return "";
}

VideoWriter::VideoWriter(const std::string& path, int width, int height, double fps, bool overwrite)
    : path_(path), width_(width), height_(height), fps_(fps), overwrite_(overwrite) {
    if (path.empty()) throw InputError("the video needs a file name");
    if (width < 2 || height < 2 || width % 2 != 0 || height % 2 != 0) {
        throw InputError("video size " + std::to_string(width) + "x" + std::to_string(height) +
                         ": both sides must be even (H.264 stores colour at half resolution)");
    }
    if (!(fps > 0.0)) throw InputError("video frame rate " + number_text(fps) + ": must be above 0");
    const fs::path target(path);
    std::error_code ec;
    if (fs::is_directory(target, ec)) throw InputError(path + ": is a folder; choose a file name");
    if (!overwrite && fs::exists(fs::symlink_status(target, ec))) {
        throw InputError(path + ": already exists; not overwriting it");
    }
    fs::path folder = target.parent_path();
    if (folder.empty()) folder = ".";
    fs::create_directories(folder, ec);
    if (!fs::is_directory(folder, ec)) throw InputError(path + ": cannot create its folder " + folder.string());

    const std::string program = find_program("ffmpeg");
    if (program.empty()) {
        // No ffmpeg: the frames as PNGs in <name>_frames/ beside the video that was asked for.
        frame_stem_ = target.stem().string();
        frames_folder_ = (folder / (frame_stem_ + "_frames")).string();
        if (!overwrite && fs::exists(fs::symlink_status(frames_folder_, ec))) {
            throw InputError(frames_folder_ + ": already exists; not overwriting the frames in it (without ffmpeg "
                             "the frames would go there)");
        }
        fs::create_directories(frames_folder_, ec);
        if (ec || !fs::is_directory(frames_folder_)) {
            throw InputError(frames_folder_ + ": cannot create the folder for the frames (" +
                             (ec ? ec.message() : std::string("a file of that name exists")) + ")");
        }
        return;
    }
    start_ffmpeg(program);
}

void VideoWriter::start_ffmpeg(const std::string& program) {
    const fs::path target(path_);
    fs::path folder = target.parent_path();
    if (folder.empty()) folder = ".";
    // ffmpeg writes into a hidden file beside the target (a rename cannot cross file systems).
    std::string partial = (folder / ("." + target.filename().string().substr(0, 200) + ".XXXXXX")).string();
    const int partial_fd = ::mkostemp(partial.data(), O_CLOEXEC);
    if (partial_fd < 0) throw InputError(path_ + ": cannot create a file in " + folder.string() + " (" + errno_text() + ")");
    ::fchmod(partial_fd, 0644);  // a new video is readable by all, as a new file usually is
    ::close(partial_fd);
    partial_ = partial;

    // ffmpeg's messages go to a temporary file (a pipe could fill up and stall it), read at the end.
    std::string messages = (fs::temp_directory_path() / "softbody-ffmpeg.XXXXXX").string();
    messages_ = ::mkostemp(messages.data(), O_CLOEXEC);
    if (messages_ < 0) {
        ::unlink(partial_.c_str());
        throw VideoError("cannot create a temporary file for ffmpeg's messages (" + errno_text() + ")");
    }
    ::unlink(messages.c_str());  // gone from the folder; the open descriptor keeps it readable

    int pipe_ends[2];
    if (::pipe2(pipe_ends, O_CLOEXEC) != 0) {
        ::unlink(partial_.c_str());
        throw VideoError("cannot make a pipe to ffmpeg (" + errno_text() + ")");
    }
    // Writing to a pipe whose reader has stopped raises SIGPIPE, which would end the whole
    // program; ignored, the write fails with EPIPE instead and ffmpeg's own message is shown.
    std::signal(SIGPIPE, SIG_IGN);

    // Raw RGB frames on standard input at the fixed rate; H.264 in yuv420p, which every player
    // reads; the file's index at its start (+faststart) so it plays while it loads. "file:"
    // makes ffmpeg take the name as a plain file name whatever characters it holds.
    const std::string size = std::to_string(width_) + "x" + std::to_string(height_);
    std::vector<std::string> args = {
        program, "-hide_banner", "-loglevel", "error", "-nostats",
        "-f", "rawvideo", "-pixel_format", "rgb24", "-video_size", size, "-framerate", number_text(fps_), "-i", "pipe:0",
        "-an", "-c:v", "libx264", "-preset", "veryfast", "-crf", "20", "-pix_fmt", "yuv420p",
        "-movflags", "+faststart", "-f", "mp4", "-y", "file:" + fs::absolute(partial_).string(),
    };
    std::vector<char*> argv;
    for (std::string& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, pipe_ends[0], 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, messages_, 2);
    const int spawned = ::posix_spawn(&child_, program.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(pipe_ends[0]);
    if (spawned != 0) {
        child_ = -1;
        ::close(pipe_ends[1]);
        ::unlink(partial_.c_str());
        throw VideoError("cannot start " + program + " (" + std::strerror(spawned) + ")");
    }
    input_ = pipe_ends[1];
    rgb_.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 3);
}

VideoWriter::~VideoWriter() { abandon(); }

void VideoWriter::abandon() {
    if (child_ > 0) {
        ::kill(child_, SIGKILL);
        wait_for_ffmpeg();
        ::unlink(partial_.c_str());
    }
    if (messages_ >= 0) ::close(messages_);
    messages_ = -1;
}

std::string VideoWriter::missing_ffmpeg_message() const {
    return "ffmpeg was not found on PATH, so " + path_ + " was not made: install it with 'sudo apt install ffmpeg'; "
           "the frames are PNG files in " + frames_folder_ + "/ instead";
}

void VideoWriter::write(const render::Image& image) {
    if (image.width != width_ || image.height != height_) {
        throw VideoError("a frame of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                         " for a video of " + std::to_string(width_) + "x" + std::to_string(height_));
    }
    if (finished_) throw VideoError(path_ + ": the video is already finished");
    if (!has_ffmpeg()) {
        // Five digits or more, so that name order is frame order (past 99,999 frames: 55 minutes at 30 a second).
        char name[32];
        std::snprintf(name, sizeof name, "_%05zu.png", frames_);
        render::write_png(frames_folder_ + "/" + frame_stem_ + name, image);
        ++frames_;
        return;
    }
    if (child_ <= 0) throw VideoError(path_ + ": ffmpeg has already stopped");
    const std::size_t pixels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
    for (std::size_t i = 0; i < pixels; ++i) std::copy_n(&image.rgba[4 * i], 3, &rgb_[3 * i]);
    std::size_t written = 0;
    while (written < rgb_.size()) {
        const ssize_t n = ::write(input_, rgb_.data() + written, rgb_.size() - written);
        if (n < 0) {
            if (errno == EINTR) continue;
            // ffmpeg stopped reading: it has failed; its exit status and message say why.
            const int status = wait_for_ffmpeg();
            ::unlink(partial_.c_str());
            throw VideoError(ffmpeg_failure(status));
        }
        written += static_cast<std::size_t>(n);
    }
    ++frames_;
}

int VideoWriter::wait_for_ffmpeg() {
    if (input_ >= 0) ::close(input_);  // the end of its input: ffmpeg finishes the file and exits
    input_ = -1;
    int status = 0;
    if (child_ <= 0) return status;
    while (::waitpid(child_, &status, 0) < 0 && errno == EINTR) {
    }
    child_ = -1;
    return status;
}

std::string VideoWriter::ffmpeg_failure(int status) const {
    std::string how = WIFEXITED(status)   ? "exit status " + std::to_string(WEXITSTATUS(status))
                      : WIFSIGNALED(status) ? "stopped by signal " + std::to_string(WTERMSIG(status))
                                            : "stopped";
    std::string said = last_line(read_all(messages_));
    std::replace(said.begin(), said.end(), '\r', ' ');
    return "ffmpeg failed (" + how + ") writing " + path_ + (said.empty() ? "" : ": " + said);
}

void VideoWriter::finish() {
    if (finished_) return;
    finished_ = true;
    if (!has_ffmpeg()) return;  // PNG frames: each is complete as it is written
    if (child_ <= 0) throw VideoError(path_ + ": ffmpeg has already stopped");
    const int status = wait_for_ffmpeg();
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        ::unlink(partial_.c_str());
        throw VideoError(ffmpeg_failure(status));
    }
    // The finished file takes its name. link() refuses to replace an existing name, so a file
    // made meanwhile under that name is never lost; rename() replaces it when asked to.
    if (overwrite_) {
        if (::rename(partial_.c_str(), path_.c_str()) != 0) {
            const std::string why = errno_text();
            ::unlink(partial_.c_str());
            throw VideoError(path_ + ": cannot save the video (" + why + ")");
        }
        return;
    }
    int linked = ::link(partial_.c_str(), path_.c_str());
    std::error_code ec;
    if (linked != 0 && (errno == EPERM || errno == EOPNOTSUPP) && !fs::exists(fs::symlink_status(path_, ec))) {
        // A file system without hard links (a FAT memory stick): checked, then renamed.
        linked = ::rename(partial_.c_str(), path_.c_str());
        if (linked == 0) return;
    }
    if (linked != 0) {
        if (errno == EEXIST) {
            throw InputError(path_ + ": was made by something else while recording; not overwriting it (the video is "
                             "in " + partial_ + ")");
        }
        const std::string why = errno_text();
        ::unlink(partial_.c_str());
        throw VideoError(path_ + ": cannot save the video (" + why + ")");
    }
    ::unlink(partial_.c_str());
}

}  // namespace softbody::app
