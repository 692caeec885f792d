// Scene files: a JSON object of
//   - the flat keys of params.h: the world's, and those of the soft body named "body" (present
//     when "mesh" is given);
//   - "soft_bodies": [ { "name": ..., "mesh": ..., body keys } ]: more soft bodies;
//   - "rigid_bodies": [ { "name": ..., "shape": ..., keys of rigid_body.h } ];
//   - "springs": [ { "a": END, "b": END, "stiffness": k, "damping": c, "rest_length": l0 } ]
//     with END { "body": NAME, "point": [x, y, z] }, { "body": NAME, "vertex": K } or
//     { "point": [x, y, z] } (fixed in the world);
//   - "title", "text": a lesson's name and what it shows (lesson.h); the physics never reads them;
//   - "expect": { "kind": CLOSED_FORM, "body": NAME, "slope": NAME }: what a lesson compares
//     with a closed form (lesson.h lists the kinds and what each needs).
// See README.md, "Scene files", for every key.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "physics/link.h"
#include "physics/params.h"
#include "physics/rigid_body.h"
#include "physics/world.h"

namespace softbody {

struct SoftBodyScene {
    std::string name;
    Params params;  // body keys only (ParamScope::Body)
    bool operator==(const SoftBodyScene&) const = default;
};

// What a lesson compares with a closed form: the form's name (lesson.h, closed_forms()) and the
// bodies it watches. Read by the lesson meter only, never by the physics.
struct LessonExpect {
    std::string kind;   // "spring_period", "terminal_velocity", ...
    std::string body;   // the body it watches (a rigid body, or a soft body for friction_slope)
    std::string slope;  // friction_slope: a fixed rigid body the body rests on ("": the ground)
    bool operator==(const LessonExpect&) const = default;
};

struct Scene {
    Params params;                           // world keys, and the soft body "body" when params.mesh is set
    std::vector<SoftBodyScene> soft_bodies;  // more soft bodies
    std::vector<RigidBodyDef> rigid_bodies;
    std::vector<SpringDef> springs;
    std::string title, text;              // a lesson's title and its short text (ignored by the physics)
    std::optional<LessonExpect> expect;   // a lesson's closed form, if it has one

    Scene() = default;
    Scene(const Params& p) : params(p) {}  // NOLINT: a scene of one soft body (or none) converts implicitly
    bool operator==(const Scene&) const = default;
    bool empty() const { return params.mesh.empty() && soft_bodies.empty() && rigid_bodies.empty(); }
};

// A mesh brought with no keys about its size or axes (`--mesh FILE`, a file dropped on the
// window, a scene file's mesh without "scale", "rotation" or "up_axis"): sized automatically
// (scale "auto": its largest side 1 m, centred) and stood up (+y up, as most exporters write).
void fit_brought_mesh(Params& params);

// Reads a scene file over `base` (keys not in the file keep base's values; arrays in the file
// replace base's). Mesh paths are taken relative to the scene file's folder. A soft body whose
// "mesh" comes without "scale" is sized automatically, and without "rotation" or "up_axis" is
// stood up (+y up), as fit_brought_mesh says. Throws InputError
// with file and line, naming the key (and the body).
Scene load_scene(const std::string& path, const Scene& base = {});

// Parses scene text; `origin` names it in errors and anchors relative mesh paths.
Scene parse_scene(const std::string& text, const std::string& origin, const Scene& base = {});

// Sets one key from command-line text: a world or flat-body key ("stiffness", "dt"), or a
// named body's ("plank.mass", "jelly.stiffness", "body.damping"). Throws InputError.
void set_scene_key(Scene& scene, std::string_view key, std::string_view text);

// Every body's name, in order: "body" (when there is a flat-key soft body), the other soft
// bodies, then the rigid bodies.
std::vector<std::string> body_names(const Scene& scene);

// Loads the meshes and makes the bodies: what World's constructor takes. Throws InputError
// naming the body and key (a missing mesh file, a flat mesh, a non-positive size, ...).
WorldDef make_world_def(const Scene& scene);

std::string scene_to_json(const Scene& scene);

enum class Overwrite { No, Yes };
// Writes atomically (temporary file, then rename). With Overwrite::No an existing file is
// left untouched and InputError is thrown. A failed write leaves any old file intact.
void save_scene(const std::string& path, const Scene& scene, Overwrite overwrite);

}  // namespace softbody
