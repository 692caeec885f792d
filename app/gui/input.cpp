#include "gui/input.h"

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
