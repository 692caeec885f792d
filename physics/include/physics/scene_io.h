// Scene files: a JSON object whose keys are exactly those of Params (see params.h).
#pragma once

#include <string>

#include "physics/params.h"

namespace softbody {

// Reads a scene file over `base` (keys not in the file keep base's values). A relative `mesh`
// path is taken relative to the scene file's folder. Throws InputError with file (and line).
Params load_scene(const std::string& path, const Params& base = {});

// Parses scene text; `origin` names it in errors and anchors a relative mesh path.
Params parse_scene(const std::string& text, const std::string& origin, const Params& base = {});

std::string scene_to_json(const Params& params);

enum class Overwrite { No, Yes };
// Writes atomically (temporary file, then rename). With Overwrite::No an existing file is
// left untouched and InputError is thrown. A failed write leaves any old file intact.
void save_scene(const std::string& path, const Params& params, Overwrite overwrite);

}  // namespace softbody
