// The Last collision tool.
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

class LastCollisionTool : public Tool {
public:
    const char* title() const override { return "Last collision"; }
    bool shown(const Session& s) const override { return s.world().rigid_body_count() > 0; }
    bool open(const Session&) const override { return true; }
    void draw(ToolContext& c) override { last_collision_body(c); }

private:
    // Eq. 38 with the numbers of the latest hit, so that a student can follow the formula through.
    void last_collision_body(ToolContext& c) {
        const auto& hit = c.session.last_collision();
        if (!hit) {
            ImGui::TextDisabled("no collision yet");
            return;
        }
        const ImpulseTerms& t = hit->terms;
        ImGui::Text("t = %.2f s: %s on %s", hit->time, hit->body_1.c_str(), hit->body_2.c_str());
        if (hit->points > 1) ImGui::TextDisabled("the point with the largest impulse of %zu", hit->points);
        ImGui::TextDisabled("lambda = -(1 + e) v_rel.n");
        ImGui::TextDisabled("         / (1/m1 + 1/m2 + rot1 + rot2)");
        if (ImGui::IsItemHovered()) {
            ImGui::SetTooltip(
                "Eq. 38. rot_i = n . ((J_i^-1 (r_i x n)) x r_i): how much of the impulse turns body i\n"
                "instead of moving it. Body 1 gets +lambda n at r1, body 2 -lambda n at r2 (Eq. 37).");
        }
        ImGui::Text("n       %7.3f %7.3f %7.3f", t.n.x, t.n.y, t.n.z);
        ImGui::Text("v_rel.n %9.4f m/s    e %.2f", t.v_rel_n, t.e);
        ImGui::Text("r1 x n  %7.3f %7.3f %7.3f m", t.r1_x_n.x, t.r1_x_n.y, t.r1_x_n.z);
        ImGui::Text("r2 x n  %7.3f %7.3f %7.3f m", t.r2_x_n.x, t.r2_x_n.y, t.r2_x_n.z);
        ImGui::Text("1/m1 %.4g  1/m2 %.4g 1/kg", t.inv_mass_1, t.inv_mass_2);
        ImGui::Text("rot1 %.4g  rot2 %.4g 1/kg", t.rotation_1, t.rotation_2);
        ImGui::Text("denominator %.4g 1/kg", t.denominator);
        ImGui::Text("lambda %.4g N s (Eq. 38 alone)", t.lambda);
        ImGui::Text("solver %.4g N s", t.solver_lambda);
        if (ImGui::IsItemHovered()) {
            ImGui::SetTooltip(
                "What the solver applied at this point: all the contacts of the step solved together,\n"
                "with friction. For one point of two bodies without friction it equals Eq. 38's lambda;\n"
                "where several points share a hit, they split it.");
        }
    }
};

const ToolRegistration kLastCollisionToolRegistered{70, [] { return std::unique_ptr<Tool>(new LastCollisionTool); }};

}  // namespace

}  // namespace softbody::app
