// The All keys tool: every key of the world, the selected soft body and each named spring,
// from the table (physics/keys.h), each in plain words with its unit; a lesson's own controls
// come first, in the Lesson tool. A key that changes nothing in the open world is not shown.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gui/key_widgets.h"
#include "gui/session.h"
#include "gui/tool.h"
#include "gui/view.h"

namespace softbody::app {

namespace {

class AllKeysTool : public Tool {
public:
    const char* title() const override { return "All keys"; }
    void draw(ToolContext& c) override { parameters_body(c); }

private:
    // Whether a world key can change anything in this world: the air only with drag on some
    // body, the quaternions' renormalising and sleeping only with rigid bodies that move.
    static bool matters(const KeyInfo& info, const World& world) {
        bool moving_rigid = false, drag = false;
        for (std::size_t b = 0; b < world.rigid_body_count(); ++b) {
            moving_rigid = moving_rigid || !world.rigid_body(b).fixed;
            drag = drag || world.rigid_body(b).drag_coefficient > 0.0f;
        }
        for (std::size_t b = 0; b < world.soft_body_count(); ++b) drag = drag || world.soft_body(b).def.drag_coefficient > 0.0f;
        if (info.name == "air_density") return drag;
        if (info.name == "renormalize_every" || info.name == "sleeping") return moving_rigid;
        return true;
    }

    // Every key with a widget, from the table (keys.h): the world's, the selected soft body's, and
    // each named spring's. A widget hands its typed value to the definition's setter, checked once.
    void parameters_body(ToolContext& c) {
        const World& world = c.session.world();
        ImGui::TextDisabled("World");
        WorldSettings settings = world.settings();
        for (const KeyInfo* info : keys_of(KeyOwner::World)) {
            if (!has_widget(*info) || !matters(*info, world)) continue;
            KeyValue value = get_key(settings, *info);
            if (key_widget(*info, value)) {
                set_key(settings, *info, value);
                c.session.edit_settings(settings);
            }
        }
        if (world.soft_body_count() > 0) {
            // Several soft bodies: the keys are the selected body's (click a body to select it).
            const std::size_t selected = c.session.selected_body();
            ImGui::Separator();
            if (world.soft_body_count() > 1) {
                if (ImGui::BeginCombo("soft body", world.soft_body(selected).name().c_str())) {
                    for (std::size_t b = 0; b < world.soft_body_count(); ++b) {
                        if (ImGui::Selectable(world.soft_body(b).name().c_str(), b == selected)) c.session.select_body(b);
                    }
                    ImGui::EndCombo();
                }
                if (ImGui::IsItemHovered()) ImGui::SetTooltip("Whose keys are below (or click a soft body in the view).");
            } else {
                ImGui::TextDisabled("Soft body '%s'", world.soft_body(selected).name().c_str());
            }
            SoftBodyDef def = world.soft_body(selected).def;
            for (const KeyInfo* info : keys_of(KeyOwner::SoftBody)) {
                if (!has_widget(*info)) continue;
                KeyValue value = get_key(def, *info);
                if (key_widget(*info, value)) {
                    set_key(def, *info, value);
                    c.session.edit_body(selected, def);
                }
            }
            ImGui::Text("pinned: %zu vertices", def.pinned.size());
            ImGui::SameLine();
            if (ImGui::SmallButton("free all")) {
                def.pinned.clear();
                c.session.edit_body(selected, def);
            }
        }
        for (std::size_t k = 0; k < world.spring_count(); ++k) {
            SpringDef def = world.def(world.spring_id(k));
            if (def.name.empty()) continue;
            ImGui::Separator();
            ImGui::TextDisabled("Spring '%s'", def.name.c_str());
            ImGui::PushID(int(k));
            for (const KeyInfo* info : keys_of(KeyOwner::Spring)) {
                KeyValue value = get_key(def, *info);
                if (key_widget(*info, value)) {
                    set_key(def, *info, value);
                    c.session.set_key(def.name + "." + std::string(info->name), key_text(*info, value));
                }
            }
            ImGui::PopID();
        }
        ImGui::TextDisabled("* applies on reset");
        if (c.session.reset_pending()) {
            ImGui::SameLine();
            if (ImGui::SmallButton("reset now")) c.session.reset();
        }
        if (ImGui::Button("World to defaults")) c.session.edit_settings(WorldSettings{});
        ImGui::SameLine();
        ImGui::TextDisabled("(Listing 8's values)");
    }
};

const ToolRegistration kAllKeysToolRegistered{90, [] { return std::unique_ptr<Tool>(new AllKeysTool); }};

}  // namespace

}  // namespace softbody::app
