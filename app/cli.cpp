#include "cli.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "physics/error.h"
#include "physics/generated.h"
#include "physics/lesson.h"
#include "physics/scene_io.h"

namespace softbody::app {

namespace {

// The shortest text that reads back as the same number: 1, 1000, 0.0001, 1e+07.
std::string shortest(double value) {
    char text[32];
    const auto result = std::to_chars(text, text + sizeof text, value);
    return std::string(text, result.ptr);
}

// What is wrong with `text` as a number from min to max, or "" when nothing is.
std::string number_problem(std::string_view text, double min, double max) {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value) || value < min ||
        value > max) {
        return "expected a number from " + shortest(min) + " to " + shortest(max) + ", got '" + std::string(text) + "'";
    }
    return "";
}

std::string whole_problem(std::string_view text, std::int64_t min, std::int64_t max) {
    std::int64_t value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size() || value < min || value > max) {
        return "expected a whole number from " + std::to_string(min) + " to " + std::to_string(max) + ", got '" +
               std::string(text) + "'";
    }
    return "";
}

// A check that CLI11 runs on the text before converting it; its message follows "OPTION: ".
CLI::Validator check(std::function<std::string(const std::string&)> problem) {
    return CLI::Validator([problem = std::move(problem)](std::string& text) { return problem(text); }, "", "");
}

}  // namespace

namespace {

// The bundled assets: beside the installed executable (PREFIX/bin/softbody finds
// PREFIX/share/softbody/assets), else the source tree's the build was made from; in the
// browser, the packaged folder.
std::string find_assets() {
#if !defined(__EMSCRIPTEN__)
    std::error_code error;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) {
        const std::filesystem::path installed = exe.parent_path().parent_path() / "share" / "softbody" / "assets";
        if (std::filesystem::exists(installed / "scenes" / "default.json", error)) return installed.string();
    }
#endif
    return SOFTBODY_ASSETS_DIR;
}

// A relative scene path that does not exist from here: the same path from the assets' folder
// ("assets/scenes/x.json" run from anywhere), or a bundled scene's name ("spring.json").
std::string find_scene(const std::string& path) {
    std::error_code error;
    const std::filesystem::path p(path);
    if (p.is_absolute() || is_generated(path) || std::filesystem::exists(p, error)) return path;
    const std::filesystem::path assets(assets_dir());
    for (const std::filesystem::path& candidate : {assets.parent_path() / p, assets / p, assets / "scenes" / p}) {
        if (std::filesystem::exists(candidate, error)) return candidate.lexically_normal().string();
    }
    return path;  // not found anywhere: its reader says so, naming the path as given
}

}  // namespace

void configure(CLI::App& app) {
    app.get_formatter()->column_width(28);
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.set_help_flag("-h,--help", "print this help and exit");
}

bool parse(CLI::App& app, int argc, char** argv, int first) {
    // CLI11 takes the arguments last first.
    std::vector<std::string> args(argv + std::min(first, argc), argv + argc);
    std::reverse(args.begin(), args.end());
    try {
        app.parse(args);
    } catch (const CLI::CallForHelp&) {
        std::cout << app.help();
        return false;
    } catch (const CLI::ParseError& e) {
        throw UsageError(e.what());
    }
    return true;
}

CLI::Option* add_number(CLI::App& app, const std::string& name, double& value, double min, double max,
                        const std::string& help) {
    return app.add_option(name, value, help)
        ->type_name("X")
        ->check(check([min, max](const std::string& text) { return number_problem(text, min, max); }));
}

CLI::Option* add_whole(CLI::App& app, const std::string& name, std::int64_t& value, std::int64_t min, std::int64_t max,
                       const std::string& help) {
    return app.add_option(name, value, help)
        ->type_name("N")
        ->check(check([min, max](const std::string& text) { return whole_problem(text, min, max); }));
}

CLI::Option* add_whole(CLI::App& app, const std::string& name, int& value, std::int64_t min, std::int64_t max,
                       const std::string& help) {
    return app.add_option(name, value, help)
        ->type_name("N")
        ->check(check([min, max](const std::string& text) { return whole_problem(text, min, max); }));
}

