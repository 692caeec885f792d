#include "gui/input.h"

#include <algorithm>
#include <cmath>

#include "gui/bindings.h"
#include "gui/session.h"
#include "gui/view.h"

namespace softbody::app {

UiRequests Controls::handle(Session& session, View& view, const InputEvent& e, float width, float height, float ui_scale) {
    UiRequests ui;
    // Buttons act where the pointer last moved to (a script's "press" carries no position).
    if (e.type == InputEvent::Type::Move) {
        pointer_x_ = e.x;
        pointer_y_ = e.y;
    }
    const float px = pointer_x_ * width, py = pointer_y_ * height;
    switch (e.type) {
        case InputEvent::Type::Press: {
            if (drag_ != Drag::None) break;
            drag_button_ = e.button;
            last_x_ = px;
            last_y_ = py;
            if (e.button == 0) {
                const auto picked = view.pick(session.world(), px, py, width, height, 18.0f * ui_scale);
                if (e.ctrl) {
                    // ctrl-click: inspect what is there (nothing: stop inspecting)
                    if (picked) session.inspect({picked->rigid, picked->body, picked->particle});
                    else session.stop_inspecting();
                    drag_button_ = -1;
                } else if (picked && e.shift && !picked->rigid) {
                    session.toggle_pin(picked->body, picked->particle);  // shift-click: pin or free
                    drag_button_ = -1;
                } else if (picked) {
                    view.begin_grab(session, *picked, px, py, width, height);
                    drag_ = Drag::Grab;
                } else {
                    drag_ = Drag::Orbit;  // left-drag on empty space turns the view
                }
            } else if (e.button == 1) {
                drag_ = e.ctrl || e.shift ? Drag::Pan : Drag::Orbit;
            } else if (e.button == 2) {
                drag_ = Drag::Pan;
            }
            break;
        }
        case InputEvent::Type::Move: {
            const float dx = px - last_x_, dy = py - last_y_;
            last_x_ = px;
            last_y_ = py;
            if (drag_ == Drag::Grab) {
                view.drag(session, px, py, width, height);
            } else if (drag_ == Drag::Orbit) {
                view.camera.orbit(-dx * 0.006f, dy * 0.006f);
            } else if (drag_ == Drag::Pan) {
                // One pixel moves the target by the width a pixel covers at the target.
                const float metres_per_pixel = 2.0f * view.camera.distance * std::tan(0.5f * view.camera.fov_y) / height;
                view.pan(session, -dx * metres_per_pixel, dy * metres_per_pixel);
            }
            break;
        }
        case InputEvent::Type::Release:
            if (e.button != drag_button_) break;
            if (drag_ == Drag::Grab) view.end_grab(session);
            drag_ = Drag::None;
            drag_button_ = -1;
            break;
        case InputEvent::Type::Scroll:
            view.camera.zoom(std::pow(0.88f, e.scroll));
            break;
        case InputEvent::Type::Key: {
            // The keys and what they do are listed in gui/bindings.cpp, which the help prints.
            const KeyBinding* binding = binding_of_key(e.key);
            if (!binding) break;
            switch (binding->command) {
                case KeyCommand::Pause: session.paused = !session.paused; break;
                case KeyCommand::Tick:
                    session.paused = true;
                    session.single_tick();
                    break;
                case KeyCommand::TickBack: session.step_back(); break;
                case KeyCommand::Reset: session.reset(); break;
                case KeyCommand::Frame: view.frame_body(session); break;
                case KeyCommand::Follow: view.follow = !view.follow; break;
                case KeyCommand::Particles: view.overlays.particles = !view.overlays.particles; break;
                case KeyCommand::Springs: view.overlays.springs = !view.overlays.springs; break;
                case KeyCommand::CentreOfMass: view.overlays.center_of_mass = !view.overlays.center_of_mass; break;
                case KeyCommand::Velocities: view.overlays.velocities = !view.overlays.velocities; break;
                case KeyCommand::Angular: view.overlays.angular = !view.overlays.angular; break;
                case KeyCommand::Record: ui.toggle_recording = true; break;
                case KeyCommand::Panels: ui.toggle_panels = true; break;
                case KeyCommand::Help: ui.toggle_help = true; break;
                case KeyCommand::CloseHelp: ui.close_help = true; break;
            }
            break;
        }
    }
    return ui;
}

}  // namespace softbody::app

