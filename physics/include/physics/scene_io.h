// Scene files: a JSON object of
//   - "world": { keys of the world (keys.h) };
//   - "soft_bodies": [ { "name": ..., "mesh": ..., keys of a soft body } ];
//   - "rigid_bodies": [ { "name": ..., "shape": ..., keys of a rigid body } ];
//   - "springs": [ { "name": ..., "a": END, "b": END, "stiffness": k, "damping": c, "rest_length": l0 } ]
//     with END { "body": NAME, "point": [x, y, z] }, { "body": NAME, "vertex": K } or
//     { "point": [x, y, z] } (fixed in the world); the name is optional;
//   - "title", "text": a lesson's name and what it shows (lesson.h); the physics never reads them;
//   - "expect": { "kind": CLOSED_FORM, "body": NAME, "slope": NAME }: what a lesson compares
//     with a closed form (lesson.h lists the kinds and what each needs).
// Names are unique across bodies and springs.
//
// The old flat form still reads, here and only here: world keys at the top level instead of in
// "world", and a soft body's keys at the top level with a "mesh", which make the soft body named
// "body" (first among the soft bodies). Top-level soft body keys without a "mesh" made no body
// then and are ignored now. Files are written in the new form.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "physics/defs.h"
#include "physics/keys.h"

namespace softbody {

// What a lesson compares with a closed form: the form's name (lesson.h, closed_forms()) and the
// bodies it watches. Read by the lesson meter only, never by the physics.
struct LessonExpect {
    std::string kind;   // "spring_period", "terminal_velocity", ...
    std::string body;   // the body it watches (a rigid body, or a soft body for friction_slope)
    std::string slope;  // friction_slope: a fixed rigid body the body rests on ("": the ground)
    bool operator==(const LessonExpect&) const = default;
};

// A world as a file describes it, and a lesson's words.
struct Scene : WorldDef {
    std::string title, text;              // a lesson's title and its short text (ignored by the physics)
    std::optional<LessonExpect> expect;   // a lesson's closed form, if it has one
    bool operator==(const Scene&) const = default;
};

// A mesh brought with no keys about its size or axes (`--mesh FILE`, a file dropped on the
// window, a scene file's mesh without "scale", "rotation" or "up_axis"): sized automatically
// (scale "auto": its largest side 1 m, centred) and stood up (+y up, as most exporters write).
void fit_brought_mesh(SoftBodyDef& def);

// Reads a scene file, or makes a generated one ("pile:100", generated.h). Mesh paths are taken
// relative to the scene file's folder. A soft body whose "mesh" comes without "scale" is sized
// automatically, and without "rotation" or "up_axis" is stood up (+y up), as fit_brought_mesh
// says. Throws InputError with file and line, naming the key (and the body).
Scene load_scene(const std::string& path);

// Parses scene text; `origin` names it in errors and anchors relative mesh paths.
Scene parse_scene(const std::string& text, const std::string& origin);

// Sets one key from command-line text, as World::set_key names keys: "dt" (the world's),
// "stiffness" (every soft body's), "bob.mass" (the thing named bob's). A "mesh" without a name
// in a scene without soft bodies makes one, named "body" (the old flat form's). Throws InputError.
void set_scene_key(Scene& scene, std::string_view key, std::string_view text);

// The keys that differ between a scene as loaded and a world as it is now, as `--set` takes
// them ("dt", "jelly.stiffness", "spring.rest_length"), each with its text: applied to the
// scene, they give the world's keys. Only things present in both by name count; `added` says
// how many bodies or springs the world has that the scene lacks, or lacks that it has (what
// keys cannot say).
struct ChangedKeys {
    std::vector<std::pair<std::string, std::string>> keys;
    std::size_t added = 0, removed = 0;
};
ChangedKeys changed_keys(const Scene& loaded, const WorldDef& now);

std::string scene_to_json(const Scene& scene);

enum class Overwrite { No, Yes };
// Writes atomically (temporary file, then rename). With Overwrite::No an existing file is
// left untouched and InputError is thrown. A failed write leaves any old file intact.
void save_scene(const std::string& path, const Scene& scene, Overwrite overwrite);

}  // namespace softbody
