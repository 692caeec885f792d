// The Display tool.
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

class DisplayTool : public Tool {
public:
    const char* title() const override { return "Display"; }
    void draw(ToolContext& c) override { display_body(c); }

private:
    void display_body(ToolContext& c) {
        auto& o = c.view.overlays;
        auto& a = c.view.appearance;
        // The text's size, for a projector at the back of a room (about 2x) or a small screen.
        ImGui::SliderFloat("text size", &c.ui.text_size, 0.75f, 3.0f, "%.2fx");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("The size of the panel's text and widgets. Ctrl-click to type a value.");
        ImGui::SameLine();
        if (ImGui::SmallButton("Projector")) c.ui.text_size = c.ui.text_size >= 1.9f ? 1.0f : 2.0f;
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Text twice the size, readable from the back of a classroom (again: back to 1x).");
        ImGui::Checkbox("rows for fingers", &c.ui.finger_rows);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Taller rows and slider grabs, for a touch screen (on from the start on a touch screen).");
        ImGui::Checkbox("particles (P)", &o.particles);
        ImGui::SameLine(180 * c.scale);
        ImGui::Checkbox("springs (S)", &o.springs);
        ImGui::Checkbox("pins", &o.pins);
        ImGui::SameLine(180 * c.scale);
        ImGui::Checkbox("centre of mass (C)", &o.center_of_mass);
        ImGui::Checkbox("velocities (V)", &o.velocities);
        ImGui::SameLine(180 * c.scale);
        ImGui::Checkbox("forces", &o.forces);
        ImGui::Checkbox("normals", &o.normals);
        ImGui::SameLine(180 * c.scale);
        ImGui::Checkbox("shadows", &a.shadows);
        ImGui::Checkbox("omega and L (W)", &o.angular);
        if (ImGui::IsItemHovered()) {
            ImGui::SetTooltip(
                "Each rigid body's angular velocity (yellow) and angular momentum (violet) at its centre of mass:\n"
                "L = J omega (Eq. 28); they point the same way only about a principal axis.");
        }
        ImGui::SameLine(180 * c.scale);
        ImGui::Checkbox("contacts", &o.contacts);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Contact points of the last step, each normal as long as its impulse (Eq. 38).");
        ImGui::Checkbox("springs between bodies", &o.links);
        ImGui::SameLine(180 * c.scale);
        ImGui::Checkbox("sleeping dimmer", &c.view.dim_sleeping);
        if (ImGui::IsItemHovered()) {
            ImGui::SetTooltip(
                "Rigid bodies that sleep drawn greyer: an island of bodies at rest for half a second sleeps (it is\n"
                "not integrated and its contacts are not solved) until something touches it, you grab it or a\n"
                "key changes. The sleeping key (All keys) turns sleeping off.");
        }
        ImGui::Checkbox("ground and grid", &a.ground);
        ImGui::SameLine(180 * c.scale);
        ImGui::Checkbox("follow the bodies (T)", &c.view.follow);
        if (ImGui::IsItemHovered()) {
            ImGui::SetTooltip(
                "The camera moves with the bodies' centre, smoothed and level, keeping them where they are in\n"
                "the view (pan to move them; it holds still while you pull a body). On for a scene with one body.");
        }
        int style = static_cast<int>(a.body);
        if (ImGui::Combo("body", &style, "solid\0ghost (see-through)\0wireframe\0hidden\0"))
            a.body = static_cast<render::BodyStyle>(style);
        ImGui::ColorEdit3("colour", &a.body_color.x, ImGuiColorEditFlags_NoInputs);
        int samples_index = a.samples >= 4 ? 2 : a.samples >= 2 ? 1 : 0;
        if (ImGui::Combo("anti-aliasing", &samples_index,
                         "off\0"
                         "2x\0"
                         "4x\0"))
            a.samples = samples_index == 0 ? 1 : samples_index == 1 ? 2 : 4;
        ImGui::Checkbox("pattern on the body", &a.pattern);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Soft checks fixed in the body's material, so rolling and squash show.");
        int springs = static_cast<int>(a.max_springs);
        if (ImGui::SliderInt("inner springs drawn", &springs, 0, 2000, "%d", ImGuiSliderFlags_Logarithmic))
            a.max_springs = static_cast<std::size_t>(springs);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("Springs along the surface are drawn, plus this many more from a fixed sample.");
    }
};

const ToolRegistration kDisplayToolRegistered{120, [] { return std::unique_ptr<Tool>(new DisplayTool); }};

}  // namespace

}  // namespace softbody::app
