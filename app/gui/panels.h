// The demo's panel: the tools (tool.h, one file each under gui/tools/) in their order, each under
// its own header, the help overlay and the error banner. It owns the tools and nothing else.
#pragma once

#include <memory>
#include <vector>

#include "gui/tool.h"

namespace softbody::app {

class LessonTool;

class Panels {
public:
    explicit Panels(float ui_scale);

    // Hands the session to the tools that watch its ticks (once, before the first frame).
    void attach(Session& session);
    // Draws everything for this frame (between the window's begin/end_ui_frame).
    void draw(Session& session, View& view, float fps);

    // Pixels the panel covers on the left of the view (none while it is hidden or folded).
    float width() const { return show_panels && !folded_ ? panel_width_ + 16.0f * scale_ : 0.0f; }
    LessonTool* lesson() const;  // the Lesson tool (its menu, its meter, the run's summary)

    UiSettings ui;
    bool show_help = false;
    bool show_panels = true;
    Recorder* recorder = nullptr;  // the Record button's (gui/recorder.h); none: no button

private:
    void help();
    void error_banner(Session& session, View& view);
    void notice_banner(Session& session);

    float scale_;  // the screen's content scale
    std::vector<std::unique_ptr<Tool>> tools_;
    float panel_width_ = 360.0f;
    bool folded_ = false;
    bool first_frame_ = true;
};

}  // namespace softbody::app
