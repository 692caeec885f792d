// What the physics tests share: small meshes built in code, parameters with every effect off
// unless a test turns it on, and a temporary folder for test files.
#pragma once

#include <grp.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "physics/error.h"
#include "physics/mesh.h"
#include "physics/keys.h"
#include "physics/scene_io.h"
#include "physics/world.h"
#include "one_body_world.h"

namespace softbody::test {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kG = 9.81;  // m/s^2: the scenes' gravity unless they say otherwise

// The four integrators a scene can name, for the tests that run under each.
inline constexpr const char* kIntegrators[] = {"verlet", "symplectic_euler", "explicit_euler", "rk4"};

// Whether an integrator keeps the energy of a body in flight: explicit Euler gains it by itself.
inline bool keeps_energy(std::string_view integrator) { return integrator != "explicit_euler"; }

// A world of a scene given as JSON text.
inline World world_of(const std::string& json, int threads = 1) {
    return World(parse_scene(json, "test.json"), WorldOptions{threads});
}

// A world of a scene with its integrator replaced by the named one.
inline World world_of(Scene scene, std::string_view integrator, int threads = 1) {
    scene.settings.integrator = *integrator_from_string(integrator);
    return World(scene, WorldOptions{threads});
}

inline World world_of(const std::string& json, std::string_view integrator) {
    return world_of(parse_scene(json, "test.json"), integrator);
}

// A mesh of points only (no faces): a valid point cloud, one particle per distinct point.
inline Mesh points(const std::vector<Vec3>& positions, const std::string& name = "test points") {
    RawMesh raw;
    raw.positions = positions;
    return build_mesh(raw, name);
}

// n points spread uniformly in a ball of the given radius about the origin, reproducibly.
inline std::vector<Vec3> random_cloud(std::size_t n, std::uint32_t seed, float radius = 1.0f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::vector<Vec3> out;
    while (out.size() < n) {
        const Vec3 p{unit(rng), unit(rng), unit(rng)};
        if (dot(p, p) <= 1.0f) out.push_back(p * radius);
    }
    return out;
}

// The 8 corners of a cube with side `side`, centred on the origin.
inline std::vector<Vec3> cube_corners(float side = 1.0f) {
    std::vector<Vec3> out;
    for (int i = 0; i < 8; ++i) {
        out.push_back({(i & 1 ? 0.5f : -0.5f) * side, (i & 2 ? 0.5f : -0.5f) * side, (i & 4 ? 0.5f : -0.5f) * side});
    }
    return out;
}

// The soft body keys a scene's JSON gives at its top level (the old flat form), as a soft body
// named "body" of `mesh`: those keys make that body when the JSON gives a "mesh", and are
// ignored without one; tests that add a body of their own points take them from here.
inline SoftBodyDef flat_body_of(const std::string& json, const Mesh& mesh) {
    // The keys' defaults first: a key the JSON gives again at its top level replaces them.
    const Scene with_mesh =
        parse_scene("{\"mesh\": \"cloud:4\", \"scale\": 1, \"up_axis\": \"z\", " + json.substr(json.find('{') + 1), "test.json");
    SoftBodyDef body = with_mesh.soft_bodies.front();
    body.mesh = mesh.source;
    body.geometry = std::make_shared<const Mesh>(mesh);
    return body;
}

// Parameters with nothing acting: no gravity, springs, dampers, drag or ground, and the mesh
// left where it is (init_height 0). Each test switches on what it examines.
inline FlatKeys bare_params() {
    FlatKeys p;
    p.auto_substeps = false;  // one step a tick, as Listing 8 takes it
    p.init_height = 0.0f;
    p.gravity = {0.0f, 0.0f, 0.0f};
    p.stiffness = 0.0f;
    p.damping = 0.0f;
    p.drag_coefficient = 0.0f;
    p.ground = false;
    return p;
}

// Listing 8's constants as this project's defaults hold them (m 1 kg, k 10 N/m, c 0.1 kg/s,
// g 9.81 m/s^2 down, dt 0.02 s, ground on), with Listing 8's one step a tick (the project's
// default picks substeps for stability). Asserted once in keys_test.cpp.
inline FlatKeys listing8_params() {
    FlatKeys p;
    p.auto_substeps = false;
    return p;
}

inline Vec3 position(const World& world, std::size_t i) { return world.soft_body(0).x[i]; }
inline Vec3 velocity(const World& world, std::size_t i) { return world.soft_body(0).v[i]; }

inline bool all_finite(const World& world) {
    for (std::size_t i = 0; i < world.soft_body(0).particle_count(); ++i) {
        if (!is_finite(position(world, i)) || !is_finite(velocity(world, i))) return false;
    }
    return true;
}

// A folder of its own under the system's temporary folder, removed with everything in it.
class TempDir {
public:
    TempDir() {
        static std::atomic<int> counter{0};
        std::random_device random;
        path_ = std::filesystem::temp_directory_path() /
                ("softbody-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
                 std::to_string(random()));
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

    // Writes text to a file in the folder and returns its path.
    std::string write(const std::string& name, const std::string& text) const {
        const std::string target = file(name);
        std::ofstream out(target, std::ios::binary);
        out << text;
        out.close();
        EXPECT_TRUE(out) << "cannot write " << target;
        return target;
    }

private:
    std::filesystem::path path_;
};

inline std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs `body` in a child process and returns its exit code (128 + the signal if one ended it).
// The body reports through its return value only: test assertions in a child would be lost.
inline int in_child(const std::function<int()>& body) {
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        int code = 90;
        try {
            code = body();
        } catch (...) {
            code = 91;
        }
        ::_exit(code);
    }
    int status = 0;
    if (::waitpid(pid, &status, 0) != pid) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Like in_child, but as a user that file permissions apply to. Root reads and writes past any
// mode, so as root the child first becomes the unprivileged user "nobody" (uid and gid 65534);
// 77 when it cannot. The files it touches must lie where others may reach them (TempDir's do).
inline int as_unprivileged_user(const std::function<int()>& body) {
    return in_child([&] {
        if (::geteuid() == 0) {
            constexpr unsigned kNobody = 65534;
            if (::setgroups(0, nullptr) != 0 || ::setgid(kNobody) != 0 || ::setuid(kNobody) != 0) return 77;
        }
        return body();
    });
}

// The message of the InputError that `action` throws ("" when it throws none).
template <class F>
std::string error_of(F&& action) {
    try {
        action();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// What is wrong with a refusal: "" when `message` is one line that names each of the parts.
inline std::string refusal_fault(const std::string& message, std::initializer_list<const char*> parts) {
    if (message.empty()) return "it was accepted";
    for (const char* part : parts) {
        if (message.find(part) == std::string::npos) return "message \"" + message + "\" lacks \"" + part + "\"";
    }
    if (message.find('\n') != std::string::npos) return "not one line: " + message;
    return "";
}

// `action` must be refused with one line that names each of the given parts.
#define EXPECT_REFUSED_NAMING(action, ...) \
    EXPECT_EQ(::softbody::test::refusal_fault(::softbody::test::error_of([&] { action; }), {__VA_ARGS__}), "") << #action

}  // namespace softbody::test
