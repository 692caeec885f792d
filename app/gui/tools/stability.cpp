// The Stability tool.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gui/session.h"
#include "gui/tool.h"
#include "gui/view.h"

namespace softbody::app {

namespace {

class StabilityTool : public Tool {
public:
    const char* title() const override { return "Stability"; }
    bool open(const Session&) const override { return true; }
    void draw(ToolContext& c) override { stability_body(c); }

private:
    void stability_body(ToolContext& c) {
        const Stability s = c.session.world().stability();
        const float fraction = static_cast<float>(s.h_omega / s.limit);
        const ImVec4 colour = !s.stable         ? ImVec4(0.90f, 0.25f, 0.20f, 1.0f)
                              : fraction > 0.9f ? ImVec4(0.95f, 0.70f, 0.20f, 1.0f)
                                                : ImVec4(0.30f, 0.75f, 0.40f, 1.0f);
        char label[64];
        std::snprintf(label, sizeof label, "h*omega %.2f of %.2f", s.h_omega, s.limit);
        ImGui::PushStyleColor(ImGuiCol_PlotHistogram, colour);
        ImGui::ProgressBar(std::min(fraction, 1.0f), ImVec2(-1, 0), label);
        ImGui::PopStyleColor();
        if (ImGui::IsItemHovered()) {
            ImGui::SetTooltip(
                "The fastest mode of the spring network (omega = %.1f rad/s) against the step h = %.4f s.\n"
                "Verlet is stable while sqrt(h^2 omega^2 + 2 h gamma) < 2, i.e. N (k h^2 + 2 c h) < 4 m.",
                s.omega_max, s.h);
        }
        ImGui::Text("substeps %d (needed %d)   growth %.3f", s.substeps, s.substeps_needed, s.growth);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("growth: how much the fastest-growing mode is amplified per step (above 1 it explodes)");
        if (!s.stable) {
            ImGui::TextColored(colour, "Unstable: this will explode.");
        } else if (fraction > 0.9f) {
            ImGui::TextColored(colour, "Close to the limit.");
        }
        WorldSettings settings = c.session.world().settings();
        if (ImGui::Checkbox("automatic substeps", &settings.auto_substeps)) c.session.edit_settings(settings);
        if (!s.stable && s.substeps_needed > 0) {
            ImGui::SameLine();
            char fix[48];
            std::snprintf(fix, sizeof fix, "Use %d substeps", s.substeps_needed);
            if (ImGui::SmallButton(fix)) {
                settings.substeps = s.substeps_needed;
                c.session.edit_settings(settings);
            }
        }
    }
};

const ToolRegistration kStabilityToolRegistered{40, [] { return std::unique_ptr<Tool>(new StabilityTool); }};

}  // namespace

}  // namespace softbody::app
