// The bundled scenes and meshes the tools offer, and where presets are kept.
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

namespace softbody::app {

// The files of a folder with one of the extensions (".json"), sorted.
std::vector<std::string> list_files(const std::string& folder, std::initializer_list<const char*> extensions);
std::vector<std::string> bundled_scenes();  // assets/scenes/*.json
std::vector<std::string> bundled_meshes();  // assets/meshes/*.obj, *.off
// $XDG_DATA_HOME/softbody/presets, or ~/.local/share/softbody/presets.
std::string presets_folder();

}  // namespace softbody::app
