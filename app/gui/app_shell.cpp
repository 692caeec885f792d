// The app shell (app_shell.h): each frame, the input (the person's, then the script's), the
// ticks due, the frame drawn, the tools over it.
#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <glm/gtc/matrix_transform.hpp>
#include <iostream>
#include <nlohmann/json.hpp>

#include "gui/app_shell.h"
#include "gui/asset_files.h"
#include "gui/setup_link.h"
#include "gui/tools/lesson.h"
#include "physics/error.h"
#include "physics/scene_io.h"
#include "render/image.h"
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
    } else if (command.verb == "export_csv") {
        session.export_series(args[0], args.size() == 2);
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

SceneOptions& launch_options() {
    static SceneOptions options;
    return options;
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
        demo->set_source(!scene.scene.empty() ? scene.scene
                         : scene.lesson != 0   ? lesson_path(scene.lesson)
                         : !scene.mesh.empty() ? scene.mesh
                                               : default_scene_path());
    } catch (const InputError& e) {
        first_error = e.what();
        demo = std::make_unique<Session>(load_scene(default_scene_path()));
        demo->set_source(default_scene_path());
    }
    if (!first_error.empty()) demo->set_error(first_error);
    return demo;
}

}  // namespace

const SceneOptions& launch_scene() { return launch_options(); }

AppShell::AppShell(const SceneOptions& scene, const WindowOptions& window_options, std::int64_t frame_count,
                 double seconds_per_frame, std::vector<ScriptCommand> commands, std::string screenshot)
    : frames(frame_count), frame_time(seconds_per_frame), scripted(frame_count >= 0), script(std::move(commands)),
      screenshot_path(std::move(screenshot)), session(make_session(scene)), window(std::make_unique<Window>(window_options)),
      renderer(std::make_unique<render::Renderer>(reinterpret_cast<render::Loader>(glfwGetProcAddress))),
      panels(window->content_scale()) {
    launch_options() = scene;
    panels.attach(*session);
    panels.recorder = &recorder;
    panels.ui.finger_rows = window->touch_screen();  // a tablet's or a phone's page: rows for fingers
    view.set_view(float(window->framebuffer_width()) / float(std::max(1, window->framebuffer_height())), panel_shift());
    view.start(*session);
    loads_seen = session->loads();
    last = window->time();
#if defined(__EMSCRIPTEN__)
    browser::on_state([this] { return state_json(); });  // the shell lives as long as the page
    // A screen of two or more pixels per CSS pixel (a tablet, a phone) already draws edges
    // finely, and 4x multisampling there would cost four times its many pixels (100 MB of
    // buffers at 2048 x 1536): one sample a pixel, unless the Display tool asks for more.
    if (window->content_scale() >= 2.0f) view.appearance.samples = 1;
#endif
}

