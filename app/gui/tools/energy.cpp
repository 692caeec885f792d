// The Energy tool.
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

class EnergyTool : public Tool {
public:
    const char* title() const override { return "Energy"; }
    bool open(const Session&) const override { return true; }
    void draw(ToolContext& c) override { energy_body(c); }

private:
    void energy_body(ToolContext& c) {
        const auto& history = c.session.energy().samples();
        if (history.size() < 2) {
            ImGui::TextDisabled("no samples yet");
            return;
        }
        // The rigid bodies' rotational energy is drawn when there are rigid bodies.
        const bool rotation = c.session.world().rigid_body_count() > 0;
        const int series_count = rotation ? 6 : 4;
        const auto value_of = [](const EnergySample& s, int series) {
            return series == 0   ? s.kinetic
                   : series == 1 ? s.gravity
                   : series == 2 ? s.elastic
                   : series == 3 ? s.total
                   : series == 4 ? s.rotational
                                 : s.contacts;
        };
        double lo = 1e300, hi = -1e300;
        for (const auto& s : history) {
            for (int series = 0; series < series_count; ++series) {
                lo = std::min(lo, value_of(s, series));
                hi = std::max(hi, value_of(s, series));
            }
        }
        if (hi - lo < 1e-9) hi = lo + 1.0;
        const ImVec2 size(ImGui::GetContentRegionAvail().x, 120 * c.scale);
        const ImVec2 origin = ImGui::GetCursorScreenPos();
        ImDrawList* draw = ImGui::GetWindowDrawList();
        draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y), IM_COL32(20, 24, 30, 255), 4.0f);
        const double t0 = history.front().time, t1 = std::max(history.back().time, t0 + 1e-6);
        const ImU32 colours[6] = {IM_COL32(90, 170, 255, 255),  IM_COL32(120, 220, 120, 255), IM_COL32(255, 170, 60, 255),
                                  IM_COL32(240, 240, 240, 255), IM_COL32(250, 200, 30, 255),  IM_COL32(240, 90, 90, 255)};
        for (int series = 0; series < series_count; ++series) {
            std::vector<ImVec2> points;
            points.reserve(history.size());
            for (const auto& s : history) {
                const double v = value_of(s, series);
                points.emplace_back(origin.x + float((s.time - t0) / (t1 - t0)) * size.x,
                                    origin.y + size.y - float((v - lo) / (hi - lo)) * size.y);
            }
            draw->AddPolyline(points.data(), static_cast<int>(points.size()), colours[series], 0, series == 3 ? 2.0f : 1.5f);
        }
        ImGui::Dummy(size);
        const char* names[5] = {"kinetic", "gravity", "elastic", "total", "rotational"};
        const auto& last = history.back();
        for (int series = 0; series < std::min(series_count, 5); ++series) {
            if (series % 2) ImGui::SameLine(180 * c.scale);
            ImGui::TextColored(ImColor(colours[series]), "%s %.3g J", names[series], value_of(last, series));
        }
        if (rotation) {
            ImGui::SameLine(180 * c.scale);
            ImGui::Text("|L| %.3g kg m^2/s", last.angular_momentum);
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("Total angular momentum about the origin, every body: conserved without torques.");
            ImGui::TextColored(ImColor(colours[5]), "contacts: %+.3g J this second", last.contacts);
            if (ImGui::IsItemHovered()) {
                ImGui::SetTooltip(
                    "What the rigid contacts' impulses (Eq. 38) did to the energy over the last second: never more\n"
                    "than zero. A bounce with e < 1 and friction take energy; a body resting on another, none.");
            }
        }
        ImGui::TextDisabled("last %.0f s, from %.1f to %.1f J", t1 - t0, lo, hi);
        if (c.session.comparing()) energy_by_integrator_body(c);
    }

    // Total energy of each compared world, in its integrator's colour, on one scale.
    void energy_by_integrator_body(ToolContext& c) {
        const auto& history = c.session.energy().samples();
        const auto& compared = c.session.compared();
        const std::size_t worlds = compared.size() + 1;
        const auto total = [](const EnergySample& s, std::size_t k) { return k == 0 ? s.total : s.compared[k - 1]; };
        double lo = 1e300, hi = -1e300;
        for (const auto& s : history) {
            if (s.compared.size() + 1 != worlds) continue;
            for (std::size_t k = 0; k < worlds; ++k) {
                if (!std::isfinite(total(s, k))) continue;
                lo = std::min(lo, total(s, k));
                hi = std::max(hi, total(s, k));
            }
        }
        if (lo > hi) return;
        if (hi - lo < 1e-9) hi = lo + 1.0;
        ImGui::TextUnformatted("total energy by integrator");
        const ImVec2 size(ImGui::GetContentRegionAvail().x, 90 * c.scale);
        const ImVec2 origin = ImGui::GetCursorScreenPos();
        ImDrawList* draw = ImGui::GetWindowDrawList();
        draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y), IM_COL32(20, 24, 30, 255), 4.0f);
        const double t0 = history.front().time, t1 = std::max(history.back().time, t0 + 1e-6);
        for (std::size_t k = 0; k < worlds; ++k) {
            const Integrator integrator = k == 0 ? c.session.world().settings().integrator : compared[k - 1].setup.integrator;
            const glm::vec3 colour = integrator_color(integrator);
            std::vector<ImVec2> points;
            for (const auto& s : history) {
                if (s.compared.size() + 1 != worlds || !std::isfinite(total(s, k))) continue;
                points.emplace_back(origin.x + float((s.time - t0) / (t1 - t0)) * size.x,
                                    origin.y + size.y - float((total(s, k) - lo) / (hi - lo)) * size.y);
            }
            draw->AddPolyline(points.data(), static_cast<int>(points.size()), ImColor(colour.r, colour.g, colour.b), 0, 2.0f);
        }
        ImGui::Dummy(size);
        ImGui::TextDisabled("from %.1f to %.1f J", lo, hi);
    }
};

const ToolRegistration kRegistered{50, [] { return std::unique_ptr<Tool>(new EnergyTool); }};

}  // namespace

}  // namespace softbody::app
