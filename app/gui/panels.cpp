// The demo's panel (panels.h): every tool under its header, the help overlay and the error banner.
#include "gui/panels.h"

#include <imgui.h>

#include <algorithm>

#include "gui/bindings.h"
#include "gui/session.h"
#include "gui/tools/lesson.h"
#include "gui/view.h"

namespace softbody::app {

Panels::Panels(float ui_scale) : scale_(ui_scale), tools_(make_tools()) {}

void Panels::attach(Session& session) {
    for (const auto& tool : tools_) tool->attach(session);
}

LessonTool* Panels::lesson() const {
    for (const auto& tool : tools_) {
        if (auto* lesson = dynamic_cast<LessonTool*>(tool.get())) return lesson;
    }
    return nullptr;
}

void Panels::draw(Session& session, View& view, float fps) {
    error_banner(session, view);
    if (show_help) help();
    if (!show_panels) return;
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    const float scale = scale_ * ui.text_size;
    ImGui::GetIO().FontGlobalScale = ui.text_size;
    // The panel takes 360 px (at 1x) on the left, or nearly the whole width of a narrow screen
    // (a phone held upright); there it starts folded, so the view is what shows first.
    panel_width_ = std::min(360.0f * scale, viewport->WorkSize.x - 16.0f * scale_);
    if (first_frame_ && viewport->WorkSize.x < 600.0f * scale_) ImGui::SetNextWindowCollapsed(true, ImGuiCond_Always);
    first_frame_ = false;
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + 8 * scale_, viewport->WorkPos.y + 8 * scale_), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(panel_width_, viewport->WorkSize.y - 16 * scale_), ImGuiCond_Always);
    // Folds by its title bar's arrow (or a double click on it); the keyboard moves through it
    // (the window's navigation is on).
    const bool open = ImGui::Begin("softbody", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
    folded_ = ImGui::IsWindowCollapsed();
    if (!open) {
        ImGui::End();
        return;
    }
    ImGui::PushItemWidth(-std::min(150.0f * scale, 0.42f * panel_width_));
    ToolContext context{session, view, ui, recorder, scale, fps};
    for (const auto& tool : tools_) {
        if (!tool->shown(session)) continue;
        if (!ImGui::CollapsingHeader(tool->title(), tool->open(session) ? ImGuiTreeNodeFlags_DefaultOpen : 0)) continue;
        ImGui::PushID(tool->title());
        tool->draw(context);
        ImGui::PopID();
    }
    ImGui::PopItemWidth();
    ImGui::Separator();
    ImGui::TextDisabled("H: help   Space: pause   R: reset   Tab: hide panels");
    ImGui::End();
}

void Panels::help() {
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + viewport->WorkSize.x * 0.5f, viewport->WorkPos.y + viewport->WorkSize.y * 0.5f),
                            ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::Begin("Controls", &show_help, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
    // The mouse and every key, from the one list the controls use (gui/bindings.cpp).
    if (ImGui::BeginTable("controls", 2, ImGuiTableFlags_RowBg)) {
        const auto row = [](const char* left, const char* right) {
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            ImGui::TextUnformatted(left);
            ImGui::TableSetColumnIndex(1);
            ImGui::TextUnformatted(right);
        };
        for (const MouseBinding& m : mouse_bindings()) row(m.gesture, m.what);
        for (const KeyBinding& k : key_bindings()) row(k.label, k.what);
        ImGui::EndTable();
    }
    ImGui::End();
}

void Panels::error_banner(Session& demo, View&) {
    if (demo.error().empty()) {
        notice_banner(demo);
        return;
    }
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    const float width = std::min(760 * scale_, viewport->WorkSize.x - 400 * scale_);
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + viewport->WorkSize.x - width - 12 * scale_, viewport->WorkPos.y + 12 * scale_));
    ImGui::SetNextWindowSize(ImVec2(width, 0));
    ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.45f, 0.08f, 0.08f, 0.94f));
    ImGui::Begin("##error", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(demo.error().c_str());
    ImGui::PopTextWrapPos();
    if (ImGui::SmallButton("Dismiss")) demo.clear_error();
    if (demo.world().status() != Status::Ok) {
        ImGui::SameLine();
        if (ImGui::SmallButton("Reset")) {
            demo.reset();
            demo.clear_error();
        }
    }
    ImGui::End();
    ImGui::PopStyleColor();
}

// A notice (what an action did) at the top right, until dismissed or replaced.
void Panels::notice_banner(Session& session) {
    if (session.notice().empty()) return;
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    const float width = std::min(760 * scale_, viewport->WorkSize.x - 400 * scale_);
    ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + viewport->WorkSize.x - width - 12 * scale_, viewport->WorkPos.y + 12 * scale_));
    ImGui::SetNextWindowSize(ImVec2(width, 0));
    ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.08f, 0.30f, 0.20f, 0.94f));
    ImGui::Begin("##notice", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(session.notice().c_str());
    ImGui::PopTextWrapPos();
    if (ImGui::SmallButton("OK")) session.clear_notice();
    ImGui::End();
    ImGui::PopStyleColor();
}

}  // namespace softbody::app
