// softbody render: simulates a scene from t = 0 at the fixed tick and writes one PNG per
// requested time, rendered headless (OSMesa, no display). Same inputs, same bytes.
// With --video the animation's frames go into one MP4 file instead (video.h: through ffmpeg).
// One JSON line per image on stdout: time, tick, state_hash, file, and the resident memory
// (a long sequence, --frames 2000 --fps 60, is the renderer's soak: the memory must stay flat).
//
// softbody render --bench measures the renderer instead (see render_bench below).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "body_view.h"
#include "cli.h"
#include "commands.h"
#include "offscreen_context.h"
#include "process_memory.h"
#include "video.h"
#include "physics/error.h"
#include "physics/generated.h"
#include "physics/mesh.h"
#include "physics/world.h"
#include "render/renderer.h"

namespace softbody::app {

namespace {

constexpr int kMinSide = 16;

struct CameraOptions {
    std::optional<float> yaw, pitch, fov, distance;
    float zoom = 1.0f;
    std::optional<glm::vec3> target;
    bool follow = false;
};

float degrees(std::string_view option, std::string_view text, double lo, double hi) {
    return static_cast<float>(parse_double(option, text, lo, hi) * std::numbers::pi / 180.0);
}

std::vector<std::string_view> split(std::string_view text, char separator) {
    std::vector<std::string_view> parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = text.find(separator, start);
        parts.push_back(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
        if (end == std::string_view::npos) break;
        start = end + 1;
    }
    return parts;
}

glm::vec3 parse_vec3(std::string_view option, std::string_view text, char separator) {
    const auto parts = split(text, separator);
    if (parts.size() != 3) {
        throw UsageError(std::string(option) + ": expected three numbers separated by '" + separator + "', got '" +
                         std::string(text) + "'");
    }
    return {float(parse_double(option, parts[0], -1e6, 1e6)), float(parse_double(option, parts[1], -1e6, 1e6)),
            float(parse_double(option, parts[2], -1e6, 1e6))};
}

void parse_camera(std::string_view text, CameraOptions& camera) {
    for (std::string_view item : split(text, ',')) {
        const std::size_t eq = item.find('=');
        const std::string_view key = item.substr(0, eq);
        const std::string_view value = eq == std::string_view::npos ? std::string_view() : item.substr(eq + 1);
        const std::string option = "--camera " + std::string(key);
        if (key == "follow" && eq == std::string_view::npos) camera.follow = true;
        else if (eq == std::string_view::npos) throw UsageError("--camera: expected KEY=VALUE, got '" + std::string(item) + "'");
        else if (key == "yaw") camera.yaw = degrees(option, value, -3600.0, 3600.0);
        else if (key == "pitch") camera.pitch = degrees(option, value, -89.0, 89.0);
        else if (key == "fov") camera.fov = degrees(option, value, 5.0, 150.0);
        else if (key == "distance") camera.distance = float(parse_double(option, value, 0.05, 300.0));
        else if (key == "zoom") camera.zoom = float(parse_double(option, value, 0.05, 20.0));
        else if (key == "target") camera.target = parse_vec3(option, value, ':');
        else throw UsageError("--camera: unknown key '" + std::string(key) + "' (yaw, pitch, fov, distance, zoom, target, follow)");
    }
}

void parse_overlays(std::string_view text, render::Overlays& on) {
    on = render::Overlays{};
    on.pins = false;
    on.links = false;
    for (std::string_view name : split(text, ',')) {
        if (name == "particles") on.particles = true;
        else if (name == "springs") on.springs = true;
        else if (name == "pins") on.pins = true;
        else if (name == "com") on.center_of_mass = true;
        else if (name == "velocity" || name == "velocities") on.velocities = true;
        else if (name == "forces") on.forces = true;
        else if (name == "normals") on.normals = true;
        else if (name == "angular") on.angular = true;
        else if (name == "contacts") on.contacts = true;
        else if (name == "links") on.links = true;
        else if (name == "none") {
        } else {
            throw UsageError("--overlay: unknown overlay '" + std::string(name) +
                             "' (particles, springs, pins, com, velocity, forces, normals, angular, contacts, links, none)");
        }
    }
}

glm::vec3 parse_color(std::string_view text) {
    if (!text.empty() && text[0] == '#') text.remove_prefix(1);
    unsigned value = 0;
    if (text.size() != 6 || std::sscanf(std::string(text).c_str(), "%6x", &value) != 1 ||
        text.find_first_not_of("0123456789abcdefABCDEF") != std::string_view::npos) {
        throw UsageError("--body-color: expected six hex digits RRGGBB, got '" + std::string(text) + "'");
    }
    return {float((value >> 16) & 0xFF) / 255.0f, float((value >> 8) & 0xFF) / 255.0f, float(value & 0xFF) / 255.0f};
}

std::pair<int, int> parse_size(std::string_view text) {
    const std::size_t x = text.find('x');
    if (x == std::string_view::npos) throw UsageError("--size: expected WxH such as 800x600, got '" + std::string(text) + "'");
    const auto w = parse_int("--size (width)", text.substr(0, x), kMinSide, OffscreenContext::kMaxSide);
    const auto h = parse_int("--size (height)", text.substr(x + 1), kMinSide, OffscreenContext::kMaxSide);
    return {int(w), int(h)};
}

// The output folder must exist (it is created) and take files: checked before any work.
void prepare_output(const std::filesystem::path& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir)) {
        throw InputError(dir.string() + ": cannot create the output folder (" +
                         (ec ? ec.message() : std::string("a file of that name exists")) + ")");
    }
    const std::filesystem::path probe = dir / ".softbody-write-test";
    {
        std::ofstream out(probe);
        if (!out || !(out << "x") || !out.flush()) throw InputError(dir.string() + ": the output folder is not writable");
    }
    std::filesystem::remove(probe, ec);
}

