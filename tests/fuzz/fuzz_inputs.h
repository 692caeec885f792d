// One input through one parser, as a fuzz target and the regression replay both run it.
//
// Each entry feeds the bytes to a parser the way a user's file or `--set` reaches it. A bad
// input must end in InputError (caught here: that is a parser doing its job). Anything else
// is a finding: a crash or a sanitizer's report, another exception (thrown on: a fuzz target
// then aborts, the replay test fails), or a result that breaks what the parser promises
// (InvariantBroken, from the checks in fuzz_inputs.cpp).
#pragma once

#include <stdexcept>
#include <string_view>

namespace softbody::fuzz {

class InvariantBroken : public std::logic_error {
public:
    using std::logic_error::logic_error;
};

// The text as an OBJ file and as an OFF file (parse_obj_text, parse_off_text), then
// build_mesh; checks the indices, the welding and the triangles of what they return.
void mesh_input(std::string_view data);

// The text as a scene file (parse_scene); what loads must be valid, and must save
// (scene_to_json) and load back to the same parameters.
void scene_input(std::string_view data);

// Each line as `--set KEY=VALUE` (set_scene_key, split at the first '='); a refused one changes
// nothing, an accepted one is valid and survives key_text and a scene file's round trip.
void set_input(std::string_view data);

}  // namespace softbody::fuzz
