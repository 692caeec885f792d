// Where a scene comes from, for every front end that opens one by name: the command line's
// --scene (cli.h) and the Python module's World (app/python). A name is a scene file (found from
// here, else from the assets' folder), a bundled scene's name ("spring.json") or a generated
// scene ("pile:100"); nothing at all is the default scene.
#pragma once

#include <string>

#include "physics/scene_io.h"

namespace softbody::app {

// Folder of the bundled assets (meshes and scenes): beside the installed executable, or the
// source tree's the build was made from.
std::string assets_dir();
std::string default_scene_path();

// A relative scene path that does not exist from here: the same path from the assets' folder
// ("assets/scenes/x.json" run from anywhere), or a bundled scene's name ("spring.json"). Any
// other name comes back as given (its reader then says it is missing, naming it so).
std::string find_scene(const std::string& name);

// Reads the scene `name` names, as find_scene finds it (the default scene for ""). Throws
// InputError as load_scene does (FileError for a file that cannot be read).
Scene open_scene(const std::string& name);

// A scene file, read, with each mesh it names by a relative path that is not beside it looked
// up in the bundled assets ("assets/meshes/cube.obj" or "meshes/cube.obj" from a preset that
// was downloaded from the page or moved from the folder it was saved in), as a scene is found
// from anywhere. Throws InputError as load_scene does.
Scene load_scene_file(const std::string& path);

// A bundled file's path as "assets/...", the form that finds it from anywhere (a link, a
// downloaded preset); empty for a path outside the bundled assets.
std::string bundled_name(const std::string& path);

// Throws InputError when the scene has nothing to simulate (no body of either kind).
void require_bodies(const Scene& scene);

}  // namespace softbody::app
