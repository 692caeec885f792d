// softbody render: simulates a scene from t = 0 at the fixed tick and writes one PNG per
// requested time, rendered headless (OSMesa, no display). Same inputs, same bytes.
// With --video the animation's frames go into one MP4 file instead (video.h: through ffmpeg).
// One JSON line per image on stdout: time, tick, state_hash, file, and the resident memory
// (a long sequence, --frames 2000 --fps 60, is the renderer's soak: the memory must stay flat).
//
// softbody render --bench measures the renderer instead (see render_bench below).
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

constexpr const char* kUsage =
    "usage: softbody render [--scene FILE] [--mesh FILE] [--set KEY=VALUE]... --at T1,T2,... --out DIR\n"
    "       softbody render [--scene FILE] [--mesh FILE] [--set KEY=VALUE]... --frames N [--fps F] --out DIR\n"
    "       softbody render [--scene FILE] [--mesh FILE] [--set KEY=VALUE]... (--frames N | --seconds T) [--fps F]\n"
    "                       --video FILE.mp4 [--overwrite]\n"
    "                       [--size WxH] [--camera KEY=VALUE,...] [--overlay NAME,...] [--body STYLE]\n"
    "                       [--body-color RRGGBB] [--no-ground] [--no-shadows] [--no-pattern] [--samples N]\n"
    "                       [--threads N]\n"
    "       softbody render --bench [--frames N]   (streaming, normals and frame times; no files)\n"
    "  --at        times in seconds; each is drawn between the two ticks around it\n"
    "  --frames    N images at F per second from t = 0 (default --fps 60), DIR/<scene>_<frame>.png\n"
    "              numbered from 0 with leading zeros (an animation's frames, in name order)\n"
    "  --seconds   as many frames as T seconds take at F per second (instead of --frames)\n"
    "  --out       folder for DIR/<scene>_t<time>.png (created if missing)\n"
    "  --video     one H.264 MP4 video of the frames instead of PNGs, through ffmpeg ('sudo apt install\n"
    "              ffmpeg'; without it the frames are PNGs in FILE_frames/ beside it); sides must be even\n"
    "  --overwrite replace an existing video file (without it, one is never replaced)\n"
    "  --size      image size, 16..8192 each way (default 800x600)\n"
    "  --camera    yaw=DEG, pitch=DEG (above the horizon), fov=DEG, distance=M, zoom=FACTOR,\n"
    "              target=X:Y:Z, follow (frame the body in every image; default: frame the\n"
    "              start of the fall once, so every image shares one camera)\n"
    "  --overlay   particles, springs, pins, com, velocity, forces, normals, angular (omega and L),\n"
    "              contacts, links (springs between bodies), or none (default: pins, links)\n"
    "  --body      solid, ghost (see-through), wireframe or hidden (default: solid)\n"
    "  --no-pattern  a plain body, without the soft checks that show it turn\n"
    "  --samples   multisample anti-aliasing, 1 (off) to 4 (default 4)\n"
    "  --debug-offset DX,DY,DZ, --debug-flip-normals and --debug-particle-mesh (a reduced body's\n"
    "              simulated particles drawn instead of its full mesh) draw deliberate faults (the screenshot\n"
    "              tests' negative checks)";

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

// The sphere to keep in view: the bodies now, and where they will land on the floor below.
void frame_body(const World& world, const Params& params, float aspect, render::Camera& camera, float zoom) {
    const WorldBounds bounds = world_bounds(world);
    const glm::vec3 c = bounds.centre;
    const float r = std::max(bounds.radius, 1e-3f);
    glm::vec3 centre = c;
    float radius = r;
    if (!params.pinned.empty()) {
        // A pinned body hangs: room below it for the sag, not the whole way to the floor.
        centre.z -= 0.4f * r;
        radius = 1.4f * r;
    } else if (params.ground && c.z - params.ground_height > 0.0f) {
        const glm::vec3 landed(c.x, c.y, std::min(c.z, params.ground_height + 0.6f * r));
        centre = 0.5f * (centre + landed);
        radius = 0.5f * glm::length(glm::vec3(c.x, c.y, c.z) - landed) + r;
    }
    // One body is framed with room to squash and roll; a group of bodies is its own margin.
    const bool alone = world.soft_body_count() + world.rigid_body_count() == 1;
    camera.frame(centre, std::max(radius, (alone ? 1.6f : 1.0f) * r), aspect, 0.85f);
    camera.zoom(zoom);
}

void apply_camera_options(const CameraOptions& options, render::Camera& camera) {
    if (options.yaw) camera.yaw = *options.yaw;
    if (options.pitch) camera.pitch = *options.pitch;
    if (options.fov) camera.fov_y = *options.fov;
}

int render_bench(int argc, char** argv);

}  // namespace

