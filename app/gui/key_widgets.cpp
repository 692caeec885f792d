#include "gui/key_widgets.h"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace softbody::app {

namespace {

// The lowest value a key takes: its minimum, or just above it when the range excludes it.
double lowest(const KeyInfo& info) { return info.above ? info.min + std::max(1e-6, std::abs(info.min) * 1e-6) : info.min; }

double clamp_to_range(const KeyInfo& info, double x) { return std::clamp(x, lowest(info), info.max); }

// The slider's ends: the table's, within the valid range, or the valid range itself.
void slider_range(const KeyInfo& info, double& lo, double& hi, const SliderSpan& span = {}) {
    lo = span.min ? *span.min : info.slider_max > info.slider_min ? info.slider_min : info.min;
    hi = span.max ? *span.max : info.slider_max > info.slider_min ? info.slider_max : info.max;
    lo = clamp_to_range(info, lo);
    hi = clamp_to_range(info, hi);
}

bool number_slider(const KeyInfo& info, const char* label, double& x, const SliderSpan& span) {
    double lo = 0.0, hi = 0.0;
    slider_range(info, lo, hi, span);
    if (info.type == KeyType::Whole) {
        int value = int(std::lround(x));
        const bool edited = ImGui::SliderInt(label, &value, int(lo), int(hi), "%d", info.slider_log ? ImGuiSliderFlags_Logarithmic : 0);
        if (edited) x = clamp_to_range(info, double(value));
        return edited;
    }
    float value = float(x);
    // Typed in (ctrl-click or double-click), a value beyond the slider's ends is kept within the valid range.
    const bool edited = ImGui::SliderFloat(label, &value, float(lo), float(hi), "%.4g",
                                           (info.slider_log && !span.min ? ImGuiSliderFlags_Logarithmic : 0));
    if (edited) {
        x = double(value);
        if (span.step && *span.step > 0.0) x = lo + std::round((x - lo) / *span.step) * *span.step;  // a lesson's steps
        x = clamp_to_range(info, x);
    }
    return edited;
}

}  // namespace

bool has_widget(const KeyInfo& info) {
    return !info.alias && info.type != KeyType::Path && info.type != KeyType::IndexList && info.type != KeyType::Quat;
}

std::string key_label(const KeyInfo& info) {
    std::string label(info.label.empty() ? info.name : info.label);
    if (!info.unit.empty()) label += " (" + std::string(info.unit) + ")";
    return label;
}

