// A tool of the demo's panel: one file each under gui/tools/, registered by the line at its end,
// drawn in order under its own header. A tool sees the session (the world and its time) and the
// view (the camera and what is drawn), and keeps only its own UI state. Adding a tool is one new
// file: a class with a title and a draw(), and a ToolRegistration.
#pragma once

#include <memory>
#include <vector>

namespace softbody::app {

class Session;
class View;
class Recorder;

// How the panel looks, which the Display tool sets: the text size (1: the screen's own; about 2
// for a projector at the back of a classroom).
struct UiSettings {
    float text_size = 1.0f;
};

struct ToolContext {
    Session& session;
    View& view;
    UiSettings& ui;
    Recorder* recorder = nullptr;  // the Record button's (gui/recorder.h); none: no button
    float scale = 1.0f;            // the UI's size against 1x
    float fps = 0.0f;              // frames drawn a second
};

class Tool {
public:
    virtual ~Tool() = default;
    virtual const char* title() const = 0;
    // Whether it has anything to show now (Rigid bodies: a world with rigid bodies).
    virtual bool shown(const Session&) const { return true; }
    // Whether its header opens by itself.
    virtual bool open(const Session&) const { return false; }
    // Once, when the panel is made: a tool that watches every tick says so here.
    virtual void attach(Session&) {}
    virtual void draw(ToolContext& context) = 0;
};

using ToolMaker = std::unique_ptr<Tool> (*)();

// A tool's place in the panel, from top to bottom (lower first), and how to make it.
struct ToolRegistration {
    ToolRegistration(int order, ToolMaker make);
};

// One of every registered tool, in their order.
std::vector<std::unique_ptr<Tool>> make_tools();

}  // namespace softbody::app