int render_command(int argc, char** argv) {
    for (int i = 2; i < argc; ++i) {
        if (std::string_view(argv[i]) == "--bench") return render_bench(argc, argv);
    }
    Args args(argc, argv, 2);
    SceneOptions scene;
    std::vector<double> times;
    long sequence_frames = 0;
    std::optional<double> seconds;
    double fps = 60.0;
    std::string out_dir, video_path;
    bool overwrite = false;
    int width = 800, height = 600;
    CameraOptions camera_options;
    render::Frame frame;
    int threads = hardware_threads();
    bool hide_ground = false;
    while (!args.done()) {
        if (scene.take(args)) continue;
        const std::string_view option = args.next();
        if (option == "--at") {
            for (std::string_view t : split(args.value(option), ',')) times.push_back(parse_double(option, t, 0.0, 1e5));
        } else if (option == "--frames") {
            sequence_frames = parse_int(option, args.value(option), 1, 1000000);
        } else if (option == "--seconds") {
            seconds = parse_double(option, args.value(option), 0.0, 1e5);
        } else if (option == "--video") {
            video_path = args.value(option);
            std::string extension = std::filesystem::path(video_path).extension().string();
            std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
            if (extension != ".mp4") throw UsageError("--video: expected a file name ending in .mp4, got '" + video_path + "'");
        } else if (option == "--overwrite") {
            overwrite = true;
        } else if (option == "--fps") {
            fps = parse_double(option, args.value(option), 1.0, 1000.0);
        } else if (option == "--out") {
            out_dir = args.value(option);
            if (out_dir.empty()) throw UsageError("--out: expected a folder");
            // `--out shot.png` would make a folder of that name: say where the images go instead.
            std::string extension = std::filesystem::path(out_dir).extension().string();
            for (char& ch : extension) ch = char(std::tolower(static_cast<unsigned char>(ch)));
            if (extension == ".png" || extension == ".mp4") {
                throw UsageError("--out " + out_dir + ": a folder, not a file; the images go into it as <scene>_t<time>.png" +
                                 (extension == ".mp4" ? " (a video: --video FILE.mp4)" : ""));
            }
        } else if (option == "--size") {
            std::tie(width, height) = parse_size(args.value(option));
        } else if (option == "--camera") {
            parse_camera(args.value(option), camera_options);
        } else if (option == "--overlay") {
            parse_overlays(args.value(option), frame.overlays);
        } else if (option == "--body") {
            const std::string_view style = args.value(option);
            if (style == "solid") frame.appearance.body = render::BodyStyle::Solid;
            else if (style == "ghost") frame.appearance.body = render::BodyStyle::Ghost;
            else if (style == "wireframe") frame.appearance.body = render::BodyStyle::Wireframe;
            else if (style == "hidden") frame.appearance.body = render::BodyStyle::Hidden;
            else throw UsageError("--body: expected solid, ghost, wireframe or hidden, got '" + std::string(style) + "'");
        } else if (option == "--body-color") {
            frame.appearance.body_color = parse_color(args.value(option));
        } else if (option == "--no-ground") {
            hide_ground = true;
        } else if (option == "--no-shadows") {
            frame.appearance.shadows = false;
        } else if (option == "--no-pattern") {
            frame.appearance.pattern = false;
        } else if (option == "--samples") {
            frame.appearance.samples = int(parse_int(option, args.value(option), 1, 4));
        } else if (option == "--threads") {
            threads = int(parse_int(option, args.value(option), 1, 256));
        } else if (option == "--debug-offset") {
            frame.debug.body_offset = parse_vec3(option, args.value(option), ',');
        } else if (option == "--debug-flip-normals") {
            frame.debug.flip_normals = true;
        } else if (option == "--debug-particle-mesh") {
            frame.debug.particle_mesh = true;
        } else if (option == "--help" || option == "-h") {
            std::cout << kUsage << "\n";
            return kOk;
        } else {
            throw UsageError("unknown option '" + std::string(option) + "'\n" + kUsage);
        }
    }
    if (sequence_frames > 0 && !times.empty()) throw UsageError("--at and --frames: give one or the other");
    if (seconds && (sequence_frames > 0 || !times.empty())) throw UsageError("--seconds: give it instead of --frames or --at");
    // T seconds at F frames a second: the frames at 0, 1/F, ... before T, so the clip lasts T.
    if (seconds) sequence_frames = std::max(1L, long(std::ceil(*seconds * fps - 1e-9)));
    const bool video = !video_path.empty();
    if (video && !times.empty()) throw UsageError("--video needs --frames N or --seconds T (an animation), not --at");
    if (video && !out_dir.empty()) throw UsageError("--video and --out: give one or the other (the frames go into the video)");
    if (video && (width % 2 != 0 || height % 2 != 0)) {
        throw UsageError("--size " + std::to_string(width) + "x" + std::to_string(height) +
                         ": a video needs even sides (H.264 stores colour at half resolution)");
    }
    if (overwrite && !video) throw UsageError("--overwrite goes with --video");
    for (long k = 0; k < sequence_frames; ++k) times.push_back(double(k) / fps);
    if (times.empty()) throw UsageError(std::string("--at T1,T2,... or --frames N is required\n") + kUsage);
    if (out_dir.empty() && !video) throw UsageError(std::string("--out DIR or --video FILE.mp4 is required\n") + kUsage);
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());

    // Inputs first (cheap, and the user's most likely mistakes), then the output folder, then GL.
    const Scene resolved = scene.resolve();
    const Params& params = resolved.params;
    World world(make_world_def(resolved), WorldOptions{threads, false});
    for (const std::string& note : world.notes()) std::cerr << "softbody: note: " << note << "\n";
    const std::string name = scene.name(resolved);
    for (std::size_t i = 1; i < times.size() && sequence_frames == 0; ++i) {
        if (time_label(times[i]) == time_label(times[i - 1])) {
            throw UsageError("--at: " + std::to_string(times[i - 1]) + " and " + std::to_string(times[i]) +
                             " round to the same file name (times are written to the millisecond)");
        }
    }
    const std::filesystem::path dir(out_dir);
    // The video refuses to replace a file and starts ffmpeg (or, without it, makes the frames'
    // folder) before the first frame is drawn.
    std::unique_ptr<VideoWriter> writer;
    if (video) {
        std::error_code ec;
        if (!overwrite && std::filesystem::exists(std::filesystem::symlink_status(video_path, ec))) {
            throw InputError(video_path + ": already exists; not overwriting it (--overwrite replaces it)");
        }
        writer = std::make_unique<VideoWriter>(video_path, width, height, fps, overwrite);
        if (!writer->has_ffmpeg()) std::cerr << "softbody: " << writer->missing_ffmpeg_message() << "\n";
    } else {
        prepare_output(dir);
    }

    OffscreenContext context(width, height);
    render::Renderer renderer(context.loader());
    if (width > renderer.info().max_size || height > renderer.info().max_size) {
        throw InputError("--size " + std::to_string(width) + "x" + std::to_string(height) + ": this OpenGL (" +
                         renderer.info().renderer + ") draws at most " + std::to_string(renderer.info().max_size) +
                         " pixels a side");
    }

    const float aspect = float(width) / float(height);
    match_ground(params, frame.appearance);
    if (hide_ground) frame.appearance.ground = false;  // drawn without it; the physics keeps it
    apply_camera_options(camera_options, frame.camera);
    frame_body(world, params, aspect, frame.camera, camera_options.zoom);
    const auto fix_camera = [&] {
        if (camera_options.target) frame.camera.target = *camera_options.target;
        if (camera_options.distance) frame.camera.distance = *camera_options.distance;
    };
    fix_camera();

    const double dt = double(params.dt);
    // File names: "t<time>" for --at; for --frames the frame number, padded with zeros to the
    // last one's width (at least 4), so that name order is frame order.
    const auto label_of = [&, digits = std::max<std::size_t>(4, std::to_string(sequence_frames - 1).size())](
                              std::size_t k, double t) {
        if (sequence_frames == 0) return "t" + time_label(t);
        const std::string number = std::to_string(k);
        return std::string(digits - std::min(digits, number.size()), '0') + number;
    };
    for (std::size_t k = 0; k < times.size(); ++k) {
        const double t = times[k];
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
                      << (writer ? " (" + video_path + " has the " + std::to_string(writer->frames()) +
                                       (writer->frames() == 1 ? " frame" : " frames") + " before it)"
                                 : "")
                      << "\n";
            return kDiverged;
        }
        world_view(world, alpha, frame);
        if (camera_options.follow) {
            frame_body(world, params, aspect, frame.camera, camera_options.zoom);
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
    if (writer) {
        // One line for the whole video: where it is (or where its frames are), and its shape.
        writer->finish();
        nlohmann::ordered_json line = {
            {"video", writer->has_ffmpeg() ? nlohmann::ordered_json(video_path) : nlohmann::ordered_json(nullptr)},
            {"frames", writer->frames()}, {"fps", fps}, {"seconds", double(writer->frames()) / fps},
            {"width", width}, {"height", height}, {"tick", world.ticks()}, {"state_hash", hex(world.state_hash())},
            {"memory_kib", resident_memory().now_kib},
        };
        if (!writer->has_ffmpeg()) line["frames_folder"] = writer->frames_folder();
        std::cout << line.dump() << std::endl;
    }
    return kOk;
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
    Args args(argc, argv, 2);
    int frames = 100;
    while (!args.done()) {
        const std::string_view option = args.next();
        if (option == "--bench") continue;
        if (option == "--frames") frames = int(parse_int(option, args.value(option), 1, 100000));
        else throw UsageError("render --bench: unknown option '" + std::string(option) + "' (only --frames N)");
    }
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
    const Params& params = resolved.params;
    World world(make_world_def(resolved));
    world.run(30);
    render::Frame frame;
    world_view(world, 1.0f, frame);
    match_ground(params, frame.appearance);
    frame_body(world, params, aspect, frame.camera, 1.0f);
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
    std::printf("%-22s %9zu %10zu %15.3f %10.3f %10.2f   + PNG %.1f ms\n", "default scene", world.mesh().render_vertices.size(),
                world.mesh().triangle_count(), renderer.timings().surface_ms, renderer.timings().upload_ms,
                median(total), median(png));
    std::cout << "\nnormals: interpolation and normal recomputation on the CPU; stream: orphaning the vertex\n"
                 "buffer and writing the new vertices; frame: draw() plus reading the pixels back.\n";
    return kOk;
}

}  // namespace

}  // namespace softbody::app
