// The Simulation tool.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gui/recorder.h"
#include "gui/session.h"
#include "gui/tool.h"
#include "gui/view.h"

namespace softbody::app {

namespace {

class SimulationTool : public Tool {
public:
    const char* title() const override { return "Simulation"; }
    bool open(const Session&) const override { return true; }
    void draw(ToolContext& c) override { simulation_body(c); }

private:
    void simulation_body(ToolContext& c) {
        const World& world = c.session.world();
        const ImVec2 button(78 * c.scale, 0);
        if (ImGui::Button(c.session.paused ? "Play" : "Pause", button)) c.session.paused = !c.session.paused;
        ImGui::SameLine();
        if (ImGui::Button("< Back", button)) c.session.step_back();
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("One tick back (key ,): the world as it was, bit for bit.");
        ImGui::SameLine();
        if (ImGui::Button("Step >", button)) {
            c.session.paused = true;
            c.session.single_tick();
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("One tick on (key . or N).");
        ImGui::SameLine();
        if (ImGui::Button("Reset", button)) c.session.reset();
        timeline_body(c);
        float time_scale = static_cast<float>(c.session.time_scale);
        if (ImGui::SliderFloat("time scale", &time_scale, 0.05f, 2.0f, "%.2fx", ImGuiSliderFlags_Logarithmic)) {
            c.session.time_scale = time_scale;
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Slow motion below 1: fewer ticks per second of wall time; dt stays fixed.");
        ImGui::SliderInt("max ticks/frame", &c.session.max_ticks_per_frame, 1, 32);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("A slow frame runs at most this many ticks; the rest of its time is dropped.");
        ImGui::Text("tick %llu   t = %.2f s", static_cast<unsigned long long>(world.ticks()), world.time());
        ImGui::Text("ticks this frame %d   physics %.2f ms/tick", c.session.ticks_last_frame(), c.session.physics_ms_per_tick());
        ImGui::Text("render %.0f FPS   %d threads", c.fps, world.threads());
        if (world.status() != Status::Ok)
            ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "diverged: reset to go on");
        else if (c.session.paused)
            ImGui::TextDisabled("paused");
        if (c.recorder) recorder_controls(*c.recorder, c.session.paused || world.status() != Status::Ok, c.scale);
    }

    // The recorded past (physics/history.h): drag to any tick of it; play goes on from there.
    void timeline_body(ToolContext& c) {
        const World& world = c.session.world();
        const History& history = c.session.history();
        const double dt = world.settings().dt;
        int oldest = static_cast<int>(history.oldest_tick()), newest = static_cast<int>(history.newest_tick());
        int tick = static_cast<int>(world.ticks());
        ImGui::BeginDisabled(newest == oldest);
        char label[64];
        std::snprintf(label, sizeof label, "t = %.2f s", tick * dt);
        if (ImGui::SliderInt("timeline", &tick, oldest, std::max(newest, oldest + 1), label)) {
            c.session.go_to_tick(static_cast<std::uint64_t>(std::clamp(tick, oldest, newest)));
        }
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
            ImGui::SetTooltip(
                "The last %.0f s are kept (%.1f MB now). Drag back to any tick and play on: the\n"
                "same future, bit for bit, unless you change something; then a new one.",
                double(history.capacity_ticks()) * dt, double(history.bytes()) / 1e6);
        }
        if (c.session.in_past()) {
            ImGui::TextColored(ImVec4(0.95f, 0.75f, 0.30f, 1.0f), "in the past: %.2f s behind", (newest - tick) * dt);
            ImGui::SameLine();
            if (ImGui::SmallButton("Back to now")) c.session.go_to_tick(history.newest_tick());
        }
    }
};

const ToolRegistration kSimulationToolRegistered{20, [] { return std::unique_ptr<Tool>(new SimulationTool); }};

}  // namespace

}  // namespace softbody::app
