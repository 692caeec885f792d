// What every subcommand shares: the scene options (--scene, --mesh, --set), exit codes, and
// a small argument reader that reports problems as one line naming the option.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "physics/params.h"
#include "physics/scene_io.h"

namespace softbody::app {

enum Exit : int { kOk = 0, kBadInput = 2, kDiverged = 3, kRuntimeFailure = 4 };

// Thrown for a usage mistake; main prints "softbody: <message>" and exits with kBadInput.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Args {
public:
    Args(int argc, char** argv, int first);
    bool done() const { return at_ >= args_.size(); }
    std::string_view peek() const { return args_[at_]; }
    std::string_view next() { return args_[at_++]; }
    // The value after an option such as --ticks; a usage error if it is missing.
    std::string_view value(std::string_view option);

private:
    std::vector<std::string_view> args_;
    std::size_t at_ = 0;
};

double parse_double(std::string_view option, std::string_view text, double min, double max);
std::int64_t parse_int(std::string_view option, std::string_view text, std::int64_t min, std::int64_t max);

// --scene FILE, --mesh FILE and --set KEY=VALUE (or NAME.KEY=VALUE for a named body), applied
// in that order whatever their order on the command line (the scene is the base, --mesh and
// --set override it).
struct SceneOptions {
    std::string scene;
    std::string mesh;
    std::vector<std::pair<std::string, std::string>> sets;

    // Consumes the option at args.peek() if it is one of ours; returns false otherwise.
    bool take(Args& args);
    // Builds the scene: the default scene when neither --scene nor --mesh is given.
    Scene resolve() const;
    // Name for output files: the scene's file stem, else the mesh's.
    std::string name(const Scene& scene) const;
};

// Folder of the bundled assets (meshes and scenes), fixed at build time.
std::string assets_dir();
std::string default_scene_path();

}  // namespace softbody::app
