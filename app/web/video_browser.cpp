// video.h in the browser build: there is no ffmpeg and no file system the user sees, so a video
// is the browser's own recorder (MediaRecorder) on a canvas of the video's size, and the finished
// clip, WebM, is handed to the browser as a download named after the file that was asked for
// (softbody-YYYYMMDD-HHMMSS.webm). The Record button, the M key and the script's `record`
// behave as on the desktop (gui/recorder.h): the same frames, one per 1/30 s of simulated time.
//
// MediaRecorder stamps frames with the wall clock, not with a rate. So each frame is held on
// the canvas for 1/fps s of recording time and the recorder is paused between frames: a clip
// still plays at the simulation's true speed, a pause leaves no gap, and frames that come faster
// than that wait in a queue (up to three seconds of them; beyond, the last one is held longer).
// finish() returns at once: the download starts when the queue has played out.
#include <emscripten.h>

#include <filesystem>
#include <string>

#include "physics/error.h"
#include "video.h"

namespace softbody::app {

namespace {

// The page side, one recorder per handle, recording a canvas that is not in the page. Its pump
// shows the queued frames one after another, each for frameMs of recording, pauses the recorder
// when the queue is empty, and stops it (which downloads the clip) once finishing.
// clang-format off
EM_JS(int, recorder_open, (int width, int height, double fps, const char* name), {
    if (typeof MediaRecorder === 'undefined' || !HTMLCanvasElement.prototype.captureStream) return 0;
    var types = ['video/webm;codecs=vp9', 'video/webm;codecs=vp8', 'video/webm'];
    var type = types.find(function(t) { return MediaRecorder.isTypeSupported(t); });
    if (!type) return 0;
    var canvas = document.createElement('canvas');
    canvas.width = width;
    canvas.height = height;
    var stream = canvas.captureStream(0);
    var rec = {
        context: canvas.getContext('2d'), track: stream.getVideoTracks()[0], chunks: [],
        recorder: new MediaRecorder(stream, {mimeType: type, videoBitsPerSecond: 8e6}),
        name: UTF8ToString(name), frameMs: 1000 / fps, queue: [], busy: false, finishing: false, abandoned: false
    };
    rec.pump = function() {
        if (rec.queue.length === 0) {
            rec.busy = false;
            if (rec.recorder.state === 'recording') rec.recorder.pause();
            if (rec.finishing && rec.recorder.state !== 'inactive') rec.recorder.stop();
            return;
        }
        rec.busy = true;
        var frame = rec.queue.shift();
        rec.context.putImageData(frame.image, 0, 0);
        if (rec.recorder.state === 'paused') rec.recorder.resume();
        rec.track.requestFrame();
        setTimeout(rec.pump, rec.frameMs * frame.holds);
    };
    rec.recorder.ondataavailable = function(event) { if (event.data.size > 0) rec.chunks.push(event.data); };
    rec.recorder.onstop = function() {
        if (rec.abandoned) return;
        var link = document.createElement('a');
        link.href = URL.createObjectURL(new Blob(rec.chunks, {type: 'video/webm'}));
        link.download = rec.name;
        document.body.appendChild(link);
        link.click();
        link.remove();
        setTimeout(function() { URL.revokeObjectURL(link.href); }, 60000);
    };
    rec.recorder.start();
    rec.recorder.pause();  // until the first frame
    var handles = Module['softbodyRecorders'] = Module['softbodyRecorders'] || [null];
    handles.push(rec);
    return handles.length - 1;
});

// A copy of the RGBA pixels (a page with threads has shared memory, which ImageData refuses);
// beyond three seconds of queued frames, the last one is held longer instead.
EM_JS(void, recorder_write, (int handle, const unsigned char* rgba, int width, int height), {
    var rec = Module['softbodyRecorders'][handle];
    if (rec.queue.length >= 3 * 1000 / rec.frameMs) {
        rec.queue[rec.queue.length - 1].holds++;
    } else {
        var pixels = new Uint8ClampedArray(HEAPU8.slice(rgba, rgba + width * height * 4).buffer);
        rec.queue.push({image: new ImageData(pixels, width, height), holds: 1});
    }
    if (!rec.busy) rec.pump();
});

// keep: play out the queue, then download; otherwise drop everything.
EM_JS(void, recorder_close, (int handle, int keep), {
    var rec = Module['softbodyRecorders'][handle];
    Module['softbodyRecorders'][handle] = null;
    if (keep) {
        rec.finishing = true;
        if (!rec.busy) rec.pump();
    } else {
        rec.abandoned = true;
        rec.queue = [];
        if (rec.recorder.state !== 'inactive') rec.recorder.stop();
    }
});
// clang-format on

}  // namespace

std::string find_program(std::string_view) { return ""; }  // a page runs no programs

// input_ holds the page's handle of the recorder (the desktop's pipe to ffmpeg).
VideoWriter::VideoWriter(const std::string& path, int width, int height, double fps, bool overwrite)
    : path_(std::filesystem::path(path).replace_extension(".webm").string()), width_(width), height_(height), fps_(fps),
      overwrite_(overwrite) {
    if (path.empty()) throw InputError("the video needs a file name");
    if (width < 2 || height < 2) throw InputError("video size " + std::to_string(width) + "x" + std::to_string(height) + ": too small");
    if (!(fps > 0.0)) throw InputError("video frame rate must be above 0");
    input_ = recorder_open(width, height, fps, std::filesystem::path(path_).filename().string().c_str());
    if (input_ <= 0) throw VideoError("this browser cannot record a canvas as WebM (MediaRecorder)");
}

VideoWriter::~VideoWriter() {
    if (!finished_ && input_ > 0) recorder_close(input_, 0);  // abandoned: nothing is downloaded
}

std::string VideoWriter::missing_ffmpeg_message() const { return ""; }

void VideoWriter::write(const render::Image& image) {
    recorder_write(input_, image.rgba.data(), image.width, image.height);
    ++frames_;
}

void VideoWriter::finish() {
    if (finished_) return;
    finished_ = true;
    recorder_close(input_, 1);
}

}  // namespace softbody::app