bool AppShell::run_frame() {
    if (window->should_close() || (scripted && frame_number >= frames)) return false;
    const std::int64_t frame = frame_number++;
    window->poll_events();
    const float width = float(window->framebuffer_width()), height = float(std::max(1, window->framebuffer_height()));
    const float ui_scale = window->content_scale();
    view.set_view(width / height, panel_shift());

    // Input: the person's (unless the UI has it: a finger's gestures on the view are for the
    // view, as the window decided where it landed), then the script's for this frame.
    const ImGuiIO& io = ImGui::GetIO();
    // Keys are the panel's while a field is typed into or the panel is moved through with the
    // keyboard (its focus shows); a panel that was only clicked leaves Space, R, M to the view.
    const bool panel_keys = io.WantTextInput || (io.NavActive && io.NavVisible) || ImGui::IsAnyItemActive();
    for (const InputEvent& event : window->take_events()) {
        const bool mouse = event.type != InputEvent::Type::Key && !event.touch;
        if ((mouse && io.WantCaptureMouse && !session->world().grab()) || (event.type == InputEvent::Type::Key && panel_keys)) continue;
        // A fingertip is wider than a mouse's point: it picks within a wider circle.
        handle(event, width, height, event.touch ? 1.6f * ui_scale : ui_scale);
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

std::string AppShell::state_json() const {
    const World& world = session->world();
    const float width = float(window->framebuffer_width()), height = float(std::max(1, window->framebuffer_height()));
    const glm::mat4 to_clip = view.camera.projection(width / height) * view.camera.view();
    // Where a point is drawn, in the canvas's pixels (y down).
    const auto on_screen = [&](double x, double y, double z) {
        const glm::vec4 clip = to_clip * glm::vec4(float(x), float(y), float(z), 1.0f);
        if (!(clip.w > 0.0f)) return nlohmann::json(nullptr);
        return nlohmann::json{(clip.x / clip.w + 1.0f) * 0.5f * width, (1.0f - clip.y / clip.w) * 0.5f * height};
    };
    nlohmann::json bodies = nlohmann::json::array();
    for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
        const Vec3 c = world.center_of_mass(b);
        bodies.push_back({{"name", world.soft_body(b).name()}, {"rigid", false}, {"position", {c.x, c.y, c.z}},
                          {"screen", on_screen(c.x, c.y, c.z)}});
    }
    for (std::size_t b = 0; b < world.rigid_body_count(); ++b) {
        const RigidMotion m = world.rigid_motion(b);
        const RigidBody& body = world.rigid_body(b);
        nlohmann::json entry{{"name", body.name}, {"rigid", true}, {"fixed", body.fixed}, {"position", {m.x.x, m.x.y, m.x.z}},
                             {"screen", on_screen(m.x.x, m.x.y, m.x.z)}};
        if (body.shape == ShapeKind::Sphere) {
            // How large the ball is drawn: its radius in pixels, sideways and up (equal unless
            // the picture is stretched or the ball is near the edge of a wide view).
            const glm::vec3 right = view.camera.right() * float(body.radius), up = view.camera.up() * float(body.radius);
            entry["screen_right"] = on_screen(m.x.x + right.x, m.x.y + right.y, m.x.z + right.z);
            entry["screen_up"] = on_screen(m.x.x + up.x, m.x.y + up.y, m.x.z + up.z);
        }
        bodies.push_back(std::move(entry));
    }
    std::vector<std::string> presets;
    for (const std::string& file : list_files(presets_folder(), {".json"})) presets.push_back(file);
    nlohmann::json out = {
        {"frame", frame_number},
        {"source", session->source()},
        {"loads", session->loads()},
        {"title", session->lesson().title},
        {"ticks", world.ticks()},
        {"time", world.time()},
        {"paused", session->paused},
        {"grabbing", bool(world.grab())},
        {"inspecting", session->particle_inspection().has_value() || session->rigid_inspection().has_value()},
        {"bodies", bodies},
        {"camera", {{"target", {view.camera.target.x, view.camera.target.y, view.camera.target.z}},
                    {"distance", view.camera.distance}, {"yaw", view.camera.yaw}, {"pitch", view.camera.pitch}}},
        {"canvas", {{"width", window->framebuffer_width()}, {"height", window->framebuffer_height()}}},
        {"ui_scale", window->content_scale()},
        {"panel", {{"shown", panels.show_panels}, {"width", panels.width()}}},
        {"notice", session->notice()},
        {"error", session->error()},
        {"presets", presets},
    };
    const ChangedKeys changed = session->changed_keys();
    out["changed_keys"] = {{"keys", changed.keys}, {"added", changed.added}, {"removed", changed.removed}};
    const Setup setup = current_setup(*session, launch_scene());  // what the Share tool's link carries
    out["setup"] = {{"query", setup_query(setup)}, {"command", setup_command(setup)}, {"lost", setup.lost}};
#if defined(__EMSCRIPTEN__)
    out["ui"] = nlohmann::json::parse(browser::ui_items_json());
#endif
    return out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void AppShell::handle(const InputEvent& event, float width, float height, float ui_scale) {
    const UiRequests ui = controls.handle(*session, view, event, width, height, ui_scale);
    panels.show_help = ui.toggle_help ? !panels.show_help : ui.close_help ? false : panels.show_help;
    if (ui.toggle_panels) panels.show_panels = !panels.show_panels;
    if (ui.toggle_recording) recorder.toggle();
}

}  // namespace softbody::app