std::string time_label(double t) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", t);
    return text;
}

std::string hex(std::uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof text, "%016" PRIx64, value);
    return text;
}

void apply_camera_options(const CameraOptions& options, render::Camera& camera) {
    if (options.yaw) camera.yaw = *options.yaw;
    if (options.pitch) camera.pitch = *options.pitch;
    if (options.fov) camera.fov_y = *options.fov;
}

// softbody render's command line as given: what the options write into, before the checks.
struct RenderArgs {
    std::vector<std::string> at_texts, camera_texts;
    std::int64_t sequence_frames = 0;
    double seconds = -1.0;
    double fps = 60.0;
    std::string out_dir, video_path, size_text, overlay_text, body_style, color_text, offset_text;
    bool overwrite = false, hide_ground = false, no_shadows = false, no_pattern = false, flip_normals = false,
         particle_mesh = false;
    int samples = 4;
    int threads = kDefaultThreads;
    bool bench = false;  // taken before the options are read (render_bench)
};

// What to render, checked: the scene, the times, the image and its look, where it goes.
struct RenderJob {
    SceneOptions scene;
    std::vector<double> times;         // sorted, each once
    std::int64_t sequence_frames = 0;  // an animation's frames (--frames, --seconds); 0 for --at
    double fps = 60.0;
    std::string out_dir, video_path;   // one of the two is set
    bool overwrite = false, hide_ground = false;
    int width = 800, height = 600;
    int threads = 1;
    CameraOptions camera;
    SceneView view;                    // the scene's own camera direction (its "view"), under --camera
    render::Frame frame;               // its overlays, appearance and deliberate faults
};

