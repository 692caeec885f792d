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

    float width() const { return show_panels ? 376.0f * scale_ : 0.0f; }  // pixels the panel covers
    LessonTool* lesson() const;  // the Lesson tool (its menu, its meter, the run's summary)

    bool show_help = false;
    bool show_panels = true;
    Recorder* recorder = nullptr;  // the Record button's (gui/recorder.h); none: no button

private:
    void help();
    void error_banner(Session& session, View& view);
    void notice_banner(Session& session);

    float scale_;
    std::vector<std::unique_ptr<Tool>> tools_;
};

}  // namespace softbody::app
