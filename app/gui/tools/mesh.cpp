// The Mesh tool.
#include <imgui.h>

#include <cstdio>
#include <filesystem>

#include "gui/asset_files.h"
#include "physics/pair_forces.h"

#include "gui/session.h"
#include "gui/tool.h"
#include "gui/view.h"

namespace softbody::app {

namespace {

namespace fs = std::filesystem;

std::string memory_text(std::size_t n) {
    // State: x, x_prev, v, rest, forces, four stage accelerations and scratch: about 30 floats a
    // particle; and what the fast kernel keeps (its packed state and per-tile partial forces).
    const double bytes = double(n) * 30.0 * 4.0 + double(PairForceKernel::memory_bytes(n));
    char text[64];
    std::snprintf(text, sizeof text, "%.1f MB", bytes / 1e6);
    return text;
}

class MeshTool : public Tool {
public:
    const char* title() const override { return "Mesh"; }
    void draw(ToolContext& c) override { mesh_body(c); }

private:
    void mesh_body(ToolContext& c) {
        const World& world = c.session.world();
        const bool soft = world.soft_body_count() > 0;
        if (soft) {
            const SoftBody& body = world.soft_body(c.session.selected_body());
            const Mesh& mesh = body.mesh;
            ImGui::TextWrapped("%s", fs::path(mesh.source).filename().string().c_str());
            if (body.reduced) {
                ImGui::Text("%zu vertices, simulated on %zu particles", mesh.vertex_to_particle.size(), body.particle_count());
                if (ImGui::IsItemHovered()) {
                    // max_particles all (0) is capped too: no body runs on more than kMaxParticles.
                    const bool all = body.def.max_particles == 0;
                    ImGui::SetTooltip(
                        "Above %s (%zu): the %zu distinct positions follow %zu particles chosen over\n"
                        "the body (skinning); each weighs %.3g particles' mass, k and c as much again.",
                        all ? "the cap on max_particles=all" : "max_particles",
                        all ? kMaxParticles : std::size_t(body.def.max_particles), mesh.particle_count(), body.particle_count(),
                        double(mesh.particle_count()) / double(body.particle_count()));
                }
            } else {
                ImGui::Text("%zu vertices -> %zu particles", mesh.vertex_to_particle.size(), body.particle_count());
            }
            ImGui::Text("scale %.4g%s, +%s up", double(body.scale_used), body.def.scale == 0.0f ? " (auto: 1 m, centred)" : "",
                        body.def.up_axis.c_str());
            if (ImGui::IsItemHovered()) {
                ImGui::SetTooltip(
                    "A mesh opened or dropped without a scene is sized so its largest side is 1 m and stood\n"
                    "up (+y up, as most exporters write). All keys: scale, up_axis (both on reset).");
            }
            ImGui::Text("%zu triangles, %zu springs + dampers", mesh.triangle_count(), body.spring_count());
            ImGui::Text("memory %s", memory_text(body.particle_count()).c_str());
        } else {
            ImGui::TextWrapped("No soft body in this scene: open a mesh to add one.");
        }
        if (ImGui::BeginCombo("scene", fs::path(c.session.source()).filename().string().c_str())) {
            for (const auto& scene : scenes_) {
                if (ImGui::Selectable(fs::path(scene).stem().string().c_str())) c.session.load_scene_file(scene);
            }
            ImGui::EndCombo();
        }
        if (ImGui::BeginCombo(
                "mesh",
                soft ? fs::path(world.soft_body(c.session.selected_body()).mesh.source).filename().string().c_str() : "(none)")) {
            for (const auto& file : meshes_) {
                if (ImGui::Selectable(fs::path(file).filename().string().c_str())) c.session.load_mesh_file(file);
            }
            ImGui::EndCombo();
        }
        ImGui::InputTextWithHint("##open", "path to an .obj or .off", open_path_, sizeof open_path_);
        ImGui::SameLine();
        if (ImGui::Button("Open") && open_path_[0]) c.session.load_mesh_file(open_path_);
        ImGui::TextDisabled("or drop a file on the window");
    }

    std::vector<std::string> scenes_ = bundled_scenes(), meshes_ = bundled_meshes();
    char open_path_[1024] = {};
};

const ToolRegistration kMeshToolRegistered{110, [] { return std::unique_ptr<Tool>(new MeshTool); }};

}  // namespace

}  // namespace softbody::app