double parse_double(std::string_view option, std::string_view text, double min, double max) {
    if (std::string problem = number_problem(text, min, max); !problem.empty()) {
        throw UsageError(std::string(option) + ": " + problem);
    }
    double value = 0.0;
    std::from_chars(text.data(), text.data() + text.size(), value);
    return value;
}

std::int64_t parse_int(std::string_view option, std::string_view text, std::int64_t min, std::int64_t max) {
    if (std::string problem = whole_problem(text, min, max); !problem.empty()) {
        throw UsageError(std::string(option) + ": " + problem);
    }
    std::int64_t value = 0;
    std::from_chars(text.data(), text.data() + text.size(), value);
    return value;
}

std::string exit_codes_help(bool can_diverge) {
    return std::string("Exit codes:\n"
                       "  0  done\n"
                       "  2  bad input: one line on stderr names the option, file or key\n") +
           (can_diverge ? "  3  the simulation diverged: stderr says which limit it crossed and what to change\n" : "") +
           "  4  anything else failed (out of memory, a write, a program it runs)";
}

void SceneOptions::add_to(CLI::App& app) {
    app.add_option("--scene", scene, "scene file (JSON) or a generated one, pile:100 (default assets/scenes/default.json)")
        ->type_name("FILE");
    app.add_option("--lesson", lesson, "lesson N, as softbody lessons numbers them (its scene file; default: none)")
        ->type_name("N")
        ->check(check([](const std::string& text) { return whole_problem(text, 1, std::int64_t(lessons().size())); }));
    app.add_option("--mesh", mesh, "mesh (.obj, .off or cloud:N), sized to 1 m and stood up (default: the scene's)")
        ->type_name("FILE");
    app.add_option("--set", sets, "a key over the scene's (NAME.KEY=VALUE: a named body's or spring's; softbody keys lists them); repeatable (default: none)")
        ->type_name("KEY=VALUE")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->allow_extra_args(false)
        ->check(check([](const std::string& text) {
            const auto eq = text.find('=');
            return eq == std::string::npos || eq == 0 ? "expected KEY=VALUE, got '" + text + "'" : std::string();
        }));
}

Scene SceneOptions::resolve() const {
    if (lesson != 0 && !scene.empty()) throw UsageError("give --scene or --lesson, not both");
    Scene resolved;
    if (lesson != 0) resolved = load_scene(lesson_path(lesson));
    else if (!scene.empty()) resolved = load_scene(find_scene(scene));
    else if (mesh.empty()) resolved = load_scene(default_scene_path());
    if (!mesh.empty()) {
        // A mesh brought on the command line: every soft body's (or, in a scene without one, a
        // new body's), sized and stood up automatically (the scene's keys were for its own
        // mesh); --set scale, up_axis or rotation overrides.
        set_scene_key(resolved, "mesh", mesh);
        for (SoftBodyDef& body : resolved.soft_bodies) fit_brought_mesh(body);
    }
    for (const std::string& assignment : sets) {
        const auto eq = assignment.find('=');
        set_scene_key(resolved, assignment.substr(0, eq), assignment.substr(eq + 1));
    }
    if (resolved.empty()) {
        throw InputError("nothing to simulate: give --mesh FILE, or a scene file with \"soft_bodies\" or \"rigid_bodies\"");
    }
    return resolved;
}

std::string SceneOptions::name() const {
    if (lesson != 0) return std::filesystem::path(lessons()[std::size_t(lesson) - 1].file).stem().string();
    if (!scene.empty()) return std::filesystem::path(scene).stem().string();
    if (!mesh.empty()) return std::filesystem::path(mesh).stem().string();
    return "default";
}

std::string assets_dir() {
    static const std::string dir = find_assets();
    return dir;
}
std::string default_scene_path() { return assets_dir() + "/scenes/default.json"; }

std::string lesson_path(std::int64_t number) {
    if (number < 1 || std::size_t(number) > lessons().size()) {
        throw UsageError("--lesson: there is no lesson " + std::to_string(number) + " (1 to " + std::to_string(lessons().size()) + ")");
    }
    return assets_dir() + "/scenes/" + std::string(lessons()[std::size_t(number) - 1].file);
}

}  // namespace softbody::app
