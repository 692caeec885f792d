// What every subcommand shares: the scene options (--scene, --mesh, --set), the exit codes, and
// reading the command line. Options are declared with CLI11 (Debian's libcli11-dev), once each
// with a line of help: --help, the checks and the one-line errors all come from that
// declaration. Only the commands' own files include <CLI/CLI.hpp>; this header names it.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "physics/scene_io.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace softbody::app {

enum Exit : int { kOk = 0, kBadInput = 2, kDiverged = 3, kRuntimeFailure = 4 };

// Thrown for a usage mistake; main prints "softbody: <message>" and exits with kBadInput.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The lay-out every subcommand's help shares (options a line each, their help in one column)
// and the policies its options share (an option given twice: the last one counts).
void configure(CLI::App& app);

// Reads argv[first..] into the app's options. False when --help (or -h) was asked for: the help
// has been printed on stdout, and the command exits 0. A mistake throws UsageError with one
// line naming the option ("--ticks: expected a whole number from 0 to 1000000000, got 'ten'").
bool parse(CLI::App& app, int argc, char** argv, int first);

// An option taking a number from min to max (a whole number for the integer ones); anything
// else is refused as "OPTION: expected a number from MIN to MAX, got 'TEXT'".
CLI::Option* add_number(CLI::App& app, const std::string& name, double& value, double min, double max,
                        const std::string& help);
CLI::Option* add_whole(CLI::App& app, const std::string& name, std::int64_t& value, std::int64_t min, std::int64_t max,
                       const std::string& help);
CLI::Option* add_whole(CLI::App& app, const std::string& name, int& value, std::int64_t min, std::int64_t max,
                       const std::string& help);

// The same checks for a value inside a longer one (--size WxH, --at T1,T2, --camera yaw=30).
double parse_double(std::string_view option, std::string_view text, double min, double max);
std::int64_t parse_int(std::string_view option, std::string_view text, std::int64_t min, std::int64_t max);

// The exit codes, for a command's help: 0, 2 and 4 always; 3 where a run can diverge.
std::string exit_codes_help(bool can_diverge);

// --scene FILE (or --lesson N), --mesh FILE and --set KEY=VALUE (or NAME.KEY=VALUE for a named body), applied
// in that order whatever their order on the command line (the scene is the base, --mesh and
// --set override it).
struct SceneOptions {
    std::string scene;
    std::int64_t lesson = 0;  // 0: none
    std::string mesh;
    std::vector<std::string> sets;  // KEY=VALUE each, checked as they are read

    // Declares the three options on app.
    void add_to(CLI::App& app);
    // Builds the scene: the default scene when neither --scene nor --mesh is given.
    Scene resolve() const;
    // Name for output files: the scene's file stem, else the mesh's.
    std::string name() const;
};

// Folder of the bundled assets (meshes and scenes): beside the installed executable, or the
// source tree's the build was made from.
std::string assets_dir();
std::string default_scene_path();
// Lesson `number`'s scene file (from 1, as `softbody lessons` numbers them); UsageError when there is none.
std::string lesson_path(std::int64_t number);

}  // namespace softbody::app
