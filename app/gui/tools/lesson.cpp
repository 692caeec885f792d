#include "gui/tools/lesson.h"

#include <imgui.h>

#include <cmath>
#include <cstdio>

#include "cli.h"
#include "gui/key_widgets.h"
#include "gui/session.h"
#include "physics/scene_io.h"

namespace softbody::app {

namespace {


// A value with its unit, or the outcome in words when the closed form predicts one.
std::string value_text(double value, const std::string& unit) {
    if (!std::isfinite(value)) return "none";
    char text[64];
    std::snprintf(text, sizeof text, "%.4g%s%s", value, unit.empty() ? "" : " ", unit.c_str());
    return text;
}

}  // namespace

bool open_lesson(Session& session, std::size_t number) {
    if (number < 1 || number > lessons().size()) {
        session.set_error("there is no lesson " + std::to_string(number) + " (1 to " + std::to_string(lessons().size()) + ")");
        return false;
    }
    return session.load_scene_file(lesson_path(std::int64_t(number)));
}

LessonTool::LessonTool() {
    for (std::size_t n = 1; n <= lessons().size(); ++n) {
        std::string title(lessons()[n - 1].file);
        try {
            title = load_scene(lesson_path(std::int64_t(n))).title;
        } catch (const std::exception&) {
            // Shown by its file name; opening it shows why it does not load.
        }
        titles_.push_back(std::to_string(n) + ". " + title);
    }
}

void LessonTool::attach(Session& session) {
    session.on_tick.push_back([this, &session](const World& world) {
        follow(session);
        if (meter_) meter_->observe(world);
    });
}

bool LessonTool::open(const Session& session) const { return !session.lesson().title.empty(); }

void LessonTool::follow(const Session& session) {
    const World& world = session.world();
    if (world_ == &world && source_ == session.source()) return;
    world_ = &world;
    source_ = session.source();
    const Scene& scene = session.lesson();
    title_ = scene.title;
    text_ = scene.text;
    number_ = lesson_number(source_);
    meter_.reset();
    error_.clear();
    if (!scene.expect) return;
    try {
        meter_.emplace(*scene.expect, world);
    } catch (const std::exception& e) {
        error_ = e.what();
    }
}

void LessonTool::draw(ToolContext& context) {
    Session& session = context.session;
    const float scale = context.scale;
    shown_.clear();  // drawn again below, or not shown this frame
    follow(session);
    const bool lesson = !title_.empty();
    // The Lessons menu, in the addendum's order.
    const std::string current = number_ > 0 ? titles_[number_ - 1] : "Lessons...";
    ImGui::SetNextItemWidth(-1);
    if (ImGui::BeginCombo("##lessons", current.c_str())) {
        for (std::size_t n = 1; n <= titles_.size(); ++n) {
            if (ImGui::Selectable(titles_[n - 1].c_str(), n == number_)) open_lesson(session, n);
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(lessons()[n - 1].equation).c_str());
        }
        ImGui::EndCombo();
    }
    if (!lesson) {
        ImGui::TextDisabled("this scene has no lesson text");
        return;
    }
    ImGui::TextColored(ImVec4(1.0f, 0.85f, 0.45f, 1.0f), "%s", title_.c_str());
    if (number_ > 0) {
        ImGui::SameLine();
        ImGui::TextDisabled("(%s)", std::string(lessons()[number_ - 1].equation).c_str());
    }
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(text_.c_str());
    ImGui::PopTextWrapPos();
    if (!error_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "%s", error_.c_str());
    controls(session);
    const std::string& notes = session.lesson().notes;
    if (!notes.empty() && ImGui::TreeNode("For the teacher")) {
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextUnformatted(notes.c_str());
        ImGui::PopTextWrapPos();
        ImGui::TreePop();
    }
    if (!meter_) return;

