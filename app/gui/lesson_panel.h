// The Lessons menu and the Lesson panel: open a lesson (physics/lesson.h, in the addendum's
// order), read its title and text, and watch "expected against actual": each closed form's
// predicted value beside the one measured from the running world, tick by tick.
// The panel owns the lesson's meter; the Demo hands it every tick through Demo::on_tick.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "physics/lesson.h"

namespace softbody::app {

class Demo;

// Loads lesson `number` (from 1) into the demo; false and the demo's error when there is none.
bool open_lesson(Demo& demo, std::size_t number);

class LessonPanel {
public:
    LessonPanel();

    // Feeds every tick of the demo's world to the lesson's meter (sets demo.on_tick).
    void attach(Demo& demo);
    // The Lessons menu and, when the scene is a lesson, its title, text and comparisons.
    void draw(Demo& demo, float scale);
    // The lesson on show for a run's summary (number, title, comparisons); null when none.
    nlohmann::ordered_json summary(const Demo& demo);

private:
    void follow(const Demo& demo);  // a new world or scene: its title, text and a new meter

    std::vector<std::string> titles_;  // each lesson's, for the menu
    const void* world_ = nullptr;      // the world the meter watches (identity only)
    std::string source_;
    std::string title_, text_;
    std::size_t number_ = 0;           // the lesson on show, 0: none
    std::optional<LessonMeter> meter_;
    std::string error_;                // why the meter could not be made
};

}  // namespace softbody::app
