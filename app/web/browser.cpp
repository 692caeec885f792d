#include "web/browser.h"

#include <emscripten.h>
#include <emscripten/html5.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <exception>
#include <filesystem>
#include <iostream>

#include "gui/asset_files.h"

namespace softbody::app::browser {

namespace {

// clang-format off

// The canvas's pixels: its laid-out size (fractions of a CSS pixel included) times the pixel
// ratio, and the page's GLFW window told that size directly, as its own resize would (its
// window and framebuffer sizes are both the canvas's pixels). Nonzero when the size changed.
EM_JS(int, fit_canvas_js, (GLFWwindow* id), {
    var canvas = Module["canvas"];
    if (!canvas) return 0;
    var rect = canvas.getBoundingClientRect();
    var ratio = window.devicePixelRatio || 1;
    var width = Math.round(rect.width * ratio), height = Math.round(rect.height * ratio);
    if (width <= 0 || height <= 0) return 0;
    var changed = 0;
    if (canvas.width != width || canvas.height != height) {
        canvas.width = width;
        canvas.height = height;
        canvas.widthNative = width;  // what the page's own resize code would restore
        canvas.heightNative = height;
        changed = 1;
    }
    var win = GLFW.WindowFromId(id);
    if (win && (win.width != width || win.height != height)) {
        win.width = width;
        win.height = height;
        GLFW.onWindowSizeChanged();
        GLFW.onFramebufferSizeChanged();
        changed = 1;
    }
    return changed;
});

EM_JS(double, pixel_ratio_js, (), { return window.devicePixelRatio || 1; });
EM_JS(int, touch_screen_js, (), {
    const coarse = window.matchMedia && window.matchMedia('(pointer: coarse)').matches;
    return (navigator.maxTouchPoints || 0) > 0 || coarse ? 1 : 0;
});

// Text from the page into buffer (size bytes); returns the bytes the whole text needs, without
// the terminating zero: the caller asks again with a larger buffer when that does not fit.
// what: 0 the page's address without its query, 1 the next file chosen ("" when none).
EM_JS(int, page_text, (int what, char* buffer, int size), {
    var text = "";
    if (what == 0) {
        text = location.origin + location.pathname;
    } else if (what == 1) {
        var chosen = Module["softbodyChosen"] || [];
        text = chosen.length ? chosen[0] : "";
        if (size > lengthBytesUTF8(text)) chosen.shift();
    }
    stringToUTF8(text, buffer, size);
    return lengthBytesUTF8(text);
});

// The clipboard: the asynchronous clipboard where there is one, else a selected text area
// copied the old way. A refusal is left for take_copy_failure().
EM_JS(void, copy_text_js, (const char* text_pointer), {
    var text = UTF8ToString(text_pointer);
    function old_way() {
        var area = document.createElement("textarea");
        area.value = text;
        area.setAttribute("readonly", "");
        area.style.position = "fixed";
        area.style.opacity = "0";
        document.body.appendChild(area);
        area.select();
        var ok = false;
        try { ok = document.execCommand("copy"); } catch (e) { ok = false; }
        area.remove();
        if (!ok) Module["softbodyCopyFailed"] = true;
    }
    Module["softbodyCopied"] = text;
    if (navigator.clipboard && navigator.clipboard.writeText) {
        navigator.clipboard.writeText(text).catch(old_way);
    } else {
        old_way();
    }
});

EM_JS(int, take_copy_failure_js, (), {
    var failed = !!Module["softbodyCopyFailed"];
    Module["softbodyCopyFailed"] = false;
    return failed ? 1 : 0;
});

// A download: the text as a file the browser saves (its downloads folder, or it asks where).
EM_JS(void, download_js, (const char* name, const char* text, const char* type), {
    var link = document.createElement("a");
    link.href = URL.createObjectURL(new Blob([UTF8ToString(text)], {type: UTF8ToString(type)}));
    link.download = UTF8ToString(name);
    document.body.appendChild(link);
    link.click();
    link.remove();
    setTimeout(function() { URL.revokeObjectURL(link.href); }, 60000);
});

// The file picker: each file chosen is written to /uploads in the page's file system and its
// path queued for take_chosen_files(). The input stays in the page (hidden) so that a script
// driving the page can find it.
EM_JS(void, choose_file_js, (const char* accept), {
    var input = document.getElementById("softbody-file");
    if (!input) {
        input = document.createElement("input");
        input.type = "file";
        input.id = "softbody-file";
        input.style.display = "none";
        document.body.appendChild(input);
        input.addEventListener("change", function() {
            var files = Array.from(input.files || []);
            input.value = "";
            files.forEach(function(file) {
                file.arrayBuffer().then(function(data) {
                    try { FS.mkdir("/uploads"); } catch (e) {}
                    var path = "/uploads/" + file.name.split("/").join("_");
                    FS.writeFile(path, new Uint8Array(data));
                    (Module["softbodyChosen"] = Module["softbodyChosen"] || []).push(path);
                });
            });
        });
    }
    input.accept = UTF8ToString(accept);
    input.click();
});

// The presets folder kept in the browser's storage (mounted by the page before the app
// starts); one save at a time, and one more after it when asked meanwhile.
EM_JS(void, store_presets_js, (), {
    if (!Module["softbodyPresetsMounted"]) return;
    var state = Module["softbodyStoring"] = Module["softbodyStoring"] || {busy: false, again: false};
    function store() {
        state.busy = true;
        FS.syncfs(false, function(error) {
            state.busy = false;
            if (error) console.warn("softbody: the presets could not be kept in this browser: " + error);
            if (state.again) {
                state.again = false;
                store();
            }
        });
    }
    if (state.busy) state.again = true;
    else store();
});

// clang-format on

std::string read_page_text(int what) {
    std::string text(256, '\0');
    int needed = page_text(what, text.data(), int(text.size()));
    if (needed >= int(text.size())) {
        text.assign(std::size_t(needed) + 1, '\0');
        needed = page_text(what, text.data(), int(text.size()));
    }
    text.resize(std::size_t(std::max(needed, 0)));
    return text;
}

std::function<void(int, int, float, float)>& touch_handler() {
    static std::function<void(int, int, float, float)> handler;
    return handler;
}
std::function<std::string()>& state_answer() {
    static std::function<std::string()> answer;
    return answer;
}

// What the presets folder holds, to notice a change (a preset saved by any tool).
std::string presets_signature() {
    std::string signature;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(presets_folder(), error)) {
        std::error_code e;
        signature += entry.path().filename().string() + ':' + std::to_string(entry.file_size(e)) + ':' +
                     std::to_string(static_cast<long long>(entry.last_write_time(e).time_since_epoch().count())) + '\n';
    }
    return signature;
}

void keep_presets_stored() {
    static int frames = 0;
    static std::string last = presets_signature();
    if (++frames % 30 != 0) return;  // about twice a second
    std::string now = presets_signature();
    if (now == last) return;
    last = std::move(now);
    store_presets_js();
}

void call_frame(void* argument) {
    auto* frame = static_cast<std::function<bool()>*>(argument);
    bool more = false;
    try {
        more = (*frame)();
        keep_presets_stored();
    } catch (const std::exception& e) {
        std::cerr << "softbody: " << e.what() << std::endl;
    }
    // Once over, the session is kept, not destroyed: the page goes on showing its last frame
    // (closing the window would take the canvas's picture with it).
    if (!more) emscripten_cancel_main_loop();
}

}  // namespace

