#include "web/browser.h"

#include <emscripten.h>
#include <emscripten/html5.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <exception>
#include <iostream>

namespace softbody::app::browser {

namespace {

// The canvas's laid-out size in CSS pixels (0 when it is not laid out).
EM_JS(int, canvas_client_width, (), { return Module['canvas'] ? Module['canvas'].clientWidth : 0; });
EM_JS(int, canvas_client_height, (), { return Module['canvas'] ? Module['canvas'].clientHeight : 0; });

void call_frame(void* argument) {
    auto* frame = static_cast<std::function<bool()>*>(argument);
    bool more = false;
    try {
        more = (*frame)();
    } catch (const std::exception& e) {
        std::cerr << "softbody: " << e.what() << std::endl;
    }
    // Once over, the session is kept, not destroyed: the page goes on showing its last frame
    // (closing the window would take the canvas's picture with it).
    if (!more) emscripten_cancel_main_loop();
}

}  // namespace

void run_frames(std::function<bool()> frame) {
    // 0 frames a second: the browser's own rate (requestAnimationFrame). The loop is not
    // simulated as infinite, so this returns and the C++ stack unwinds normally.
    emscripten_set_main_loop_arg(call_frame, new std::function<bool()>(std::move(frame)), 0, false);
}

void fit_canvas(GLFWwindow* window) {
    const int width = canvas_client_width(), height = canvas_client_height();
    if (width <= 0 || height <= 0) return;
    int current_width = 0, current_height = 0;
    glfwGetWindowSize(window, &current_width, &current_height);
    if (width != current_width || height != current_height) glfwSetWindowSize(window, width, height);
}

}  // namespace softbody::app::browser