// The options of softbody render, in the groups its help shows.
void declare_options(CLI::App& app, RenderArgs& args, SceneOptions& scene) {
    scene.add_to(app);
    const std::string output = "What to draw and where", look = "Camera and look", debug = "Deliberate faults (the screenshot tests')";
    app.add_option("--at", args.at_texts, "times in s; each image is drawn between the two ticks around it (default: none)")
        ->option_text("T1,T2,...")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->allow_extra_args(false)
        ->group(output);
    add_whole(app, "--frames", args.sequence_frames, 1, 1000000, "an animation: N frames at --fps from t = 0, <scene>_0000.png, ... (default: none)")
        ->group(output);
    add_number(app, "--seconds", args.seconds, 0.0, 1e5, "an animation as long as T seconds, instead of --frames (default: none)")->type_name("T")->group(output);
    add_number(app, "--fps", args.fps, 1.0, 1000.0, "frames a second of an animation or video (default 60)")->type_name("F")->group(output);
    app.add_option("--out", args.out_dir, "folder for DIR/<scene>_t<time>.png, made if missing (this or --video is required)")
        ->type_name("DIR")
        ->group(output);
    app.add_option("--video", args.video_path,
                   "one H.264 MP4 instead, by ffmpeg (without it: PNGs in FILE_frames/) (default: none)")
        ->type_name("FILE.mp4")
        ->group(output);
    app.add_flag("--overwrite", args.overwrite, "replace an existing video file (without it, one is never replaced)")->group(output);
    app.add_option("--size", args.size_text, "image size, 16..8192 each way; a video's sides even (default 800x600)")
        ->type_name("WxH")
        ->group(output);
    add_whole(app, "--threads", args.threads, 1, 256, "threads for the physics (default " + std::to_string(args.threads) + "; the same pictures at any count)")
        ->group(output);
    app.add_option("--camera", args.camera_texts,
                   "yaw=, pitch=, fov= (deg), distance=M, zoom=F, target=X:Y:Z, follow (default: framed once)")
        ->option_text("KEY=VALUE,...")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->allow_extra_args(false)
        ->group(look);
    app.add_option("--overlay", args.overlay_text,
                   "particles, springs, pins, com, velocity, forces, normals, angular, contacts, links, none (default pins,links)")
        ->type_name("NAME,...")
        ->group(look);
    app.add_option("--body", args.body_style, "solid, ghost (see-through), wireframe or hidden (default solid)")->type_name("STYLE")->group(look);
    app.add_option("--body-color", args.color_text, "the soft body's colour, six hex digits (default: the demo's orange)")
        ->type_name("RRGGBB")
        ->group(look);
    app.add_flag("--no-ground", args.hide_ground, "draw without the ground (the physics keeps it)")->group(look);
    app.add_flag("--no-shadows", args.no_shadows, "no shadows")->group(look);
    app.add_flag("--no-pattern", args.no_pattern, "a plain body, without the soft checks that show it turn")->group(look);
    add_whole(app, "--samples", args.samples, 1, 4, "multisample anti-aliasing, 1 (off) to 4 (default 4)")->group(look);
    app.add_flag("--bench", args.bench, "time the renderer instead (softbody render --bench --help)")
        ->group(look);
    app.add_option("--debug-offset", args.offset_text, "draw the soft bodies shifted by DX,DY,DZ metres (default 0,0,0)")
        ->type_name("DX,DY,DZ")
        ->group(debug);
    app.add_flag("--debug-flip-normals", args.flip_normals, "draw the surface normals flipped")->group(debug);
    app.add_flag("--debug-particle-mesh", args.particle_mesh, "draw a reduced body's simulated particles instead of its full mesh")
        ->group(debug);
}

// The look of the images: overlays, the body's style and colour, shadows, pattern, samples,
// and the deliberate faults.
void read_look(const CLI::App& app, const RenderArgs& args, render::Frame& frame) {
    if (app.count("--overlay") > 0) parse_overlays(args.overlay_text, frame.overlays);
    if (app.count("--body") > 0) {
        const std::string& body_style = args.body_style;
        if (body_style == "solid") frame.appearance.body = render::BodyStyle::Solid;
        else if (body_style == "ghost") frame.appearance.body = render::BodyStyle::Ghost;
        else if (body_style == "wireframe") frame.appearance.body = render::BodyStyle::Wireframe;
        else if (body_style == "hidden") frame.appearance.body = render::BodyStyle::Hidden;
        else throw UsageError("--body: expected solid, ghost, wireframe or hidden, got '" + body_style + "'");
    }
    if (app.count("--body-color") > 0) frame.appearance.body_color = parse_color(args.color_text);
    if (args.no_shadows) frame.appearance.shadows = false;
    if (args.no_pattern) frame.appearance.pattern = false;
    frame.appearance.samples = args.samples;
    if (!args.offset_text.empty()) frame.debug.body_offset = parse_vec3("--debug-offset", args.offset_text, ',');
    frame.debug.flip_normals = args.flip_normals;
    frame.debug.particle_mesh = args.particle_mesh;
}