void run_frames(std::function<bool()> frame) {
    // 0 frames a second: the browser's own rate (requestAnimationFrame). The loop is not
    // simulated as infinite, so this returns and the C++ stack unwinds normally.
    emscripten_set_main_loop_arg(call_frame, new std::function<bool()>(std::move(frame)), 0, false);
}

void fit_canvas(GLFWwindow* window) { fit_canvas_js(window); }

float pixel_ratio() {
    const double ratio = pixel_ratio_js();
    return ratio > 0.25 && ratio < 16.0 ? float(ratio) : 1.0f;
}

bool touch_screen() { return touch_screen_js() != 0; }

void on_touch(std::function<void(int, int, float, float)> handler) { touch_handler() = std::move(handler); }
void on_state(std::function<std::string()> answer) { state_answer() = std::move(answer); }

std::vector<std::string> take_chosen_files() {
    std::vector<std::string> files;
    for (std::string file = read_page_text(1); !file.empty(); file = read_page_text(1)) files.push_back(std::move(file));
    return files;
}

void choose_file(const std::string& accept) { choose_file_js(accept.c_str()); }
std::string page_address() { return read_page_text(0); }
void copy_text(const std::string& text) { copy_text_js(text.c_str()); }
bool take_copy_failure() { return take_copy_failure_js() != 0; }
void download(const std::string& name, const std::string& text, const std::string& type) {
    download_js(name.c_str(), text.c_str(), type.c_str());
}
void store_presets() { store_presets_js(); }

}  // namespace softbody::app::browser

// What the page calls (web/softbody-page.js, and the tests through it).
extern "C" {

EMSCRIPTEN_KEEPALIVE void softbody_touch(int phase, int id, float x, float y) {
    auto& handler = softbody::app::browser::touch_handler();
    if (!handler) return;
    try {
        handler(phase, id, x, y);
    } catch (const std::exception& e) {
        std::cerr << "softbody: " << e.what() << std::endl;
    }
}

// The app's state as JSON, valid until the next call ("{}" before the app runs).
EMSCRIPTEN_KEEPALIVE const char* softbody_state() {
    static std::string text;
    auto& answer = softbody::app::browser::state_answer();
    try {
        text = answer ? answer() : std::string("{}");
    } catch (const std::exception& e) {
        text = "{}";
        std::cerr << "softbody: " << e.what() << std::endl;
    }
    return text.c_str();
}

}  // extern "C"
