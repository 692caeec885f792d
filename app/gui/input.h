// Mouse and keyboard events, from the window or from a script, in one form; the controls
// that turn them into camera moves, grabs, pins and commands; and the fingers of a touch
// screen, turned into the same events (and into the panel's pointer).
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
    bool touch = false;        // made from fingers: aimed at the view, whatever the panel wants
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

// The pointer the panel (the UI) sees while a finger works it, one state a frame: the panel
// needs a frame to see where a finger is before it sees it press, and a frame pressed before
// it sees it lift, or a tap would land where the last one was.
struct UiPointer {
    float x = 0.0f, y = 0.0f;  // pixels of the view
    bool away = true;          // no pointer over the panel (after a finger has lifted)
    bool down = false;
    float scroll = 0.0f;       // pixels the content is dragged down by (a finger's vertical drag)
    bool keep = false;         // a press or a release: shown for a frame of its own, never merged
};

// Fingers on a touch screen, as the gestures a class uses:
//   on the view: one finger drags a body when it starts on one, else turns the view; two
//   fingers pan, and pinching zooms; a tap is a click; a long press (half a second without
//   moving) inspects what is under the finger, as ctrl-click does.
//   on the panel: a tap is a click; a sideways drag moves a slider; an up or down drag
//   scrolls the panel; a long press, then a drag, drags whatever is under the finger.
// A finger belongs to where it first touched (the panel or the view) until it lifts.
class TouchGestures {
public:
    enum class Phase { Down, Move, Up, Cancel };
    // x, y: pixels of a width x height view; scale: pixels per CSS pixel (distances a finger
    // must move are in those); on_ui: whether a finger that comes down is on the panel.
    void touch(Phase phase, int id, float x, float y, double time, float width, float height, float scale, bool on_ui);
    // The long press's clock: called every frame.
    void update(double time, float width, float height);
    // What the fingers did for the controls, and for the panel's pointer, each taken once.
    std::vector<InputEvent> take_events();
    std::vector<UiPointer> take_ui();
    bool active() const { return !fingers_.empty(); }

    static constexpr double kLongPress = 0.5;  // s without moving
    static constexpr float kSlop = 10.0f;      // CSS px a finger may wander and still tap

private:
    struct Finger {
        int id;
        float x, y;    // now, pixels
        float x0, y0;  // where it came down
    };
    enum class Mode { Idle, Pending, Drag, Two, Done, UiPending, UiDrag, UiScroll };
    Finger* find(int id);
    void emit(InputEvent::Type type, float x, float y, int button = 0, bool ctrl = false, float scroll = 0.0f);
    void ui(float x, float y, bool down, bool keep, float scroll = 0.0f);
    void ui_away();
    void start_two();

    std::vector<Finger> fingers_;
    Mode mode_ = Mode::Idle;
    double down_time_ = 0.0;
    float width_ = 1.0f, height_ = 1.0f, slop_ = kSlop;
    float last_spread_ = 0.0f;  // distance between two fingers, pixels
    std::vector<InputEvent> events_;
    std::vector<UiPointer> ui_;
};

}  // namespace softbody::app