// The values that are lists or pairs, checked as the options' own values are, and the options
// checked against each other: the job, or a UsageError naming the option at fault.
void check_options(const CLI::App& app, RenderArgs& args, RenderJob& job) {
    std::vector<double>& times = job.times;
    for (const std::string& text : args.at_texts) {
        for (std::string_view t : split(text, ',')) times.push_back(parse_double("--at", t, 0.0, 1e5));
    }
    const std::string& video_path = args.video_path;
    if (!video_path.empty()) {
        std::string extension = std::filesystem::path(video_path).extension().string();
        std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        if (extension != ".mp4") throw UsageError("--video: expected a file name ending in .mp4, got '" + video_path + "'");
    }
    const std::string& out_dir = args.out_dir;
    if (app.count("--out") > 0) {
        if (out_dir.empty()) throw UsageError("--out: expected a folder");
        // `--out shot.png` would make a folder of that name: say where the images go instead.
        std::string extension = std::filesystem::path(out_dir).extension().string();
        for (char& ch : extension) ch = char(std::tolower(static_cast<unsigned char>(ch)));
        if (extension == ".png" || extension == ".mp4") {
            throw UsageError("--out " + out_dir + ": a folder, not a file; the images go into it as <scene>_t<time>.png" +
                             (extension == ".mp4" ? " (a video: --video FILE.mp4)" : ""));
        }
    }
    int& width = job.width;
    int& height = job.height;
    if (!args.size_text.empty()) std::tie(width, height) = parse_size(args.size_text);
    for (const std::string& text : args.camera_texts) parse_camera(text, job.camera);
    read_look(app, args, job.frame);

    std::int64_t& sequence_frames = args.sequence_frames;
    const double seconds = args.seconds, fps = args.fps;
    if (sequence_frames > 0 && !times.empty()) throw UsageError("--at and --frames: give one or the other");
    if (seconds >= 0.0 && (sequence_frames > 0 || !times.empty())) throw UsageError("--seconds: give it instead of --frames or --at");
    // T seconds at F frames a second: the frames at 0, 1/F, ... before T, so the clip lasts T.
    if (seconds >= 0.0) sequence_frames = std::max<std::int64_t>(1, std::int64_t(std::ceil(seconds * fps - 1e-9)));
    const bool video = !video_path.empty();
    if (video && !times.empty()) throw UsageError("--video needs --frames N or --seconds T (an animation), not --at");
    if (video && !out_dir.empty()) throw UsageError("--video and --out: give one or the other (the frames go into the video)");
    if (video && (width % 2 != 0 || height % 2 != 0)) {
        throw UsageError("--size " + std::to_string(width) + "x" + std::to_string(height) +
                         ": a video needs even sides (H.264 stores colour at half resolution)");
    }
    if (args.overwrite && !video) throw UsageError("--overwrite goes with --video");
    for (std::int64_t k = 0; k < sequence_frames; ++k) times.push_back(double(k) / fps);
    if (times.empty()) throw UsageError("--at T1,T2,... or --frames N is required");
    if (out_dir.empty() && !video) throw UsageError("--out DIR or --video FILE.mp4 is required");
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());

    job.sequence_frames = sequence_frames;
    job.fps = fps;
    job.out_dir = out_dir;
    job.video_path = video_path;
    job.overwrite = args.overwrite;
    job.hide_ground = args.hide_ground;
    job.threads = args.threads;
}

// Reads and checks the command line into `job`; false when it only asked for help.
bool read_options(int argc, char** argv, RenderJob& job) {
    CLI::App app("Simulates from t = 0 at the fixed tick and draws it headless (OSMesa, no display): one PNG per time\n"
                 "asked for (--at), an animation's frames (--frames, --seconds) or one H.264 video (--video). Prints a\n"
                 "JSON line per image (time, tick, state_hash, file, memory_kib), or one for the video. Same inputs, same bytes.",
                 "softbody render");
    configure(app);
    RenderArgs args;
    declare_options(app, args, job.scene);
    app.footer(exit_codes_help(true));
    if (!parse(app, argc, argv, 2)) return false;
    check_options(app, args, job);
    return true;
}

