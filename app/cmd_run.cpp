// softbody [run]: the interactive demo. A GLFW window, the renderer, the tools, and the loop of
// Listing 8: wall time into the fixed-tick clock, ticks, then draw the interpolated state
// (gui/app_shell.h). With --frames it runs a fixed number of frames at a fixed frame time
// (deterministic), replays --script, saves --screenshot and exits: how the tests drive it
// without a person. In the browser build the same shell runs one frame per animation frame.
#include <CLI/CLI.hpp>

#include <memory>

#include "cli.h"
#include "commands.h"
#include "gui/app_shell.h"
#include "gui/bindings.h"
#if defined(__EMSCRIPTEN__)
#include "web/browser.h"
#endif

namespace softbody::app {

int run_command(int argc, char** argv, int first) {
    CLI::App app("Opens the interactive demo: a window with the scene falling onto the ground and the panels on the left\n"
                 "(app/README.md, \"The demo\"). With --frames it runs that many frames at a fixed frame time and prints a JSON\n"
                 "summary instead of waiting for a person: how the tests and recordings drive it.",
                 first == 1 ? "softbody" : "softbody run");
    configure(app);
    SceneOptions scene;
    scene.add_to(app);
    WindowOptions window_options;
    std::int64_t frames = -1;
    double frame_time = 1.0 / 60.0;
    std::string script_path, screenshot_path, size_text;
    app.add_option("--size", size_text, "the window's size, at least 320x240 (default " + std::to_string(window_options.width) + "x" +
                                            std::to_string(window_options.height) + ")")
        ->type_name("WxH");
    add_whole(app, "--frames", frames, 1, 10'000'000, "run N frames, print a JSON summary and exit (default: until the window closes)");
    add_number(app, "--frame-time", frame_time, 1e-4, 1.0, "with --frames, each frame's time in s instead of the clock's (default 1/60)")
        ->type_name("S");
    app.add_option("--script", script_path, "timed input to replay: moves, presses, keys, values (app/gui/script.h) (default: none)")
        ->type_name("FILE");
    app.add_option("--screenshot", screenshot_path, "with --frames, save the whole window, panels included, at the end (default: none)")
        ->type_name("FILE.png");
    app.footer("\n" + controls_text(36) + "\nA scene that cannot load, or diverges, is shown in the window as an error; the app goes on.\n" +
               exit_codes_help(false));
    if (!parse(app, argc, argv, first)) return kOk;
    if (!size_text.empty()) {
        const auto x = size_text.find('x');
        if (x == std::string::npos) throw UsageError("--size: expected WxH, got '" + size_text + "'");
        window_options.width = static_cast<int>(parse_int("--size", std::string_view(size_text).substr(0, x), 320, 8192));
        window_options.height = static_cast<int>(parse_int("--size", std::string_view(size_text).substr(x + 1), 240, 8192));
    }
    if (!screenshot_path.empty() && frames < 0) throw UsageError("--screenshot needs --frames N");
    std::vector<ScriptCommand> script = script_path.empty() ? std::vector<ScriptCommand>{} : load_script(script_path);
    window_options.vsync = frames < 0;

    auto session = std::make_unique<AppShell>(scene, window_options, frames, frame_time, std::move(script), screenshot_path);
#if defined(__EMSCRIPTEN__)
    browser::run_frames([session = std::shared_ptr<AppShell>(std::move(session))] {
        if (session->run_frame()) return true;
        session->summarise();
        return false;
    });
#else
    while (session->run_frame()) {
    }
    session->summarise();
#endif
    return kOk;
}

}  // namespace softbody::app
