// The app shell (app_shell.h): each frame, the input (the person's, then the script's), the
// ticks due, the frame drawn, the tools over it.
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <iostream>

#include "gui/app_shell.h"
#include "gui/tools/lesson.h"
#include "physics/error.h"
#include "physics/scene_io.h"
#include "render/image.h"

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

void run_script_command(Session& session, View& view, const ScriptCommand& command) {
    const auto& args = command.args;
    if (command.verb == "set") {
        session.set_key(args[0], args[1]);
    } else if (command.verb == "load_scene") {
        session.load_scene_file(args[0]);
    } else if (command.verb == "load_mesh") {
        session.load_mesh_file(args[0]);
    } else if (command.verb == "save_preset") {
        session.save_preset(args[0], args.size() == 2);
    } else if (command.verb == "reset") {
        session.reset();
    } else if (command.verb == "inspect") {
        if (args[0] == "none") session.stop_inspecting();
        else session.inspect({false, 0, static_cast<std::uint32_t>(std::stoul(args[0]))});
    } else if (command.verb == "compare") {
        std::vector<CompareSetup> others;
        if (args[0] != "off") {
            for (const std::string& a : args) others.push_back(*parse_compare_setup(a));
        }
        if (session.compare(others)) view.frame_body(session);
    } else if (command.verb == "rewind") {
        session.rewind(std::stod(args[0]));
    } else if (command.verb == "step_back") {
        session.step_back();
    } else if (command.verb == "lesson") {
        open_lesson(session, std::size_t(std::stoul(args[0])));
    } else if (command.verb == "add") {
        const std::string& what = args[0];
        session.add_body(what == "soft_ball"   ? Session::AddKind::SoftBall
                      : what == "soft_cube" ? Session::AddKind::SoftCube
                      : what == "rigid_box" ? Session::AddKind::RigidBox
                      : what == "rigid_ball" ? Session::AddKind::RigidBall
                                             : Session::AddKind::MeshFile,
                      view.drop_point(session.world()), args.size() > 1 ? args[1] : std::string());
    } else if (command.verb == "pause") {
        session.paused = true;
    } else if (command.verb == "play") {
        session.paused = false;
    }
}

// The first world. A scene that cannot load is shown as an error over the default scene, not a
// dead window.
std::unique_ptr<Session> make_session(const SceneOptions& scene) {
    std::string first_error;
    Scene resolved;
    try {
        resolved = scene.resolve();
    } catch (const InputError& e) {
        first_error = e.what();
        resolved = load_scene(default_scene_path());
    }
    std::unique_ptr<Session> demo;
    try {
        demo = std::make_unique<Session>(resolved);
        for (const std::string& note : demo->world().notes()) std::cerr << "softbody: note: " << note << "\n";
        demo->set_source(!scene.scene.empty() ? scene.scene : !scene.mesh.empty() ? scene.mesh : default_scene_path());
    } catch (const InputError& e) {
        first_error = e.what();
        demo = std::make_unique<Session>(load_scene(default_scene_path()));
        demo->set_source(default_scene_path());
    }
    if (!first_error.empty()) demo->set_error(first_error);
    return demo;
}

}  // namespace

AppShell::AppShell(const SceneOptions& scene, const WindowOptions& window_options, std::int64_t frame_count,
                 double seconds_per_frame, std::vector<ScriptCommand> commands, std::string screenshot)
    : frames(frame_count), frame_time(seconds_per_frame), scripted(frame_count >= 0), script(std::move(commands)),
      screenshot_path(std::move(screenshot)), session(make_session(scene)), window(std::make_unique<Window>(window_options)),
      renderer(std::make_unique<render::Renderer>(reinterpret_cast<render::Loader>(glfwGetProcAddress))),
      panels(window->content_scale()) {
    panels.attach(*session);
    panels.recorder = &recorder;
    view.set_view(float(window->framebuffer_width()) / float(std::max(1, window->framebuffer_height())), panel_shift());
    view.start(*session);
    loads_seen = session->loads();
    last = window->time();
}

bool AppShell::run_frame() {
    if (window->should_close() || (scripted && frame_number >= frames)) return false;
    const std::int64_t frame = frame_number++;
    window->poll_events();
    const float width = float(window->framebuffer_width()), height = float(std::max(1, window->framebuffer_height()));
    const float ui_scale = window->content_scale();
    view.set_view(width / height, panel_shift());

    // Input: the person's (unless the UI has it), then the script's for this frame.
    const ImGuiIO& io = ImGui::GetIO();
    for (const InputEvent& event : window->take_events()) {
        const bool mouse = event.type != InputEvent::Type::Key;
        if ((mouse && io.WantCaptureMouse && !session->world().grab()) || (!mouse && io.WantCaptureKeyboard)) continue;
        handle(event, width, height, ui_scale);
    }
    for (; next_command < script.size() && script[next_command].frame <= frame - script_start; ++next_command) {
        const ScriptCommand& command = script[next_command];
        if (command.verb == "loop") {
            script_start = frame;
            next_command = std::size_t(-1);  // the loop's ++ makes it 0
            continue;
        }
        if (command.verb == "input") {
            handle(command.input, width, height, ui_scale);
        } else if (command.verb == "record") {
            if (command.args[0] == "stop") recorder.stop();
            else recorder.start(command.args.size() == 2 ? command.args[1] : "");
        } else {
            run_script_command(*session, view, command);
        }
    }
    // A file dropped on the window: a scene (a saved preset) opens as one, a mesh goes to the
    // selected soft body.
    for (const std::string& file : window->take_dropped_files()) session->open_file(file);

    // Physics: whole fixed ticks for the time that passed (fixed frame time when scripted).
    const double now = window->time();
    const double elapsed = scripted ? frame_time : now - last;
    session->advance(elapsed);
    last = now;
    // A new world (a scene, a lesson, a mesh loaded): framed as it starts.
    if (session->loads() != loads_seen) {
        loads_seen = session->loads();
        view.start(*session);
    }
    view.follow_bodies(*session, elapsed);  // paused too: the view still catches up (after a step back, say)

    // Draw: the scene, then the UI over it.
    renderer->draw(view.make_frame(*session), static_cast<int>(width), static_cast<int>(height), 0);
    // Recording takes the 3D view now, before the UI is drawn over it, right of the panel.
    recorder.frame(*renderer, panels.show_panels ? static_cast<int>(panels.width()) : 0, session->world().time());
    if (std::string failure = recorder.take_error(); !failure.empty()) session->set_error(failure);
    window->begin_ui_frame();
    panels.draw(*session, view, scripted ? float(1.0 / frame_time) : io.Framerate);
    window->end_ui_frame();
    if (scripted && frame + 1 == frames && !screenshot_path.empty()) {
        save_window(screenshot_path, static_cast<int>(width), static_cast<int>(height));
    }
    window->swap_buffers();
    if (frame == kWarmupFrames) after_warmup = resident_memory();
    return true;
}

void AppShell::handle(const InputEvent& event, float width, float height, float ui_scale) {
    const UiRequests ui = controls.handle(*session, view, event, width, height, ui_scale);
    panels.show_help = ui.toggle_help ? !panels.show_help : ui.close_help ? false : panels.show_help;
    if (ui.toggle_panels) panels.show_panels = !panels.show_panels;
    if (ui.toggle_recording) recorder.toggle();
}

}  // namespace softbody::app