// --at times are written to the millisecond: two that round alike would write one file twice.
void check_file_names(const RenderJob& job) {
    const std::vector<double>& times = job.times;
    for (std::size_t i = 1; i < times.size() && job.sequence_frames == 0; ++i) {
        if (time_label(times[i]) == time_label(times[i - 1])) {
            throw UsageError("--at: " + std::to_string(times[i - 1]) + " and " + std::to_string(times[i]) +
                             " round to the same file name (times are written to the millisecond)");
        }
    }
}

// Where the images go, made ready before the first frame is drawn: the video refuses to replace
// a file and starts ffmpeg (or, without it, makes the frames' folder); else the output folder
// is made and checked (null writer).
std::unique_ptr<VideoWriter> open_output(const RenderJob& job) {
    if (job.video_path.empty()) {
        prepare_output(job.out_dir);
        return nullptr;
    }
    std::error_code ec;
    if (!job.overwrite && std::filesystem::exists(std::filesystem::symlink_status(job.video_path, ec))) {
        throw InputError(job.video_path + ": already exists; not overwriting it (--overwrite replaces it)");
    }
    auto writer = std::make_unique<VideoWriter>(job.video_path, job.width, job.height, job.fps, job.overwrite);
    if (!writer->has_ffmpeg()) std::cerr << "softbody: " << writer->missing_ffmpeg_message() << "\n";
    return writer;
}

// The one line for a whole video: where it is (or where its frames are), and its shape.
void print_video_line(const RenderJob& job, VideoWriter& writer, const World& world) {
    writer.finish();
    nlohmann::ordered_json line = {
        {"video", writer.has_ffmpeg() ? nlohmann::ordered_json(job.video_path) : nlohmann::ordered_json(nullptr)},
        {"frames", writer.frames()}, {"fps", job.fps}, {"seconds", double(writer.frames()) / job.fps},
        {"width", job.width}, {"height", job.height}, {"tick", world.ticks()}, {"state_hash", hex(world.state_hash())},
        {"memory_kib", resident_memory().now_kib},
    };
    if (!writer.has_ffmpeg()) line["frames_folder"] = writer.frames_folder();
    std::cout << line.dump() << std::endl;
}

