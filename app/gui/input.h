// Mouse and keyboard events, from the window or from a script, in one form; and the controls
// that turn them into camera moves, grabs, pins and commands.
#pragma once

#include <vector>

namespace softbody::app {

class Session;
class View;

struct InputEvent {
    enum class Type { Move, Press, Release, Scroll, Key } type = Type::Move;
    float x = 0.0f, y = 0.0f;  // pointer, as fractions of the view (0..1, y down)
    int button = 0;            // 0 left, 1 right, 2 middle
    bool shift = false, ctrl = false;
    float scroll = 0.0f;       // wheel clicks, positive away from the user
    int key = 0;               // GLFW key code
};

// What a key press asks of the user interface (the rest the controls do themselves).
struct UiRequests {
    bool toggle_help = false;
    bool close_help = false;
    bool toggle_panels = false;
    bool toggle_recording = false;
};

class Controls {
public:
    // width, height: the view in pixels (pick radius and pan speed are in pixels).
    UiRequests handle(Session& session, View& view, const InputEvent& event, float width, float height, float ui_scale);

private:
    enum class Drag { None, Orbit, Pan, Grab } drag_ = Drag::None;
    float pointer_x_ = 0.5f, pointer_y_ = 0.5f;  // fractions of the view
    float last_x_ = 0.0f, last_y_ = 0.0f;        // pixels, at the previous move
    int drag_button_ = -1;
};

}  // namespace softbody::app
