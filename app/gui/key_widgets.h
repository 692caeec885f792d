// One key of the table (physics/keys.h) as a Dear ImGui widget: a slider for a number (over
// decades where the table says so), a box for true or false, a list for a word, three numbers or
// a colour for a vector, a box beside it for "auto", "all" or "none". Its label carries the unit,
// its tooltip the meaning, the equation, the valid range and when it applies; right-click sets
// the default. The value travels typed: what the slider holds is what set_key checks.
#pragma once

#include <optional>
#include <string>

#include "physics/keys.h"

namespace softbody::app {

// Whether a key has a widget (a file path, vertex indices and a quaternion have none here: the
// Mesh panel opens files, the mouse pins vertices, rotation stands for the quaternion).
bool has_widget(const KeyInfo& info);

// A slider's own ends and step, where a lesson gives them (else the key's slider).
struct SliderSpan {
    std::optional<double> min, max, step;
};

// Draws the widget for `value`; true when the user changed it (then `value` holds the new one,
// within the key's valid range). `label` replaces the key's name on screen when given.
bool key_widget(const KeyInfo& info, KeyValue& value, const std::string& label = {}, const SliderSpan& span = {});

// The key's tooltip, for the last item drawn.
void key_tooltip(const KeyInfo& info);

// "stiffness (N/m)": the key's name, and its unit in brackets.
std::string key_label(const KeyInfo& info);

}  // namespace softbody::app