// The frame loop: the world run up to each time, drawn between the two ticks around it, and
// each image written (a PNG and its JSON line, or a frame of the video). kDiverged when the
// simulation fails before the last time.
int render_frames(RenderJob& job, const WorldSettings& params, World& world, render::Renderer& renderer, VideoWriter* writer) {
    render::Frame& frame = job.frame;
    const CameraOptions& camera_options = job.camera;
    const std::int64_t sequence_frames = job.sequence_frames;
    const int width = job.width, height = job.height;
    const float aspect = float(width) / float(height);
    match_ground(params, frame.appearance);
    if (job.hide_ground) frame.appearance.ground = false;  // drawn without it; the physics keeps it
    constexpr double kRadians = 3.14159265358979323846 / 180.0;
    if (job.view.yaw) frame.camera.yaw = float(*job.view.yaw * kRadians);
    if (job.view.pitch) frame.camera.pitch = float(*job.view.pitch * kRadians);
    apply_camera_options(camera_options, frame.camera);
    frame_body(world, aspect, frame.camera, camera_options.zoom);
    const auto fix_camera = [&] {
        if (camera_options.target) frame.camera.target = *camera_options.target;
        if (camera_options.distance) frame.camera.distance = *camera_options.distance;
    };
    fix_camera();

    const std::string name = job.scene.name();
    const std::filesystem::path dir(job.out_dir);
    const double dt = double(params.dt);
    // File names: "t<time>" for --at; for --frames the frame number, padded with zeros to the
    // last one's width (at least 4), so that name order is frame order.
    const auto label_of = [&, digits = std::max<std::size_t>(4, std::to_string(sequence_frames - 1).size())](
                              std::size_t k, double t) {
        if (sequence_frames == 0) return "t" + time_label(t);
        const std::string number = std::to_string(k);
        return std::string(digits - std::min(digits, number.size()), '0') + number;
    };
    for (std::size_t k = 0; k < job.times.size(); ++k) {
        const double t = job.times[k];
        // The image at time t lies between ticks n - 1 and n: n = ceil(t / dt).
        // dt is a float (0.02f is not 0.02): a time within 1e-4 tick of a tick is that tick.
        double ticks_exact = t / dt;
        if (std::abs(ticks_exact - std::round(ticks_exact)) < 1e-4) ticks_exact = std::round(ticks_exact);
        auto n = static_cast<std::uint64_t>(std::ceil(ticks_exact - 1e-9));
        const float alpha = n == 0 ? 1.0f : float(std::clamp(1.0 - (double(n) - ticks_exact), 0.0, 1.0));
        while (world.ticks() < n && world.status() == Status::Ok) world.tick();
        if (world.status() != Status::Ok) {
            if (writer) writer->finish();  // the frames up to the divergence make a clip too
            std::cerr << "softbody: the simulation diverged before t = " << t << " s: " << world.divergence()
                      << (writer ? " (" + job.video_path + " has the " + std::to_string(writer->frames()) +
                                       (writer->frames() == 1 ? " frame" : " frames") + " before it)"
                                 : "")
                      << "\n";
            return kDiverged;
        }
        world_view(world, alpha, frame);
        if (camera_options.follow) {
            frame_body(world, aspect, frame.camera, camera_options.zoom);
            fix_camera();
        }
        renderer.draw(frame, width, height);
        if (writer) {
            writer->write(renderer.read_back());
            continue;
        }
        const std::filesystem::path file = dir / (name + "_" + label_of(k, t) + ".png");
        render::write_png(file.string(), renderer.read_back());
        nlohmann::ordered_json line = {
            {"time", t}, {"tick", world.ticks()}, {"alpha", alpha}, {"state_hash", hex(world.state_hash())},
            {"file", file.string()}, {"memory_kib", resident_memory().now_kib},
        };
        std::cout << line.dump() << std::endl;
    }
    if (writer) print_video_line(job, *writer, world);
    return kOk;
}

int render_bench(int argc, char** argv);

}  // namespace

// The stages in the order a user's mistakes are cheapest to find: the options, the scene, the
// file names, the output, then GL and the frames.
int render_command(int argc, char** argv) {
    for (int i = 2; i < argc; ++i) {
        if (std::string_view(argv[i]) == "--bench") return render_bench(argc, argv);
    }
    RenderJob job;
    if (!read_options(argc, argv, job)) return kOk;

    const Scene resolved = job.scene.resolve();
    job.view = resolved.view;
    World world(resolved, WorldOptions{job.threads, false});
    for (const std::string& note : world.notes()) std::cerr << "softbody: note: " << note << "\n";
    check_file_names(job);
    const std::unique_ptr<VideoWriter> writer = open_output(job);

    OffscreenContext context(job.width, job.height);
    render::Renderer renderer(context.loader());
    if (job.width > renderer.info().max_size || job.height > renderer.info().max_size) {
        throw InputError("--size " + std::to_string(job.width) + "x" + std::to_string(job.height) + ": this OpenGL (" +
                         renderer.info().renderer + ") draws at most " + std::to_string(renderer.info().max_size) +
                         " pixels a side");
    }
    return render_frames(job, resolved.settings, world, renderer, writer.get());
}

namespace {

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

// Benchmark: the per-frame cost of streaming the particles into the GPU mesh and recomputing
// the normals (meshes of 500, 2,500 and 10,000 vertices), and whole headless frames at 800x600.
// Medians over the frames, so a busy machine disturbs the figures less.
int render_bench(int argc, char** argv) {
    CLI::App app("Times the renderer's own code, headless: streaming the particles and recomputing the normals of deforming\n"
                 "tori (500, 2,500 and 10,000 vertices), and whole 800x600 frames of the default scene (medians). No files.",
                 "softbody render --bench");
    configure(app);
    int frames = 100;
    bool bench = true;
    app.add_flag("--bench", bench, "time the renderer (this command)");
    add_whole(app, "--frames", frames, 1, 100000, "frames to time for each row, after 10 warm-up frames (default 100)");
    app.footer(exit_codes_help(false));
    if (!parse(app, argc, argv, 2)) return kOk;
    using Clock = std::chrono::steady_clock;
    const auto ms_since = [](Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); };
    const int width = 800, height = 600;
    const float aspect = float(width) / float(height);
    OffscreenContext context(width, height);
    render::Renderer renderer(context.loader());
    std::cout << "renderer: " << renderer.info().renderer << ", " << renderer.info().version << "\n";
    std::cout << "medians over " << frames << " frames (after 10 warm-up frames), 800x600, 4x MSAA, soft shadows\n\n";
    std::printf("%-22s %9s %10s %15s %10s %10s\n", "mesh", "vertices", "triangles", "normals ms", "stream ms",
                "frame ms");

