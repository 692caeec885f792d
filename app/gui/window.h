// The desktop window: GLFW with an OpenGL 3.3 core context, glad loaded from it, and Dear
// ImGui's platform and renderer backends attached. Nothing here knows about the simulation.
#pragma once

#include <deque>
#include <functional>
#include <string>
#include <vector>

#include "gui/input.h"

struct GLFWwindow;

namespace softbody::app {

struct WindowOptions {
    int width = 1280;
    int height = 800;
    bool vsync = true;
    bool visible = true;
    std::string title = "softbody";
};

class Window {
public:
    // Throws std::runtime_error with one line when there is no display or no GL 3.3 context.
    explicit Window(const WindowOptions& options);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    bool should_close() const;
    void request_close();
    void poll_events();
    void swap_buffers();
    double time() const;  // seconds since start, for the frame clock

    // Framebuffer size in pixels (larger than the window size on high-DPI screens; in the
    // browser both are the canvas's pixels).
    int framebuffer_width() const;
    int framebuffer_height() const;
    // The UI's scale: the screen's (the device's pixel ratio in the browser).
    float content_scale() const { return content_scale_; }
    // Whether the window is on a screen that takes fingers (the page on a tablet or a phone).
    bool touch_screen() const { return touch_screen_; }

    // A finger on the window (the page's touch screen), in framebuffer pixels: what it does
    // arrives as take_events()' events (touch set) for the view, or as the panel's pointer.
    void touch(TouchGestures::Phase phase, int id, float x, float y);

    // Files dropped on the window, and mouse/keyboard events, each taken once.
    std::vector<std::string> take_dropped_files();
    std::vector<InputEvent> take_events();

    GLFWwindow* handle() const { return window_; }

    // ImGui frame boundaries (platform + renderer backends).
    void begin_ui_frame();
    void end_ui_frame();

private:
    bool ui_at(float x, float y) const;  // the panel, a banner or an open list is there
    void take_touches();
    void feed_ui_pointer();

    GLFWwindow* window_ = nullptr;
    float content_scale_ = 1.0f;
    std::vector<std::string> dropped_;
    std::vector<InputEvent> events_;
    float cursor_x_ = 0.0f, cursor_y_ = 0.0f;  // last pointer position, fractions of the window
    TouchGestures touches_;
    // The panel's pointer while fingers work it, one state a frame (input.h, UiPointer); from
    // the first touch until a mouse moves, the panel sees this pointer instead of the mouse.
    std::deque<UiPointer> ui_queue_;
    UiPointer ui_pointer_;
    bool ui_from_touch_ = false;
    bool touch_screen_ = false;

    friend struct WindowCallbacks;
};

}  // namespace softbody::app
