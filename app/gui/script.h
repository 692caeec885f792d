// Scripted input for testing the app without a person: a text file of timed events.
//
//   # frame  command   arguments
//   10       move      0.50 0.55        pointer to a fraction of the view (x right, y down)
//   11       press     left [shift|ctrl]
//   40       release   left
//   50       scroll    -2               wheel clicks
//   60       key       space            a key by its name in gui/bindings.cpp (space, period, t, ...)
//   70       set       stiffness 40     as --set, or a slider (plank.mass 7 for a named body)
//   80       load_scene assets/scenes/pig.json
//   81       load_mesh  my.obj
//   90       save_preset out.json [overwrite]
//   91       export_csv run.csv [overwrite]   the Graph tool's Export CSV: every tick so far
//   92       inspect 12                 the inspector on particle 12 of the first soft body (or none)
//   93       rewind 2.0                 back 2 s on the timeline (paused there; play goes on)
//   94       step_back                  one tick back
//   94       lesson 3                   open lesson 3, as the Lessons menu does
//   96       compare explicit_euler rk4:2   integrators beside the main world (NAME[:SUBSTEPS]), or off
//   95       reset | pause | play
//   96       record start [FILE.mp4] | record stop   the Record button (gui/recorder.h)
//   97       add soft_ball              the Add menu: soft_ball, soft_cube, rigid_box, rigid_ball, mesh FILE
//   400      loop                       start the script again (from its frame 0) here
//
// Events run at the start of their frame, in file order.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gui/session.h"
#include "gui/input.h"

namespace softbody::app {

struct ScriptCommand {
    std::int64_t frame = 0;
    std::string verb;  // "input" for mouse/keyboard events, else the command
    InputEvent input;
    std::vector<std::string> args;
    std::size_t line = 0;
};

// "explicit_euler" or "rk4:4" (four substeps a tick; without a number, automatic).
std::optional<CompareSetup> parse_compare_setup(const std::string& text);

// Throws InputError naming the file and line of anything it cannot read.
std::vector<ScriptCommand> load_script(const std::string& path);

}  // namespace softbody::app
