#include "cli.h"

#include <charconv>
#include <cmath>
#include <filesystem>

#include "physics/error.h"
#include "physics/scene_io.h"

namespace softbody::app {

Args::Args(int argc, char** argv, int first) {
    for (int i = first; i < argc; ++i) args_.emplace_back(argv[i]);
}

std::string_view Args::value(std::string_view option) {
    if (done()) throw UsageError(std::string(option) + " needs a value");
    return next();
}

namespace {
// The shortest text that reads back as the same number: 1, 1000, 0.0001, 1e+07.
std::string shortest(double value) {
    char text[32];
    const auto result = std::to_chars(text, text + sizeof text, value);
    return std::string(text, result.ptr);
}
}  // namespace

double parse_double(std::string_view option, std::string_view text, double min, double max) {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value) ||
        value < min || value > max) {
        throw UsageError(std::string(option) + ": expected a number from " + shortest(min) + " to " + shortest(max) +
                         ", got '" + std::string(text) + "'");
    }
    return value;
}

std::int64_t parse_int(std::string_view option, std::string_view text, std::int64_t min, std::int64_t max) {
    std::int64_t value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size() || value < min || value > max) {
        throw UsageError(std::string(option) + ": expected a whole number from " + std::to_string(min) + " to " +
                         std::to_string(max) + ", got '" + std::string(text) + "'");
    }
    return value;
}

bool SceneOptions::take(Args& args) {
    const std::string_view option = args.peek();
    if (option == "--scene") {
        args.next();
        scene = args.value(option);
    } else if (option == "--mesh") {
        args.next();
        mesh = args.value(option);
    } else if (option == "--set") {
        args.next();
        const std::string_view assignment = args.value(option);
        const auto eq = assignment.find('=');
        if (eq == std::string_view::npos || eq == 0) {
            throw UsageError("--set: expected KEY=VALUE, got '" + std::string(assignment) + "'");
        }
        sets.emplace_back(std::string(assignment.substr(0, eq)), std::string(assignment.substr(eq + 1)));
    } else {
        return false;
    }
    return true;
}

Scene SceneOptions::resolve() const {
    Scene resolved;
    if (!scene.empty()) resolved = load_scene(scene);
    else if (mesh.empty()) resolved = load_scene(default_scene_path());
    if (!mesh.empty()) {
        // A mesh brought on the command line: sized and stood up automatically (the scene's
        // keys were for its own mesh); --set scale, up_axis or rotation overrides.
        resolved.params.mesh = mesh;
        fit_brought_mesh(resolved.params);
    }
    for (const auto& [key, value] : sets) set_scene_key(resolved, key, value);
    if (resolved.empty()) {
        throw InputError("nothing to simulate: give --mesh FILE, or a scene file with a \"mesh\", \"soft_bodies\" or "
                         "\"rigid_bodies\"");
    }
    return resolved;
}

std::string SceneOptions::name(const Scene& resolved) const {
    if (!scene.empty()) return std::filesystem::path(scene).stem().string();
    if (!mesh.empty()) return std::filesystem::path(resolved.params.mesh).stem().string();
    return "default";
}

std::string assets_dir() { return SOFTBODY_ASSETS_DIR; }
std::string default_scene_path() { return assets_dir() + "/scenes/default.json"; }

}  // namespace softbody::app
