// softbody [run]: the interactive demo. A GLFW window, the renderer, the ImGui panels, and the
// loop of Listing 8: wall time into the fixed-tick clock, ticks, then draw the interpolated
// state. With --frames it runs a fixed number of frames at a fixed frame time (deterministic),
// replays --script, saves --screenshot and exits: how the tests drive it without a person.
// In the browser build the same session runs one frame per animation frame of the page.
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <CLI/CLI.hpp>

#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "commands.h"
#include "gui/bindings.h"
#include "gui/demo.h"
#include "gui/input.h"
#include "gui/lesson_panel.h"
#include "gui/panels.h"
#include "gui/recorder.h"
#include "gui/script.h"
#include "gui/window.h"
#include "process_memory.h"
#include "physics/error.h"
#include "physics/scene_io.h"
#include "render/image.h"
#include "render/renderer.h"
#include "world_json.h"
#if defined(__EMSCRIPTEN__)
#include "web/browser.h"
#endif

namespace softbody::app {

namespace {

// The whole window, UI included, as it is in the back buffer now.
void save_window(const std::string& path, int width, int height) {
    render::Image image(width, height);
    std::vector<std::uint8_t> rows(image.rgba.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    const std::size_t stride = static_cast<std::size_t>(width) * 4;
    for (int y = 0; y < height; ++y) {  // GL's rows start at the bottom
        std::copy_n(rows.data() + static_cast<std::size_t>(height - 1 - y) * stride, stride,
                    image.rgba.data() + static_cast<std::size_t>(y) * stride);
    }
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    render::write_png(path, image);
}

void run_script_command(Demo& demo, const ScriptCommand& command) {
    const auto& args = command.args;
    if (command.verb == "set") {
        demo.set_key(args[0], args[1]);
    } else if (command.verb == "load_scene") {
        demo.load_scene_file(args[0]);
    } else if (command.verb == "load_mesh") {
        demo.load_mesh_file(args[0]);
    } else if (command.verb == "save_preset") {
        demo.save_preset(args[0], args.size() == 2);
    } else if (command.verb == "reset") {
        demo.reset();
    } else if (command.verb == "inspect") {
        if (args[0] == "none") demo.stop_inspecting();
        else demo.inspect_particle(0, static_cast<std::uint32_t>(std::stoul(args[0])));
    } else if (command.verb == "compare") {
        std::vector<CompareSetup> others;
        if (args[0] != "off") {
            for (const std::string& a : args) others.push_back(*parse_compare_setup(a));
        }
        demo.compare(others);
    } else if (command.verb == "rewind") {
        demo.rewind(std::stod(args[0]));
    } else if (command.verb == "step_back") {
        demo.step_back();
    } else if (command.verb == "lesson") {
        open_lesson(demo, std::size_t(std::stoul(args[0])));
    } else if (command.verb == "add") {
        const std::string& what = args[0];
        demo.add_body(what == "soft_ball"   ? Demo::AddKind::SoftBall
                      : what == "soft_cube" ? Demo::AddKind::SoftCube
                      : what == "rigid_box" ? Demo::AddKind::RigidBox
                      : what == "rigid_ball" ? Demo::AddKind::RigidBall
                                             : Demo::AddKind::MeshFile,
                      args.size() > 1 ? args[1] : std::string());
    } else if (command.verb == "pause") {
        demo.paused = true;
    } else if (command.verb == "play") {
        demo.paused = false;
    }
}

// One session of the demo: the world, the window, the renderer and the panels, and what the
// loop keeps from one frame to the next. It lives on the heap and runs a frame at a time: on the
// desktop the loop below calls run_frame() until it says the session is over; in the browser the
// page's animation frames call it (app/web/browser.h), and nothing may live on the stack of the
// function that started it.
class Session {
public:
    Session(const SceneOptions& scene, const WindowOptions& window_options, std::int64_t frame_count, double seconds_per_frame,
            std::vector<ScriptCommand> commands, std::string screenshot);
    bool run_frame();  // one frame; false once the scripted frames are done or the window is closed
    void summarise();  // the JSON summary on stdout

private:
    // The panels cover the left of the window: frame the body in the rest of it.
    float panel_shift() const {
        return panels.show_panels ? 0.5f * panels.width() / float(std::max(1, window->framebuffer_width())) : 0.0f;
    }

    const std::int64_t frames;  // -1: run until the window is closed
    const double frame_time;
    const bool scripted;
    const std::vector<ScriptCommand> script;
    const std::string screenshot_path;
    std::unique_ptr<Demo> demo;
    std::unique_ptr<Window> window;
    std::unique_ptr<render::Renderer> renderer;
    Panels panels;
    Controls controls;
    Recorder recorder;  // the Record button and the M key: the 3D view into a video

    std::int64_t frame_number = 0;
    std::size_t next_command = 0;
    std::int64_t script_start = 0;
    static constexpr std::int64_t kWarmupFrames = 100;
    ResidentMemory after_warmup;  // once the first frames have allocated what every frame reuses
    double last = 0.0;
};

// The first world. A scene that cannot load is shown as an error over the default scene, not a
// dead window.
std::unique_ptr<Demo> make_demo(const SceneOptions& scene) {
    std::string first_error;
    Scene resolved;
    try {
        resolved = scene.resolve();
    } catch (const InputError& e) {
        first_error = e.what();
        resolved = load_scene(default_scene_path());
    }
    std::unique_ptr<Demo> demo;
    try {
        demo = std::make_unique<Demo>(resolved);
        for (const std::string& note : demo->world().notes()) std::cerr << "softbody: note: " << note << "\n";
        demo->set_source(!scene.scene.empty() ? scene.scene : !scene.mesh.empty() ? scene.mesh : default_scene_path());
    } catch (const InputError& e) {
        first_error = e.what();
        demo = std::make_unique<Demo>(load_scene(default_scene_path()));
        demo->set_source(default_scene_path());
    }
    if (!first_error.empty()) demo->set_error(first_error);
    return demo;
}

Session::Session(const SceneOptions& scene, const WindowOptions& window_options, std::int64_t frame_count,
                 double seconds_per_frame, std::vector<ScriptCommand> commands, std::string screenshot)
    : frames(frame_count), frame_time(seconds_per_frame), scripted(frame_count >= 0), script(std::move(commands)),
      screenshot_path(std::move(screenshot)), demo(make_demo(scene)), window(std::make_unique<Window>(window_options)),
      renderer(std::make_unique<render::Renderer>(reinterpret_cast<render::Loader>(glfwGetProcAddress))),
      panels(window->content_scale()) {
    panels.lesson.attach(*demo);
    panels.recorder = &recorder;
    demo->set_view(float(window->framebuffer_width()) / float(std::max(1, window->framebuffer_height())), panel_shift());
    demo->frame_body();
    last = window->time();
}

bool Session::run_frame() {
    if (window->should_close() || (scripted && frame_number >= frames)) return false;
    const std::int64_t frame = frame_number++;
    window->poll_events();
    const float width = float(window->framebuffer_width()), height = float(std::max(1, window->framebuffer_height()));
    const float ui_scale = window->content_scale();
    demo->set_view(width / height, panel_shift());

    // Input: the person's (unless the UI has it), then the script's for this frame.
    const ImGuiIO& io = ImGui::GetIO();
    for (const InputEvent& event : window->take_events()) {
        const bool mouse = event.type != InputEvent::Type::Key;
        if ((mouse && io.WantCaptureMouse && !demo->grabbing()) || (!mouse && io.WantCaptureKeyboard)) continue;
        const UiRequests ui = controls.handle(*demo, event, width, height, ui_scale);
        panels.show_help = ui.toggle_help ? !panels.show_help : ui.close_help ? false : panels.show_help;
        if (ui.toggle_panels) panels.show_panels = !panels.show_panels;
        if (ui.toggle_recording) recorder.toggle();
    }
    for (; next_command < script.size() && script[next_command].frame <= frame - script_start; ++next_command) {
        const ScriptCommand& command = script[next_command];
        if (command.verb == "loop") {
            script_start = frame;
            next_command = std::size_t(-1);  // the loop's ++ makes it 0
            continue;
        }
        if (command.verb == "input") {
            const UiRequests ui = controls.handle(*demo, command.input, width, height, ui_scale);
            panels.show_help = ui.toggle_help ? !panels.show_help : ui.close_help ? false : panels.show_help;
            if (ui.toggle_panels) panels.show_panels = !panels.show_panels;
            if (ui.toggle_recording) recorder.toggle();
        } else if (command.verb == "record") {
            if (command.args[0] == "stop") recorder.stop();
            else recorder.start(command.args.size() == 2 ? command.args[1] : "");
        } else {
            run_script_command(*demo, command);
        }
    }
    for (const std::string& file : window->take_dropped_files()) demo->load_mesh_file(file);

    // Physics: whole fixed ticks for the time that passed (fixed frame time when scripted).
    const double now = window->time();
    demo->advance(scripted ? frame_time : now - last);
    last = now;

    // Draw: the scene, then the UI over it.
    renderer->draw(demo->make_frame(), static_cast<int>(width), static_cast<int>(height), 0);
    // Recording takes the 3D view now, before the UI is drawn over it, right of the panel.
    recorder.frame(*renderer, panels.show_panels ? static_cast<int>(panels.width()) : 0, demo->world().time());
    if (std::string failure = recorder.take_error(); !failure.empty()) demo->set_error(failure);
    window->begin_ui_frame();
    panels.draw(*demo, scripted ? float(1.0 / frame_time) : io.Framerate);
    window->end_ui_frame();
    if (scripted && frame + 1 == frames && !screenshot_path.empty()) {
        save_window(screenshot_path, static_cast<int>(width), static_cast<int>(height));
    }
    window->swap_buffers();
    if (frame == kWarmupFrames) after_warmup = resident_memory();
    return true;
}

void Session::summarise() {
    // A recording still going when the app closes is finished, not lost.
    recorder.finish();
    if (std::string failure = recorder.take_error(); !failure.empty()) demo->set_error(failure);

    // A summary for scripts and tests: what the session ended with.
    const World& world = demo->world();
    const Vec3 com = world.center_of_mass();
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016" PRIx64, world.state_hash());
    std::size_t particles = 0, pinned = 0;
    for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
        particles += world.soft_body(b).particle_count();
        pinned += world.soft_body(b).def.pinned.size();
    }
    nlohmann::ordered_json out = {
        {"particles", particles}, {"ticks", world.ticks()},
        {"sim_time", world.time()},   {"com", {com.x, com.y, com.z}},       {"status", world.status() == Status::Ok ? "ok" : "diverged"},
        {"pinned", pinned}, {"error", demo->error()}, {"state_hash", hash},
        {"soft_bodies", soft_bodies_json(world)},
        {"rigid_bodies", rigid_bodies_json(world)},
        {"scene", nlohmann::json::parse(scene_to_json(demo->scene()))},
    };
    // The integrator comparison: each world's integrator, substeps and total energy now.
    if (demo->comparing()) {
        const auto entry = [](World& w) {
            char h[17];
            std::snprintf(h, sizeof h, "%016" PRIx64, w.state_hash());
            return nlohmann::ordered_json{{"integrator", std::string(to_string(w.settings().integrator))}, {"substeps", w.substeps_in_use()},
                                          {"ticks", w.ticks()}, {"status", w.status() == Status::Ok ? "ok" : "diverged"},
                                          {"total_energy", w.energy().total()}, {"state_hash", h}};
        };
        nlohmann::ordered_json worlds = nlohmann::ordered_json::array();
        worlds.push_back(entry(demo->world()));
        for (const ComparedWorld& c : demo->compared()) worlds.push_back(entry(*c.world));
        out["compared"] = worlds;
    }
    // The view: whether the camera follows the bodies, and where it looks now.
    out["camera"] = {{"follow", demo->follow},
                     {"target", {demo->camera.target.x, demo->camera.target.y, demo->camera.target.z}}};
    // The timeline: what the record holds.
    const History& history = demo->history();
    out["history"] = {{"oldest_tick", history.oldest_tick()}, {"newest_tick", history.newest_tick()},
                      {"keyframes", history.keyframe_count()}, {"bytes", history.bytes()}, {"in_past", demo->in_past()}};
    // The inspector's read-out, as the panel shows it.
    if (const auto in = demo->particle_inspection()) {
        nlohmann::ordered_json terms = nlohmann::ordered_json::array();
        for (const ForceTerm& t : in->terms) {
            terms.push_back({{"name", t.name}, {"equation", t.equation}, {"force", {t.force.x, t.force.y, t.force.z}},
                             {"detail", t.detail}});
        }
        out["inspection"] = {{"particle", in->particle}, {"x", {in->x.x, in->x.y, in->x.z}}, {"v", {in->v.x, in->v.y, in->v.z}},
                             {"terms", terms}, {"net", {in->net.x, in->net.y, in->net.z}}, {"on_ground", in->on_ground}};
    }
    if (auto lesson = panels.lesson.summary(*demo); !lesson.is_null()) out["lesson"] = std::move(lesson);
    if (const auto& recording = recorder.last()) {
        out["recording"] = {{"path", recording->path}, {"video", recording->video}, {"frames", recording->frames},
                            {"message", recording->message}};
    }
    // Resident now and at its peak, after the warm-up and at the end: flat means the ends agree.
    const ResidentMemory end = resident_memory();
    out["memory_kib"] = {{"after_warmup", after_warmup.now_kib}, {"peak_after_warmup", after_warmup.peak_kib},
                         {"end", end.now_kib},                   {"peak", end.peak_kib}};
    // A file name need not be UTF-8: its odd bytes are replaced in the summary, not fatal.
    std::cout << out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << std::endl;
}

}  // namespace

int run_command(int argc, char** argv, int first) {
    CLI::App app("Opens the interactive demo: a window with the scene falling onto the ground and the panels on the left\n"
                 "(README, \"The demo\"). With --frames it runs that many frames at a fixed frame time and prints a JSON\n"
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

    auto session = std::make_unique<Session>(scene, window_options, frames, frame_time, std::move(script), screenshot_path);
#if defined(__EMSCRIPTEN__)
    browser::run_frames([session = std::shared_ptr<Session>(std::move(session))] {
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
