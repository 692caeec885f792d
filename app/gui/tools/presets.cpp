// The Presets tool.
#include <imgui.h>

#include <cstdio>
#include <filesystem>

#include "gui/asset_files.h"

#include "gui/session.h"
#include "gui/tool.h"
#include "gui/view.h"

namespace softbody::app {

namespace {

namespace fs = std::filesystem;

class PresetsTool : public Tool {
public:
    const char* title() const override { return "Presets"; }
    PresetsTool() { std::snprintf(preset_path_, sizeof preset_path_, "%s/my_scene.json", presets_folder().c_str()); }
    void draw(ToolContext& c) override { presets_body(c); }

private:
    void presets_body(ToolContext& c) {
        ImGui::InputText("##preset", preset_path_, sizeof preset_path_);
        if (ImGui::Button("Save")) {
            std::error_code ec;
            const fs::path path(preset_path_);
            if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);
            if (fs::exists(path, ec))
                confirm_overwrite_ = preset_path_;
            else
                c.session.save_preset(preset_path_, false);
        }
        ImGui::SameLine();
        if (ImGui::Button("Load")) c.session.load_scene_file(preset_path_);
        ImGui::SameLine();
        ImGui::TextDisabled("JSON scene files");
        if (!confirm_overwrite_.empty()) ImGui::OpenPopup("Overwrite?");
        if (ImGui::BeginPopupModal("Overwrite?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
            ImGui::Text("%s already exists.\nReplace it with the current parameters?", confirm_overwrite_.c_str());
            if (ImGui::Button("Replace")) {
                c.session.save_preset(confirm_overwrite_, true);
                confirm_overwrite_.clear();
                ImGui::CloseCurrentPopup();
            }
            ImGui::SameLine();
            if (ImGui::Button("Cancel")) {
                confirm_overwrite_.clear();
                ImGui::CloseCurrentPopup();
            }
            ImGui::EndPopup();
        }
    }

    char preset_path_[1024] = {};
    std::string confirm_overwrite_;  // path awaiting "overwrite?" (empty: none)
};

const ToolRegistration kPresetsToolRegistered{130, [] { return std::unique_ptr<Tool>(new PresetsTool); }};

}  // namespace

}  // namespace softbody::app
