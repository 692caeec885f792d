// The Inspector tool.
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

class InspectorTool : public Tool {
public:
    const char* title() const override { return "Inspector"; }
    bool shown(const Session& s) const override { return s.particle_inspection() || s.rigid_inspection(); }
    bool open(const Session&) const override { return true; }
    void draw(ToolContext& c) override { inspector_body(c); }

private:
    // One particle's forces, one line each, named by equation, as Listing 8's CalcForce adds them;
    // or a rigid body's, each with its torque about the centre of mass.
    void inspector_body(ToolContext& c) {
        const auto vec = [](const char* label, const Vec3& v, const char* unit) {
            ImGui::Text("%-8s %8.3f %8.3f %8.3f %s", label, double(v.x), double(v.y), double(v.z), unit);
        };
        if (const auto in = c.session.particle_inspection()) {
            ImGui::Text("particle %u of '%s'%s", in->particle, c.session.world().soft_body(in->body).name().c_str(),
                        in->mass == 0.0f ? " (pinned)" : "");
            vec("x", in->x, "m");
            vec("v", in->v, "m/s");
            vec("a", in->a, "m/s^2");
            ImGui::TextDisabled("force      from          |F|, N");
            for (const ForceTerm& t : in->terms) {
                ImGui::Text("%-10s %-10s %9.4g", t.name.substr(0, 10).c_str(), t.equation.c_str(), double(length(t.force)));
                if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s: %s\n%s", t.name.c_str(), t.equation.c_str(), t.detail.c_str());
                ImGui::TextDisabled("  (%.3f, %.3f, %.3f)", double(t.force.x), double(t.force.y), double(t.force.z));
                if (t.name == "friction") ImGui::TextWrapped("  %s", t.detail.c_str());
            }
            ImGui::Separator();
            ImGui::Text("%-21s %9.4g", "net = m a", double(length(in->net)));
            ImGui::TextDisabled("  (%.3f, %.3f, %.3f)", double(in->net.x), double(in->net.y), double(in->net.z));
            if (!in->strongest.empty()) {
                ImGui::TextDisabled("strongest pairs (Eq. 21 + 22):");
                for (const PairTerm& p : in->strongest) {
                    ImGui::Text("  %-5u l %.3f/%.3f m %.3g N", p.other, double(p.length), double(p.rest_length),
                                double(length(p.spring + p.damper)));
                }
            }
            ImGui::TextDisabled("ctrl-click elsewhere to stop");
            return;
        }
        const auto in = c.session.rigid_inspection();
        if (!in) return;
        const RigidBody& body = c.session.world().rigid_body(in->body);
        ImGui::Text("rigid body '%s'%s", body.name.c_str(), body.fixed ? " (fixed)" : "");
        if (!body.fixed) {
            const World& world = c.session.world();
            if (world.rigid_asleep(in->body)) {
                ImGui::TextColored(ImVec4(0.55f, 0.75f, 1.0f, 1.0f), "asleep: at rest, not integrated");
                if (ImGui::IsItemHovered()) {
                    ImGui::SetTooltip(
                        "Its island's bodies were all slower than 5 cm/s at every point for 0.5 s: it costs nothing\n"
                        "until an awake body or a soft body touches it, it is grabbed, or a key changes.");
                }
            } else if (world.rigid_rest_time(in->body) > 0.0) {
                ImGui::TextDisabled("awake, at rest for %.2f s", world.rigid_rest_time(in->body));
            } else {
                ImGui::TextDisabled("awake, moving");
            }
        }
        ImGui::TextDisabled("force          |F| N   |tau| N m");
        for (const WrenchTerm& t : in->terms) {
            ImGui::Text("%-14s %-8s %8.4g %8.4g", t.name.substr(0, 14).c_str(), t.equation.c_str(), length(t.force),
                        length(t.torque));
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (%s)\n%s", t.name.c_str(), t.equation.c_str(), t.detail.c_str());
        }
        ImGui::Separator();
        ImGui::Text("sum: F %.4g N, tau %.4g N m", length(in->force), length(in->torque));
        ImGui::TextDisabled("P, L, omega, q, J_world: the Rigid bodies panel");
    }
};

const ToolRegistration kInspectorToolRegistered{30, [] { return std::unique_ptr<Tool>(new InspectorTool); }};

}  // namespace

}  // namespace softbody::app
