#include "gui/bindings.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace softbody::app {

namespace {

constexpr MouseBinding kMouse[] = {
    {"left-drag on a body", "pull it by that point: a damped spring to the cursor"},
    {"shift + left-click", "pin or free a particle"},
    {"ctrl + left-click", "inspect a particle or a rigid body: every force on it (on the sky: stop)"},
    {"left-drag elsewhere, right-drag", "orbit the camera"},
    {"middle-drag, ctrl + right-drag", "pan (shift + right-drag too)"},
    {"wheel", "zoom"},
    {"drop a file on the window", "load an .obj or .off mesh"},
};

constexpr KeyBinding kKeys[] = {
    {KeyCommand::Pause, {GLFW_KEY_SPACE, 0}, {"space", nullptr}, "Space", "pause / play"},
    {KeyCommand::Tick, {GLFW_KEY_N, GLFW_KEY_PERIOD}, {"n", "period"}, "N or .", "one tick on (and pause)"},
    {KeyCommand::TickBack, {GLFW_KEY_COMMA, 0}, {"comma", nullptr}, ", (comma)", "one tick back (the timeline keeps the last 20 s)"},
    {KeyCommand::Reset, {GLFW_KEY_R, 0}, {"r", nullptr}, "R", "reset"},
    {KeyCommand::Frame, {GLFW_KEY_F, 0}, {"f", nullptr}, "F", "frame the bodies"},
    {KeyCommand::Follow, {GLFW_KEY_T, 0}, {"t", nullptr}, "T", "camera follows the bodies / stays (Display panel)"},
    {KeyCommand::Particles, {GLFW_KEY_P, 0}, {"p", nullptr}, "P", "particles on / off"},
    {KeyCommand::Springs, {GLFW_KEY_S, 0}, {"s", nullptr}, "S", "springs on / off"},
    {KeyCommand::CentreOfMass, {GLFW_KEY_C, 0}, {"c", nullptr}, "C", "centre of mass on / off"},
    {KeyCommand::Velocities, {GLFW_KEY_V, 0}, {"v", nullptr}, "V", "velocity arrows on / off"},
    {KeyCommand::Angular, {GLFW_KEY_W, 0}, {"w", nullptr}, "W", "rigid bodies' omega and L arrows on / off"},
    {KeyCommand::Record, {GLFW_KEY_M, 0}, {"m", nullptr}, "M", "record the view into a video / stop"},
    {KeyCommand::Panels, {GLFW_KEY_TAB, 0}, {"tab", nullptr}, "Tab", "hide / show the panels"},
    {KeyCommand::Help, {GLFW_KEY_H, GLFW_KEY_F1}, {"h", "f1"}, "H or F1", "this help / hide it"},
    {KeyCommand::CloseHelp, {GLFW_KEY_ESCAPE, 0}, {"escape", nullptr}, "Esc", "close the help"},
};

}  // namespace

std::span<const KeyBinding> key_bindings() { return kKeys; }
std::span<const MouseBinding> mouse_bindings() { return kMouse; }

const KeyBinding* binding_of_key(int glfw_key) {
    for (const KeyBinding& binding : kKeys) {
        if (glfw_key != 0 && (binding.keys[0] == glfw_key || binding.keys[1] == glfw_key)) return &binding;
    }
    return nullptr;
}

int key_of_name(const std::string& name) {
    for (const KeyBinding& binding : kKeys) {
        for (int k = 0; k < 2; ++k) {
            if (binding.names[k] && name == binding.names[k]) return binding.keys[k];
        }
    }
    return 0;
}

std::string controls_text(std::size_t column) {
    const auto line = [column](const char* left, const char* right) {
        std::string text = "  " + std::string(left);
        text += text.size() < column ? std::string(column - text.size(), ' ') : std::string("  ");
        return text + right + "\n";
    };
    std::string text = "Mouse (in the view; the panels keep the mouse while they use it):\n";
    for (const MouseBinding& m : kMouse) text += line(m.gesture, m.what);
    text += "\nKeys:\n";
    for (const KeyBinding& k : kKeys) text += line(k.label, k.what);
    return text;
}

}  // namespace softbody::app
