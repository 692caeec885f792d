// The Add tool: a soft ball or cube, a rigid box or ball, or any bundled mesh dropped above the
// scene where the camera looks, made in the running world; and the selected body taken out.
#include <imgui.h>

#include <algorithm>
#include <filesystem>

#include "gui/asset_files.h"
#include "gui/session.h"
#include "gui/tool.h"
#include "gui/view.h"

namespace softbody::app {

namespace {

class AddTool : public Tool {
public:
    const char* title() const override { return "Add"; }

    void draw(ToolContext& c) override {
        ImGui::TextWrapped("Drops a body above the scene where the camera looks; the others go on as they were.");
        const ImVec2 button(ImGui::GetContentRegionAvail().x * 0.48f, 0.0f);
        const auto add = [&](Session::AddKind kind, const std::string& mesh = {}) {
            c.session.add_body(kind, c.view.drop_point(c.session.world()), mesh);
        };
        if (ImGui::Button("Soft ball", button)) add(Session::AddKind::SoftBall);
        ImGui::SameLine();
        if (ImGui::Button("Soft cube", button)) add(Session::AddKind::SoftCube);
        if (ImGui::Button("Rigid box", button)) add(Session::AddKind::RigidBox);
        ImGui::SameLine();
        if (ImGui::Button("Rigid ball", button)) add(Session::AddKind::RigidBall);
        if (!meshes_.empty()) {
            mesh_ = std::min(mesh_, meshes_.size() - 1);
            const std::string current = std::filesystem::path(meshes_[mesh_]).filename().string();
            if (ImGui::BeginCombo("##addmesh", current.c_str())) {
                for (std::size_t k = 0; k < meshes_.size(); ++k) {
                    if (ImGui::Selectable(std::filesystem::path(meshes_[k]).filename().string().c_str(), k == mesh_)) mesh_ = k;
                }
                ImGui::EndCombo();
            }
            ImGui::SameLine();
            if (ImGui::Button("Add mesh")) add(Session::AddKind::MeshFile, meshes_[mesh_]);
        }
        // Taking out: the soft body the All keys tool edits, or the rigid body inspected.
        const World& world = c.session.world();
        if (const auto rigid = c.session.rigid_inspection()) {
            const std::string label = "Remove '" + world.rigid_body(rigid->body).name + "'";
            if (ImGui::Button(label.c_str())) c.session.remove_body(true, rigid->body);
        } else if (world.soft_body_count() > 0) {
            const std::string label = "Remove '" + world.soft_body(c.session.selected_body()).name() + "'";
            if (ImGui::Button(label.c_str())) c.session.remove_body(false, c.session.selected_body());
        }
        if (ImGui::IsItemHovered()) {
            ImGui::SetTooltip(
                "Takes the selected body out of the world, with the springs attached to it (the Timeline goes\n"
                "back across it). Select a soft body by clicking it, a rigid body by ctrl-clicking it.");
        }
    }

private:
    std::vector<std::string> meshes_ = bundled_meshes();
    std::size_t mesh_ = 0;
};

const ToolRegistration kAddToolRegistered{80, [] { return std::unique_ptr<Tool>(new AddTool); }};

}  // namespace

}  // namespace softbody::app
