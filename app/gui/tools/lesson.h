// The Lessons menu and the Lesson panel: open a lesson (physics/lesson.h, in the addendum's
// order), read its title and text, and watch "expected against actual": each closed form's
// predicted value beside the one measured from the running world, tick by tick.
// The tool owns the lesson's meter; the session hands it every tick (Session::on_tick).
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "gui/tool.h"
#include "physics/lesson.h"

namespace softbody::app {

class Session;

// Loads lesson `number` (from 1) into the session; false and the session's error when there is none.
bool open_lesson(Session& session, std::size_t number);

class LessonTool : public Tool {
public:
    LessonTool();
    const char* title() const override { return "Lesson"; }
    bool open(const Session& session) const override;
    // Feeds every tick of the session's world to the lesson's meter.
    void attach(Session& session) override;
    // The Lessons menu and, when the scene is a lesson, its title, text and comparisons.
    void draw(ToolContext& context) override;
    // The lesson on show for a run's summary (number, title, its controls as last drawn: key,
    // label, value and where on the window, comparisons); null when none.
    nlohmann::ordered_json summary(const Session& session);

private:
    void follow(const Session& session);  // a new world or scene: its title, text and a new meter
    void controls(Session& session);      // the lesson's own controls

    std::vector<std::string> titles_;  // each lesson's, for the menu
    const void* world_ = nullptr;      // the world the meter watches (identity only)
    std::string source_;
    std::string title_, text_;
    std::size_t number_ = 0;           // the lesson on show, 0: none
    std::optional<LessonMeter> meter_;
    std::string error_;                // why the meter could not be made
    struct ShownControl {
        std::string key, label, value;
        float x = 0, y = 0, w = 0, h = 0;  // the widget, in fractions of the window
    };
    std::vector<ShownControl> shown_;  // the controls as the last frame drew them
};

}  // namespace softbody::app
