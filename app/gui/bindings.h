// The desktop demo's keys and mouse, listed once. The controls act on these keys (input.cpp),
// scripts name them (script.cpp), and the help overlay (H) and `softbody run --help` both print
// this list: a key is bound here or nowhere, so neither list can miss one.
#pragma once

#include <span>
#include <string>

namespace softbody::app {

enum class KeyCommand {
    Pause, Tick, TickBack, Reset, Frame, Follow,
    Particles, Springs, CentreOfMass, Velocities, Angular,
    Record, Panels, Help, CloseHelp,
};

struct KeyBinding {
    KeyCommand command;
    int keys[2];            // GLFW key codes (0: no second key)
    const char* names[2];   // the same keys as a script's `key` command writes them
    const char* label;      // as the help shows them
    const char* what;
};

struct MouseBinding {
    const char* gesture;
    const char* what;
};

std::span<const KeyBinding> key_bindings();
std::span<const MouseBinding> mouse_bindings();

// What a key does: null for a key that does nothing.
const KeyBinding* binding_of_key(int glfw_key);
// The key a script names ("space", "period", "t"): 0 for a name that is no key here.
int key_of_name(const std::string& name);

// Both lists as text, a line each with the gesture or key in a column `column` wide (for
// `softbody run --help`).
std::string controls_text(std::size_t column);

}  // namespace softbody::app
