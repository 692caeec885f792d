// The Compare integrators tool.
#include <imgui.h>

#include <algorithm>
#include <string>

#include "gui/session.h"
#include "gui/tool.h"
#include "gui/view.h"

namespace softbody::app {

namespace {

class CompareTool : public Tool {
public:
    const char* title() const override { return "Compare integrators"; }
    bool open(const Session& s) const override { return s.comparing(); }
    void draw(ToolContext& c) override { compare_body(c); }

private:
    // Up to four integrators on the same scene at once: which ones, each one's substeps, and
    // what each is doing now.
    void compare_body(ToolContext& c) {
        constexpr Integrator kAll[4] = {Integrator::Verlet, Integrator::SymplecticEuler, Integrator::ExplicitEuler,
                                        Integrator::RK4};
        const Integrator main = c.session.world().settings().integrator;
        const auto swatch = [](Integrator integrator) {
            const glm::vec3 colour = integrator_color(integrator);
            ImGui::ColorButton("##colour", ImVec4(colour.r, colour.g, colour.b, 1.0f), ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
            ImGui::SameLine();
        };
        if (!c.session.comparing()) {
            ImGui::TextWrapped("The scene again from t = 0, beside copies of itself stepped by other integrators.");
            swatch(main);
            ImGui::Text("%s (this world's; All keys)", std::string(to_string(main)).c_str());
            std::vector<CompareSetup> others;
            for (int k = 0; k < 4; ++k) {
                if (kAll[k] == main) continue;
                ImGui::PushID(k);
                swatch(kAll[k]);
                ImGui::Checkbox(std::string(to_string(kAll[k])).c_str(), &compare_pick_[k]);
                ImGui::SameLine(200 * c.scale);
                ImGui::SetNextItemWidth(90 * c.scale);
                ImGui::SliderInt("##substeps", &compare_substeps_[k], 0, 16, compare_substeps_[k] == 0 ? "auto" : "%d substeps");
                if (ImGui::IsItemHovered()) ImGui::SetTooltip("Its substeps a tick: 0 is automatic (what stability needs).");
                ImGui::PopID();
                if (compare_pick_[k]) others.push_back({kAll[k], compare_substeps_[k] == 0, std::max(1, compare_substeps_[k])});
            }
            ImGui::BeginDisabled(others.empty());
            if (ImGui::Button("Compare") && c.session.compare(others)) c.view.frame_body(c.session);
            ImGui::EndDisabled();
            return;
        }
        // Running: a row each, with its energy now against the plot's first sample.
        const auto& history = c.session.energy().samples();
        if (!history.empty() && ImGui::BeginTable("compared", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
            ImGui::TableSetupColumn("integrator");
            ImGui::TableSetupColumn("substeps");
            ImGui::TableSetupColumn("E, J");
            ImGui::TableSetupColumn("change");
            ImGui::TableHeadersRow();
            const auto row = [&](Integrator integrator, const World& world, double start, double now) {
                ImGui::TableNextRow();
                ImGui::TableSetColumnIndex(0);
                swatch(integrator);
                ImGui::TextUnformatted(std::string(to_string(integrator)).c_str());
                ImGui::TableSetColumnIndex(1);
                ImGui::Text("%d", world.substeps_in_use());
                ImGui::TableSetColumnIndex(2);
                ImGui::Text("%.4g", now);
                ImGui::TableSetColumnIndex(3);
                if (world.status() != Status::Ok)
                    ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "diverged");
                else
                    ImGui::Text("%+.2f%%", start != 0.0 ? 100.0 * (now - start) / std::abs(start) : 0.0);
            };
            const EnergySample& first = history.front();
            const EnergySample& last = history.back();
            row(main, c.session.world(), first.total, last.total);
            for (std::size_t k = 0; k < c.session.compared().size() && k < last.compared.size() && k < first.compared.size();
                 ++k) {
                const ComparedWorld& copy = c.session.compared()[k];
                row(copy.setup.integrator, *copy.world, first.compared[k], last.compared[k]);
            }
            ImGui::EndTable();
        }
        if (ImGui::Checkbox("overlaid", &c.view.compare_overlaid)) c.view.frame_body(c.session);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Draw the copies over this world instead of beside it.");
        ImGui::SameLine();
        if (ImGui::Button("Stop comparing") && c.session.compare({})) c.view.frame_body(c.session);
        ImGui::TextWrapped("The mouse grabs the first world only; keys, pins, Reset and the timeline act on all.");
    }

    bool compare_pick_[4] = {false, true, true, false};  // integrators to compare (Integrator's order)
    int compare_substeps_[4] = {0, 0, 0, 0};             // each one's substeps; 0: automatic
};

const ToolRegistration kCompareToolRegistered{60, [] { return std::unique_ptr<Tool>(new CompareTool); }};

}  // namespace

}  // namespace softbody::app