    // Deforming tori: every frame has new positions, so new normals and a new upload.
    for (const auto& [rings, segments] : {std::pair{20, 25}, std::pair{50, 50}, std::pair{100, 100}}) {
        // The shared torus (physics/generated.h): --scene torus:100x100 opens the same body.
        const Mesh mesh = generated_mesh("torus:" + std::to_string(rings) + "x" + std::to_string(segments));
        const std::size_t n = mesh.particle_count();
        Vec3Array x;
        x.resize(n);
        render::Frame frame;
        frame.soft_bodies.resize(1);
        frame.soft_bodies[0].mesh = &mesh;
        frame.soft_bodies[0].positions = span_of(x);
        frame.camera.frame({0.0f, 0.0f, 0.5f}, 0.8f, aspect);
        std::vector<double> surface, stream, total;
        for (int f = -10; f < frames; ++f) {
            // A squash-and-stretch wobble about the torus's centre.
            const float s = 1.0f + 0.2f * std::sin(0.3f * float(f));
            for (std::size_t i = 0; i < n; ++i) {
                const Vec3 p = mesh.positions[i];
                x.set(i, {p.x / std::sqrt(s), p.y / std::sqrt(s), 0.5f + p.z * s});
            }
            const auto start = Clock::now();
            renderer.draw(frame, width, height);
            (void)renderer.read_back();  // waits for the frame: the time includes the GPU's work
            const double ms = ms_since(start);
            if (f < 0) continue;
            surface.push_back(renderer.timings().surface_ms);
            stream.push_back(renderer.timings().upload_ms);
            total.push_back(ms);
        }
        std::printf("%-22s %9zu %10zu %15.3f %10.3f %10.2f\n", mesh.source.c_str(), mesh.render_vertices.size(),
                    mesh.triangle_count(), median(surface), median(stream), median(total));
    }

    // The default scene as `softbody render` draws it, and what writing the PNG adds.
    SceneOptions scene;
    const Scene resolved = scene.resolve();
    const WorldSettings& params = resolved.settings;
    World world(resolved);
    world.run(30);
    render::Frame frame;
    world_view(world, 1.0f, frame);
    match_ground(params, frame.appearance);
    frame_body(world, aspect, frame.camera, 1.0f);
    std::vector<double> total, png;
    const auto png_path = std::filesystem::temp_directory_path() / "softbody_render_bench.png";
    for (int f = -10; f < frames; ++f) {
        const auto start = Clock::now();
        renderer.draw(frame, width, height);
        const render::Image image = renderer.read_back();
        const double ms = ms_since(start);
        const auto png_start = Clock::now();
        if (f % 10 == 0) render::write_png(png_path.string(), image);
        if (f >= 0) total.push_back(ms);
        if (f >= 0 && f % 10 == 0) png.push_back(ms_since(png_start));
    }
    std::filesystem::remove(png_path);
    std::printf("%-22s %9zu %10zu %15.3f %10.3f %10.2f   + PNG %.1f ms\n", "default scene", world.soft_body(0).mesh.render_vertices.size(),
                world.soft_body(0).mesh.triangle_count(), renderer.timings().surface_ms, renderer.timings().upload_ms,
                median(total), median(png));
    std::cout << "\nnormals: interpolation and normal recomputation on the CPU; stream: orphaning the vertex\n"
                 "buffer and writing the new vertices; frame: draw() plus reading the pixels back.\n";
    return kOk;
}

}  // namespace

}  // namespace softbody::app