    // Expected against actual, live.
    ImGui::Separator();
    ImGui::TextDisabled("expected against actual");
    for (const Comparison& c : meter_->comparisons(session.world())) {
        ImGui::Text("%s", c.name.c_str());
        ImGui::SameLine();
        ImGui::TextDisabled("(%s)", c.equation.c_str());
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", c.formula.c_str());
        ImGui::Indent(8.0f * scale);
        ImGui::PushTextWrapPos(0.0f);
        if (!c.predicted_text.empty())
            ImGui::Text("predicted: %s", c.predicted_text.c_str());
        else
            ImGui::Text("predicted: %s   %s", value_text(c.predicted, c.unit).c_str(), c.formula.c_str());
        if (c.measured)
            ImGui::Text("measured:  %s   %s", value_text(*c.measured, c.unit).c_str(), c.measured_text.c_str());
        else
            ImGui::Text("measured:  %s", c.measured_text.empty() ? "not yet" : c.measured_text.c_str());
        ImGui::PopTextWrapPos();
        if (c.agrees) {
            const bool ok = *c.agrees;
            if (c.tolerance > 0.0) {
                ImGui::TextColored(ok ? ImVec4(0.35f, 0.8f, 0.45f, 1.0f) : ImVec4(1.0f, 0.45f, 0.3f, 1.0f),
                                   ok ? "agrees within %.2g%%" : "differs by more than %.2g%%", c.tolerance * 100.0);
            } else {
                ImGui::TextColored(ok ? ImVec4(0.35f, 0.8f, 0.45f, 1.0f) : ImVec4(1.0f, 0.45f, 0.3f, 1.0f),
                                   ok ? "as predicted" : "not as predicted");
            }
        }
        ImGui::Unindent(8.0f * scale);
    }
}

// The keys the lesson is about, first and in its own words; every other key is under All keys.
void LessonTool::controls(Session& session) {
    const std::vector<LessonControl>& list = session.lesson().controls;
    if (list.empty()) return;
    ImGui::Separator();
    for (const LessonControl& control : list) {
        try {
            const ThingNames names = thing_names(session.world().def());
            const KeyInfo& info = *resolve_key(control.key, names).front().info;
            KeyValue value = session.world().key(control.key);
            const std::string label = control.unit.empty() ? control.label : control.label + " (" + control.unit + ")";
            if (key_widget(info, value, label, SliderSpan{control.min, control.max, control.step})) {
                session.set_key(control.key, key_text(info, value));
            }
            const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax(), size = ImGui::GetIO().DisplaySize;
            shown_.push_back({control.key, label, key_text(info, value), lo.x / size.x, lo.y / size.y, (hi.x - lo.x) / size.x,
                              (hi.y - lo.y) / size.y});
        } catch (const std::exception&) {
            // A control naming a body taken out of the world: nothing to show for it now.
        }
    }
    if (session.reset_pending()) {
        ImGui::TextDisabled("* applies on reset");
        ImGui::SameLine();
        if (ImGui::SmallButton("Reset now##lesson")) session.reset();
    }
}

nlohmann::ordered_json LessonTool::summary(const Session& session) {
    follow(session);
    if (title_.empty()) return nullptr;
    nlohmann::ordered_json out = {{"number", number_}, {"title", title_}, {"error", error_}};
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    if (meter_) {
        for (const Comparison& c : meter_->comparisons(session.world())) {
            const auto number = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); };
            list.push_back({{"name", c.name},
                            {"equation", c.equation},
                            {"unit", c.unit},
                            {"predicted", number(c.predicted)},
                            {"measured", c.measured ? number(*c.measured) : nlohmann::ordered_json()},
                            {"predicted_text", c.predicted_text},
                            {"measured_text", c.measured_text},
                            {"tolerance", c.tolerance},
                            {"agrees", c.agrees ? nlohmann::ordered_json(*c.agrees) : nlohmann::ordered_json()}});
        }
    }
    nlohmann::ordered_json controls = nlohmann::ordered_json::array();
    for (const ShownControl& c : shown_) {
        controls.push_back({{"key", c.key}, {"label", c.label}, {"value", c.value}, {"rect", {c.x, c.y, c.w, c.h}}});
    }
    out["controls"] = controls;
    out["comparisons"] = list;
    return out;
}

namespace {
const ToolRegistration kLessonToolRegistered{10, [] { return std::unique_ptr<Tool>(new LessonTool); }};
}  // namespace

}  // namespace softbody::app
