// The Dear ImGui panels of the demo: Simulation, Parameters, Mesh, Display, Energy, Stability,
// Rigid bodies, Last collision, Compare integrators, Presets, and the help overlay. They read and edit the Demo; they own only UI state.
#pragma once

#include <string>
#include <vector>

#include "gui/lesson_panel.h"

namespace softbody::app {

class Demo;
class Recorder;

class Panels {
public:
    explicit Panels(float ui_scale);

    // Draws everything for this frame (between the window's begin/end_ui_frame).
    void draw(Demo& demo, float fps);

    float width() const { return show_panels ? 376.0f * scale_ : 0.0f; }  // pixels the panel covers

    bool show_help = false;
    bool show_panels = true;
    LessonPanel lesson;  // the Lessons menu and the Lesson panel (lesson_panel.h)
    Recorder* recorder = nullptr;  // the Record button's (gui/recorder.h); none: no button

private:
    void simulation(Demo& demo, float fps);
    void timeline(Demo& demo);
    void parameters(Demo& demo);
    void add(Demo& demo);  // the Add menu: bodies dropped into the scene
    void mesh(Demo& demo);
    void rigid_bodies(Demo& demo);
    void last_collision(Demo& demo);
    void inspector(Demo& demo);
    void display(Demo& demo);
    void energy(Demo& demo);
    void energy_by_integrator(Demo& demo);
    void compare(Demo& demo);
    void stability(Demo& demo);
    void presets(Demo& demo);
    void help();
    void error_banner(Demo& demo);

    float scale_;
    std::vector<std::string> scenes_, meshes_;  // bundled assets
    char open_path_[1024] = {};
    char preset_path_[1024] = {};
    std::string confirm_overwrite_;             // path awaiting "overwrite?" (empty: none)
    int rigid_selected_ = 0;                    // the rigid body the panel shows
    int add_mesh_ = 0;                          // the mesh file the Add menu drops
    bool compare_pick_[4] = {false, true, true, false};  // integrators to compare (params.h order)
    int compare_substeps_[4] = {0, 0, 0, 0};             // each one's substeps; 0: automatic
};

}  // namespace softbody::app
