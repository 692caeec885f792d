// The Share tool: the setup as a link (in the page) or a command line (on the desktop) that
// opens the same world, and, in the page, which has no folder to share, the preset as a file
// to download and a file to upload.
#include <imgui.h>

#include <filesystem>
#include <string>

#include "cli.h"
#include "gui/app_shell.h"
#include "gui/session.h"
#include "gui/setup_link.h"
#include "gui/tool.h"
#include "physics/scene_io.h"
#if defined(__EMSCRIPTEN__)
#include "web/browser.h"
#endif

namespace softbody::app {

namespace {

class ShareTool : public Tool {
public:
    const char* title() const override { return "Share"; }
    void draw(ToolContext& c) override { share_body(c); }

private:
    void share_body(ToolContext& c) {
        const Setup setup = current_setup(c.session, launch_scene());
#if defined(__EMSCRIPTEN__)
        const std::string query = setup_query(setup);
        const std::string link = browser::page_address() + (query.empty() ? "" : "?" + query);
        if (ImGui::Button("Copy link")) {
            browser::copy_text(link);
            c.session.set_notice("Link copied: " + link + (setup.lost.empty() ? "" : "\n" + setup.lost));
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("The scene and every key changed, in an address that opens this setup.");
        if (browser::take_copy_failure()) {
            c.session.set_error("The browser did not let the link be copied. Here it is, to copy by hand:\n" + link);
        }
        ImGui::SameLine();
        if (ImGui::Button("Download preset")) {
            const std::string name = file_stem(c.session) + ".json";
            browser::download(name, scene_to_json(portable(c.session.scene())), "application/json");
            c.session.set_notice("Downloaded " + name + ": Upload opens it here, and the desktop app opens it with "
                                 "Presets > Load or when it is dropped on the window.");
        }
        ImGui::SameLine();
        if (ImGui::Button("Upload")) browser::choose_file(".json,.obj,.off");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("A preset (.json) opens as a scene; a mesh (.obj, .off) becomes the body.");
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextDisabled("%s", link.c_str());
#else
        const std::string command = setup_command(setup);
        if (ImGui::Button("Copy command line")) {
            ImGui::SetClipboardText(command.c_str());
            c.session.set_notice("Copied: " + command + (setup.lost.empty() ? "" : "\n" + setup.lost));
        }
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextDisabled("%s", command.c_str());
#endif
        if (!setup.lost.empty()) ImGui::TextColored(ImVec4(0.95f, 0.75f, 0.30f, 1.0f), "%s", setup.lost.c_str());
        ImGui::PopTextWrapPos();
    }

#if defined(__EMSCRIPTEN__)
    // The scene as a file that opens wherever it is put: the bundled meshes it names as
    // "assets/meshes/...", which the page and the desktop app both find from anywhere (cli.h).
    static Scene portable(Scene scene) {
        const auto bundled = [](std::string& mesh) {
            if (std::string name = bundled_name(mesh); !name.empty()) mesh = std::move(name);
        };
        for (SoftBodyDef& body : scene.soft_bodies) bundled(body.mesh);
        for (RigidBodyDef& body : scene.rigid_bodies) bundled(body.mesh);
        return scene;
    }

    // The downloaded file's name: the scene's or the mesh's own, else the presets' usual one.
    static std::string file_stem(const Session& session) {
        const std::string stem = std::filesystem::path(session.source()).stem().string();
        return stem.empty() ? "my_scene" : stem;
    }
#endif
};

const ToolRegistration kShareToolRegistered{15, [] { return std::unique_ptr<Tool>(new ShareTool); }};

}  // namespace

}  // namespace softbody::app
