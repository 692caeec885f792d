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

Scene open_scene(const std::string& name) {
    if (name.empty()) return load_scene(default_scene_path());
    return is_generated(name) ? load_scene(name) : load_scene_file(find_scene(name));
}

Scene load_scene_file(const std::string& path) {
    Scene scene = load_scene(path);
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    const std::filesystem::path assets(assets_dir());
    const auto find = [&](std::string& mesh) {
        std::error_code error;
        if (mesh.empty() || is_generated(mesh) || std::filesystem::exists(mesh, error)) return;
        // As the file named it: the reader joined it to the file's folder.
        const std::filesystem::path named = std::filesystem::path(mesh).lexically_relative(folder.empty() ? "." : folder);
        if (named.empty() || named.is_absolute() || *named.begin() == "..") return;
        for (const std::filesystem::path& candidate : {assets.parent_path() / named, assets / named, assets / "meshes" / named}) {
            if (std::filesystem::exists(candidate, error)) {
                mesh = candidate.lexically_normal().string();
                return;
            }
        }
    };
    for (SoftBodyDef& body : scene.soft_bodies) find(body.mesh);
    for (RigidBodyDef& body : scene.rigid_bodies) find(body.mesh);
    return scene;
}

std::string bundled_name(const std::string& path) {
    const std::filesystem::path assets = std::filesystem::path(assets_dir()).lexically_normal();
    std::error_code error;
    const std::filesystem::path absolute = std::filesystem::absolute(path, error);
    if (error || path.empty()) return {};
    const std::filesystem::path relative = absolute.lexically_normal().lexically_relative(assets);
    if (relative.empty() || *relative.begin() == ".." || relative.is_absolute()) return {};
    return "assets/" + relative.generic_string();
}


void require_bodies(const Scene& scene) {
    if (scene.empty()) {
        throw InputError("nothing to simulate: give --mesh FILE, or a scene file with \"soft_bodies\" or \"rigid_bodies\"");
    }
}

}  // namespace softbody::app
