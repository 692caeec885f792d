// The app shell: the window, the loop, the fixed-tick clock's feed and the picking; the
// renderer, the panel of tools and the controls around one session. It runs a frame at a
// time: on the desktop `softbody run` calls run_frame() until it says the session is over; in
// the browser the page's animation frames call it (app/web/browser.h), and nothing may live on
// the stack of the function that started it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cli.h"
#include "gui/input.h"
#include "gui/panels.h"
#include "gui/recorder.h"
#include "gui/script.h"
#include "gui/session.h"
#include "gui/view.h"
#include "gui/window.h"
#include "process_memory.h"
#include "render/renderer.h"

namespace softbody::app {

// What the app was started with (--scene or --lesson, --mesh, --set): while the session still
// shows its first world, a link or a command line that gives that world names these (the
// Share tool), as the world's own record of its start already holds the --set keys.
const SceneOptions& launch_scene();

class AppShell {
public:
    // With frame_count >= 0, runs that many frames of seconds_per_frame each, replaying the
    // script, and saves the window to `screenshot` at the end (when given); else runs on the
    // clock until the window closes.
    AppShell(const SceneOptions& scene, const WindowOptions& window_options, std::int64_t frame_count, double seconds_per_frame,
             std::vector<ScriptCommand> commands, std::string screenshot);
    bool run_frame();  // one frame; false once the scripted frames are done or the window is closed
    void summarise();  // the JSON summary on stdout (run_summary.cpp)
    // What the app shows now, as JSON: the page's state question (app/web/browser.h), which the
    // browser tests ask: the scene, the bodies and where they are drawn, the camera, the canvas,
    // the panel and its items, the notice.
    std::string state_json() const;

private:
    // The panels cover the left of the window: frame the body in the rest of it.
    float panel_shift() const {
        return panels.show_panels ? 0.5f * panels.width() / float(std::max(1, window->framebuffer_width())) : 0.0f;
    }
    void handle(const InputEvent& event, float width, float height, float ui_scale);

    const std::int64_t frames;  // -1: run until the window is closed
    const double frame_time;
    const bool scripted;
    const std::vector<ScriptCommand> script;
    const std::string screenshot_path;
    std::unique_ptr<Session> session;
    View view;
    std::unique_ptr<Window> window;
    std::unique_ptr<render::Renderer> renderer;
    Panels panels;
    Controls controls;
    Recorder recorder;  // the Record button and the M key: the 3D view into a video

    std::uint64_t loads_seen = 0;  // the session's loads the view has framed
    std::int64_t frame_number = 0;
    std::size_t next_command = 0;
    std::int64_t script_start = 0;
    static constexpr std::int64_t kWarmupFrames = 100;
    ResidentMemory after_warmup;  // once the first frames have allocated what every frame reuses
    double last = 0.0;
};

}  // namespace softbody::app