void key_tooltip(const KeyInfo& info) {
    if (!ImGui::IsItemHovered()) return;
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
    ImGui::TextUnformatted(std::string(info.meaning).c_str());
    ImGui::TextDisabled("key: %s", std::string(info.name).c_str());
    if (!info.unit.empty()) ImGui::Text("unit: %s", std::string(info.unit).c_str());
    if (!info.equation.empty()) ImGui::Text("enters: %s", std::string(info.equation).c_str());
    ImGui::Text("valid: %s", key_range_text(info).c_str());
    ImGui::TextDisabled(info.on_reset ? "applies on reset (it changes how the body is built)" : "applies at once");
    ImGui::TextDisabled("right-click: back to the default");
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

bool key_widget(const KeyInfo& info, KeyValue& value, const std::string& shown, const SliderSpan& span) {
    std::string words = shown.empty() ? key_label(info) : shown;
    if (info.on_reset) words += " *";
    // The label on a line of its own above a slider, list or vector (and the box of its word, if
    // it has one), so that no label is cut short however narrow the panel or large the text; a
    // true/false box keeps its label beside it.
    const bool above = info.type != KeyType::Bool;
    const std::string label = (above ? "" : words) + "##" + std::string(info.name);
    bool edited = false;
    ImGui::PushID(std::string(info.name).c_str());
    if (above) ImGui::TextUnformatted(words.c_str());
    // A word for 0 ("auto", "all") or for unset ("none", "auto"): a box for it, and the widget
    // for a value when it is off.
    const std::string_view word = info.optional ? info.unset_word : info.zero_word;
    if (!word.empty()) {
        const bool is_word = info.optional ? std::holds_alternative<std::monostate>(value)
                                           : std::holds_alternative<double>(value) && std::get<double>(value) == 0.0;
        bool box = is_word;
        if (ImGui::Checkbox(std::string(word).c_str(), &box)) {
            edited = true;
            if (box) {
                value = info.optional ? KeyValue(std::monostate{}) : KeyValue(0.0);
            } else {
                KeyValue fallback = default_value(info);
                const bool fallback_is_word = std::holds_alternative<std::monostate>(fallback) ||
                                              (std::holds_alternative<double>(fallback) && std::get<double>(fallback) == 0.0);
                if (fallback_is_word) {
                    double lo = 0.0, hi = 0.0;
                    slider_range(info, lo, hi);
                    fallback = info.type == KeyType::Vec3 ? KeyValue(Vec3d{}) : KeyValue(info.type == KeyType::Whole ? std::round(hi) : lo + 0.5 * (hi - lo));
                    if (info.name == "color") fallback = Vec3d{0.8, 0.8, 0.8};
                }
                value = fallback;
            }
        }
        key_tooltip(info);
        if (box) {
            if (!above) {
                ImGui::SameLine();
                ImGui::TextUnformatted(words.c_str());
            }
            ImGui::PopID();
            return edited;
        }
        ImGui::SameLine();  // the value's widget beside the word's box
    }
    if (above) ImGui::SetNextItemWidth(-FLT_MIN);
    switch (info.type) {
        case KeyType::Number:
        case KeyType::Whole: {
            double x = std::holds_alternative<double>(value) ? std::get<double>(value) : 0.0;
            if (number_slider(info, label.c_str(), x, span)) {
                value = x;
                edited = true;
            }
            break;
        }
        case KeyType::Bool: {
            bool b = std::holds_alternative<bool>(value) && std::get<bool>(value);
            if (ImGui::Checkbox(label.c_str(), &b)) {
                value = b;
                edited = true;
            }
            break;
        }
        case KeyType::Vec3: {
            const Vec3d v = std::holds_alternative<Vec3d>(value) ? std::get<Vec3d>(value) : Vec3d{};
            float xyz[3] = {float(v.x), float(v.y), float(v.z)};
            bool changed = false;
            if (info.name == "color") {
                changed = ImGui::ColorEdit3(label.c_str(), xyz, ImGuiColorEditFlags_NoInputs);
            } else {
                double lo = 0.0, hi = 0.0;
                slider_range(info, lo, hi, span);
                changed = ImGui::DragFloat3(label.c_str(), xyz, info.unit == "deg" ? 1.0f : 0.05f, float(lo), float(hi), "%.2f");
            }
            if (changed) {
                value = Vec3d{clamp_to_range(info, xyz[0]), clamp_to_range(info, xyz[1]), clamp_to_range(info, xyz[2])};
                edited = true;
            }
            break;
        }
        case KeyType::Word: {
            const std::string now = std::holds_alternative<std::string>(value) ? std::get<std::string>(value) : "";
            if (ImGui::BeginCombo(label.c_str(), now.c_str())) {
                for (std::string_view choice : info.choices) {
                    if (ImGui::Selectable(std::string(choice).c_str(), choice == now)) {
                        value = std::string(choice);
                        edited = true;
                    }
                }
                ImGui::EndCombo();
            }
            break;
        }
        case KeyType::Path:
        case KeyType::IndexList:
        case KeyType::Quat: break;
    }
    key_tooltip(info);
    if (ImGui::IsItemClicked(ImGuiMouseButton_Right)) {
        value = default_value(info);
        edited = true;
    }
    // Named values (gravity's planets): a button each, on as many lines as the panel needs.
    for (std::size_t i = 0; i < info.presets.size(); ++i) {
        const KeyPreset& preset = info.presets[i];
        const std::string name(preset.name);
        if (i > 0) {
            const float next = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + ImGui::CalcTextSize(name.c_str()).x +
                               2.0f * ImGui::GetStyle().FramePadding.x;
            if (next < ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x) ImGui::SameLine();
        }
        const KeyValue preset_value = parse_key_text(info, preset.text);
        const bool now = key_text(info, preset_value) == key_text(info, value);  // as stored (a float's digits)
        if (now) ImGui::BeginDisabled();
        if (ImGui::SmallButton(name.c_str())) {
            value = preset_value;
            edited = true;
        }
        if (now) ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s = %s", std::string(info.name).c_str(), std::string(preset.text).c_str());
    }
    ImGui::PopID();
    return edited;
}

}  // namespace softbody::app
