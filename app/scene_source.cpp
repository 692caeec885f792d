#include "scene_source.h"

#include <filesystem>

#include "physics/error.h"
#include "physics/generated.h"

namespace softbody::app {

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

}  // namespace

std::string assets_dir() {
    static const std::string dir = find_assets();
    return dir;
}

std::string default_scene_path() { return assets_dir() + "/scenes/default.json"; }

std::string find_scene(const std::string& name) {
    std::error_code error;
    const std::filesystem::path p(name);
    if (p.is_absolute() || is_generated(name) || std::filesystem::exists(p, error)) return name;
    const std::filesystem::path assets(assets_dir());
    for (const std::filesystem::path& candidate : {assets.parent_path() / p, assets / p, assets / "scenes" / p}) {
        if (std::filesystem::exists(candidate, error)) return candidate.lexically_normal().string();
    }
    return name;  // not found anywhere: its reader says so, naming the path as given
}

Scene open_scene(const std::string& name) { return load_scene(name.empty() ? default_scene_path() : find_scene(name)); }

void require_bodies(const Scene& scene) {
    if (scene.empty()) {
        throw InputError("nothing to simulate: give --mesh FILE, or a scene file with \"soft_bodies\" or \"rigid_bodies\"");
    }
}

}  // namespace softbody::app
