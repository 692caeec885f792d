#include "gui/asset_files.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "cli.h"

namespace softbody::app {

namespace fs = std::filesystem;

std::vector<std::string> list_files(const std::string& folder, std::initializer_list<const char*> extensions) {
    std::vector<std::string> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        const std::string ext = entry.path().extension().string();
        for (const char* wanted : extensions) {
            if (ext == wanted) files.push_back(entry.path().string());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::string presets_folder() {
    const char* data = std::getenv("XDG_DATA_HOME");
    const char* home = std::getenv("HOME");
    if (data && *data) return std::string(data) + "/softbody/presets";
    if (home && *home) return std::string(home) + "/.local/share/softbody/presets";
    return "presets";
}

std::vector<std::string> bundled_scenes() { return list_files(assets_dir() + "/scenes", {".json"}); }
std::vector<std::string> bundled_meshes() { return list_files(assets_dir() + "/meshes", {".obj", ".off"}); }

}  // namespace softbody::app
