// The Rigid bodies tool.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "gui/session.h"
#include "gui/tool.h"
#include "gui/view.h"

namespace softbody::app {

namespace {

class RigidBodiesTool : public Tool {
public:
    const char* title() const override { return "Rigid bodies"; }
    bool shown(const Session& s) const override { return s.world().rigid_body_count() > 0; }
    bool open(const Session&) const override { return true; }
    void draw(ToolContext& c) override { rigid_bodies_body(c); }

private:
    void rigid_bodies_body(ToolContext& c) {
        const World& world = c.session.world();
        const int count = static_cast<int>(world.rigid_body_count());
        rigid_selected_ = std::clamp(rigid_selected_, 0, count - 1);
        if (ImGui::BeginCombo("body##rigid", world.rigid_body(std::size_t(rigid_selected_)).name.c_str())) {
            for (int b = 0; b < count; ++b) {
                if (ImGui::Selectable(world.rigid_body(std::size_t(b)).name.c_str(), b == rigid_selected_)) rigid_selected_ = b;
            }
            ImGui::EndCombo();
        }
        const std::size_t i = std::size_t(rigid_selected_);
        const RigidBody& body = world.rigid_body(i);
        RigidBodyDef def = world.def(world.rigid_body_id(i));
        ImGui::TextDisabled("%s, volume %.4g m^3%s", std::string(to_string(body.shape)).c_str(), body.volume,
                            body.hull_mass_properties ? " (its hull's: the mesh is open)" : "");

        // Keys: restitution and friction act at once; mass and fixed at reset.
        bool edited = false;
        float mass = float(body.mass);
        if (ImGui::SliderFloat("mass *", &mass, 0.01f, 1000.0f, "%.3g kg", ImGuiSliderFlags_Logarithmic)) {
            def.mass = double(std::max(mass, 1e-3f));
            def.density.reset();
            edited = true;
        }
        if (ImGui::Checkbox("fixed *", &def.fixed)) edited = true;
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Infinite mass: scenery such as a fulcrum or a ramp.");
        float e = def.restitution.value_or(world.settings().restitution);
        if (ImGui::SliderFloat("restitution e", &e, 0.0f, 1.0f, "%.2f")) {
            def.restitution = e;
            edited = true;
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Eq. 38: an impact's normal velocity leaves at -e times the speed it came in with.");
        float mu = def.friction.value_or(world.settings().dynamic_friction);
        if (ImGui::SliderFloat("friction mu", &mu, 0.0f, 2.0f, "%.2f")) {
            def.friction = mu;
            edited = true;
        }
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Coulomb friction in impulse form: |tangential impulse| <= mu x normal impulse.");
        if (edited) c.session.edit_rigid_body(i, def);
        if (c.session.reset_pending()) {
            ImGui::TextDisabled("* applies on reset");
            ImGui::SameLine();
            if (ImGui::SmallButton("reset now##rigid")) c.session.reset();
        }

        // State: Listing 10's thirteen numbers and what follows from them (Eq. 28, 32, 36).
        const RigidMotion m = world.rigid_motion(i);
        ImGui::Text("x     %8.3f %8.3f %8.3f m", m.x.x, m.x.y, m.x.z);
        ImGui::Text("P     %8.3f %8.3f %8.3f kg m/s", m.P.x, m.P.y, m.P.z);
        ImGui::Text("L     %8.3f %8.3f %8.3f kg m^2/s", m.L.x, m.L.y, m.L.z);
        ImGui::Text("q     %7.4f %7.4f %7.4f %7.4f", m.q.w, m.q.x, m.q.y, m.q.z);
        const double norm = m.q.norm();
        ImGui::TextColored(std::abs(norm - 1.0) > 1e-3 ? ImVec4(1.0f, 0.55f, 0.3f, 1.0f) : ImVec4(0.7f, 0.7f, 0.7f, 1.0f),
                           "|q| = %.9f", norm);
        if (ImGui::IsItemHovered()) {
            ImGui::SetTooltip(
                "A unit quaternion has |q| = 1; rounding and explicit Euler make it drift, and a drifted q\n"
                "no longer rotates: it scales and shears. Listing 9 renormalises every few steps\n"
                "(renormalize_every; 0 lets you watch it drift).");
        }
        ImGui::Text("v     %8.3f %8.3f %8.3f m/s", m.v.x, m.v.y, m.v.z);
        ImGui::Text("omega %8.3f %8.3f %8.3f rad/s", m.omega.x, m.omega.y, m.omega.z);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Eq. 36: omega = R J_body^-1 R^T L, after each step.");
        const Mat3 J = m.R * body.J_body * m.R.transposed();
        ImGui::TextDisabled("J_world = R J_body R^T (Eq. 32), kg m^2:");
        for (int r = 0; r < 3; ++r) ImGui::Text("      %9.4f %9.4f %9.4f", J.m[r][0], J.m[r][1], J.m[r][2]);
        if (!body.fixed) {
            ImGui::Text("kinetic %.4g J = %.4g translation + %.4g rotation", 0.5 * dot(m.P, m.v) + 0.5 * dot(m.L, m.omega),
                        0.5 * dot(m.P, m.v), 0.5 * dot(m.L, m.omega));
        }
    }

    int rigid_selected_ = 0;  // the rigid body the tool shows
};

const ToolRegistration kRigidBodiesToolRegistered{100, [] { return std::unique_ptr<Tool>(new RigidBodiesTool); }};

}  // namespace

}  // namespace softbody::app
