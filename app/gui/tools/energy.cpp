// The Energy tool.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gui/plot.h"
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
        // One line per energy, each in its own colour and marked with its own shape (gui/plot.h).
        std::vector<double> times;
        std::vector<std::vector<double>> values(static_cast<std::size_t>(series_count));
        for (const auto& s : history) {
            times.push_back(s.time);
            for (int series = 0; series < series_count; ++series) values[std::size_t(series)].push_back(value_of(s, series));
        }
        const char* line_names[6] = {"kinetic", "gravity", "elastic", "total", "rotational", "contacts, last second"};
        std::vector<PlotLine> lines;
        for (int series = 0; series < std::min(series_count, 5); ++series) {
            lines.push_back({line_names[series], &times, &values[std::size_t(series)], 0, std::size_t(series)});
        }
        plot("energy", lines, "time (s)", "energy (J)", 120.0f * c.scale);
        const auto& last = history.back();
        for (int series = 0; series < std::min(series_count, 5); ++series) {
            if (series % 2) ImGui::SameLine(180 * c.scale);
            ImGui::Text("%s %.3g J", line_names[series], value_of(last, series));
        }
        if (rotation) {
            ImGui::SameLine(180 * c.scale);
            ImGui::Text("|L| %.3g kg m^2/s", last.angular_momentum);
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("Total angular momentum about the origin, every body: conserved without torques.");
            ImGui::Text("contacts: %+.3g J this second", last.contacts);
            if (ImGui::IsItemHovered()) {
                ImGui::SetTooltip(
                    "What the rigid contacts' impulses (Eq. 38) did to the energy over the last second: never more\n"
                    "than zero. A bounce with e < 1 and friction take energy; a body resting on another, none.");
            }
        }
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

const ToolRegistration kEnergyToolRegistered{50, [] { return std::unique_ptr<Tool>(new EnergyTool); }};

}  // namespace

}  // namespace softbody::app