// --- Touch ----------------------------------------------------------------------------------

namespace softbody::app {

namespace {

// A pinch's zoom as wheel clicks: the controls zoom by 0.88 a click, so spreading the fingers
// to twice as far apart brings the view twice as close.
float pinch_clicks(float spread_before, float spread_after) {
    if (!(spread_before > 0.0f) || !(spread_after > 0.0f)) return 0.0f;
    return std::log(spread_after / spread_before) / -std::log(0.88f);
}

}  // namespace

TouchGestures::Finger* TouchGestures::find(int id) {
    for (Finger& f : fingers_) {
        if (f.id == id) return &f;
    }
    return nullptr;
}

void TouchGestures::emit(InputEvent::Type type, float x, float y, int button, bool ctrl, float scroll) {
    InputEvent e;
    e.type = type;
    e.x = x / width_;
    e.y = y / height_;
    e.button = button;
    e.ctrl = ctrl;
    e.scroll = scroll;
    e.touch = true;
    events_.push_back(e);
}

void TouchGestures::ui(float x, float y, bool down, bool keep, float scroll) {
    UiPointer p;
    p.x = x;
    p.y = y;
    p.away = false;
    p.down = down;
    p.keep = keep;
    p.scroll = scroll;
    ui_.push_back(p);
}

void TouchGestures::ui_away() {
    UiPointer p;
    p.keep = true;
    ui_.push_back(p);
}

void TouchGestures::start_two() {
    const Finger &a = fingers_[0], &b = fingers_[1];
    const float mx = 0.5f * (a.x + b.x), my = 0.5f * (a.y + b.y);
    emit(InputEvent::Type::Move, mx, my);
    emit(InputEvent::Type::Press, mx, my, 2);  // the middle button: pan
    last_spread_ = std::hypot(a.x - b.x, a.y - b.y);
    mode_ = Mode::Two;
}

void TouchGestures::touch(Phase phase, int id, float x, float y, double time, float width, float height, float scale,
                          bool on_ui) {
    width_ = std::max(width, 1.0f);
    height_ = std::max(height, 1.0f);
    slop_ = kSlop * std::max(scale, 0.5f);
    Finger* finger = find(id);
    if (phase == Phase::Down && !finger) {
        fingers_.push_back(Finger{id, x, y, x, y});
        if (mode_ == Mode::Idle) {
            down_time_ = time;
            if (on_ui) {
                ui(x, y, false, true);  // the panel sees where the finger is before it presses
                mode_ = Mode::UiPending;
            } else {
                mode_ = Mode::Pending;
            }
        } else if (mode_ == Mode::Pending) {
            start_two();
        } else if (mode_ == Mode::Drag) {
            emit(InputEvent::Type::Release, fingers_[0].x, fingers_[0].y, 0);
            start_two();
        }
        return;  // a third finger, or one beside a finger on the panel, is only counted
    }
    if (!finger) return;
    const bool first = finger == &fingers_[0];
    const bool second = fingers_.size() > 1 && finger == &fingers_[1];
    if (phase == Phase::Move || phase == Phase::Down) {
        const float dy = y - finger->y;
        finger->x = x;
        finger->y = y;
        const float moved = std::hypot(x - finger->x0, y - finger->y0);
        switch (mode_) {
            case Mode::Pending:
                if (moved > slop_) {
                    // A drag from where the finger came down: what is there is grabbed.
                    emit(InputEvent::Type::Move, finger->x0, finger->y0);
                    emit(InputEvent::Type::Press, finger->x0, finger->y0, 0);
                    emit(InputEvent::Type::Move, x, y);
                    mode_ = Mode::Drag;
                }
                break;
            case Mode::Drag:
                if (first) emit(InputEvent::Type::Move, x, y);
                break;
            case Mode::Two:
                if (first || second) {
                    const Finger &a = fingers_[0], &b = fingers_[1];
                    emit(InputEvent::Type::Move, 0.5f * (a.x + b.x), 0.5f * (a.y + b.y));
                    const float spread = std::hypot(a.x - b.x, a.y - b.y);
                    if (const float clicks = pinch_clicks(last_spread_, spread); clicks != 0.0f) {
                        emit(InputEvent::Type::Scroll, 0.5f * (a.x + b.x), 0.5f * (a.y + b.y), 0, false, clicks);
                    }
                    last_spread_ = spread;
                }
                break;
            case Mode::UiPending:
                if (first && moved > slop_) {
                    if (std::abs(y - finger->y0) > std::abs(x - finger->x0)) {
                        ui(x, y, false, false, y - finger->y0);  // up or down: the panel scrolls
                        mode_ = Mode::UiScroll;
                    } else {
                        ui(finger->x0, finger->y0, true, true);  // sideways: a slider follows
                        ui(x, y, true, false);
                        mode_ = Mode::UiDrag;
                    }
                }
                break;
            case Mode::UiDrag:
                if (first) ui(x, y, true, false);
                break;
            case Mode::UiScroll:
                if (first) ui(x, y, false, false, dy);
                break;
            case Mode::Idle:
            case Mode::Done:
                break;
        }
        return;
    }

    // Up or Cancel: the finger leaves.
    const bool cancel = phase == Phase::Cancel;
    const Finger gone = *finger;
    fingers_.erase(fingers_.begin() + (finger - fingers_.data()));
    switch (mode_) {
        case Mode::Pending:
            if (!cancel) {  // a tap: a click where the finger came down
                emit(InputEvent::Type::Move, gone.x0, gone.y0);
                emit(InputEvent::Type::Press, gone.x0, gone.y0, 0);
                emit(InputEvent::Type::Release, gone.x0, gone.y0, 0);
            }
            mode_ = Mode::Idle;
            break;
        case Mode::Drag:
            if (first) {
                emit(InputEvent::Type::Release, gone.x, gone.y, 0);
                mode_ = fingers_.empty() ? Mode::Idle : Mode::Done;
            }
            break;
        case Mode::Two:
            if (first || second) {
                emit(InputEvent::Type::Release, gone.x, gone.y, 2);
                mode_ = fingers_.empty() ? Mode::Idle : Mode::Done;  // no jump into a one-finger turn
            }
            break;
        case Mode::UiPending:
            if (first) {
                if (!cancel) {  // a tap on the panel: pressed for a frame, then lifted
                    ui(gone.x0, gone.y0, true, true);
                    ui(gone.x0, gone.y0, false, true);
                }
                ui_away();
                mode_ = fingers_.empty() ? Mode::Idle : Mode::Done;
            }
            break;
        case Mode::UiDrag:
            if (first) {
                if (!cancel) ui(gone.x, gone.y, false, true);
                ui_away();  // a cancelled drag lifts away from what it held: no click
                mode_ = fingers_.empty() ? Mode::Idle : Mode::Done;
            }
            break;
        case Mode::UiScroll:
            if (first) {
                ui_away();
                mode_ = fingers_.empty() ? Mode::Idle : Mode::Done;
            }
            break;
        case Mode::Idle:
        case Mode::Done:
            break;
    }
    if (fingers_.empty()) mode_ = Mode::Idle;
}

void TouchGestures::update(double time, float width, float height) {
    if (fingers_.empty() || time - down_time_ < kLongPress) return;
    width_ = std::max(width, 1.0f);
    height_ = std::max(height, 1.0f);
    const Finger& f = fingers_[0];
    if (mode_ == Mode::Pending) {
        // Held still: inspect what is under the finger (on the sky: stop inspecting).
        emit(InputEvent::Type::Move, f.x0, f.y0);
        emit(InputEvent::Type::Press, f.x0, f.y0, 0, true);
        emit(InputEvent::Type::Release, f.x0, f.y0, 0, true);
        mode_ = Mode::Done;
    } else if (mode_ == Mode::UiPending) {
        ui(f.x0, f.y0, true, true);  // held on the panel: pressed, and a drag drags what is there
        mode_ = Mode::UiDrag;
    }
}

std::vector<InputEvent> TouchGestures::take_events() {
    std::vector<InputEvent> events;
    events.swap(events_);
    return events;
}

std::vector<UiPointer> TouchGestures::take_ui() {
    std::vector<UiPointer> pointers;
    pointers.swap(ui_);
    return pointers;
}

}  // namespace softbody::app
